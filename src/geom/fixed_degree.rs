//! Frames of surfaces of degree 1 to 3 in each direction — Bezier patches, the conics of the
//! exact shapes — with every array exactly as long as the degree needs, so each loop has a fixed
//! trip count, and the span's net relative to its local origin kept from one parameter to the
//! next.

use glam::{DVec3, DVec4};

use super::knots::FirstBasis;
use super::surface::{Homogeneous, SurfaceDerivs};
use super::{Frame, NurbsSurface};

/// A span's control net relative to the corner its parameters are nearest to (the local origin
/// of [`NurbsSurface::derivs_from_basis`]): `local[i][j] = (w (P − O), w)` of the net entry
/// `(i0 + i, j0 + j)`. Kept while consecutive parameters share the span and the corner.
struct LocalNet<const NU: usize, const NV: usize> {
    /// `(i0, j0)` and the origin's net index, once loaded.
    key: Option<NetKey>,
    origin: DVec3,
    local: [[DVec4; NV]; NU],
}

/// The net index of a span's first control point, and of its local origin.
type NetKey = ((usize, usize), (usize, usize));

impl<const NU: usize, const NV: usize> LocalNet<NU, NV> {
    fn new() -> Self {
        Self {
            key: None,
            origin: DVec3::ZERO,
            local: [[DVec4::ZERO; NV]; NU],
        }
    }

    /// Makes this the net for `key`, unless it already is.
    #[inline(always)]
    fn load(&mut self, surface: &NurbsSurface, key: NetKey) {
        if self.key == Some(key) {
            return;
        }
        let ((i0, j0), (oi, oj)) = key;
        let corner = surface.homogeneous_point(oi, oj);
        self.origin = corner.truncate() / corner.w;
        let origin4 = self.origin.extend(0.0);
        for (i, row) in self.local.iter_mut().enumerate() {
            for (j, local) in row.iter_mut().enumerate() {
                let pw = surface.homogeneous_point(i0 + i, j0 + j);
                *local = pw - origin4 * pw.w;
            }
        }
        self.key = Some(key);
    }

    /// The point and first derivatives of a rational surface: `A^(k,l) = Σ_j N^(l)_j(v) Σ_i
    /// N^(k)_i(u) local[i][j]` for `k + l ≤ 1`, then the quotient rule, adding the same terms in
    /// the same order as [`NurbsSurface::derivs_from_basis`].
    #[inline(always)]
    fn rational_derivs(&self, bu: &FirstBasis<NU>, bv: &FirstBasis<NV>) -> SurfaceDerivs {
        let mut h = Homogeneous::default();
        for l in 0..NV {
            let mut column = [DVec4::ZERO; 3];
            for i in 0..NU {
                let local = self.local[i][l];
                column[0] += local * bu.value[i];
                column[1] += local * bu.slope[i];
            }
            let nv = [bv.value[l], bv.slope[l]];
            h.add_column(&column, |k| nv[k], 1);
        }
        h.rational(self.origin, 1)
    }

    /// The point and first derivatives of a polynomial surface (all weights 1):
    /// `S − O = Σ_j N_j(v) Σ_i N_i(u) (P_ij − O)`, `Su = Σ_j N_j(v) Σ_i N'_i(u) (P_ij − O)`,
    /// `Sv = Σ_j N'_j(v) Σ_i N_i(u) (P_ij − O)`: the rational quotient with the weight sums
    /// taken as exactly 1 and 0.
    #[inline(always)]
    fn polynomial_derivs(&self, bu: &FirstBasis<NU>, bv: &FirstBasis<NV>) -> SurfaceDerivs {
        let (mut a, mut au, mut av) = (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO);
        for l in 0..NV {
            let (mut c0, mut c1) = (DVec3::ZERO, DVec3::ZERO);
            for i in 0..NU {
                let local = self.local[i][l].truncate();
                c0 += local * bu.value[i];
                c1 += local * bu.slope[i];
            }
            a += c0 * bv.value[l];
            au += c1 * bv.value[l];
            av += c0 * bv.slope[l];
        }
        SurfaceDerivs {
            point: self.origin + a,
            su: au,
            sv: av,
            ..SurfaceDerivs::default()
        }
    }
}

/// The end of a span (index 0 or `N − 1`) whose basis function is larger at the parameter.
#[inline(always)]
fn nearest_end<const N: usize>(b: &FirstBasis<N>) -> usize {
    if b.value[0] >= b.value[N - 1] {
        0
    } else {
        N - 1
    }
}

