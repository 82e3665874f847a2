//! Surface derivatives against central finite differences, and points and first derivatives
//! against an independent NURBS implementation (the `curvo` crate), on random rational surfaces.

use glam::DVec3;
use glint::geom::{NurbsSurface, SurfaceDerivs};
use nalgebra::Point4;
use rand::{rngs::StdRng, Rng, SeedableRng};

/// A random clamped knot vector for `count` control points of `degree`, with some interior knots
/// repeated (up to `degree` times). Distinct knots lie at least 0.05 apart, so that finite
/// differences with a small step resolve every span.
fn random_knots(rng: &mut StdRng, degree: usize, count: usize) -> Vec<f64> {
    let interior = count - degree - 1;
    let mut inner: Vec<f64> = Vec::new();
    while inner.len() < interior {
        let k = 0.05 * f64::from(rng.random_range(1..20));
        if inner.contains(&k) {
            continue;
        }
        let repeat = rng.random_range(1..=degree).min(interior - inner.len());
        inner.extend(std::iter::repeat_n(k, repeat));
    }
    inner.sort_by(f64::total_cmp);
    let mut knots = vec![0.0; degree + 1];
    knots.extend(inner);
    knots.extend(std::iter::repeat_n(1.0, degree + 1));
    knots
}

struct RandomSurface {
    surface: NurbsSurface,
    degrees: (usize, usize),
    knots: (Vec<f64>, Vec<f64>),
    points: Vec<Vec<DVec3>>,
    weights: Vec<Vec<f64>>,
}

fn random_surface(rng: &mut StdRng, degree_u: usize, degree_v: usize) -> RandomSurface {
    let count_u = degree_u + 1 + rng.random_range(0..4);
    let count_v = degree_v + 1 + rng.random_range(0..4);
    let knots_u = random_knots(rng, degree_u, count_u);
    let knots_v = random_knots(rng, degree_v, count_v);
    let points: Vec<Vec<DVec3>> = (0..count_u)
        .map(|i| {
            (0..count_v)
                .map(|j| {
                    DVec3::new(i as f64, j as f64, 0.0)
                        + DVec3::new(
                            rng.random_range(-0.4..0.4),
                            rng.random_range(-0.4..0.4),
                            rng.random_range(-1.0..1.0),
                        )
                })
                .collect()
        })
        .collect();
    let weights: Vec<Vec<f64>> = (0..count_u)
        .map(|_| (0..count_v).map(|_| rng.random_range(0.3..3.0)).collect())
        .collect();
    let surface = NurbsSurface::new(
        degree_u,
        degree_v,
        knots_u.clone(),
        knots_v.clone(),
        &points,
        Some(&weights),
    )
    .unwrap();
    RandomSurface {
        surface,
        degrees: (degree_u, degree_v),
        knots: (knots_u, knots_v),
        points,
        weights,
    }
}

/// A random parameter at least `margin` away from every knot, so that the surface is smooth
/// around it.
fn random_smooth_parameter(rng: &mut StdRng, knots: &[f64], margin: f64) -> f64 {
    loop {
        let t: f64 = rng.random_range(margin..1.0 - margin);
        if knots.iter().all(|k| (t - k).abs() > margin) {
            return t;
        }
    }
}

fn close(a: DVec3, b: DVec3, tolerance: f64, scale: f64) -> bool {
    (a - b).length() <= tolerance * scale.max(1.0)
}

