//! The local frame of a surface point: position, unit normal and the two unit tangent
//! directions the highlight operations work in, including the limit frame at degenerate points.

use glam::DVec3;

use super::surface::{Domain, NurbsSurface, SurfaceDerivs};

/// The frame `(du, dv, N)` at a surface point (docs/geometry.md).
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
    #[inline(always)]
    pub(super) fn from_derivs(d: &SurfaceDerivs, u: f64, v: f64, domain: &Domain) -> Option<Frame> {
        const RATIO_SQUARED: f64 = VANISHING_RATIO * VANISHING_RATIO;
        let (sq_u, sq_v) = (d.su.length_squared(), d.sv.length_squared());
        if !(sq_u.is_finite() && sq_v.is_finite()) || sq_u.max(sq_v) == 0.0 {
            return None;
        }
        // The normal, the vector du points along, and whether this is a limit frame.
        let (normal, along_u, degenerate, sin_squared) = if sq_u < RATIO_SQUARED * sq_v {
            let s = edge_sign(v, domain.v);
            let (n, sin_squared) = unit_cross(d.suv, d.sv, d.suv.length_squared() * sq_v)?;
            (s * n, s * d.suv, true, sin_squared)
        } else if sq_v < RATIO_SQUARED * sq_u {
            let s = edge_sign(u, domain.u);
            let (n, sin_squared) = unit_cross(d.su, d.suv, sq_u * d.suv.length_squared())?;
            (s * n, d.su, true, sin_squared)
        } else {
            let (n, sin_squared) = unit_cross(d.su, d.sv, sq_u * sq_v)?;
            (n, d.su, false, sin_squared)
        };
        // du ⊥ N holds in exact arithmetic, and to rounding where the cross product was long.
        // Where it was short (its two vectors nearly parallel) N carries an error of about
        // 1e-16 / sin, and du is projected onto N's tangent plane to stay orthogonal to it.
        let du = if sin_squared < SHORT_CROSS_SIN_SQUARED {
            (along_u - along_u.dot(normal) * normal).try_normalize()?
        } else {
            along_u.try_normalize()?
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

/// `+1` when `t` is nearer the start of `range` (or halfway), `−1` when nearer its end: the sign
/// of the step from the nearest edge into the domain.
fn edge_sign(t: f64, range: (f64, f64)) -> f64 {
    if t - range.0 <= range.1 - t {
        1.0
    } else {
        -1.0
    }
}

/// `normalize(a × b)` and `sin²` of the angle between a and b, or `None` when `|a × b|²` is too
/// small next to `|a|² |b|²` (given as `squared_lengths`) to give a direction.
fn unit_cross(a: DVec3, b: DVec3, squared_lengths: f64) -> Option<(DVec3, f64)> {
    let n = a.cross(b);
    let sq = n.length_squared();
    (sq.is_finite() && sq > VANISHING_RATIO * VANISHING_RATIO * squared_lengths)
        .then(|| (n * sq.sqrt().recip(), sq / squared_lengths))
}

/// The world axes at the origin: the frame of last resort.
pub(super) const WORLD_AXES: Frame = Frame {
    point: DVec3::ZERO,
    normal: DVec3::Z,
    du: DVec3::X,
    dv: DVec3::Y,
    degenerate: false,
};

/// Below this `sin²` between the two vectors of a cross product (sin < 1e-4), the frame's du is
/// projected onto the normal's tangent plane (see [`Frame`]'s construction).
const SHORT_CROSS_SIN_SQUARED: f64 = 1e-8;

impl NurbsSurface {
    /// The frame at (u, v) (see [`Frame`]); never NaN.
    pub fn frame(&self, u: f64, v: f64) -> Frame {
        let mut out = [WORLD_AXES];
        self.frames(&[(u, v)], &mut out);
        out[0]
    }

    /// The frames at many parameters: `out[k]` is the frame at `params[k]`, as
    /// [`frame`](Self::frame) gives it.
    ///
    /// Degrees 1 to 3 in each direction (Bezier patches, the conics of the exact shapes) are
    /// evaluated with arrays of exactly their length (see `fixed_degree`), the same operations
    /// in the same order as for any other degree, so the same frames.
    ///
    /// # Panics
    /// If the slices differ in length.
    pub fn frames(&self, params: &[(f64, f64)], out: &mut [Frame]) {
        assert_eq!(params.len(), out.len(), "one frame per parameter");
        match (self.knots_u().degree(), self.knots_v().degree()) {
            (1, 1) => self.frames_fixed::<2, 2>(params, out),
            (1, 2) => self.frames_fixed::<2, 3>(params, out),
            (1, 3) => self.frames_fixed::<2, 4>(params, out),
            (2, 1) => self.frames_fixed::<3, 2>(params, out),
            (2, 2) => self.frames_fixed::<3, 3>(params, out),
            (2, 3) => self.frames_fixed::<3, 4>(params, out),
            (3, 1) => self.frames_fixed::<4, 2>(params, out),
            (3, 2) => self.frames_fixed::<4, 3>(params, out),
            (3, 3) => self.frames_fixed::<4, 4>(params, out),
            _ => {
                for (&(u, v), frame) in params.iter().zip(out) {
                    *frame = self.frame_general(u, v);
                }
            }
        }
    }

    /// The frame at (u, v) for any degree: basis functions to first order, and second
    /// derivatives only where the regular frame does not exist.
    pub(crate) fn frame_general(&self, u: f64, v: f64) -> Frame {
        let bu = self.knots_u().basis_derivs(u, 1);
        let bv = self.knots_v().basis_derivs(v, 1);
        self.frame_with(u, v, |order| {
            if order <= 1 {
                self.derivs_from_basis(&bu, &bv, order)
            } else {
                self.derivs(u, v, order)
            }
        })
    }

    /// The frame at (u, v) given a way to get the derivatives there up to an order.
    ///
    /// Regular points need only first derivatives; second derivatives are asked for only where
    /// a first derivative vanishes. Where no limit formula applies, the frame is taken a little
    /// way inside the patch (toward the domain centre), and as a last resort — a patch collapsed
    /// to a point — the world axes.
    pub(crate) fn frame_with(
        &self,
        u: f64,
        v: f64,
        derivs: impl Fn(usize) -> SurfaceDerivs,
    ) -> Frame {
        let domain = self.domain();
        let first = derivs(1);
        let regular = Frame::from_derivs(&first, u, v, &domain).filter(|f| !f.degenerate);
        if let Some(frame) = regular {
            return frame;
        }
        if let Some(frame) = Frame::from_derivs(&derivs(2), u, v, &domain) {
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
                degenerate: true,
                ..WORLD_AXES
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
        assert_eq!(f.point, DVec3::ONE);
        assert!((f.normal.cross(f.du) - f.dv).length() < 1e-15);
    }

    #[test]
    fn edge_sign_points_into_the_domain() {
        assert_eq!(edge_sign(0.0, (0.0, 1.0)), 1.0);
        assert_eq!(edge_sign(0.5, (0.0, 1.0)), 1.0);
        assert_eq!(edge_sign(0.9, (0.0, 1.0)), -1.0);
        assert_eq!(edge_sign(2.6, (2.0, 3.0)), -1.0);
        assert_eq!(edge_sign(2.4, (2.0, 3.0)), 1.0);
    }

    /// A biquadratic patch over `[0, 1]²`, curved in z, with its v = 0 row and u = 0 column
    /// collapsed to one point: the corner (0, 0) has no first derivatives at all. The net is
    /// mirrored in u and in v as asked, to put that corner at each corner of the domain.
    fn corner_patch(mirror_u: bool, mirror_v: bool) -> NurbsSurface {
        let mut points = vec![vec![DVec3::ZERO; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                let (x, y) = (i as f64, j as f64);
                let p = if i == 0 || j == 0 {
                    DVec3::ZERO
                } else {
                    DVec3::new(x, y, 0.3 * x * y - 0.2 * x * x)
                };
                let (a, b) = (
                    if mirror_u { 2 - i } else { i },
                    if mirror_v { 2 - j } else { j },
                );
                points[a][b] = p;
            }
        }
        let knots = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
        NurbsSurface::new(2, 2, knots.clone(), knots, &points, None).unwrap()
    }

    #[test]
    fn a_corner_where_both_edges_collapse_takes_the_normal_from_just_inside() {
        // The collapsed corner at each of the four corners of the domain: the fallback steps
        // toward the centre from whichever side.
        for (mirror_u, mirror_v) in [(false, false), (true, false), (false, true), (true, true)] {
            let (u, v) = (f64::from(u8::from(mirror_u)), f64::from(u8::from(mirror_v)));
            let s = corner_patch(mirror_u, mirror_v);
            let f = s.frame(u, v);
            assert!(f.degenerate, "({u}, {v}): {f:?}");
            let inside = s.frame(u + 1e-6 * (0.5 - u), v + 1e-6 * (0.5 - v));
            assert!(!inside.degenerate);
            assert!(
                inside.normal.dot(f.normal) > 1.0 - 1e-4,
                "({u}, {v}): {f:?} vs {inside:?}"
            );
            assert_eq!(f.point, DVec3::ZERO);
        }
    }

    #[test]
    fn nearness_to_a_collapsed_edge_is_relative_to_the_other_derivative() {
        // The apex patch made 10⁴ times larger: |Su| / |Sv| = 2v whatever the size, so v = 10⁻⁹
        // is within the vanishing ratio of the edge, and v = 10⁻⁷ is not.
        let s = apex_patch().map_points(|p| 1e4 * p);
        let near = s.frame(0.3, 1e-9);
        assert!(near.degenerate, "{near:?}");
        assert!((near.normal - DVec3::Z).length() < 1e-12);
        assert!(!s.frame(0.3, 1e-7).degenerate);
        // And 10⁻⁴ times smaller.
        let s = apex_patch().map_points(|p| 1e-4 * p);
        assert!(s.frame(0.3, 1e-9).degenerate);
        assert!(!s.frame(0.3, 1e-7).degenerate);
    }

    #[test]
    fn a_tangent_nearly_parallel_to_the_other_keeps_du_orthogonal_to_the_normal() {
        // A bilinear patch whose Su and Sv meet at an angle of about 10⁻⁷, turned off the axes so
        // that rounding reaches every component: the normal's error (about 10⁻⁹) would tilt an
        // unprojected du off the tangent plane. At a large scale too: the angle, not the
        // tangents' lengths, decides the projection.
        let e = 1e-7;
        let turn = glam::DMat3::from_axis_angle(DVec3::new(1.0, 2.0, 3.0).normalize(), 0.7);
        let knots = vec![0.0, 0.0, 1.0, 1.0];
        for scale in [1.0, 1e3] {
            let points: Vec<Vec<DVec3>> = [
                [DVec3::ZERO, DVec3::new(1.0, e, 0.3)],
                [DVec3::new(1.0, 0.0, 0.3), DVec3::new(2.0, e, 0.6 + e)],
            ]
            .iter()
            .map(|row| row.iter().map(|&p| scale * (turn * p)).collect())
            .collect();
            let s = NurbsSurface::new(1, 1, knots.clone(), knots.clone(), &points, None).unwrap();
            for (u, v) in [(0.0, 0.0), (0.4, 0.7), (1.0, 1.0)] {
                let f = s.frame(u, v);
                assert!(!f.degenerate);
                assert!(
                    f.du.dot(f.normal).abs() < 1e-14,
                    "({u}, {v}) at {scale}: {f:?}"
                );
                assert!((f.du.cross(f.dv) - f.normal).length() < 1e-14, "{f:?}");
            }
        }
    }

    /// The unit sphere with its parameters swapped: u runs pole to pole, v around, so the
    /// collapsed edges are u = 0 and u = 1 and there Sv vanishes.
    fn transposed_sphere() -> NurbsSurface {
        let s = crate::geom::shapes::sphere(DVec3::ZERO, 1.0).unwrap();
        let (rows, columns) = (s.count_v(), s.count_u());
        let points: Vec<Vec<DVec3>> = (0..rows)
            .map(|i| (0..columns).map(|j| s.control_point(j, i).0).collect())
            .collect();
        let weights: Vec<Vec<f64>> = (0..rows)
            .map(|i| (0..columns).map(|j| s.control_point(j, i).1).collect())
            .collect();
        NurbsSurface::new(
            s.knots_v().degree(),
            s.knots_u().degree(),
            s.knots_v().knots().to_vec(),
            s.knots_u().knots().to_vec(),
            &points,
            Some(&weights),
        )
        .unwrap()
    }

    #[test]
    fn a_pole_has_the_exact_limit_frame_whichever_edge_it_is() {
        // At the poles the normal is ±z exactly, and du is the limit of the tangent along u
        // from inside. Taken a small step inside instead, either would be off by about the
        // step: the tolerance tells the limit from any fallback.
        let sphere = crate::geom::shapes::sphere(DVec3::ZERO, 1.0).unwrap();
        for u in [0.0, 0.1, 0.37, 0.5, 0.9, 1.0] {
            // u runs around: du is east at the meridian's longitude.
            let p = sphere.point(u, 0.5);
            let east = DVec3::new(-p.y, p.x, 0.0).normalize();
            for (v, pole) in [(0.0, -DVec3::Z), (1.0, DVec3::Z)] {
                let f = sphere.frame(u, v);
                assert!(f.degenerate, "({u}, {v})");
                assert!((f.normal - pole).length() < 1e-12, "({u}, {v}): {f:?}");
                assert!(
                    (f.du - east).length() < 1e-12,
                    "({u}, {v}): {f:?} vs {east}"
                );
                assert!((f.normal.cross(f.du) - f.dv).length() < 1e-15);
            }
        }
        let turned = transposed_sphere();
        for v in [0.0, 0.1, 0.37, 0.5, 0.9, 1.0] {
            // u runs pole to pole: du is the meridian's direction, away from the south pole
            // and toward the north one; swapping the parameters turned the normal inward.
            let p = turned.point(0.5, v);
            let out = DVec3::new(p.x, p.y, 0.0).normalize();
            for (u, pole, du) in [(0.0, DVec3::Z, out), (1.0, -DVec3::Z, -out)] {
                let f = turned.frame(u, v);
                assert!(f.degenerate, "({u}, {v})");
                assert!((f.normal - pole).length() < 1e-12, "({u}, {v}): {f:?}");
                assert!((f.du - du).length() < 1e-12, "({u}, {v}): {f:?} vs {du}");
            }
        }
    }

    #[test]
    fn nearly_parallel_vectors_give_no_direction_at_any_scale() {
        // Two vectors 10⁻⁹ apart in angle are below the vanishing ratio: no normal from them,
        // whether they are long or short, as the regular and either limit formula meet them.
        let domain = Domain {
            u: (0.0, 1.0),
            v: (0.0, 1.0),
        };
        for scale in [1e-4, 1.0, 1e4] {
            let (a, b) = (scale * DVec3::X, scale * DVec3::new(1.0, 1e-9, 0.0));
            let regular = SurfaceDerivs {
                su: a,
                sv: b,
                ..SurfaceDerivs::default()
            };
            assert_eq!(Frame::from_derivs(&regular, 0.5, 0.5, &domain), None);
            let collapsed_v = SurfaceDerivs {
                sv: a,
                suv: b,
                ..SurfaceDerivs::default()
            };
            assert_eq!(Frame::from_derivs(&collapsed_v, 0.5, 0.0, &domain), None);
            let collapsed_u = SurfaceDerivs {
                su: a,
                suv: b,
                ..SurfaceDerivs::default()
            };
            assert_eq!(Frame::from_derivs(&collapsed_u, 0.0, 0.5, &domain), None);
            // 10⁻⁷ apart they do give one, across both.
            let c = scale * DVec3::new(1.0, 1e-7, 0.0);
            for d in [
                SurfaceDerivs {
                    su: a,
                    sv: c,
                    ..SurfaceDerivs::default()
                },
                SurfaceDerivs {
                    sv: a,
                    suv: c,
                    ..SurfaceDerivs::default()
                },
                SurfaceDerivs {
                    su: a,
                    suv: c,
                    ..SurfaceDerivs::default()
                },
            ] {
                let f = Frame::from_derivs(&d, 0.0, 0.0, &domain).unwrap();
                assert!(
                    (f.normal.abs() - DVec3::Z).length() < 1e-9,
                    "{scale}: {f:?}"
                );
            }
        }
    }
}