/// Parameters evaluated together: first their derivatives, then their frames, so that the
/// square roots and divisions of neighbouring frames overlap in the processor.
const BATCH: usize = 32;

/// First derivatives of one surface of degrees 1 to 3 in each direction, one parameter after
/// another, keeping the span's net while the parameters stay in it.
pub(super) struct FixedDerivs(Fixed);

/// [`FixedDerivs`] for each pair of degrees.
enum Fixed {
    D11(LocalNet<2, 2>),
    D12(LocalNet<2, 3>),
    D13(LocalNet<2, 4>),
    D21(LocalNet<3, 2>),
    D22(LocalNet<3, 3>),
    D23(LocalNet<3, 4>),
    D31(LocalNet<4, 2>),
    D32(LocalNet<4, 3>),
    D33(LocalNet<4, 4>),
}

impl FixedDerivs {
    /// The point and first derivatives at (u, v) of `surface`, the surface this was made for.
    pub(super) fn at(&mut self, surface: &NurbsSurface, u: f64, v: f64) -> SurfaceDerivs {
        match &mut self.0 {
            Fixed::D11(net) => net.derivs_at(surface, u, v),
            Fixed::D12(net) => net.derivs_at(surface, u, v),
            Fixed::D13(net) => net.derivs_at(surface, u, v),
            Fixed::D21(net) => net.derivs_at(surface, u, v),
            Fixed::D22(net) => net.derivs_at(surface, u, v),
            Fixed::D23(net) => net.derivs_at(surface, u, v),
            Fixed::D31(net) => net.derivs_at(surface, u, v),
            Fixed::D32(net) => net.derivs_at(surface, u, v),
            Fixed::D33(net) => net.derivs_at(surface, u, v),
        }
    }
}

impl<const NU: usize, const NV: usize> LocalNet<NU, NV> {
    /// The point and first derivatives at (u, v), loading the span's net if it is not loaded.
    #[inline(always)]
    fn derivs_at(&mut self, surface: &NurbsSurface, u: f64, v: f64) -> SurfaceDerivs {
        let bu = surface.knots_u().first_basis::<NU>(u);
        let bv = surface.knots_v().first_basis::<NV>(v);
        let first = (bu.span + 1 - NU, bv.span + 1 - NV);
        let key = (
            first,
            (first.0 + nearest_end(&bu), first.1 + nearest_end(&bv)),
        );
        self.load(surface, key);
        if surface.is_rational() {
            self.rational_derivs(&bu, &bv)
        } else {
            self.polynomial_derivs(&bu, &bv)
        }
    }
}

impl NurbsSurface {
    /// The fixed-degree evaluation of this surface's first derivatives, for degrees 1 to 3 in
    /// each direction; `None` for any other.
    pub(super) fn fixed_derivs(&self) -> Option<FixedDerivs> {
        let fixed = match (self.knots_u().degree(), self.knots_v().degree()) {
            (1, 1) => Fixed::D11(LocalNet::new()),
            (1, 2) => Fixed::D12(LocalNet::new()),
            (1, 3) => Fixed::D13(LocalNet::new()),
            (2, 1) => Fixed::D21(LocalNet::new()),
            (2, 2) => Fixed::D22(LocalNet::new()),
            (2, 3) => Fixed::D23(LocalNet::new()),
            (3, 1) => Fixed::D31(LocalNet::new()),
            (3, 2) => Fixed::D32(LocalNet::new()),
            (3, 3) => Fixed::D33(LocalNet::new()),
            _ => return None,
        };
        Some(FixedDerivs(fixed))
    }

