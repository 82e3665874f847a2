//! The local frame of a surface point: position, unit normal and the two unit tangent
//! directions the highlight operations work in, including the limit frame at degenerate points.

use glam::DVec3;

use super::knots::BasisDerivs;
use super::surface::{Domain, NurbsSurface, SurfaceDerivs};

/// The frame `(du, dv, N)` at a surface point (DESIGN §3).
///
/// `N = normalize(Su × Sv)`, `du = normalize(Su)`, `dv = N × du`; the three are orthonormal and
/// right-handed (`du × dv = N`). At a degenerate point (a collapsed row of control points, where
/// `Su × Sv` vanishes) the limit of that frame from inside the patch is used, and `degenerate` is
/// set. Every component is finite.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// The surface point S(u, v).
    pub point: DVec3,
    /// Unit normal N.
    pub normal: DVec3,
    /// Unit tangent along increasing u.
    pub du: DVec3,
    /// Unit tangent `N × du`, along increasing v where the parametrisation is orthogonal.
    pub dv: DVec3,
    /// True when `Su × Sv` vanished here and the frame is the limit from inside the patch.
    pub degenerate: bool,
}

/// Below this ratio a first derivative counts as vanished next to the other, and two tangents as
/// parallel. Rounding makes a computed `Su` wrong by about `1e-16 |Sv|`, so the naive normal
/// from a short `Su` has an angular error near `1e-16 |Sv| / |Su|`, while the limit normal used
/// instead is off by the distance to the collapsed edge, proportional to `|Su| / |Sv|`. The two
/// errors cross at `sqrt(1e-16) = 1e-8`, so neither exceeds about 1e-8 radians.
const VANISHING_RATIO: f64 = 1e-8;

/// Fractions of the way from a fully degenerate point toward the domain centre at which the frame
/// is looked for when no limit formula applies (a corner where two edges collapse, a cusp).
const INWARD_STEPS: [f64; 5] = [1e-9, 1e-7, 1e-5, 1e-3, 1e-1];

impl Frame {
    /// The frame from first (and, at degenerate points, second) derivatives at (u, v), or `None`
    /// when neither the regular nor a limit formula determines it.
    ///
    /// - Regular: `N = normalize(Su × Sv)`, `du = normalize(Su)`, `dv = N × du`.
    /// - `Su` vanishes (a collapsed edge `v = v0`): `Su(v0 + h) ≈ h Suv`, so
    ///   `N = s normalize(Suv × Sv)` and `du = s normalize(Suv)` with `s = +1` near `v_min`
    ///   (h > 0) and `−1` near `v_max`.
    /// - `Sv` vanishes (a collapsed edge `u = u0`): `N = s normalize(Su × Suv)` with `s = +1` near
    ///   `u_min` and `−1` near `u_max`; `du = normalize(Su)`.
    fn from_derivs(d: &SurfaceDerivs, u: f64, v: f64, domain: &Domain) -> Option<Frame> {
        let (len_u, len_v) = (d.su.length(), d.sv.length());
        if !(len_u.is_finite() && len_v.is_finite()) || len_u.max(len_v) == 0.0 {
            return None;
        }
        let (normal, du, degenerate) = if len_u < VANISHING_RATIO * len_v {
            let s = edge_sign(v, domain.v);
            let n = d.suv.cross(d.sv);
            if !is_non_degenerate_cross(n, d.suv, d.sv) {
                return None;
            }
            (s * n.normalize(), s * d.suv.normalize(), true)
        } else if len_v < VANISHING_RATIO * len_u {
            let s = edge_sign(u, domain.u);
            let n = d.su.cross(d.suv);
            if !is_non_degenerate_cross(n, d.su, d.suv) {
                return None;
            }
            (s * n.normalize(), d.su / len_u, true)
        } else {
            let n = d.su.cross(d.sv);
            if !is_non_degenerate_cross(n, d.su, d.sv) {
                return None;
            }
            (n.normalize(), d.su / len_u, false)
        };
        Some(Frame {
            point: d.point,
            normal,
            du,
            dv: normal.cross(du),
            degenerate,
        })
    }
}

/// `+1` when `t` is nearer the start of `range`, `−1` when nearer its end: the sign of the step
/// from the nearest edge into the domain.
fn edge_sign(t: f64, range: (f64, f64)) -> f64 {
    if t - range.0 <= range.1 - t {
        1.0
    } else {
        -1.0
    }
}

