//! Which pixels a triangle covers: the top-left fill rule on fans and grids that tile a region
//! (every pixel centre inside covered exactly once, none outside), and degenerate input —
//! zero-area, collinear, NaN and infinite positions, vertices on pixel centres, huge triangles.
//!
//! Positions are given in pixels (x right, y down) on an orthographic camera (w = 1) with power
//! of two viewports, so a pixel position that is a multiple of 1/256 survives the trip through
//! clip space exactly and sits on the rasterizer's sub-pixel grid.

use glam::{DVec2, Vec4};
use glint::render::raster::{rasterize, RasterOptions, RasterStats, Viewport, VisibilityBuffer};
use proptest::prelude::*;
use rand::{rngs::StdRng, Rng, SeedableRng};

const SIZE: u32 = 64;
const VIEWPORT: Viewport = Viewport {
    width: SIZE,
    height: SIZE,
};

/// The clip-space vertex at pixel position `(x, y)` of a `size × size` viewport, depth 0.5.
fn at_pixel(p: DVec2, size: u32) -> Vec4 {
    let s = f64::from(size);
    Vec4::new(
        (2.0 * p.x / s - 1.0) as f32,
        (1.0 - 2.0 * p.y / s) as f32,
        0.5,
        1.0,
    )
}

fn render(size: u32, points: &[DVec2], triangles: &[[u32; 3]]) -> (VisibilityBuffer, RasterStats) {
    let positions: Vec<Vec4> = points.iter().map(|&p| at_pixel(p, size)).collect();
    let viewport = Viewport {
        width: size,
        height: size,
    };
    rasterize(viewport, &positions, triangles, &RasterOptions::default())
}

/// How many of the triangles cover each pixel, each rasterized alone.
fn coverage_count(size: u32, points: &[DVec2], triangles: &[[u32; 3]]) -> Vec<u32> {
    let mut count = vec![0; (size * size) as usize];
    for triangle in triangles {
        let (buffer, _) = render(size, points, &[*triangle]);
        for (c, &t) in count.iter_mut().zip(&buffer.triangle) {
            *c += u32::from(t != u32::MAX);
        }
    }
    count
}

/// The pixel centre of pixel index `i` in a `size`-wide image.
fn centre(i: usize, size: u32) -> DVec2 {
    let size = size as usize;
    DVec2::new((i % size) as f64 + 0.5, (i / size) as f64 + 0.5)
}

/// Rounds to the 1/256-pixel grid.
fn on_grid(p: DVec2) -> DVec2 {
    (p * 256.0).round() / 256.0
}

/// A fan of `n` triangles around `centre` to a rim at radius `radius`, alternately wound.
fn fan(centre: DVec2, radius: f64, n: usize) -> (Vec<DVec2>, Vec<[u32; 3]>) {
    let mut points = vec![centre];
    for k in 0..n {
        let angle = std::f64::consts::TAU * k as f64 / n as f64;
        points.push(on_grid(
            centre + DVec2::new(angle.cos(), angle.sin()) * radius,
        ));
    }
    let triangles = (0..n as u32)
        .map(|k| {
            let (a, b) = (1 + k, 1 + (k + 1) % n as u32);
            if k % 2 == 0 {
                [0, a, b]
            } else {
                [b, a, 0]
            }
        })
        .collect();
    (points, triangles)
}

/// Whether `p` is strictly inside (`Some(true)`), strictly outside (`Some(false)`) or on the
/// boundary (`None`) of the convex polygon `rim`.
fn in_convex_polygon(rim: &[DVec2], p: DVec2) -> Option<bool> {
    let sides: Vec<f64> = (0..rim.len())
        .map(|i| (rim[(i + 1) % rim.len()] - rim[i]).perp_dot(p - rim[i]))
        .collect();
    if sides.iter().all(|&s| s > 0.0) || sides.iter().all(|&s| s < 0.0) {
        Some(true)
    } else if sides.iter().any(|&s| s > 0.0) && sides.iter().any(|&s| s < 0.0) {
        Some(false)
    } else {
        None
    }
}

