//! Outlines: ink lines where the G-buffer is discontinuous — silhouettes against the background
//! and against farther surfaces, creases, and (optionally) borders between patches.

use rayon::prelude::*;

use super::camera::Camera;
use super::gbuffer::{GBuffer, EMPTY, PIXELS_PER_JOB};
use super::scene::Outlines;

/// Relative jump in the second difference of inverse view depth that marks an occlusion edge.
/// Inverse depth is affine in screen space across a plane, so its second difference vanishes on
/// smooth surfaces and is large where a nearer surface overlaps a farther one.
const DEPTH_JUMP: f32 = 0.02;

/// Per pixel, 1 where a line is drawn and 0 elsewhere, for lines `outlines.width` pixels wide.
pub fn outline_mask(gbuffer: &GBuffer, camera: &Camera, outlines: &Outlines) -> Vec<f32> {
    let (w, h) = (gbuffer.width as i64, gbuffer.height as i64);
    let forward = camera.forward();
    let inverse_depth: Vec<f32> = gbuffer
        .texels
        .iter()
        .map(|t| 1.0 / (t.position - camera.eye).dot(forward).max(1e-6))
        .collect();
    let crease_cos = outlines.crease_degrees.to_radians().cos();
    let slot = |x: i64, y: i64| -> Option<usize> {
        let s = gbuffer.slot[(y * w + x) as usize];
        (s != EMPTY).then_some(s as usize)
    };
    // Two neighbouring pixels differ when exactly one is covered, or when both are and either
    // they lie on different patches (with patch borders on) or the normal turns by more than
    // the crease angle.
    let differs = |a: Option<usize>, b: Option<usize>| -> bool {
        match (a, b) {
            (None, None) => false,
            (Some(a), Some(b)) => {
                let (a, b) = (&gbuffer.texels[a], &gbuffer.texels[b]);
                (outlines.patch_borders && a.patch != b.patch)
                    || (a.patch == b.patch && a.frame.n.dot(b.frame.n) < crease_cos)
            }
            _ => true,
        }
    };
    // A nearer surface overlapping a farther one: the second difference of inverse depth across
    // the pixel jumps.
    let occludes = |x: i64, y: i64, dx: i64, dy: i64| -> bool {
        let (x0, y0, x1, y1) = (x - dx, y - dy, x + dx, y + dy);
        if x0 < 0 || y0 < 0 || x1 >= w || y1 >= h {
            return false;
        }
        match (slot(x0, y0), slot(x, y), slot(x1, y1)) {
            (Some(a), Some(c), Some(b)) => {
                let (a, c, b) = (inverse_depth[a], inverse_depth[c], inverse_depth[b]);
                (a + b - 2.0 * c).abs() > DEPTH_JUMP * c
            }
            _ => false,
        }
    };
    // A pixel is an edge pixel when it differs from its right or lower neighbour.
    let edges: Vec<bool> = (0..(w * h) as usize)
        .into_par_iter()
        .with_min_len(PIXELS_PER_JOB)
        .map(|i| {
            let (x, y) = (i as i64 % w, i as i64 / w);
            let here = slot(x, y);
            (x + 1 < w && differs(here, slot(x + 1, y)))
                || (y + 1 < h && differs(here, slot(x, y + 1)))
                || (here.is_some() && (occludes(x, y, 1, 0) || occludes(x, y, 0, 1)))
        })
        .collect();
    // Widen each edge pixel to a disc of the line's width.
    let radius = ((outlines.width.max(1.0) - 1.0) * 0.5).max(0.0);
    let reach = radius.ceil() as i64;
    let mut mask = vec![0.0; (w * h) as usize];
    for (i, _) in edges.iter().enumerate().filter(|(_, &edge)| edge) {
        let (x, y) = (i as i64 % w, i as i64 / w);
        for dy in -reach..=reach {
            for dx in -reach..=reach {
                let (nx, ny) = (x + dx, y + dy);
                if (dx * dx + dy * dy) as f32 <= radius * radius + 1e-3
                    && (0..w).contains(&nx)
                    && (0..h).contains(&ny)
                {
                    mask[(ny * w + nx) as usize] = 1.0;
                }
            }
        }
    }
    mask
}
