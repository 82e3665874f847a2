//! Grid evaluation: basis values computed once per u sample and once per v sample, and the net
//! contracted along u once per u sample and v-span, so each grid point costs one short
//! contraction along v (docs/geometry.md). Tessellation evaluates this way.

use super::knots::BasisDerivs;
use super::surface::{ContractedRows, LocalOrigin};
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

    /// The frames of row `i` (u sample i) at every v sample, in order; each equal to
    /// `surface.frame(us[i], vs[j])`.
    pub fn row_frames(&self, i: usize) -> impl Iterator<Item = Frame> + '_ {
        let mut row = RowContraction::new(self, i);
        (0..self.vs.len()).map(move |j| self.frame_in_row(&mut row, j))
    }

    /// The frame at grid node (i, j) alone.
    pub fn frame(&self, i: usize, j: usize) -> Frame {
        self.frame_in_row(&mut RowContraction::new(self, i), j)
    }

    fn frame_in_row(&self, row: &mut RowContraction<'_, 'a>, j: usize) -> Frame {
        let i = row.i;
        let (rows, origin) = row.at(j);
        let bv = &self.basis_v[j];
        self.surface.frame_with(self.us[i], self.vs[j], |order| {
            self.surface.derivs_from_rows(rows, bv, origin, order)
        })
    }
}

/// The u-contraction of one grid row, kept while consecutive v samples share its v-span and
/// local origin.
struct RowContraction<'g, 'a> {
    grid: &'g GridEvaluator<'a>,
    i: usize,
    /// The v-span and origin index `rows` was contracted for.
    key: Option<(usize, (usize, usize))>,
    rows: ContractedRows,
}

impl<'g, 'a> RowContraction<'g, 'a> {
    fn new(grid: &'g GridEvaluator<'a>, i: usize) -> Self {
        Self {
            grid,
            i,
            key: None,
            rows: ContractedRows::default(),
        }
    }

    /// The contracted rows and origin for v sample j.
    fn at(&mut self, j: usize) -> (&ContractedRows, LocalOrigin) {
        let surface = self.grid.surface;
        let (bu, bv) = (&self.grid.basis_u[self.i], &self.grid.basis_v[j]);
        let origin = surface.local_origin(bu, bv);
        let key = Some((bv.span, origin.index));
        if self.key != key {
            self.rows = surface.contract_u(bu, bv.span, origin, 2);
            self.key = key;
        }
        (&self.rows, origin)
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::geom::shapes;

    #[test]
    fn grid_frames_are_the_direct_frames_on_every_span() {
        // The torus is rational with four spans each way (double knots at ¼, ½ and ¾), off the
        // origin; the samples fall inside spans, on the knots and at both ends.
        let torus = shapes::torus(2.0, 0.5)
            .unwrap()
            .map_points(|p| p + DVec3::new(3.0, -1.0, 2.0));
        let samples: Vec<f64> = (0..=20).map(|k| f64::from(k) / 20.0).collect();
        let grid = GridEvaluator::new(&torus, &samples, &samples);
        let mut seen = 0;
        for i in 0..grid.us().len() {
            for (j, got) in grid.row_frames(i).enumerate() {
                let (u, v) = (grid.us()[i], grid.vs()[j]);
                let want = torus.frame(u, v);
                assert!(
                    (got.point - want.point).length() < 1e-13
                        && (got.normal - want.normal).length() < 1e-13
                        && (got.du - want.du).length() < 1e-13,
                    "({u}, {v}): {got:?} vs {want:?}"
                );
                assert_eq!(got, grid.frame(i, j));
                seen += 1;
            }
        }
        assert_eq!(seen, 21 * 21);
    }
}