#[test]
fn fans_cover_every_pixel_centre_once() {
    // Centred on a pixel centre (spokes along pixel rows, columns and diagonals through pixel
    // centres, the hub itself a pixel centre) and off it; 24 and 32 spokes.
    for (hub, n) in [
        (DVec2::new(31.5, 32.5), 24),
        (DVec2::new(30.5, 29.5), 32),
        (DVec2::new(31.296875, 33.7421875), 24),
        (DVec2::new(32.83984375, 30.1015625), 17),
    ] {
        let (points, triangles) = fan(hub, 25.3, n);
        let count = coverage_count(SIZE, &points, &triangles);
        let mut inside = 0;
        for (i, &c) in count.iter().enumerate() {
            match in_convex_polygon(&points[1..], centre(i, SIZE)) {
                Some(true) => {
                    assert_eq!(c, 1, "pixel {i} inside the fan at {hub} covered {c} times");
                    inside += 1;
                }
                Some(false) => assert_eq!(c, 0, "pixel {i} outside the fan at {hub} covered"),
                None => assert!(c <= 1, "pixel {i} on the rim covered {c} times"),
            }
        }
        assert!(inside > 1500, "the fan covers its disc ({inside} pixels)");
    }
}

/// A grid of `columns × rows` quads over the rectangle `[min, max]`, each split along a random
/// diagonal into two triangles of random winding. Interior vertices are displaced by up to
/// `jitter` of a cell in each direction, then rounded to a multiple of `grain` pixels (0: not
/// rounded); vertices on the border move only along it, so the union is exactly the rectangle.
/// No triangle folds over while the displacement stays below a quarter of a cell.
fn jittered_grid(
    min: DVec2,
    max: DVec2,
    (columns, rows): (usize, usize),
    (jitter, grain): (f64, f64),
    rng: &mut StdRng,
) -> (Vec<DVec2>, Vec<[u32; 3]>) {
    let cell = (max - min) / DVec2::new(columns as f64, rows as f64);
    let mut points = Vec::new();
    for j in 0..=rows {
        for i in 0..=columns {
            let mut p = min + cell * DVec2::new(i as f64, j as f64);
            let mut shift = || rng.random_range(-jitter..=jitter);
            if i > 0 && i < columns {
                p.x += shift() * cell.x;
            }
            if j > 0 && j < rows {
                p.y += shift() * cell.y;
            }
            if grain > 0.0 {
                p = (p / grain).round() * grain;
            }
            points.push(p);
        }
    }
    let index = |i: usize, j: usize| (j * (columns + 1) + i) as u32;
    let mut triangles = Vec::new();
    for j in 0..rows {
        for i in 0..columns {
            let (a, b) = (index(i, j), index(i + 1, j));
            let (c, d) = (index(i + 1, j + 1), index(i, j + 1));
            let halves = if rng.random() {
                [[a, b, c], [a, c, d]]
            } else {
                [[a, b, d], [b, c, d]]
            };
            for [p, q, r] in halves {
                triangles.push(if rng.random() { [p, q, r] } else { [p, r, q] });
            }
        }
    }
    (points, triangles)
}

/// Under the top-left rule a pixel centre on the left or top side of an axis-aligned rectangle
/// is inside, one on the right or bottom side is not: `min ≤ p < max`.
fn in_half_open_rect(min: DVec2, max: DVec2, p: DVec2) -> bool {
    p.x >= min.x && p.x < max.x && p.y >= min.y && p.y < max.y
}

fn assert_grid_covers_rect(size: u32, min: DVec2, max: DVec2, points: &[DVec2], t: &[[u32; 3]]) {
    let count = coverage_count(size, points, t);
    for (i, &c) in count.iter().enumerate() {
        let expected = u32::from(in_half_open_rect(min, max, centre(i, size)));
        assert_eq!(c, expected, "pixel {i} of the grid over {min}..{max}");
    }
}

