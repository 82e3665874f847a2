//! The exact NURBS sphere against the analytic sphere: points, normals and the
//! (east, north, outward) frame, including the seams and the poles.

use glam::DVec3;
use glint::geom::shapes;
use rand::{rngs::StdRng, Rng, SeedableRng};

const CENTER: DVec3 = DVec3::new(0.5, -1.25, 2.0);
const RADIUS: f64 = 2.5;

/// Parameters to check: random ones plus every seam and knot line, and both poles.
fn samples() -> Vec<(f64, f64)> {
    let mut rng = StdRng::seed_from_u64(7);
    let mut uv: Vec<(f64, f64)> = (0..2000).map(|_| (rng.random(), rng.random())).collect();
    let lines = [0.0, 0.125, 0.25, 0.5, 0.75, 1.0];
    for &a in &lines {
        for &b in &[0.0, 0.1, 0.25, 0.5, 0.75, 0.9, 1.0] {
            uv.push((a, b));
            uv.push((b, a));
        }
    }
    uv
}

/// The east direction of the meridian u, from its point on the equator.
fn meridian_east(sphere: &glint::geom::NurbsSurface, u: f64) -> DVec3 {
    let r = sphere.point(u, 0.5) - CENTER;
    DVec3::new(-r.y, r.x, 0.0).normalize()
}

#[test]
fn points_normals_and_tangents_match_the_analytic_sphere() {
    let sphere = shapes::sphere(CENTER, RADIUS).unwrap();
    let mut checked = 0;
    for (u, v) in samples() {
        let f = sphere.frame(u, v);
        let r = f.point - CENTER;
        assert!(
            (r.length() - RADIUS).abs() <= 1e-12 * RADIUS,
            "|p| at ({u}, {v})"
        );
        let outward = r / RADIUS;
        assert!((f.normal - outward).length() <= 1e-12, "N at ({u}, {v})");
        if v == 0.0 || v == 1.0 {
            continue; // east and north are undefined at the poles: see the pole test
        }
        // Each u is a meridian of constant longitude; take its east direction where the
        // meridian is far from the poles, so that the reference is exact near them too.
        let east = meridian_east(&sphere, u);
        let north = outward.cross(east);
        assert!((f.du - east).length() <= 1e-12, "du at ({u}, {v}): {f:?}");
        assert!((f.dv - north).length() <= 1e-12, "dv at ({u}, {v}): {f:?}");
        assert!(!f.degenerate);
        checked += 1;
    }
    assert!(checked >= 1000);
}

#[test]
fn poles_have_finite_limit_frames_continuous_with_the_inside() {
    let sphere = shapes::sphere(CENTER, RADIUS).unwrap();
    for i in 0..=40 {
        let u = i as f64 / 40.0;
        let east = meridian_east(&sphere, u);
        for (v, inside, z) in [(0.0, 1e-6, -1.0), (1.0, 1.0 - 1e-6, 1.0)] {
            let f = sphere.frame(u, v);
            assert!(f.degenerate, "pole at u = {u}");
            assert!(f.normal.is_finite() && f.du.is_finite() && f.dv.is_finite());
            assert!((f.point - (CENTER + z * RADIUS * DVec3::Z)).length() < 1e-12);
            assert!((f.normal - z * DVec3::Z).length() < 1e-12, "{f:?}");
            assert!((f.du - east).length() < 1e-9, "du at pole, u = {u}: {f:?}");
            let near = sphere.frame(u, inside);
            assert!(!near.degenerate);
            // Within the angle the sphere turns over 1e-6 of the meridian (π·1e-6 rad).
            assert!((near.normal - f.normal).length() < 4e-6);
            assert!((near.du - f.du).length() < 1e-9);
            assert!((near.dv - f.dv).length() < 4e-6);
        }
    }
}
