//! Edge widths for analytic anti-aliasing: per texel, how fast the highlight's signed inside
//! value changes across the pixel (its [`Footprint`]).

use glam::Vec3;
use rayon::prelude::*;

use super::directions::initial_half_vector;
use super::gbuffer::{GBuffer, EMPTY, PIXELS_PER_JOB};
use super::scene::Scene;
use crate::highlight::{Footprint, PreparedLayer};

/// Per texel, the footprint of the signed value `s` over the layers of its patch's highlight,
/// the largest `|∂s/∂x|` and `|∂s/∂y|` ([`Footprint::HARD`] without one). The derivatives are
/// central differences `(s₊ − s₋)/2` between the neighbours on the same patch, exact for the
/// nearly quadratic `s` about a highlight's centre; one-sided where a neighbour is on another
/// patch or off the image, and 0 where both are.
pub(super) fn edge_widths(gbuffer: &GBuffer, scene: &Scene) -> Vec<Footprint> {
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
                return Footprint::HARD;
            }
            let i = t.pixel as usize;
            let (x, y) = (i % w, i / w);
            // The texel of a neighbour on the same patch.
            let same_patch = |pixel: Option<usize>| {
                let slot = gbuffer.slot[pixel?];
                (slot != EMPTY && gbuffer.texels[slot as usize].patch == t.patch)
                    .then_some(slot as usize)
            };
            let (left, right) = (
                same_patch((x > 0).then(|| i - 1)),
                same_patch((x + 1 < w).then(|| i + 1)),
            );
            let (up, down) = (
                same_patch((y > 0).then(|| i - w)),
                same_patch((y + 1 < h).then(|| i + w)),
            );
            (0..layer_lists[t.patch as usize].len())
                .map(|j| {
                    let at = |n: usize| signed[n * most + j];
                    let s = at(k);
                    let derivative =
                        |before: Option<usize>, after: Option<usize>| match (before, after) {
                            (Some(b), Some(a)) => 0.5 * (at(a) - at(b)).abs(),
                            (None, Some(a)) => (at(a) - s).abs(),
                            (Some(b), None) => (s - at(b)).abs(),
                            (None, None) => 0.0,
                        };
                    Footprint {
                        x: derivative(left, right),
                        y: derivative(up, down),
                    }
                })
                .fold(Footprint::HARD, Footprint::max)
        })
        .collect()
}