#[test]
fn jittered_grid_covers_every_pixel_centre_once() {
    let mut rng = StdRng::seed_from_u64(11);
    // The left and top sides run through pixel centres, and so do many interior vertices.
    let (min, max) = (DVec2::new(4.5, 6.5), DVec2::new(60.9375, 57.5));
    let (points, triangles) = jittered_grid(min, max, (9, 7), (0.2, 0.0), &mut rng);
    assert_grid_covers_rect(SIZE, min, max, &points, &triangles);
    // An unjittered grid: every diagonal and side through the same pixel centres.
    let (min, max) = (DVec2::new(2.5, 3.5), DVec2::new(62.5, 59.5));
    let (points, triangles) = jittered_grid(min, max, (12, 8), (0.0, 0.0), &mut rng);
    assert_grid_covers_rect(SIZE, min, max, &points, &triangles);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Random grids at sub-pixel positions, partly off-screen, with random jitter: vertices
    /// anywhere, or on a grid of 1/8 or 1/2 pixel so that many edges and vertices pass through
    /// pixel centres. Cells of at least 4 pixels keep jitter plus rounding below a quarter cell.
    #[test]
    fn random_jittered_grids_cover_every_pixel_centre_once(
        grain in prop_oneof![Just(1.0 / 256.0), Just(0.125), Just(0.5)],
        corner in (-64i32..192, -64i32..192),
        cell in (32i32..96, 32i32..96),
        cells in (1usize..6, 1usize..6),
        jitter in 0.0f64..0.15,
        seed in any::<u64>(),
    ) {
        const SMALL: u32 = 32;
        // Corner and cell size are multiples of 1/256 pixel, so the border is exact.
        let min = DVec2::new(f64::from(corner.0), f64::from(corner.1)) / 8.0;
        let cell = DVec2::new(f64::from(cell.0), f64::from(cell.1)) / 8.0;
        let min = (min / grain).round() * grain;
        let cell = (cell / grain).round() * grain;
        let max = min + cell * DVec2::new(cells.0 as f64, cells.1 as f64);
        let (points, triangles) =
            jittered_grid(min, max, cells, (jitter, grain), &mut StdRng::seed_from_u64(seed));
        assert_grid_covers_rect(SMALL, min, max, &points, &triangles);
    }
}

#[test]
fn vertices_on_pixel_centres_follow_the_top_left_rule() {
    // Left side x = 2.5 and top side y = 2.5 are in, the hypotenuse x + y = 13 is out.
    let points = [(2.5, 2.5), (10.5, 2.5), (2.5, 10.5)].map(|(x, y)| DVec2::new(x, y));
    for triangle in [[0, 1, 2], [0, 2, 1]] {
        let (buffer, stats) = render(SIZE, &points, &[triangle]);
        for (i, &t) in buffer.triangle.iter().enumerate() {
            let p = centre(i, SIZE);
            let expected = p.x >= 2.5 && p.y >= 2.5 && p.x + p.y < 13.0;
            assert_eq!(t != u32::MAX, expected, "pixel centre {p}");
        }
        assert_eq!(stats.pixels_covered, 36);
    }
}

#[test]
fn zero_area_and_collinear_triangles_are_culled() {
    let points = [
        (10.5, 10.5),
        (20.5, 10.5),
        (30.5, 10.5), // collinear along a pixel row
        (12.25, 14.75),
        (12.25, 14.75), // coincident
        (40.0, 40.0),
        (40.0001, 40.0001),
        (40.0, 50.0), // collapses to a line on the 1/256 grid
    ]
    .map(|(x, y)| DVec2::new(x, y));
    let triangles = [[0, 1, 2], [3, 4, 3], [0, 0, 0], [5, 6, 7], [3, 3, 4]];
    let (buffer, stats) = render(SIZE, &points, &triangles);
    assert_eq!(stats.triangles_culled, triangles.len());
    assert_eq!(stats.triangles_rasterized, 0);
    assert!(buffer.triangle.iter().all(|&t| t == u32::MAX));
    assert!(buffer.depth.iter().all(|&d| d == f32::INFINITY));
}

