//! Edge widths for analytic anti-aliasing: per texel, how fast the highlight's signed inside
//! value changes across the pixel (its [`Footprint`]).

use rayon::prelude::*;

use glam::Vec3;

use crate::highlight::{Footprint, LayerScratch, PointChunk, PreparedLayer};
use crate::math::{Lanes, LANES};
use crate::render::directions::{initial_half_vectors, view_lanes};
use crate::render::gbuffer::{GBuffer, Texel, EMPTY, PIXELS_PER_JOB};
use crate::render::scene::Scene;

/// What the edge-width stage finds per texel.
#[derive(Clone, Debug, Default, PartialEq)]
pub(in crate::render) struct EdgeWidths {
    /// The footprint the box coverage of each highlight edge takes.
    pub footprints: Vec<Footprint>,
    /// Whether some layer's `s` may change sign within the pixel ([`straddles_zero`]): a
    /// highlight edge may cross it though no neighbour's colour shows it.
    pub straddles: Vec<bool>,
}

/// The working memory of the signed values of up to [`LANES`] texels of one patch.
struct SignedScratch {
    view: Lanes,
    half_vectors: [Vec3; LANES],
    /// The texels' frames and half vectors.
    points: PointChunk,
    layer: LayerScratch,
    out: [f32; LANES],
}

impl Default for SignedScratch {
    fn default() -> Self {
        Self {
            view: Lanes::default(),
            half_vectors: [Vec3::ZERO; LANES],
            points: PointChunk::default(),
            layer: LayerScratch::default(),
            out: [0.0; LANES],
        }
    }
}

impl SignedScratch {
    /// The frames and initial half vectors of `texels` (up to [`LANES`], on one patch).
    fn fill(&mut self, scene: &Scene, texels: &[Texel]) {
        let n = texels.len();
        view_lanes(scene, texels, &mut self.view);
        initial_half_vectors(scene, texels, &self.view, &mut self.half_vectors[..n]);
        let hs = &self.half_vectors;
        self.points.set(n, |k| (texels[k].frame, hs[k]));
    }
}

/// At a peak or dip of `s`, the most one one-sided slope may exceed the other by and still be
/// taken for a smooth extremum rather than a jump (an occlusion within a patch).
const PEAK_RATIO: f32 = 4.0;

/// Per texel of a G-buffer, the signed value `s` of each layer of its patch's highlight.
#[derive(Debug)]
pub(in crate::render) struct SignedValues<'s> {
    /// Per patch, its highlight's layers, left to right (none without a highlight).
    pub layers: Vec<Vec<&'s PreparedLayer>>,
    /// The most layers a patch has: the stride of `values`.
    most: usize,
    /// `values[k * most + j]`: layer `j`'s `s` at texel `k` (0 past its patch's layers).
    values: Vec<f32>,
}

impl SignedValues<'_> {
    /// Layer `layer`'s `s` at texel `texel`.
    #[inline]
    pub fn at(&self, texel: usize, layer: usize) -> f32 {
        self.values[texel * self.most + layer]
    }

    /// Each layer's `s` at texel `texel`, left to right (0 past its patch's layers).
    #[inline]
    pub fn of(&self, texel: usize) -> &[f32] {
        &self.values[texel * self.most..(texel + 1) * self.most]
    }
}

/// Per texel of `gbuffer`, the signed value of each layer of its patch's highlight
/// ([`signed_values_of`] its texels).
pub(in crate::render) fn signed_values<'s>(
    gbuffer: &GBuffer,
    scene: &'s Scene,
) -> SignedValues<'s> {
    signed_values_of(&gbuffer.texels, scene)
}

/// Per texel of `texels`, the signed value of each layer of its patch's highlight, for runs of
/// texels on one patch up to [`LANES`] at a time, side by side.
pub(in crate::render) fn signed_values_of<'s>(
    texels: &[Texel],
    scene: &'s Scene,
) -> SignedValues<'s> {
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
    let mut signed = vec![0.0f32; texels.len() * most];
    if most > 0 {
        signed
            .par_chunks_mut(most * PIXELS_PER_JOB)
            .zip(texels.par_chunks(PIXELS_PER_JOB))
            .for_each_init(SignedScratch::default, |scratch, (values, texels)| {
                let mut start = 0;
                for run in texels.chunk_by(|a, b| a.patch == b.patch) {
                    let layers = &layer_lists[run[0].patch as usize];
                    for piece in run.chunks(LANES) {
                        let n = piece.len();
                        let values = &mut values[start * most..(start + n) * most];
                        start += n;
                        if layers.is_empty() {
                            continue;
                        }
                        scratch.fill(scene, piece);
                        for (j, layer) in layers.iter().enumerate() {
                            let out = &mut scratch.out[..n];
                            layer.signed_chunk(&scratch.points, &mut scratch.layer, out);
                            for (texel, &s) in values.chunks_exact_mut(most).zip(out.iter()) {
                                texel[j] = s;
                            }
                        }
                    }
                }
            });
    }
    SignedValues {
        layers: layer_lists,
        most,
        values: signed,
    }
}

