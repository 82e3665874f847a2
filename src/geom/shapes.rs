//! Exact shapes as NURBS surfaces, each on the parameter domain \[0, 1\]².
//!
//! Quadrics and the torus are built from the rational quadratic circle: nine control points on
//! the square around the unit circle, weights `1, √2/2, 1, …`, knots `0,0,0,¼,¼,½,½,¾,¾,1,1,1`.
//! Its points lie exactly on the circle, so every shape here is exact, not an approximation.

use std::f64::consts::FRAC_1_SQRT_2;

use glam::{DVec2, DVec3};

use super::surface::MAX_COORDINATE;
use super::{GeomError, NurbsSurface};

/// The full circle's knots (degree 2, nine control points).
const CIRCLE_KNOTS: [f64; 12] = [
    0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0,
];

/// The half circle's knots (degree 2, five control points).
const HALF_CIRCLE_KNOTS: [f64; 8] = [0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0];

/// The unit circle's nine control points, counter-clockwise from (1, 0), with their weights.
fn circle() -> [(DVec2, f64); 9] {
    let w = FRAC_1_SQRT_2;
    [
        (DVec2::new(1.0, 0.0), 1.0),
        (DVec2::new(1.0, 1.0), w),
        (DVec2::new(0.0, 1.0), 1.0),
        (DVec2::new(-1.0, 1.0), w),
        (DVec2::new(-1.0, 0.0), 1.0),
        (DVec2::new(-1.0, -1.0), w),
        (DVec2::new(0.0, -1.0), 1.0),
        (DVec2::new(1.0, -1.0), w),
        (DVec2::new(1.0, 0.0), 1.0),
    ]
}

/// A surface of revolution about +z: the profile's control points `(r, z)` with weights, swept
/// counter-clockwise along u. `P_ij = (x_i r_j, y_i r_j, z_j)`, `w_ij = w_i w_j`.
fn revolve(profile: &[(DVec2, f64)], profile_knots: &[f64]) -> Result<NurbsSurface, GeomError> {
    let ring = circle();
    let points: Vec<Vec<DVec3>> = ring
        .iter()
        .map(|(c, _)| {
            profile
                .iter()
                .map(|(rz, _)| DVec3::new(c.x * rz.x, c.y * rz.x, rz.y))
                .collect()
        })
        .collect();
    let weights: Vec<Vec<f64>> = ring
        .iter()
        .map(|(_, wi)| profile.iter().map(|(_, wj)| wi * wj).collect())
        .collect();
    NurbsSurface::new(
        2,
        profile_knots.len() - profile.len() - 1,
        CIRCLE_KNOTS.to_vec(),
        profile_knots.to_vec(),
        &points,
        Some(&weights),
    )
}

fn check_positive(name: &'static str, value: f64) -> Result<(), GeomError> {
    if value > 0.0 && value <= MAX_COORDINATE {
        Ok(())
    } else {
        Err(GeomError::NotPositive { name, value })
    }
}

/// The sphere of `radius` about `center`: u runs east (counter-clockwise about +z, from +x),
/// v from the south pole to the north pole, so `(du, dv, N) = (east, north, outward)`.
/// Its v = 0 and v = 1 rows collapse to the poles.
pub fn sphere(center: DVec3, radius: f64) -> Result<NurbsSurface, GeomError> {
    check_positive("radius", radius)?;
    let w = FRAC_1_SQRT_2;
    let meridian = [
        (DVec2::new(0.0, -1.0), 1.0),
        (DVec2::new(1.0, -1.0), w),
        (DVec2::new(1.0, 0.0), 1.0),
        (DVec2::new(1.0, 1.0), w),
        (DVec2::new(0.0, 1.0), 1.0),
    ];
    Ok(revolve(&meridian, &HALF_CIRCLE_KNOTS)?.map_points(|p| center + radius * p))
}

/// The open cylinder of `radius` about +z from z = 0 to z = `height`: u around (east), v up,
/// normals outward.
pub fn cylinder(radius: f64, height: f64) -> Result<NurbsSurface, GeomError> {
    check_positive("radius", radius)?;
    check_positive("height", height)?;
    let side = [
        (DVec2::new(radius, 0.0), 1.0),
        (DVec2::new(radius, height), 1.0),
    ];
    revolve(&side, &[0.0, 0.0, 1.0, 1.0])
}

