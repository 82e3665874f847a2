//! A point of the unit sphere as a highlight reads it, found analytically: its frame (east,
//! north, outward) and its patch parameters (u, v) on the exact NURBS sphere of
//! [`shapes::sphere`](crate::geom::shapes::sphere).

use std::f64::consts::{FRAC_PI_2, SQRT_2, TAU};

use glam::{DVec2, DVec3};

use super::closed_form_ops::AnalyticFrame;

/// A point of the unit sphere about the origin with its analytic frame and parameters.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpherePoint {
    /// `N = p/|p|`, `du = (−N.y, N.x, 0)/|…|` (east; −x at the poles), `dv = N × du` (north).
    pub frame: AnalyticFrame,
    /// The (u, v) of the NURBS sphere at the point ([`sphere_parameters`]).
    pub uv: DVec2,
}

impl SpherePoint {
    /// The sphere point in the direction of `p` (not zero).
    #[must_use]
    pub fn at(p: DVec3) -> Self {
        let n = p.normalize();
        let du = DVec3::new(-n.y, n.x, 0.0)
            .try_normalize()
            .unwrap_or(DVec3::NEG_X);
        Self {
            frame: AnalyticFrame {
                du,
                dv: n.cross(du),
                n,
            },
            uv: sphere_parameters(n),
        }
    }
}

/// Where along a rational quadratic quarter circle (control points at angles 0, 45° and 90°,
/// the middle one at distance √2 with weight `1/√2`) the point at angle φ ∈ [0, π/2] lies:
/// with `r = s/(1 − s)` the arc is at `tan φ = r(√2 + r)/(1 + √2 r)`, whose positive root is
/// `r = (sin φ − cos φ + 1)/(√2 cos φ)`, so `s = (sin φ − cos φ + 1)/(sin φ − cos φ + 1 + √2 cos φ)`.
#[must_use]
fn quarter_arc_parameter(phi: f64) -> f64 {
    let (sin, cos) = phi.clamp(0.0, FRAC_PI_2).sin_cos();
    let top = sin - cos + 1.0;
    top / (top + SQRT_2 * cos)
}

/// The parameter in `[0, 1]` of angle `angle ∈ [0, arcs · π/2]` along `arcs` quarter circles
/// of equal knot spans: `(k + s)/arcs` in the k-th quarter, s from [`quarter_arc_parameter`].
#[must_use]
fn arcs_parameter(angle: f64, arcs: u32) -> f64 {
    let k = (angle / FRAC_PI_2).floor().clamp(0.0, f64::from(arcs - 1));
    (k + quarter_arc_parameter(angle - k * FRAC_PI_2)) / f64::from(arcs)
}

/// The (u, v) of the unit sphere's NURBS patch at the unit normal `n`: u runs counter-clockwise
/// about +z from +x over four quarter circles, `λ = atan2(y, x)` in [0, 2π); v runs from the
/// south pole to the north over two, `χ = asin z + π/2`.
#[must_use]
pub fn sphere_parameters(n: DVec3) -> DVec2 {
    let longitude = n.y.atan2(n.x).rem_euclid(TAU);
    let from_south = n.z.clamp(-1.0, 1.0).asin() + FRAC_PI_2;
    DVec2::new(arcs_parameter(longitude, 4), arcs_parameter(from_south, 2))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::shapes;

    #[test]
    fn the_parameters_land_on_the_point_of_the_nurbs_sphere() {
        let sphere = shapes::sphere(DVec3::ZERO, 1.0).unwrap();
        for i in 0..40 {
            for j in 1..20 {
                let longitude = f64::from(i) * TAU / 40.0 + 0.013;
                let latitude = f64::from(j) * std::f64::consts::PI / 20.0 - FRAC_PI_2;
                let n = DVec3::new(
                    latitude.cos() * longitude.cos(),
                    latitude.cos() * longitude.sin(),
                    latitude.sin(),
                );
                let uv = sphere_parameters(n);
                let back = sphere.point(uv.x, uv.y);
                assert!((back - n).length() < 1e-12, "{n} → {uv} → {back}");
            }
        }
    }

    #[test]
    fn the_frame_is_east_north_outward() {
        let p = SpherePoint::at(DVec3::new(0.0, -2.0, 0.0));
        assert!((p.frame.n - DVec3::NEG_Y).length() < 1e-15);
        assert!((p.frame.du - DVec3::X).length() < 1e-15);
        assert!((p.frame.dv - DVec3::Z).length() < 1e-15);
        let pole = SpherePoint::at(DVec3::Z);
        assert_eq!(pole.frame.du, DVec3::NEG_X);
    }
}
