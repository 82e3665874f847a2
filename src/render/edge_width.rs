//! Edge widths for analytic anti-aliasing: per texel, how fast the highlight's signed inside
//! value changes across the pixel.

use glam::Vec3;
use rayon::prelude::*;

use super::directions::initial_half_vector;
use super::gbuffer::{GBuffer, EMPTY, PIXELS_PER_JOB};
use super::scene::Scene;
use crate::highlight::PreparedLayer;

/// Per texel, the largest `fwidth(s)` over the layers of its patch's highlight (0 without one).
/// Differences are taken forward, or backward at the edge of the patch or image.
pub(super) fn edge_widths(gbuffer: &GBuffer, scene: &Scene) -> Vec<f32> {
    let half_vectors: Vec<Option<Vec3>> = gbuffer
        .texels
        .par_iter()
        .with_min_len(PIXELS_PER_JOB)
        .map(|t| {
            scene.looks[t.patch as usize]
                .highlight
                .as_ref()
                .map(|_| initial_half_vector(scene, t))
        })
        .collect();
    let layer_lists: Vec<Vec<&PreparedLayer>> = scene
        .looks
        .iter()
        .map(|look| {
            look.highlight
                .as_ref()
                .map_or_else(Vec::new, |h| h.layers())
        })
        .collect();
    let most = layer_lists.iter().map(Vec::len).max().unwrap_or(0);
    // signed[k * most + j]: layer j's signed value at texel k.
    let signed: Vec<f32> = gbuffer
        .texels
        .par_iter()
        .zip(&half_vectors)
        .with_min_len(PIXELS_PER_JOB)
        .flat_map_iter(|(t, h)| {
            let layers = &layer_lists[t.patch as usize];
            (0..most).map(move |j| match (h, layers.get(j)) {
                (Some(h), Some(layer)) => layer.signed(&t.frame, *h),
                _ => 0.0,
            })
        })
        .collect();
    let (w, h) = (gbuffer.width as usize, gbuffer.height as usize);
    gbuffer
        .texels
        .par_iter()
        .with_min_len(PIXELS_PER_JOB)
        .enumerate()
        .map(|(k, t)| {
            if half_vectors[k].is_none() {
                return 0.0;
            }
            let i = t.pixel as usize;
            let (x, y) = (i % w, i / w);
            // The texel of a neighbour on the same patch: forward if possible, else backward.
            let same_patch = |pixel: Option<usize>| {
                let slot = gbuffer.slot[pixel?];
                (slot != EMPTY && gbuffer.texels[slot as usize].patch == t.patch)
                    .then_some(slot as usize)
            };
            let nx = same_patch((x + 1 < w).then(|| i + 1))
                .or_else(|| same_patch((x > 0).then(|| i - 1)));
            let ny = same_patch((y + 1 < h).then(|| i + w))
                .or_else(|| same_patch((y > 0).then(|| i - w)));
            (0..layer_lists[t.patch as usize].len())
                .map(|j| {
                    let s = signed[k * most + j];
                    let dx = nx.map_or(0.0, |n| (signed[n * most + j] - s).abs());
                    let dy = ny.map_or(0.0, |n| (signed[n * most + j] - s).abs());
                    dx + dy
                })
                .fold(0.0, f32::max)
        })
        .collect()
}
