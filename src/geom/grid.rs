//! Grid evaluation: basis values computed once per u sample and once per v sample, so each grid
//! point costs one small tensor contraction (DESIGN §3). Tessellation evaluates this way.

use super::knots::BasisDerivs;
use super::{Frame, NurbsSurface};

/// Evaluates a surface on the grid `us × vs` with the basis functions (to second order) of each
/// sample precomputed.
#[derive(Clone, Debug)]
pub struct GridEvaluator<'a> {
    surface: &'a NurbsSurface,
    us: Vec<f64>,
    vs: Vec<f64>,
    basis_u: Vec<BasisDerivs>,
    basis_v: Vec<BasisDerivs>,
}

impl<'a> GridEvaluator<'a> {
    /// A grid over the given parameter samples (each clamped to the surface's domain).
    pub fn new(surface: &'a NurbsSurface, us: &[f64], vs: &[f64]) -> Self {
        let domain = surface.domain();
        let us: Vec<f64> = us.iter().map(|u| u.clamp(domain.u.0, domain.u.1)).collect();
        let vs: Vec<f64> = vs.iter().map(|v| v.clamp(domain.v.0, domain.v.1)).collect();
        let basis_u = us
            .iter()
            .map(|&u| surface.knots_u().basis_derivs(u, 2))
            .collect();
        let basis_v = vs
            .iter()
            .map(|&v| surface.knots_v().basis_derivs(v, 2))
            .collect();
        Self {
            surface,
            us,
            vs,
            basis_u,
            basis_v,
        }
    }

    /// A uniform grid of `samples_u × samples_v` points spanning the whole domain, edges
    /// included (`samples ≥ 2` in each direction).
    pub fn uniform(surface: &'a NurbsSurface, samples_u: usize, samples_v: usize) -> Self {
        let domain = surface.domain();
        let spread = |(a, b): (f64, f64), n: usize| -> Vec<f64> {
            let n = n.max(2);
            (0..n)
                .map(|i| a + (b - a) * i as f64 / (n - 1) as f64)
                .collect()
        };
        Self::new(
            surface,
            &spread(domain.u, samples_u),
            &spread(domain.v, samples_v),
        )
    }

    /// The u samples.
    pub fn us(&self) -> &[f64] {
        &self.us
    }

    /// The v samples.
    pub fn vs(&self) -> &[f64] {
        &self.vs
    }

    /// The point at grid node (i, j), i indexing u samples and j v samples.
    pub fn point(&self, i: usize, j: usize) -> glam::DVec3 {
        self.surface
            .derivs_from_basis(&self.basis_u[i], &self.basis_v[j], 0)
            .point
    }

    /// The frame at grid node (i, j); equal to `surface.frame(us[i], vs[j])`.
    pub fn frame(&self, i: usize, j: usize) -> Frame {
        self.surface
            .frame_from_basis(self.us[i], self.vs[j], &self.basis_u[i], &self.basis_v[j])
    }
}
