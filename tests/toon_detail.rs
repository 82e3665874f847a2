//! The X-Toon detail maps at their boundaries, against the formulas of Barla, Thollot &
//! Markosian 2006 evaluated in f64, and their validation: out-of-range parameters are errors,
//! and no input gives NaN.

use glam::Vec3;
use glint::toon::{DetailMap, ViewDetail, XToonError};

const EYE: Vec3 = Vec3::new(1.0, -2.0, 0.5);

/// The focal axis: the unit direction the eye looks along.
fn forward() -> Vec3 {
    Vec3::new(0.3, 1.0, -0.2).normalize()
}

fn view(map: DetailMap, invert: bool) -> ViewDetail {
    map.prepare(invert).unwrap().in_view(EYE, forward())
}

/// D at the point `z` along the focal axis (depth maps), facing the eye.
fn at(v: &ViewDetail, z: f32) -> f32 {
    let point = EYE + z * forward();
    let to_eye = -forward();
    v.value(point, to_eye, to_eye, to_eye, to_eye)
}

/// The LOA formula of X-Toon (Barla et al. 2006) `1 − log(z / z_min) / log(r)`, clamped to
/// [0, 1], in f64.
fn depth_reference(z: f64, z_min: f64, r: f64) -> f64 {
    (1.0 - (z / z_min).ln() / r.ln()).clamp(0.0, 1.0)
}

#[test]
fn depth_is_one_at_z_min_zero_at_r_z_min_and_clamped_beyond() {
    for (z_min, r) in [(4.0_f32, 3.0_f32), (0.5, 10.0), (100.0, 1.5)] {
        let v = view(DetailMap::Depth { z_min, r }, false);
        assert_eq!(at(&v, z_min), 1.0);
        assert!(at(&v, r * z_min).abs() < 1e-6, "{}", at(&v, r * z_min));
        assert_eq!(at(&v, 0.5 * z_min), 1.0);
        assert_eq!(at(&v, 2.0 * r * z_min), 0.0);
        for k in 1..20 {
            let z = z_min * r.powf(k as f32 / 20.0);
            let want = depth_reference(f64::from(z), f64::from(z_min), f64::from(r));
            assert!((f64::from(at(&v, z)) - want).abs() < 1e-5, "z = {z}");
        }
        // A point beside the axis has the depth of its projection on it.
        let side = forward().any_orthonormal_vector();
        let point = EYE + 1.5 * z_min * forward() + 3.0 * side;
        assert!(
            (v.value(point, Vec3::Z, Vec3::Z, Vec3::Z, Vec3::Z) - at(&v, 1.5 * z_min)).abs() < 1e-6
        );
    }
}

#[test]
fn depth_behind_or_at_the_eye_is_full_detail() {
    let v = view(DetailMap::Depth { z_min: 2.0, r: 4.0 }, false);
    assert_eq!(at(&v, 0.0), 1.0);
    assert_eq!(at(&v, -5.0), 1.0);
}

/// The depth-of-field formula of X-Toon (Barla et al. 2006) in f64 (its assumption
/// `z−_max > 0` holds in the cases it is used for here), clamped to [0, 1].
fn focus_reference(z: f64, z_c: f64, z_min: f64, r: f64) -> f64 {
    let d = if z < z_c {
        let (near_min, near_max) = (z_c - z_min, z_c - r * z_min);
        1.0 - (z / near_min).ln() / (near_max / near_min).ln()
    } else {
        let (far_min, far_max) = (z_c + z_min, z_c + r * z_min);
        (z / far_max).ln() / (far_min / far_max).ln()
    };
    d.clamp(0.0, 1.0)
}

#[test]
fn depth_of_field_is_one_in_the_focus_band_and_continuous_at_its_edges() {
    let (z_c, z_min, r) = (10.0_f32, 1.0_f32, 3.0_f32);
    // The focus point off the axis: the distance to the eye is what counts.
    let side = forward().any_orthonormal_vector();
    let focus = EYE + 6.0 * forward() + 8.0 * side; // 10 from the eye
    let v = view(
        DetailMap::DepthOfField {
            focus: focus.to_array(),
            z_min,
            r,
        },
        false,
    );
    for z in [z_c - z_min, z_c - 0.5, z_c, z_c + 0.3, z_c + z_min] {
        assert_eq!(at(&v, z), 1.0, "z = {z}");
    }
    // Continuous at both band edges, 0 at z_c ± r z_min and beyond.
    for edge in [z_c - z_min, z_c + z_min] {
        for delta in [1e-3_f32, 1e-2] {
            assert!(1.0 - at(&v, edge - delta) < 0.01 && 1.0 - at(&v, edge + delta) < 0.01);
        }
    }
    assert!(at(&v, z_c - r * z_min).abs() < 1e-5);
    assert!(at(&v, z_c + r * z_min).abs() < 1e-5);
    assert_eq!(at(&v, 0.5 * (z_c - r * z_min)), 0.0);
    assert_eq!(at(&v, 2.0 * (z_c + r * z_min)), 0.0);
    for k in 0..=40 {
        let z = 6.0 + 0.2 * k as f32;
        let want = focus_reference(f64::from(z), 10.0, 1.0, 3.0);
        assert!((f64::from(at(&v, z)) - want).abs() < 1e-5, "z = {z}");
    }
}