#[test]
fn nan_infinite_and_out_of_range_input_is_skipped() {
    let good = [
        Vec4::new(-0.5, -0.5, 0.5, 1.0),
        Vec4::new(0.5, -0.5, 0.5, 1.0),
        Vec4::new(0.0, 0.5, 0.5, 1.0),
    ];
    let bad = [
        Vec4::new(f32::NAN, 0.0, 0.5, 1.0),
        Vec4::new(0.0, f32::INFINITY, 0.5, 1.0),
        Vec4::new(0.0, 0.0, 0.5, f32::NEG_INFINITY),
        Vec4::new(0.0, 0.0, f32::NAN, f32::NAN),
    ];
    let positions: Vec<Vec4> = good.iter().chain(&bad).copied().collect();
    let triangles = [
        [0, 1, 3],
        [4, 1, 2],
        [0, 5, 2],
        [6, 6, 6],
        [0, 1, 7],
        [0, 1, 99],
        [u32::MAX, 0, 1],
        [0, 1, 2],
    ];
    let (buffer, stats) = rasterize(VIEWPORT, &positions, &triangles, &RasterOptions::default());
    assert_eq!(stats.triangles_invalid, 7);
    let (alone, _) = rasterize(VIEWPORT, &good, &[[0, 1, 2]], &RasterOptions::default());
    assert!(alone.triangle.contains(&0));
    let relabelled: Vec<u32> = alone
        .triangle
        .iter()
        .map(|&t| if t == 0 { 7 } else { t })
        .collect();
    assert_eq!(buffer.triangle, relabelled);
    assert_eq!(buffer.barycentric, alone.barycentric);
    assert_eq!(buffer.depth, alone.depth);
}

/// Screen-space barycentrics `(b1, b2)` of `p` in the triangle `v` (exact for w = 1).
fn screen_barycentric(v: [DVec2; 3], p: DVec2) -> [f64; 2] {
    let area = (v[1] - v[0]).perp_dot(v[2] - v[0]);
    [
        (v[2] - v[0]).perp_dot(v[0] - p) / area,
        (v[1] - v[0]).perp_dot(p - v[0]) / area,
    ]
}

#[test]
fn huge_triangles_cover_the_viewport_with_exact_barycentrics() {
    // Corners a million pixels away, inside the guard band; then a thousand times further,
    // where the triangle is clipped to the guard band first.
    for (scale, clipped) in [(1e6, 0), (1e9, 1)] {
        let v = [(-0.9, -0.7), (0.95, -0.9), (0.2, 1.0)].map(|(x, y)| DVec2::new(x, y) * scale);
        for triangle in [[0, 1, 2], [2, 1, 0]] {
            let (buffer, stats) = render(SIZE, &v, &[triangle]);
            assert_eq!(stats.pixels_covered, u64::from(SIZE * SIZE));
            assert_eq!(stats.triangles_clipped, clipped);
            let corners = triangle.map(|i| {
                let p = at_pixel(v[i as usize], SIZE);
                DVec2::new(f64::from(p.x) + 1.0, 1.0 - f64::from(p.y)) * f64::from(SIZE) / 2.0
            });
            for (i, b) in buffer.barycentric.iter().enumerate() {
                let expected = screen_barycentric(corners, centre(i, SIZE));
                for k in 0..2 {
                    assert!(
                        (f64::from(b[k]) - expected[k]).abs() < 1e-5,
                        "pixel {i}: {b:?} vs {expected:?} (scale {scale})"
                    );
                }
            }
        }
    }
}

/// A clip-space coordinate from a wide range: ordinary values, extremes, zero and tiny values.
fn coordinate() -> impl Strategy<Value = f32> {
    prop_oneof![
        4 => -3.0f32..3.0,
        1 => -1e30f32..1e30,
        1 => Just(0.0f32),
        1 => -1e-30f32..1e-30,
        1 => prop::num::f32::ANY,
    ]
}

