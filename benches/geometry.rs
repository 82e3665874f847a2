//! Point + frame evaluations per second: glint against the `curvo` crate computing the same
//! quantities (point, unit normal, du, dv) on the same surfaces, at random (u, v) — one call per
//! point, and all points in one `frames` call — and over a 256 × 256 grid. Run with
//! `cargo bench --bench geometry`; the summary at the end prints the speed-ups measured side by
//! side in this run.

mod support;

use std::hint::black_box;

use criterion::{Criterion, Throughput};
use glam::DVec3;
use glint::geom::{shapes, GridEvaluator, NurbsSurface};
use nalgebra::{Point4, Vector3};
use rand::{rngs::StdRng, Rng, SeedableRng};

type CurvoSurface = curvo::prelude::NurbsSurface3D<f64>;

const RANDOM_POINTS: usize = 4096;
const GRID: usize = 256;

/// The same surface as a `curvo` surface (homogeneous net `control_points[i][j]`).
fn to_curvo(s: &NurbsSurface) -> CurvoSurface {
    let net = (0..s.count_u())
        .map(|i| {
            (0..s.count_v())
                .map(|j| {
                    let (p, w) = s.control_point(i, j);
                    Point4::new(p.x * w, p.y * w, p.z * w, w)
                })
                .collect()
        })
        .collect();
    CurvoSurface::new(
        s.knots_u().degree(),
        s.knots_v().degree(),
        s.knots_u().knots().to_vec(),
        s.knots_v().knots().to_vec(),
        net,
    )
}

/// A bicubic rational patch with 6 × 6 random control points and weights, clamped knots.
fn random_bicubic(rng: &mut StdRng) -> NurbsSurface {
    let points: Vec<Vec<DVec3>> = (0..6)
        .map(|i| {
            (0..6)
                .map(|j| DVec3::new(i as f64, j as f64, rng.random_range(-1.0..1.0)))
                .collect()
        })
        .collect();
    let weights: Vec<Vec<f64>> = (0..6)
        .map(|_| (0..6).map(|_| rng.random_range(0.5..2.0)).collect())
        .collect();
    let knots = vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.6, 1.0, 1.0, 1.0, 1.0];
    NurbsSurface::new(3, 3, knots.clone(), knots, &points, Some(&weights)).unwrap()
}

/// The frame from curvo's first rational derivatives `[[S, Sv], [Su, ..]]`.
fn curvo_frame(d: &[Vec<Vector3<f64>>]) -> [Vector3<f64>; 4] {
    let (su, sv) = (&d[1][0], &d[0][1]);
    let n = su.cross(sv).normalize();
    let du = su.normalize();
    [d[0][0], n, du, n.cross(&du)]
}

fn bench_surface(c: &mut Criterion, name: &str, surface: &NurbsSurface, uvs: &[(f64, f64)]) {
    let reference = to_curvo(surface);

    let mut group = c.benchmark_group(format!("random_uv/{name}"));
    group.throughput(Throughput::Elements(uvs.len() as u64));
    group.bench_function("glint", |b| {
        b.iter(|| {
            for &(u, v) in uvs {
                black_box(surface.frame(u, v));
            }
        })
    });
    let mut frames = vec![surface.frame(0.5, 0.5); uvs.len()];
    group.bench_function("glint_batch", |b| {
        b.iter(|| {
            surface.frames(uvs, &mut frames);
            black_box(&frames);
        })
    });
    group.bench_function("curvo", |b| {
        b.iter(|| {
            for &(u, v) in uvs {
                black_box(curvo_frame(&reference.rational_derivatives(u, v, 1)));
            }
        })
    });
    group.finish();

    let mut group = c.benchmark_group(format!("grid_256/{name}"));
    group.throughput(Throughput::Elements((GRID * GRID) as u64));
    group.bench_function("glint", |b| {
        b.iter(|| {
            let grid = GridEvaluator::uniform(surface, GRID, GRID);
            for i in 0..GRID {
                for frame in grid.row_frames(i) {
                    black_box(frame);
                }
            }
        })
    });
    group.bench_function("curvo", |b| {
        b.iter(|| {
            let ders = reference.regular_sample_rational_derivatives(GRID - 1, GRID - 1, 1);
            for row in &ders {
                for d in row {
                    black_box(curvo_frame(d));
                }
            }
        })
    });
    group.finish();
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    let mut rng = StdRng::seed_from_u64(5);
    // Random parameters off the poles, where curvo's plain normal is undefined.
    let uvs: Vec<(f64, f64)> = (0..RANDOM_POINTS)
        .map(|_| (rng.random(), rng.random_range(0.001..0.999)))
        .collect();
    let sphere = shapes::sphere(DVec3::ZERO, 1.0).unwrap();
    let bicubic = random_bicubic(&mut rng);
    bench_surface(&mut c, "sphere", &sphere, &uvs);
    bench_surface(&mut c, "bicubic", &bicubic, &uvs);
    c.final_summary();

    support::print_ratios(
        "curvo time / glint time for the same frames (higher = glint faster)",
        &[
            ("random_uv/sphere", "curvo", "glint"),
            ("random_uv/sphere", "curvo", "glint_batch"),
            ("random_uv/bicubic", "curvo", "glint"),
            ("random_uv/bicubic", "curvo", "glint_batch"),
            ("grid_256/sphere", "curvo", "glint"),
            ("grid_256/bicubic", "curvo", "glint"),
        ],
    );
}
