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
/// patch or off the image, and 0 where both are. Where `s` peaks or dips at the texel (the two
/// one-sided slopes differ in sign) the larger slope is taken, so that a highlight narrower
/// than the spacing of pixels still covers some of the pixel nearest it. Where the slope grows
/// by more than itself from one side to the other, `|s₊ + s₋ − 2s| > |s₊ − s₋|/2`, `s` is not
/// near enough to a straight edge for the box coverage to hold and the footprint is 0 along
/// that axis (a hard edge, as without anti-aliasing). Across a silhouette (a neighbour inside the
/// image that no surface covers) the footprint is 0 along that axis: there the surface turns
/// away within the pixel, `s` is far from linear, and a straight edge fitted to it would put
/// highlight where the surface ends — the edge is left hard, for the silhouette's own
/// anti-aliasing (supersampling) to smooth.
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
            // A neighbour inside the image that no surface covers: the texel is on a silhouette.
            let empty = |pixel: Option<usize>| pixel.is_some_and(|p| gbuffer.slot[p] == EMPTY);
            let silhouette_x = empty((x > 0).then(|| i - 1)) || empty((x + 1 < w).then(|| i + 1));
            let silhouette_y = empty((y > 0).then(|| i - w)) || empty((y + 1 < h).then(|| i + w));
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
                            (Some(b), Some(a)) => {
                                let (ahead, behind) = (at(a) - s, s - at(b));
                                let central = 0.5 * (ahead + behind);
                                if ahead * behind <= 0.0 {
                                    ahead.abs().max(behind.abs())
                                } else if (ahead - behind).abs() > central.abs() {
                                    0.0
                                } else {
                                    central.abs()
                                }
                            }
                            (None, Some(a)) => (at(a) - s).abs(),
                            (Some(b), None) => (s - at(b)).abs(),
                            (None, None) => 0.0,
                        };
                    let across = |silhouette: bool, before, after| {
                        if silhouette {
                            0.0
                        } else {
                            derivative(before, after)
                        }
                    };
                    Footprint {
                        x: across(silhouette_x, left, right),
                        y: across(silhouette_y, up, down),
                    }
                })
                .fold(Footprint::HARD, Footprint::max)
        })
        .collect()
}