/// Whatever the positions, nothing panics, no NaN is written, depths lie in [0, 1],
/// barycentrics lie in the triangle, every input triangle is accounted for exactly once
/// (invalid, culled or rasterized), and each covered pixel is one its triangle covers alone.
#[test]
fn arbitrary_positions_never_give_nan() {
    use proptest::test_runner::{Config, TestRunner};
    use std::cell::Cell;
    let mut runner = TestRunner::new(Config {
        cases: 1000,
        failure_persistence: None,
        ..Config::default()
    });
    let (covered, cases_covering) = (Cell::new(0u64), Cell::new(0u32));
    let strategy = (
        prop::collection::vec(coordinate(), 4 * 9),
        prop::collection::vec(prop::array::uniform3(0u32..10), 1..12),
    );
    runner
        .run(&strategy, |(coords, triangles)| {
            let positions: Vec<Vec4> = coords.chunks(4).map(Vec4::from_slice).collect();
            let viewport = Viewport {
                width: 24,
                height: 16,
            };
            let options = RasterOptions::default();
            let (buffer, stats) = rasterize(viewport, &positions, &triangles, &options);
            prop_assert_eq!(stats.triangles_in, triangles.len());
            // Each triangle alone: exactly one outcome, and the counts add up to the batch's.
            let alone: Vec<(VisibilityBuffer, RasterStats)> = triangles
                .iter()
                .map(|t| rasterize(viewport, &positions, &[*t], &options))
                .collect();
            let mut sum = RasterStats::default();
            for (t, (_, s)) in triangles.iter().zip(&alone) {
                let outcomes = s.triangles_invalid
                    + s.triangles_culled
                    + usize::from(s.triangles_rasterized > 0);
                prop_assert_eq!(outcomes, 1, "{:?}: {:?}", t, s);
                sum = sum + *s;
            }
            prop_assert_eq!(stats.triangles_invalid, sum.triangles_invalid);
            prop_assert_eq!(stats.triangles_culled, sum.triangles_culled);
            prop_assert_eq!(stats.triangles_clipped, sum.triangles_clipped);
            prop_assert_eq!(stats.triangles_rasterized, sum.triangles_rasterized);
            prop_assert_eq!(stats.fragments, sum.fragments);
            let drawn = buffer.triangle.iter().filter(|&&t| t != u32::MAX).count() as u64;
            prop_assert_eq!(stats.pixels_covered, drawn);
            covered.set(covered.get() + drawn);
            cases_covering.set(cases_covering.get() + u32::from(drawn > 0));
            for i in 0..buffer.triangle.len() {
                let (t, d, [b1, b2]) = (buffer.triangle[i], buffer.depth[i], buffer.barycentric[i]);
                if t == u32::MAX {
                    prop_assert!(d == f32::INFINITY && b1 == 0.0 && b2 == 0.0);
                } else {
                    prop_assert!((t as usize) < triangles.len());
                    prop_assert!(alone[t as usize].0.triangle[i] == 0, "pixel {} of {}", i, t);
                    prop_assert!((0.0..=1.0).contains(&d), "depth {}", d);
                    let tolerance = 1e-4;
                    prop_assert!(
                        b1 >= -tolerance && b2 >= -tolerance && b1 + b2 <= 1.0 + tolerance,
                        "barycentrics {} {}",
                        b1,
                        b2
                    );
                }
            }
            Ok(())
        })
        .unwrap();
    // The per-pixel checks above ran on many cases and pixels.
    println!(
        "{} pixels covered in {} cases",
        covered.get(),
        cases_covering.get()
    );
    assert!(
        cases_covering.get() >= 100,
        "{} cases",
        cases_covering.get()
    );
    assert!(covered.get() >= 10_000, "{} pixels", covered.get());
}

#[test]
fn extreme_w_ratios_give_finite_barycentrics() {
    // Clipping against the far plane and the guard band leaves vertices with 1/w ranging over
    // thirty orders of magnitude.
    let positions = [
        Vec4::new(0.0, 0.0, 0.0, 3.932_363_7e29),
        Vec4::new(-2.111_996_4, 0.0, 0.0, 0.495_272_46),
        Vec4::new(0.0, 0.365_648_2, 0.0, -3.354_688e29),
    ];
    let viewport = Viewport {
        width: 24,
        height: 16,
    };
    let (buffer, stats) = rasterize(
        viewport,
        &positions,
        &[[0, 1, 2]],
        &RasterOptions::default(),
    );
    assert_eq!(stats.triangles_clipped, 1);
    assert!(stats.pixels_covered > 0);
    for (&t, b) in buffer.triangle.iter().zip(&buffer.barycentric) {
        if t == 0 {
            assert!(
                b[0] >= -1e-4 && b[1] >= -1e-4 && b[0] + b[1] <= 1.0 + 1e-4,
                "{b:?}"
            );
        }
    }
}