/// The torus about +z with tube centre radius `major` and tube radius `minor`
/// (`0 < minor < major`): u around the z axis, v around the tube starting at the outer equator
/// and turning up, normals outward.
pub fn torus(major: f64, minor: f64) -> Result<NurbsSurface, GeomError> {
    check_positive("major_radius", major)?;
    check_positive("minor_radius", minor)?;
    if minor >= major {
        return Err(GeomError::TorusTube { major, minor });
    }
    // The outer equator lies at major + minor.
    check_positive("major_radius + minor_radius", major + minor)?;
    let tube: Vec<(DVec2, f64)> = circle()
        .iter()
        .map(|(c, w)| (DVec2::new(major + minor * c.x, minor * c.y), *w))
        .collect();
    revolve(&tube, &CIRCLE_KNOTS)
}

/// The `width × height` rectangle in the z = 0 plane centred on the origin, u along +x, v along
/// +y, normal +z.
pub fn plane(width: f64, height: f64) -> Result<NurbsSurface, GeomError> {
    check_positive("width", width)?;
    check_positive("height", height)?;
    let (x, y) = (0.5 * width, 0.5 * height);
    let points = vec![
        vec![DVec3::new(-x, -y, 0.0), DVec3::new(-x, y, 0.0)],
        vec![DVec3::new(x, -y, 0.0), DVec3::new(x, y, 0.0)],
    ];
    let knots = vec![0.0, 0.0, 1.0, 1.0];
    NurbsSurface::new(1, 1, knots.clone(), knots, &points, None)
}

/// The Bezier patch with control net `points[i][j]` (`degree_u + 1` rows along u of
/// `degree_v + 1` points along v).
pub fn bezier(
    degree_u: usize,
    degree_v: usize,
    points: &[Vec<DVec3>],
) -> Result<NurbsSurface, GeomError> {
    let clamped = |p: usize| -> Vec<f64> {
        std::iter::repeat_n(0.0, p + 1)
            .chain(std::iter::repeat_n(1.0, p + 1))
            .collect()
    };
    NurbsSurface::new(
        degree_u,
        degree_v,
        clamped(degree_u),
        clamped(degree_v),
        points,
        None,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cylinder_points_lie_on_it_with_outward_normals() {
        let s = cylinder(2.0, 3.0).unwrap();
        for i in 0..=20 {
            for j in 0..=4 {
                let (u, v) = (i as f64 / 20.0, j as f64 / 4.0);
                let f = s.frame(u, v);
                let radial = DVec3::new(f.point.x, f.point.y, 0.0);
                assert!((radial.length() - 2.0).abs() < 1e-12);
                assert!((f.point.z - 3.0 * v).abs() < 1e-12);
                assert!((f.normal - radial / 2.0).length() < 1e-12);
                assert!((f.dv - DVec3::Z).length() < 1e-12);
            }
        }
    }

    #[test]
    fn torus_points_lie_on_it_with_outward_normals() {
        let (big, small) = (3.0, 1.0);
        let s = torus(big, small).unwrap();
        for i in 0..=16 {
            for j in 0..=16 {
                let f = s.frame(i as f64 / 16.0, j as f64 / 16.0);
                let p = f.point;
                let ring = DVec3::new(p.x, p.y, 0.0).normalize() * big;
                assert!(((p - ring).length() - small).abs() < 1e-12);
                assert!((f.normal - (p - ring) / small).length() < 1e-12);
            }
        }
    }

    #[test]
    fn plane_faces_up_and_bezier_reproduces_its_corners() {
        let f = plane(2.0, 4.0).unwrap().frame(1.0, 1.0);
        assert!((f.point - DVec3::new(1.0, 2.0, 0.0)).length() < 1e-15);
        assert!((f.normal - DVec3::Z).length() < 1e-15);
        let net: Vec<Vec<DVec3>> = (0..3)
            .map(|i| {
                (0..4)
                    .map(|j| DVec3::new(i as f64, j as f64, (i * j) as f64))
                    .collect()
            })
            .collect();
        let b = bezier(2, 3, &net).unwrap();
        assert!((b.point(1.0, 1.0) - net[2][3]).length() < 1e-14);
        assert!((b.point(0.0, 1.0) - net[0][3]).length() < 1e-14);
    }

    #[test]
    fn shapes_reject_bad_sizes() {
        assert!(sphere(DVec3::ZERO, 0.0).is_err());
        assert!(sphere(DVec3::ZERO, f64::NAN).is_err());
        assert!(torus(1.0, 2.0).is_err());
        assert!(cylinder(1.0, -1.0).is_err());
    }

    #[test]
    fn a_torus_reaching_beyond_the_largest_coordinate_is_refused_not_a_panic() {
        assert!(matches!(
            torus(1e6, 0.35),
            Err(GeomError::NotPositive {
                name: "major_radius + minor_radius",
                ..
            })
        ));
        assert!(torus(999_999.0, 0.5).is_ok());
    }
}