/// Whether `n = a × b` is long enough, relative to `|a| |b|`, to give a direction.
fn is_non_degenerate_cross(n: DVec3, a: DVec3, b: DVec3) -> bool {
    let len = n.length();
    len.is_finite() && len > VANISHING_RATIO * a.length() * b.length()
}

impl NurbsSurface {
    /// The frame at (u, v) (see [`Frame`]); never NaN.
    pub fn frame(&self, u: f64, v: f64) -> Frame {
        let bu = self.knots_u().basis_derivs(u, 2);
        let bv = self.knots_v().basis_derivs(v, 2);
        self.frame_from_basis(u, v, &bu, &bv)
    }

    /// The frame at (u, v) from basis values precomputed to second order.
    ///
    /// Regular points need only first derivatives; second derivatives are contracted only where
    /// a first derivative vanishes. Where no limit formula applies, the frame is taken a little
    /// way inside the patch (toward the domain centre), and as a last resort — a patch collapsed
    /// to a point — the world axes.
    pub(crate) fn frame_from_basis(
        &self,
        u: f64,
        v: f64,
        bu: &BasisDerivs,
        bv: &BasisDerivs,
    ) -> Frame {
        let domain = self.domain();
        let first = self.derivs_from_basis(bu, bv, 1);
        let regular = Frame::from_derivs(&first, u, v, &domain).filter(|f| !f.degenerate);
        if let Some(frame) = regular {
            return frame;
        }
        let second = self.derivs_from_basis(bu, bv, 2);
        if let Some(frame) = Frame::from_derivs(&second, u, v, &domain) {
            return frame;
        }
        let point = first.point;
        let (uc, vc) = domain.center();
        INWARD_STEPS
            .iter()
            .find_map(|&t| {
                let (ui, vi) = (u + t * (uc - u), v + t * (vc - v));
                let d = self.derivs(ui, vi, 2);
                Frame::from_derivs(&d, ui, vi, &domain)
            })
            .map(|f| Frame {
                point,
                degenerate: true,
                ..f
            })
            .unwrap_or(Frame {
                point,
                normal: DVec3::Z,
                du: DVec3::X,
                dv: DVec3::Y,
                degenerate: true,
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A bilinear patch whose v = 0 row collapses to the origin: S(u, v) = (v (2u − 1), v, 0).
    fn apex_patch() -> NurbsSurface {
        let points = vec![
            vec![DVec3::ZERO, DVec3::new(-1.0, 1.0, 0.0)],
            vec![DVec3::ZERO, DVec3::new(1.0, 1.0, 0.0)],
        ];
        let knots = vec![0.0, 0.0, 1.0, 1.0];
        NurbsSurface::new(1, 1, knots.clone(), knots, &points, None).unwrap()
    }

    #[test]
    fn collapsed_edge_gets_the_limit_frame() {
        // Su = (2v, 0, 0) vanishes at v = 0; Su × Sv = (0, 0, 2v).
        let s = apex_patch();
        for &u in &[0.0, 0.3, 1.0] {
            let f = s.frame(u, 0.0);
            assert!(f.degenerate);
            assert!((f.normal - DVec3::Z).length() < 1e-15, "{f:?}");
            assert!((f.du - DVec3::X).length() < 1e-15, "{f:?}");
            let inside = s.frame(u, 1e-3);
            assert!(!inside.degenerate);
            assert!((inside.normal - f.normal).length() < 1e-12);
        }
    }

    #[test]
    fn patch_collapsed_to_a_point_still_has_a_finite_frame() {
        let points = vec![vec![DVec3::ONE; 2]; 2];
        let knots = vec![0.0, 0.0, 1.0, 1.0];
        let s = NurbsSurface::new(1, 1, knots.clone(), knots, &points, None).unwrap();
        let f = s.frame(0.5, 0.5);
        assert!(f.degenerate && f.normal.is_finite() && f.du.is_finite() && f.dv.is_finite());
        assert!((f.normal.cross(f.du) - f.dv).length() < 1e-15);
    }

    #[test]
    fn edge_sign_points_into_the_domain() {
        assert_eq!(edge_sign(0.0, (0.0, 1.0)), 1.0);
        assert_eq!(edge_sign(0.9, (0.0, 1.0)), -1.0);
    }
}