    /// [`frames`](Self::frames) for degrees `NU − 1` along u and `NV − 1` along v. Where the
    /// regular frame does not exist (a collapsed edge), the general evaluation takes over.
    pub(super) fn frames_fixed<const NU: usize, const NV: usize>(
        &self,
        params: &[(f64, f64)],
        out: &mut [Frame],
    ) {
        let domain = self.domain();
        let mut net = LocalNet::<NU, NV>::new();
        let frame = |d: &SurfaceDerivs, u: f64, v: f64| {
            Frame::from_derivs(d, u, v, &domain)
                .filter(|f| !f.degenerate)
                .unwrap_or_else(|| self.frame_general(u, v))
        };
        if let ([(u, v)], [out]) = (params, &mut *out) {
            // One frame (a point of a line, a probe): no batch to clear and fill.
            *out = frame(&net.derivs_at(self, *u, *v), *u, *v);
            return;
        }
        let mut derivs = [SurfaceDerivs::default(); BATCH];
        for (params, out) in params.chunks(BATCH).zip(out.chunks_mut(BATCH)) {
            for (&(u, v), d) in params.iter().zip(&mut derivs) {
                *d = net.derivs_at(self, u, v);
            }
            for ((&(u, v), d), out) in params.iter().zip(&derivs).zip(out) {
                *out = frame(d, u, v);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use rand::rngs::StdRng;
    use rand::{Rng, SeedableRng};

    use super::*;
    use crate::geom::frame::WORLD_AXES;
    use crate::geom::shapes;

    /// A surface of degrees (p, q) with two spans each way (a double interior knot along v when
    /// q ≥ 2), control points off the origin and, when `rational`, random weights.
    fn random_surface(rng: &mut StdRng, p: usize, q: usize, rational: bool) -> NurbsSurface {
        let knots = |degree: usize, interior: &[f64]| -> Vec<f64> {
            let mut k = vec![0.0; degree + 1];
            k.extend_from_slice(interior);
            k.extend(std::iter::repeat_n(1.0, degree + 1));
            k
        };
        let knots_u = knots(p, &[0.4]);
        let knots_v = if q >= 2 {
            knots(q, &[0.55, 0.55])
        } else {
            knots(q, &[0.55])
        };
        let (count_u, count_v) = (knots_u.len() - p - 1, knots_v.len() - q - 1);
        let points: Vec<Vec<DVec3>> = (0..count_u)
            .map(|i| {
                (0..count_v)
                    .map(|j| {
                        let jitter = DVec3::new(rng.random(), rng.random(), rng.random());
                        DVec3::new(100.0 + i as f64, -50.0 + j as f64, 3.0) + 0.4 * jitter
                    })
                    .collect()
            })
            .collect();
        let weights: Vec<Vec<f64>> = (0..count_u)
            .map(|_| (0..count_v).map(|_| rng.random_range(0.5..2.0)).collect())
            .collect();
        NurbsSurface::new(
            p,
            q,
            knots_u,
            knots_v,
            &points,
            rational.then_some(&weights[..]),
        )
        .unwrap()
    }

    /// Random parameters, the domain's corners and edges, and knots.
    fn parameters(rng: &mut StdRng) -> Vec<(f64, f64)> {
        let special = [0.0, 0.4, 0.5, 0.55, 1.0];
        let mut params: Vec<(f64, f64)> = (0..300).map(|_| (rng.random(), rng.random())).collect();
        params.extend(
            special
                .iter()
                .flat_map(|&u| special.iter().map(move |&v| (u, v))),
        );
        params
    }

    #[test]
    fn frames_of_degrees_1_to_3_are_the_general_evaluation() {
        let mut rng = StdRng::seed_from_u64(11);
        for p in 1..=3 {
            for q in 1..=3 {
                for rational in [false, true] {
                    let surface = random_surface(&mut rng, p, q, rational);
                    let params = parameters(&mut rng);
                    let mut frames = vec![WORLD_AXES; params.len()];
                    surface.frames(&params, &mut frames);
                    for (&(u, v), got) in params.iter().zip(&frames) {
                        let want = surface.frame_general(u, v);
                        let what = format!("degrees ({p}, {q}), rational {rational}, ({u}, {v})");
                        // One frame alone is the frame of a batch.
                        assert_eq!(surface.frame(u, v), *got, "{what}");
                        if rational {
                            // The same operations in the same order.
                            assert_eq!(*got, want, "{what}");
                        } else {
                            // Weight sums taken as exactly 1 and 0: rounding apart.
                            assert!((got.point - want.point).length() < 1e-12, "{what}");
                            for (a, b) in [(got.normal, want.normal), (got.du, want.du)] {
                                assert!((a - b).length() < 1e-13, "{what}: {a} vs {b}");
                            }
                            assert_eq!(got.degenerate, want.degenerate, "{what}");
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn collapsed_edges_fall_back_to_the_general_limit_frame() {
        let sphere = shapes::sphere(DVec3::new(3.0, -2.0, 1.0), 2.0).unwrap();
        let params: Vec<(f64, f64)> = [0.0, 0.3, 0.999, 1.0]
            .iter()
            .flat_map(|&u| [0.0, 1e-12, 0.5, 1.0].map(|v| (u, v)))
            .collect();
        let mut frames = vec![WORLD_AXES; params.len()];
        sphere.frames(&params, &mut frames);
        for (&(u, v), got) in params.iter().zip(&frames) {
            assert_eq!(*got, sphere.frame_general(u, v), "({u}, {v})");
            if v == 0.0 || v == 1.0 {
                assert!(got.degenerate, "a pole at ({u}, {v})");
            }
        }
    }
}