#[test]
fn derivatives_match_central_differences_for_degrees_1_to_5() {
    let mut rng = StdRng::seed_from_u64(11);
    let h = 1e-5;
    let mut checked = 0;
    for degree_u in 1..=5 {
        for degree_v in 1..=5 {
            for _ in 0..4 {
                let r = random_surface(&mut rng, degree_u, degree_v);
                let s = &r.surface;
                for _ in 0..20 {
                    let u = random_smooth_parameter(&mut rng, &r.knots.0, 3.0 * h);
                    let v = random_smooth_parameter(&mut rng, &r.knots.1, 3.0 * h);
                    let d = s.derivs(u, v, 2);
                    let at = |du: f64, dv: f64| s.derivs(u + du, v + dv, 1);
                    let diff =
                        |a: SurfaceDerivs, b: SurfaceDerivs, f: fn(&SurfaceDerivs) -> DVec3| {
                            (f(&a) - f(&b)) / (2.0 * h)
                        };
                    let (up, um, vp, vm) = (at(h, 0.0), at(-h, 0.0), at(0.0, h), at(0.0, -h));
                    let point = |d: &SurfaceDerivs| d.point;
                    let su = |d: &SurfaceDerivs| d.su;
                    let sv = |d: &SurfaceDerivs| d.sv;
                    let scale = d.su.length() + d.sv.length();
                    let scale2 = d.suu.length() + d.suv.length() + d.svv.length();
                    let what = format!("degrees ({degree_u}, {degree_v}) at ({u}, {v})");
                    assert!(close(diff(up, um, point), d.su, 1e-6, scale), "Su, {what}");
                    assert!(close(diff(vp, vm, point), d.sv, 1e-6, scale), "Sv, {what}");
                    assert!(close(diff(up, um, su), d.suu, 1e-5, scale2), "Suu, {what}");
                    assert!(close(diff(vp, vm, su), d.suv, 1e-5, scale2), "Suv, {what}");
                    assert!(close(diff(up, um, sv), d.suv, 1e-5, scale2), "Svu, {what}");
                    assert!(close(diff(vp, vm, sv), d.svv, 1e-5, scale2), "Svv, {what}");
                    checked += 1;
                }
            }
        }
    }
    assert_eq!(checked, 25 * 4 * 20);
}

/// The same surface as a `curvo` surface: its net is `control_points[i][j]` in homogeneous
/// coordinates `(w x, w y, w z, w)`.
fn to_curvo(r: &RandomSurface) -> curvo::prelude::NurbsSurface3D<f64> {
    let net = r
        .points
        .iter()
        .zip(&r.weights)
        .map(|(row, weights)| {
            row.iter()
                .zip(weights)
                .map(|(p, &w)| Point4::new(p.x * w, p.y * w, p.z * w, w))
                .collect()
        })
        .collect();
    curvo::prelude::NurbsSurface3D::new(
        r.degrees.0,
        r.degrees.1,
        r.knots.0.clone(),
        r.knots.1.clone(),
        net,
    )
}

#[test]
fn points_and_first_derivatives_agree_with_curvo() {
    let mut rng = StdRng::seed_from_u64(12);
    for degree_u in 1..=5 {
        for degree_v in 1..=5 {
            for _ in 0..4 {
                let r = random_surface(&mut rng, degree_u, degree_v);
                let reference = to_curvo(&r);
                // Random parameters, and every knot (0 and 1 among them) against every knot and
                // against random values: span lookup is decided at the knots.
                let knots = |k: &[f64]| {
                    let mut k = k.to_vec();
                    k.dedup();
                    k
                };
                let (knots_u, knots_v) = (knots(&r.knots.0), knots(&r.knots.1));
                let mut params: Vec<(f64, f64)> =
                    (0..25).map(|_| (rng.random(), rng.random())).collect();
                for &u in &knots_u {
                    params.extend(knots_v.iter().map(|&v| (u, v)));
                    params.push((u, rng.random()));
                }
                params.extend(knots_v.iter().map(|&v| (rng.random(), v)));
                assert!(params.contains(&(1.0, 1.0)) && params.contains(&(0.0, 0.0)));
                for (u, v) in params {
                    let d = r.surface.derivs(u, v, 1);
                    let ders = reference.rational_derivatives(u, v, 1);
                    let vec = |x: &nalgebra::Vector3<f64>| DVec3::new(x.x, x.y, x.z);
                    let what = format!("degrees ({degree_u}, {degree_v}) at ({u}, {v})");
                    let scale = d.point.length() + d.su.length() + d.sv.length();
                    assert!(
                        close(d.point, vec(&ders[0][0]), 1e-12, scale),
                        "point, {what}"
                    );
                    assert!(close(d.su, vec(&ders[1][0]), 1e-10, scale), "Su, {what}");
                    assert!(close(d.sv, vec(&ders[0][1]), 1e-10, scale), "Sv, {what}");
                }
            }
        }
    }
}