#[test]
fn near_silhouette_is_one_facing_the_camera_and_zero_at_the_silhouette() {
    let v = view(DetailMap::NearSilhouette { r: 2.5 }, false);
    let to_eye = Vec3::new(0.0, 0.6, 0.8);
    let d = |n: Vec3| v.value(Vec3::ZERO, to_eye, Vec3::X, n, Vec3::X);
    assert_eq!(d(to_eye), 1.0);
    assert_eq!(d(-to_eye), 1.0);
    assert_eq!(d(Vec3::X), 0.0);
    let n = Vec3::new(0.0, 0.8, 0.6);
    let want = (0.6_f64 * 0.8 + 0.8 * 0.6).powf(2.5);
    assert!((f64::from(d(n)) - want).abs() < 1e-6);
    // r = 0 keeps full detail everywhere, even at the silhouette.
    let flat = view(DetailMap::NearSilhouette { r: 0.0 }, false);
    assert_eq!(
        flat.value(Vec3::ZERO, to_eye, Vec3::X, Vec3::X, Vec3::X),
        1.0
    );
}

#[test]
fn highlight_is_one_along_the_reflected_light_and_follows_phong() {
    let v = view(DetailMap::Highlight { s: 8.0 }, false);
    let n = Vec3::Z;
    let light = Vec3::new(0.6, 0.0, 0.8);
    let mirror = Vec3::new(-0.6, 0.0, 0.8);
    assert!((v.value(Vec3::ZERO, mirror, light, Vec3::Y, n) - 1.0).abs() < 1e-6);
    let to_eye = Vec3::new(0.0, 0.6, 0.8);
    let want = (0.8_f64 * 0.8).powi(8);
    assert!((f64::from(v.value(Vec3::ZERO, to_eye, light, Vec3::Y, n)) - want).abs() < 1e-6);
    // The highlight map reflects about the normal it is given, not the near-silhouette one.
    assert!(v.value(Vec3::ZERO, mirror, light, n, Vec3::Y) < 0.01);
}

#[test]
fn inversion_gives_one_minus_d() {
    let map = DetailMap::Depth { z_min: 2.0, r: 4.0 };
    let (plain, inverted) = (view(map.clone(), false), view(map, true));
    for z in [0.0, 2.0, 3.0, 5.0, 8.0, 100.0] {
        assert_eq!(at(&inverted, z), 1.0 - at(&plain, z));
    }
}

#[test]
fn out_of_range_parameters_are_errors_that_name_them() {
    let cases: [(DetailMap, &str); 8] = [
        (
            DetailMap::Depth { z_min: 0.0, r: 2.0 },
            "depth z_min is 0, outside the allowed range (0, inf)",
        ),
        (
            DetailMap::Depth {
                z_min: -1.0,
                r: 2.0,
            },
            "depth z_min is -1",
        ),
        (
            DetailMap::Depth { z_min: 1.0, r: 1.0 },
            "depth r is 1, outside the allowed range (1, inf)",
        ),
        (
            DetailMap::Depth {
                z_min: 1.0,
                r: f32::NAN,
            },
            "depth r is NaN, but it must be a finite number",
        ),
        (
            DetailMap::DepthOfField {
                focus: [0.0, f32::INFINITY, 0.0],
                z_min: 1.0,
                r: 2.0,
            },
            "depth of field focus coordinate is inf",
        ),
        (
            DetailMap::DepthOfField {
                focus: [0.0; 3],
                z_min: 1.0,
                r: 0.5,
            },
            "depth of field r is 0.5",
        ),
        (
            DetailMap::NearSilhouette { r: -0.5 },
            "near-silhouette r is -0.5, outside the allowed range [0, inf)",
        ),
        (
            DetailMap::Highlight { s: 0.9 },
            "highlight s is 0.9, outside the allowed range [1, inf)",
        ),
    ];
    for (map, message) in cases {
        let e = map.prepare(false).unwrap_err();
        assert!(matches!(e, XToonError::Param(_)));
        assert!(e.to_string().starts_with(message), "{e}");
    }
}

#[test]
fn extreme_parameters_and_points_never_give_nan() {
    let extremes = [f32::MIN_POSITIVE, 1e-30, 1e-3, 1.0, 1e3, 1e30, f32::MAX];
    let above_one = [1.0 + f32::EPSILON, 1.001, 2.0, 1e6, f32::MAX];
    let points = [
        EYE,
        EYE + forward() * 1e-30,
        EYE - forward(),
        EYE + forward() * 1e30,
        Vec3::splat(1e30),
        Vec3::ZERO,
    ];
    let vectors = [Vec3::Z, Vec3::X, -Vec3::Z, Vec3::ZERO];
    let mut maps = Vec::new();
    for &a in &extremes {
        maps.push(DetailMap::NearSilhouette { r: a });
        maps.push(DetailMap::Highlight { s: a.max(1.0) });
        for &r in &above_one {
            maps.push(DetailMap::Depth { z_min: a, r });
            maps.push(DetailMap::DepthOfField {
                focus: (EYE + forward()).to_array(),
                z_min: a,
                r,
            });
            maps.push(DetailMap::DepthOfField {
                focus: [1e30, 0.0, 0.0],
                z_min: a,
                r,
            });
        }
    }
    for map in maps {
        for invert in [false, true] {
            let v = view(map.clone(), invert);
            for &p in &points {
                for &a in &vectors {
                    for &b in &vectors {
                        let d = v.value(p, a, b, a, b);
                        assert!((0.0..=1.0).contains(&d), "{map:?} at {p}: {d}");
                    }
                }
            }
        }
    }
}