/// Per texel, the footprint of the signed value `s` over the layers of its patch's highlight,
/// the largest `|∂s/∂x|` and `|∂s/∂y|` ([`Footprint::HARD`] without one), each from
/// [`axis_slope`] over the neighbours on the same patch along that axis. Across a silhouette
/// (a neighbour inside the image that no surface covers) the footprint is 0 along that axis:
/// there the surface turns away within the pixel, and the edge is left hard, for the
/// silhouette's own anti-aliasing (supersampling) to smooth.
pub(in crate::render) fn edge_widths(gbuffer: &GBuffer, scene: &Scene) -> EdgeWidths {
    let patches: Vec<u32> = gbuffer.texels.iter().map(|t| t.patch).collect();
    edge_widths_of(gbuffer, &signed_values(gbuffer, scene), &patches, None)
}

/// [`edge_widths`] from the signed values of the layers at the texels of `gbuffer` and the
/// texels' `patches` (side by side: the neighbours are looked up by patch, and the texels
/// themselves are large), at the texels `wanted` marks (all without it; [`Footprint::HARD`]
/// and no straddle elsewhere).
pub(in crate::render) fn edge_widths_of(
    gbuffer: &GBuffer,
    signed: &SignedValues,
    patches: &[u32],
    wanted: Option<&[bool]>,
) -> EdgeWidths {
    let (w, h) = (gbuffer.width as usize, gbuffer.height as usize);
    let (footprints, straddles) = gbuffer
        .texels
        .par_iter()
        .with_min_len(PIXELS_PER_JOB)
        .enumerate()
        .map(|(k, t)| {
            let layers = signed.layers[t.patch as usize].len();
            if layers == 0 || wanted.is_some_and(|wanted| !wanted[k]) {
                return (Footprint::HARD, false);
            }
            let i = t.pixel as usize;
            let (x, y) = (i % w, i / w);
            // The texel of a neighbour on the same patch.
            let same_patch = |pixel: Option<usize>| {
                let slot = gbuffer.slot[pixel?];
                (slot != EMPTY && patches[slot as usize] == t.patch).then_some(slot as usize)
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
            (0..layers)
                .map(|j| {
                    let at = |n: usize| signed.at(n, j);
                    let s = at(k);
                    let derivative = |before: Option<usize>, after: Option<usize>| {
                        axis_slope(s, before.map(at), after.map(at))
                    };
                    let across = |silhouette: bool, before, after| {
                        if silhouette {
                            0.0
                        } else {
                            derivative(before, after)
                        }
                    };
                    let footprint = Footprint {
                        x: across(silhouette_x, left, right),
                        y: across(silhouette_y, up, down),
                    };
                    let straddle = |before: Option<usize>, after: Option<usize>| {
                        straddles_zero(s, before.map(at), after.map(at))
                    };
                    (footprint, straddle(left, right) || straddle(up, down))
                })
                .fold((Footprint::HARD, false), |(f, near), (g, also)| {
                    (f.max(g), near || also)
                })
        })
        .unzip();
    EdgeWidths {
        footprints,
        straddles,
    }
}

/// The slope of `s` along one axis for the box coverage of a straight edge, from its values at
/// the neighbours `before` and `after` (None: off the image or on another patch); 0 where no
/// edge of `s` lies along the axis within reach of the texel, or where `s` is too far from
/// straight for the box coverage to hold — the edge is then hard, as without anti-aliasing:
///
/// - where `s` changes sign between the texel and a neighbour (an edge between their centres),
///   the central difference `(s₊ − s₋)/2`, or the one-sided one where a neighbour is missing —
///   exact for the nearly quadratic `s` about a highlight's centre; but 0 where the slope
///   grows by more than itself from one side to the other, `|s₊ + s₋ − 2s| > |s₊ − s₋|/2`
///   (the surface turning away toward a silhouette);
/// - where `s` has no sign change but peaks toward 0 at the texel (a local maximum below 0, or
///   minimum above it), the larger one-sided slope, so that a highlight narrower than the
///   spacing of pixels still covers some of the pixel nearest it — unless it is more than
///   [`PEAK_RATIO`] times the other: a jump where one surface passes behind another;
/// - otherwise 0: the neighbours lie on the texel's side of every edge.
#[must_use]
fn axis_slope(s: f32, before: Option<f32>, after: Option<f32>) -> f32 {
    let crosses = |n: Option<f32>| n.is_some_and(|n| (n >= 0.0) != (s >= 0.0));
    if !crosses(before) && !crosses(after) {
        let (Some(b), Some(a)) = (before, after) else {
            return 0.0;
        };
        let (ahead, behind) = (a - s, s - b);
        let toward_zero = if s < 0.0 {
            ahead <= 0.0 && behind >= 0.0
        } else {
            ahead >= 0.0 && behind <= 0.0
        };
        let (low, high) = (ahead.abs().min(behind.abs()), ahead.abs().max(behind.abs()));
        return if toward_zero && high <= PEAK_RATIO * low {
            high
        } else {
            0.0
        };
    }
    match (before, after) {
        (Some(b), Some(a)) => {
            let (ahead, behind) = (a - s, s - b);
            let central = 0.5 * (ahead + behind);
            if ahead * behind > 0.0 && (ahead - behind).abs() > central.abs() {
                0.0
            } else {
                central.abs()
            }
        }
        (None, Some(n)) | (Some(n), None) => (n - s).abs(),
        (None, None) => 0.0,
    }
}

/// Whether `s` may change sign within the pixel along one axis: the parabola through the
/// neighbours' values `before`, `s`, `after` (at −1, 0, 1) takes both signs over [−½, ½] — the
/// ends, and the vertex where it lies inside. With one neighbour, the straight line through it;
/// with none, never. This bounds `ε − ‖N − H'‖²/2` over the pixel where the sign at its centre
/// says nothing: a highlight smaller than the spacing of pixels, between their centres.
#[must_use]
fn straddles_zero(s: f32, before: Option<f32>, after: Option<f32>) -> bool {
    let (low, high) = match (before, after) {
        (Some(b), Some(a)) => {
            let (slope, curve) = (0.5 * (a - b), 0.5 * (a + b) - s);
            let at = |x: f32| s + x * (slope + curve * x);
            let (mut low, mut high) = (at(-0.5).min(at(0.5)), at(-0.5).max(at(0.5)));
            if curve != 0.0 {
                let vertex = -slope / (2.0 * curve);
                if vertex.abs() <= 0.5 {
                    (low, high) = (low.min(at(vertex)), high.max(at(vertex)));
                }
            }
            (low, high)
        }
        (None, Some(n)) | (Some(n), None) => {
            let half = 0.5 * (n - s).abs();
            (s - half, s + half)
        }
        (None, None) => (s, s),
    };
    low < 0.0 && high >= 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_highlight_between_centres_straddles_the_pixel_nearest_it() {
        // s = 0.02 − (x − 0.3)²·2 sampled at −1, 0, 1: negative at all three centres, positive
        // near x = 0.3.
        let s = |x: f32| 0.02 - 2.0 * (x - 0.3) * (x - 0.3);
        assert!(s(-1.0) < 0.0 && s(0.0) < 0.0 && s(1.0) < 0.0);
        assert!(straddles_zero(s(0.0), Some(s(-1.0)), Some(s(1.0))));
        // Its neighbour at x = −1 lies farther from it: no.
        assert!(!straddles_zero(s(-1.0), Some(s(-2.0)), Some(s(0.0))));
        // A straight edge, s = 0.05 − 0.2 x, crossing at x = 0.25: the pixel it crosses, not
        // the ones beyond.
        assert!(straddles_zero(0.05, Some(0.25), Some(-0.15)));
        assert!(!straddles_zero(-0.15, Some(0.05), Some(-0.35)));
        assert!(!straddles_zero(0.25, Some(0.45), Some(0.05)));
        assert!(straddles_zero(0.05, None, Some(-0.1)));
        assert!(!straddles_zero(-0.3, None, None));
    }

    #[test]
    fn a_straight_edge_between_centres_takes_the_central_difference() {
        // s = 0.1 − 0.2 x at x = −1, 0, 1: the edge at x = 0.5.
        assert!((axis_slope(0.1, Some(0.3), Some(-0.1)) - 0.2).abs() < 1e-6);
        // One-sided where the other neighbour is missing.
        assert!((axis_slope(0.1, None, Some(-0.1)) - 0.2).abs() < 1e-6);
    }

    #[test]
    fn no_edge_along_the_axis_or_a_runaway_slope_is_hard() {
        // All three inside, or all outside and falling: no edge near.
        assert_eq!(axis_slope(0.3, Some(0.5), Some(0.1)), 0.0);
        assert_eq!(axis_slope(-0.3, Some(-0.1), Some(-0.5)), 0.0);
        assert_eq!(axis_slope(-0.3, None, Some(-0.5)), 0.0);
        // Toward a silhouette: the slope quadruples across the texel.
        assert_eq!(axis_slope(0.05, Some(0.1), Some(-0.2)), 0.0);
    }

    #[test]
    fn a_peak_toward_zero_takes_the_larger_slope_and_a_jump_none() {
        // A highlight between centres: s peaks at −0.05 with neighbours −0.15 and −0.2.
        assert!((axis_slope(-0.05, Some(-0.15), Some(-0.2)) - 0.15).abs() < 1e-6);
        // A peak away from zero (a dip below 0) is no highlight.
        assert_eq!(axis_slope(-0.3, Some(-0.1), Some(-0.2)), 0.0);
        // One side jumps (another part of the surface): no footprint.
        assert_eq!(axis_slope(-0.05, Some(-0.06), Some(-0.9)), 0.0);
    }
}
