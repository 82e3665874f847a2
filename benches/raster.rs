//! Rasterizer throughput: a 1280 × 720 frame of about 100k small triangles — a bumpy ellipsoid
//! tessellated as a 224 × 224 grid, in perspective, covering most of the screen, both its front
//! and back halves drawn (no back-face culling) — with 1 and with 2 threads in the same run.
//!
//! Two ways of calling it: `frame_loop` renders on a thread pool built once, reusing a
//! `Rasterizer` and its buffer from frame to frame (how a renderer calls it); `one_shot` calls
//! `rasterize` with `RasterOptions::threads`, which builds the pool and allocates the buffer and
//! working memory in every call.
//!
//! Run with `cargo bench --bench raster`: criterion reports the time per frame and the triangle
//! rate (`thrpt`, Melem/s = million triangles per second); the summary at the end prints the
//! medians and the 2-thread speed-ups.

mod support;

use std::f32::consts::{PI, TAU};
use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, Throughput};
use glam::{Mat4, Vec3, Vec4};
use glint::render::raster::{rasterize, RasterOptions, Rasterizer, Viewport, VisibilityBuffer};

const VIEWPORT: Viewport = Viewport {
    width: 1280,
    height: 720,
};
const GRID: u32 = 224;
const FRAME_LOOP: &str = "raster_1280x720/frame_loop";
const ONE_SHOT: &str = "raster_1280x720/one_shot";

/// Clip-space positions and indexed triangles of the ellipsoid mesh.
fn mesh() -> (Vec<Vec4>, Vec<[u32; 3]>) {
    let aspect = VIEWPORT.width as f32 / VIEWPORT.height as f32;
    let view_projection = Mat4::perspective_rh(PI / 3.0, aspect, 0.1, 20.0)
        * Mat4::look_at_rh(Vec3::new(0.0, 0.3, 2.1), Vec3::ZERO, Vec3::Y);
    let mut positions = Vec::new();
    for j in 0..=GRID {
        let v = PI * j as f32 / GRID as f32;
        for i in 0..=GRID {
            let u = TAU * i as f32 / GRID as f32;
            let bump = 1.0 + 0.04 * (7.0 * u).sin() * (5.0 * v).sin();
            let p = Vec3::new(1.9 * v.sin() * u.cos(), v.cos(), v.sin() * u.sin()) * bump;
            positions.push(view_projection * p.extend(1.0));
        }
    }
    let index = |i: u32, j: u32| j * (GRID + 1) + i;
    let triangles = (0..GRID)
        .flat_map(|j| (0..GRID).map(move |i| (i, j)))
        .flat_map(|(i, j)| {
            let (a, b) = (index(i, j), index(i + 1, j));
            let (c, d) = (index(i + 1, j + 1), index(i, j + 1));
            [[a, b, c], [a, c, d]]
        })
        .collect();
    (positions, triangles)
}

fn main() {
    let mut c = Criterion::default()
        .sample_size(30)
        .measurement_time(Duration::from_secs(6))
        .configure_from_args();
    let (positions, triangles) = mesh();

    let (_, stats) = rasterize(VIEWPORT, &positions, &triangles, &RasterOptions::default());
    println!(
        "{} triangles: {} culled, {} rasterized, {} pixels covered ({:.0}% of the frame), \
         overdraw {:.2}",
        stats.triangles_in,
        stats.triangles_culled,
        stats.triangles_rasterized,
        stats.pixels_covered,
        100.0 * stats.pixels_covered as f64 / f64::from(VIEWPORT.width * VIEWPORT.height),
        stats.fragments as f64 / stats.pixels_covered as f64
    );

    let mut group = c.benchmark_group(FRAME_LOOP);
    group.throughput(Throughput::Elements(triangles.len() as u64));
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a thread pool");
        let mut rasterizer = Rasterizer::new();
        let mut buffer = VisibilityBuffer::default();
        let options = RasterOptions::default();
        group.bench_function(format!("threads_{threads}"), |b| {
            pool.install(|| {
                b.iter(|| {
                    black_box(rasterizer.rasterize_into(
                        VIEWPORT,
                        &positions,
                        &triangles,
                        &options,
                        &mut buffer,
                    ))
                })
            })
        });
    }
    group.finish();

    let mut group = c.benchmark_group(ONE_SHOT);
    group.throughput(Throughput::Elements(triangles.len() as u64));
    for threads in [1, 2] {
        let options = RasterOptions {
            threads,
            ..RasterOptions::default()
        };
        group.bench_function(format!("threads_{threads}"), |b| {
            b.iter(|| black_box(rasterize(VIEWPORT, &positions, &triangles, &options)))
        });
    }
    group.finish();
    c.final_summary();

    support::print_ratios(
        "1-thread time / 2-thread time for the same frame (the speed-up)",
        &[
            (FRAME_LOOP, "threads_1", "threads_2"),
            (ONE_SHOT, "threads_1", "threads_2"),
        ],
    );
}
