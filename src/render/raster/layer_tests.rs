//! Drawing over a kept layer checked against a full raster: every split of overlapping and
//! tied triangles between the layer and the triangles drawn over it gives the same buffer.

use glam::Vec4;

use super::Layer;
use crate::render::raster::{rasterize, RasterOptions, Rasterizer, Viewport, VisibilityBuffer};

/// A triangle at depth `z` (orthographic, w = 1) with corners `(x, y)` in NDC.
fn at(z: f32, corners: [(f32, f32); 3], positions: &mut Vec<Vec4>) -> [u32; 3] {
    let first = positions.len() as u32;
    positions.extend(corners.map(|(x, y)| Vec4::new(x, y, z, 1.0)));
    [first, first + 1, first + 2]
}

#[test]
fn drawing_over_a_layer_gives_the_full_raster_bit_for_bit() {
    let mut positions = Vec::new();
    let big = [(-0.9, -0.9), (0.9, -0.8), (0.0, 0.9)];
    let triangles = vec![
        // 0 and 1 cover the same pixels at the same depth: 0 wins both ways.
        at(0.5, big, &mut positions),
        at(0.5, big, &mut positions),
        // Nearer over part of them, then farther over all.
        at(
            0.25,
            [(-0.5, -0.5), (0.6, -0.2), (-0.1, 0.7)],
            &mut positions,
        ),
        at(
            0.75,
            [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0)],
            &mut positions,
        ),
        // Crossing 0 and 1: nearer on one side, farther on the other.
        [
            positions.len() as u32,
            positions.len() as u32 + 1,
            positions.len() as u32 + 2,
        ],
    ];
    positions.extend([
        Vec4::new(-1.0, 0.0, 0.2, 1.0),
        Vec4::new(1.0, -0.3, 0.8, 1.0),
        Vec4::new(0.2, 1.0, 0.5, 1.0),
    ]);
    let viewport = Viewport {
        width: 150,
        height: 97,
    };
    let (full, _) = rasterize(viewport, &positions, &triangles, &RasterOptions::default());
    // Every way of holding some triangles in the layer and drawing the rest over it.
    for held in 0u32..1 << triangles.len() {
        let split = |want: bool| -> Vec<std::ops::Range<u32>> {
            (0..triangles.len() as u32)
                .filter(|&t| (held >> t & 1 == 1) == want)
                .map(|t| t..t + 1)
                .collect()
        };
        let mut rasterizer = Rasterizer::new();
        let mut layer = Layer::default();
        rasterizer.rasterize_layer_into(
            viewport,
            &positions,
            (&triangles, &split(true)),
            None,
            &mut layer,
        );
        let mut over = VisibilityBuffer::default();
        let stats = rasterizer.rasterize_over_into(
            viewport,
            &positions,
            (&triangles, &split(false)),
            (None, &layer),
            &mut over,
        );
        assert_eq!(stats.triangles_in, split(false).len(), "held {held:b}");
        let bits = |b: &VisibilityBuffer| {
            let depth: Vec<u32> = b.depth.iter().map(|z| z.to_bits()).collect();
            let bary: Vec<[u32; 2]> = b.barycentric.iter().map(|c| c.map(f32::to_bits)).collect();
            (depth, b.triangle.clone(), bary)
        };
        assert!(bits(&over) == bits(&full), "held {held:b}");
    }
    // The tie went to the lower index, and the layer's triangles do show.
    let centre = full.hit(75, 60).unwrap();
    assert!(centre.triangle != 1);
    assert!(full.triangle.contains(&3));
}

/// The buffer's bits: depth, triangle and barycentrics.
fn bits(b: &VisibilityBuffer) -> (Vec<u32>, Vec<u32>, Vec<[u32; 2]>) {
    let depth = b.depth.iter().map(|z| z.to_bits()).collect();
    let bary = b.barycentric.iter().map(|c| c.map(f32::to_bits)).collect();
    (depth, b.triangle.clone(), bary)
}

#[test]
fn drawing_over_a_layer_into_a_buffer_that_holds_its_copy_writes_what_a_fresh_draw_does() {
    let viewport = Viewport {
        width: 300,
        height: 200,
    };
    // Two layers of a big triangle, at two depths, and a small triangle that moves across
    // the tiles frame by frame, drawn over one of them.
    let layer_of = |z: f32, rasterizer: &mut Rasterizer, layer: &mut Layer| {
        let mut positions = Vec::new();
        let triangles = [at(
            z,
            [(-0.9, -0.9), (0.9, -0.8), (0.0, 0.9)],
            &mut positions,
        )];
        let all = std::slice::from_ref(&(0..1));
        rasterizer.rasterize_layer_into(viewport, &positions, (&triangles, all), None, layer);
    };
    // Triangle 0 is the layer's, not drawn over it; triangle 1 is the small one.
    let small = |frame: usize| {
        let mut positions = Vec::new();
        let x = -1.0 + 0.25 * frame as f32;
        let corners = [(x, -0.3), (x + 0.3, -0.2), (x + 0.1, 0.4)];
        let triangles = vec![[0, 0, 0], at(0.4, corners, &mut positions)];
        (positions, triangles)
    };
    let mut rasterizer = Rasterizer::new();
    let (mut near, mut far) = (Layer::default(), Layer::default());
    layer_of(0.5, &mut rasterizer, &mut near);
    layer_of(0.3, &mut rasterizer, &mut far);
    let mut buffers = [VisibilityBuffer::default(), VisibilityBuffer::default()];
    let mut copies = [super::LayerCopy::default(), super::LayerCopy::default()];
    let mut kept_tiles = 0;
    for frame in 0..9 {
        // The layer drawn over changes at frame 5, and is drawn again (a new stamp, the same
        // buffer object) at frame 7 with other pixels.
        if frame == 7 {
            layer_of(0.7, &mut rasterizer, &mut near);
        }
        let layer = if (5..7).contains(&frame) { &far } else { &near };
        let (positions, triangles) = small(frame);
        let ranges = std::slice::from_ref(&(1..2));
        let (buffer, copy) = (&mut buffers[frame % 2], &mut copies[frame % 2]);
        kept_tiles += copy.copied_tiles();
        let stats = rasterizer.rasterize_over_keeping(
            viewport,
            &positions,
            (&triangles, ranges),
            (None, layer),
            (buffer, copy),
        );
        let mut fresh = VisibilityBuffer::default();
        let fresh_stats = Rasterizer::new().rasterize_over_into(
            viewport,
            &positions,
            (&triangles, ranges),
            (None, layer),
            &mut fresh,
        );
        assert!(bits(buffer) == bits(&fresh), "frame {frame}");
        assert_eq!(stats, fresh_stats, "frame {frame}");
    }
    // Tiles were left as they were, not just copied again every time.
    assert!(kept_tiles > 0);
}
