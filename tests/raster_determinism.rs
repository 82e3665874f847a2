//! The visibility buffer does not depend on how the work is split: byte-identical for any
//! thread count and tile size.

use glam::{Mat4, Vec3, Vec4};
use glint::render::raster::{rasterize, RasterOptions, Rasterizer, Viewport, VisibilityBuffer};
use rand::{rngs::StdRng, Rng, SeedableRng};

const VIEWPORT: Viewport = Viewport {
    width: 240,
    height: 176,
};

/// A few thousand random triangles of all sizes in front of, around and behind a perspective
/// camera, some of them repeated (exact depth ties).
fn scene() -> (Vec<Vec4>, Vec<[u32; 3]>) {
    let mut rng = StdRng::seed_from_u64(2024);
    let projection = Mat4::perspective_rh(1.1, 240.0 / 176.0, 0.1, 30.0)
        * Mat4::look_at_rh(Vec3::new(0.0, 0.0, 2.0), Vec3::ZERO, Vec3::Y);
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for _ in 0..3000 {
        let mut centre = Vec3::new(
            rng.random_range(-3.0..3.0),
            rng.random_range(-2.0..2.0),
            rng.random_range(-6.0..2.5),
        );
        // Mostly small triangles; some large ones, some across the near plane (z ≈ 1.9).
        let size = match rng.random_range(0..20) {
            0 => 2.0,
            1 => {
                centre = centre * Vec3::new(0.2, 0.2, 0.0) + Vec3::new(0.0, 0.0, 1.9);
                0.5
            }
            _ => 0.15,
        };
        let first = positions.len() as u32;
        for _ in 0..3 {
            let offset = Vec3::new(
                rng.random_range(-size..size),
                rng.random_range(-size..size),
                rng.random_range(-size..size),
            );
            positions.push(projection * (centre + offset).extend(1.0));
        }
        triangles.push([first, first + 1, first + 2]);
        if rng.random_bool(0.05) {
            triangles.push([first + 2, first + 1, first]);
        }
    }
    (positions, triangles)
}

/// The buffer's bytes: depth as bit patterns, so that comparing them is exact.
fn bytes(buffer: &VisibilityBuffer) -> (Vec<u32>, Vec<u32>, Vec<[u32; 2]>) {
    (
        buffer.depth.iter().map(|d| d.to_bits()).collect(),
        buffer.triangle.clone(),
        buffer
            .barycentric
            .iter()
            .map(|b| b.map(f32::to_bits))
            .collect(),
    )
}

#[test]
fn buffers_are_identical_for_any_thread_count_and_tile_size() {
    let (positions, triangles) = scene();
    let run = |threads, tile_size| {
        let options = RasterOptions { threads, tile_size };
        rasterize(VIEWPORT, &positions, &triangles, &options)
    };
    let (reference, reference_stats) = run(1, 64);

    assert!(reference_stats.triangles_clipped > 40);
    assert!(reference_stats.pixels_covered > 20_000);
    assert!(reference_stats.fragments > 2 * reference_stats.pixels_covered);
    for threads in [1, 2, 3] {
        for tile_size in [16, 64, 37] {
            let (buffer, stats) = run(threads, tile_size);
            assert!(
                bytes(&buffer) == bytes(&reference),
                "{threads} threads, {tile_size}-pixel tiles"
            );
            assert_eq!(stats, reference_stats);
        }
    }
}

#[test]
fn a_reused_rasterizer_and_buffer_give_what_a_fresh_call_gives() {
    let (positions, triangles) = scene();
    let mut rasterizer = Rasterizer::new();
    let mut buffer = VisibilityBuffer::default();
    // Frames of different sizes, triangle counts and tilings through the same memory.
    let frames = [
        (VIEWPORT, triangles.len(), 64),
        (
            Viewport {
                width: 64,
                height: 40,
            },
            500,
            16,
        ),
        (VIEWPORT, 2000, 37),
        (
            Viewport {
                width: 0,
                height: 9,
            },
            10,
            64,
        ),
    ];
    for (viewport, count, tile_size) in frames {
        let options = RasterOptions {
            threads: 2,
            tile_size,
        };
        let stats = rasterizer.rasterize_into(
            viewport,
            &positions,
            &triangles[..count],
            &options,
            &mut buffer,
        );
        let (fresh, fresh_stats) = rasterize(viewport, &positions, &triangles[..count], &options);
        assert!(
            bytes(&buffer) == bytes(&fresh),
            "{viewport:?}, {count} triangles"
        );
        assert_eq!(
            (buffer.width, buffer.height),
            (viewport.width, viewport.height)
        );
        assert_eq!(stats, fresh_stats);
    }
}

#[test]
fn rasterizing_some_pixels_of_each_row_draws_them_as_the_whole_viewport_does() {
    let (positions, triangles) = scene();
    let (whole, _) = rasterize(VIEWPORT, &positions, &triangles, &RasterOptions::default());
    let mut rng = StdRng::seed_from_u64(7);
    let width = VIEWPORT.width;
    // Per row a random span, some empty, some the whole row, some past its end.
    let rows: Vec<(u32, u32)> = (0..VIEWPORT.height)
        .map(|_| match rng.random_range(0..6) {
            0 => (0, 0),
            1 => (0, width),
            2 => (width - 3, width + 10),
            _ => {
                let a = rng.random_range(0..width);
                (a, rng.random_range(a..=width))
            }
        })
        .collect();
    let mut buffer = VisibilityBuffer::default();
    // Through a buffer that held the whole frame: the pixels left out must be emptied.
    let mut rasterizer = Rasterizer::new();
    rasterizer.rasterize_into(
        VIEWPORT,
        &positions,
        &triangles,
        &RasterOptions::default(),
        &mut buffer,
    );
    for tile_size in [16, 37, 64] {
        let options = RasterOptions {
            threads: 2,
            tile_size,
        };
        rasterizer.rasterize_rows_into(
            VIEWPORT,
            &positions,
            &triangles,
            None,
            Some(&rows),
            &options,
            &mut buffer,
        );
        let (mut kept, mut left_out) = (0, 0);
        for (y, &(a, b)) in rows.iter().enumerate() {
            for x in 0..width {
                let i = y * width as usize + x as usize;
                if (a..b).contains(&x) {
                    assert_eq!(buffer.triangle[i], whole.triangle[i], "({x}, {y})");
                    assert_eq!(buffer.depth[i].to_bits(), whole.depth[i].to_bits());
                    assert_eq!(
                        buffer.barycentric[i].map(f32::to_bits),
                        whole.barycentric[i].map(f32::to_bits)
                    );
                    kept += u32::from(whole.triangle[i] != u32::MAX);
                } else {
                    assert_eq!(buffer.triangle[i], u32::MAX, "({x}, {y}) left out");
                    left_out += u32::from(whole.triangle[i] != u32::MAX);
                }
            }
        }
        assert!(
            kept > 5_000 && left_out > 5_000,
            "{kept} kept, {left_out} left out"
        );
    }
}
