//! Highlight edges for adaptive anti-aliasing: per texel, whether its highlight's edges cross
//! its pixel smoothly enough to be drawn at one sample, from the quadratic of a layer's signed
//! value over the pixel.

use rayon::prelude::*;

use super::band_edge::JUMP;
use super::edge_width::SignedValues;
use super::settled::SettledTexels;
use crate::highlight::PreparedLayer;
use crate::math::{BoxQuadratic, LevelCrossing};
use crate::render::directions::initial_half_vector;
use crate::render::gbuffer::{GBuffer, PIXELS_PER_JOB};
use crate::render::neighbourhood::{around, one_patch_around};
use crate::render::scene::Scene;

/// The most of a pixel's area by which a layer's edge may depart from straight over the box (as
/// [`BoxQuadratic::crossing`] measures it) for the quadratic through the nine centres to follow
/// it: more is an edge that turns within the pixel, a corner of a squared highlight or a
/// highlight about as small as the pixel. The quadratic's cover of the box follows a bend that
/// [`STRAIGHT_AREA`](super::band_edge::STRAIGHT_AREA) would leave to supersampling: on the
/// analytic sphere at 256², `final`'s highlight matte holds or improves on every view of the
/// accuracy ladder from 0.02 up to this (ε = 0.001 at 30° off centre: 1 − IoU 1.1 · 10⁻³ at
/// 0.02, 5.1 · 10⁻⁴ at 0.2), and the teapot's smooth pixels stop growing beyond it.
pub(in crate::render) const SMOOTH_BEND: f32 = 0.2;

/// How a pixel's highlight meets the edges of its layers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(in crate::render) enum HighlightEdge {
    /// Its box lies inside one patch and no layer's edge reaches it (or the patch has no
    /// highlight): its centre's highlight is the box's.
    Clear,
    /// Its box lies inside one patch; one layer's edge crosses it smoothly, and every other
    /// layer covers all of it or none: the box's highlight is that layer's cover of the box by
    /// the quadratic of its `s` ([`SmoothEdge`]), each Boolean of a partly covering layer with
    /// wholly covering or uncovering ones being exact.
    Smooth,
    /// Neither: beside another patch, a silhouette or the image's edge; two layers' edges
    /// within reach; an edge that bends sharply over the pixel or jumps there; a feathered or
    /// masked layer whose fade or mask may reach the pixel. Drawn hard at one sample.
    Hard,
}

impl HighlightEdge {
    /// Whether the pixel's highlight is right as drawn at one sample.
    #[must_use]
    pub fn is_drawn(self) -> bool {
        match self {
            HighlightEdge::Clear | HighlightEdge::Smooth => true,
            HighlightEdge::Hard => false,
        }
    }
}

/// The one layer's edge across a [`HighlightEdge::Smooth`] pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(in crate::render) struct SmoothEdge {
    /// The layer, numbered left to right in its expression.
    pub layer: usize,
    /// Its `s` over the box.
    pub quadratic: BoxQuadratic,
}

impl SmoothEdge {
    /// The fraction of the box inside the layer's edge, `s > 0`, with the quadratic moved to
    /// pass through `s` at the centre (its value from better frames).
    #[must_use]
    pub fn coverage(&self, s: f32) -> f32 {
        BoxQuadratic {
            centre: s,
            ..self.quadratic
        }
        .coverage_above(0.0)
    }
}

/// Per texel of a G-buffer, how its highlight's edges meet its pixel, and the edge of each
/// smooth one.
#[derive(Clone, Debug, Default)]
pub(in crate::render) struct HighlightEdges {
    pub kinds: Vec<HighlightEdge>,
    /// The slots of the [`HighlightEdge::Smooth`] texels, increasing, and their edges.
    smooth_slots: Vec<u32>,
    smooth: Vec<SmoothEdge>,
}

impl HighlightEdges {
    /// The edge across the texel in slot `slot`, when it is smooth.
    #[must_use]
    pub fn smooth(&self, slot: usize) -> Option<&SmoothEdge> {
        let slot = u32::try_from(slot).ok()?;
        let i = self.smooth_slots.binary_search(&slot).ok()?;
        Some(&self.smooth[i])
    }

    /// The slots of the texels whose values the smooth edges' quadratics are made of: the 3 × 3
    /// neighbourhood of each smooth texel of `gbuffer`, unordered, some more than once.
    pub fn neighbourhoods<'g>(&'g self, gbuffer: &'g GBuffer) -> impl Iterator<Item = usize> + 'g {
        let size = (gbuffer.width as usize, gbuffer.height as usize);
        self.smooth_slots.iter().flat_map(move |&slot| {
            let pixel = gbuffer.texels[slot as usize].pixel as usize;
            around(pixel, size).map(|n| gbuffer.slot[n] as usize)
        })
    }

    /// Makes each smooth edge's quadratic again of `s` (of its layer in `signed`) at its nine
    /// texels' settled copies (where `settled` has them): where the G-buffer's frames are
    /// interpolated, they place `s` a small part of a pixel off, and the quadratic's slopes and
    /// bends with it. An edge that no longer crosses its box smoothly is made
    /// [`HighlightEdge::Hard`].
    pub fn settle(
        &mut self,
        gbuffer: &GBuffer,
        scene: &Scene,
        signed: &SignedValues,
        settled: &SettledTexels,
    ) {
        let size = (gbuffer.width as usize, gbuffer.height as usize);
        let smooth: Vec<bool> = self
            .smooth_slots
            .par_iter()
            .zip(self.smooth.par_iter_mut())
            .with_min_len(PIXELS_PER_JOB / 16)
            .map(|(&slot, edge)| {
                let t = &gbuffer.texels[slot as usize];
                let layer = signed.layers[t.patch as usize][edge.layer];
                let mut values = [0.0f32; 9];
                for (value, n) in values.iter_mut().zip(around(t.pixel as usize, size)) {
                    let n = gbuffer.slot[n] as usize;
                    let texel = settled.get(n).unwrap_or(&gbuffer.texels[n]);
                    *value = layer.signed(&texel.frame, initial_half_vector(scene, texel));
                }
                let d = [
                    [values[0], values[1], values[2]],
                    [values[3], values[4], values[5]],
                    [values[6], values[7], values[8]],
                ];
                edge.quadratic = BoxQuadratic::through(&d);
                matches!(
                    edge.quadratic.crossing(0.0, SMOOTH_BEND, JUMP),
                    Some(LevelCrossing::Straight)
                )
            })
            .collect();
        for (&slot, still) in self.smooth_slots.iter().zip(smooth) {
            if !still {
                self.kinds[slot as usize] = HighlightEdge::Hard;
            }
        }
    }
}

/// How a pixel's highlight meets the edges of its layers, with the edge of a smooth one.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Classified {
    Clear,
    Smooth(SmoothEdge),
    Hard,
}

/// Per texel of `gbuffer`, how its highlight's edges meet its pixel ([`classify`] of the
/// layers' `s` at the nine texels of its 3 × 3 neighbourhood), [`HighlightEdge::Hard`] where a
/// neighbour is off the image, uncovered or on another patch ([`one_patch_around`], `patches`
/// per texel).
#[must_use]
pub(in crate::render) fn highlight_edges(
    gbuffer: &GBuffer,
    signed: &SignedValues,
    patches: &[u32],
) -> HighlightEdges {
    let classify_texel = |k: usize| {
        let t = &gbuffer.texels[k];
        match one_patch_around(gbuffer, patches, t) {
            Some(slots) => {
                let layers = &signed.layers[t.patch as usize];
                classify(layers, |j| slots.map(|row| row.map(|k| signed.at(k, j))))
            }
            None => Classified::Hard,
        }
    };
    // Chunk by chunk, so that only the smooth edges are kept beside the kinds.
    // Per chunk, its texels' kinds and the smooth edges among them, by slot.
    type Chunk = (Vec<HighlightEdge>, Vec<(u32, SmoothEdge)>);
    let chunks: Vec<Chunk> = gbuffer
        .texels
        .par_chunks(PIXELS_PER_JOB)
        .enumerate()
        .map(|(chunk, texels)| {
            let first = chunk * PIXELS_PER_JOB;
            let mut kinds = Vec::with_capacity(texels.len());
            let mut smooth = Vec::new();
            for k in first..first + texels.len() {
                kinds.push(match classify_texel(k) {
                    Classified::Clear => HighlightEdge::Clear,
                    Classified::Smooth(edge) => {
                        smooth.push((k as u32, edge));
                        HighlightEdge::Smooth
                    }
                    Classified::Hard => HighlightEdge::Hard,
                });
            }
            (kinds, smooth)
        })
        .collect();
    let mut edges = HighlightEdges::default();
    for (kinds, smooth) in chunks {
        edges.kinds.extend(kinds);
        for (slot, edge) in smooth {
            edges.smooth_slots.push(slot);
            edges.smooth.push(edge);
        }
    }
    edges
}

/// Whether no edge of `layers` reaches the box, from each layer's `s` at its 3 × 3
/// neighbourhood ([`classify`]).
#[must_use]
pub(in crate::render) fn highlights_clear_of_box(
    layers: &[&PreparedLayer],
    values: impl Fn(usize) -> [[f32; 3]; 3],
) -> bool {
    classify(layers, values) == Classified::Clear
}

/// How the edges of `layers` meet a pixel, from each layer's `s` at its 3 × 3 neighbourhood
/// (`values(j)[y][x]`, the pixel at `[1][1]`), one surface across it, each taken as the
/// quadratic through the nine ([`BoxQuadratic`]). A layer is clear of the box where `s` stays
/// beyond its feather's half-width `φ` over the box's [reach](BoxQuadratic::reach): `|s| −
/// reach > φ` (a masked one only where it covers none of it, `s < 0`).
///
/// - Every layer clear: [`Classified::Clear`].
/// - One layer not clear, unfeathered and unmasked, whose edge `s = 0` is near enough to
///   straight over the box that the quadratic stands for `s` there ([`BoxQuadratic::crossing`]
///   within [`SMOOTH_BEND`] and [`JUMP`]): [`Classified::Smooth`], its cover of the box
///   then taken from the quadratic itself ([`BoxQuadratic::coverage_above`]).
/// - Otherwise [`Classified::Hard`].
#[must_use]
fn classify(layers: &[&PreparedLayer], values: impl Fn(usize) -> [[f32; 3]; 3]) -> Classified {
    let mut smooth = None;
    for (j, layer) in layers.iter().enumerate() {
        let quadratic = BoxQuadratic::through(&values(j));
        let reach = quadratic.reach();
        if !(reach.is_finite() && quadratic.centre.is_finite()) {
            return Classified::Hard;
        }
        let fade = 0.5 * layer.feather();
        let inside = quadratic.centre - reach > fade;
        let outside = quadratic.centre + reach < -fade;
        if inside && layer.is_masked() {
            return Classified::Hard;
        }
        if inside || outside {
            continue;
        }
        if fade > 0.0 || layer.is_masked() || smooth.is_some() {
            return Classified::Hard;
        }
        match quadratic.crossing(0.0, SMOOTH_BEND, JUMP) {
            Some(LevelCrossing::Straight) => {
                smooth = Some(SmoothEdge {
                    layer: j,
                    quadratic,
                })
            }
            Some(LevelCrossing::Bent) | None => return Classified::Hard,
        }
    }
    smooth.map_or(Classified::Clear, Classified::Smooth)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::highlight::{Expr, Layer, Mask, PreparedExpr};
    use crate::render::fixtures::nine;

    fn prepared(layers: Vec<Layer>) -> Vec<PreparedLayer> {
        layers
            .into_iter()
            .map(|l| match Expr::Layer(l).prepare().unwrap() {
                PreparedExpr::Layer(l) => l,
                PreparedExpr::Combine(..) => unreachable!(),
            })
            .collect()
    }

    fn plain() -> Layer {
        Layer::new(Vec::new(), 0.1, [1.0, 1.0, 1.0])
    }

    #[test]
    fn one_smooth_edge_among_clear_layers_is_drawn_from_its_quadratic() {
        let layers = prepared(vec![plain(), plain()]);
        let layers: Vec<&_> = layers.iter().collect();
        // Layer 1's edge 0.2 px from the centre, gently curved; layer 0 wholly inside, by 0.3
        // past its reach.
        let edge = |x: f32, y: f32| 0.02 - 0.1 * x + 0.02 * y - 0.002 * y * y;
        let values = |j: usize| match j {
            0 => nine(|x, _| 0.5 + 0.05 * x),
            _ => nine(edge),
        };
        match classify(&layers, values) {
            Classified::Smooth(e) => {
                assert_eq!(e.layer, 1);
                assert_eq!(e.quadratic, BoxQuadratic::through(&nine(edge)));
            }
            other => panic!("{other:?}"),
        }
        // Both layers far from their edges: clear.
        let far = |j: usize| nine(move |x, _| if j == 0 { -0.5 } else { 0.5 } + 0.01 * x);
        assert_eq!(classify(&layers, far), Classified::Clear);
    }

    #[test]
    fn two_edges_a_bend_or_a_jump_is_hard() {
        let layers = prepared(vec![plain(), plain()]);
        let layers: Vec<&_> = layers.iter().collect();
        let edge = || nine(|x, y| 0.02 - 0.1 * x + 0.02 * y);
        // Both layers' edges cross the box.
        assert_eq!(classify(&layers, |_| edge()), Classified::Hard);
        // A highlight a pixel across: its edge bends right round over the box.
        let small = |j: usize| {
            if j == 0 {
                nine(|x, y| 0.01 - 0.1 * (x * x + y * y))
            } else {
                nine(|_, _| -1.0)
            }
        };
        assert_eq!(classify(&layers, small), Classified::Hard);
        // One column lies on a part of the patch far behind: s jumps there.
        let jump = |j: usize| {
            if j == 0 {
                nine(|x, _| if x > 0.5 { 0.9 } else { 0.01 - 0.05 * x })
            } else {
                nine(|_, _| -1.0)
            }
        };
        assert_eq!(classify(&layers, jump), Classified::Hard);
        // Not finite: hard.
        let nan = |_: usize| nine(|x, _| if x > 0.5 { f32::NAN } else { -1.0 });
        assert_eq!(classify(&layers, nan), Classified::Hard);
    }

    #[test]
    fn a_feathered_or_masked_layer_is_clear_only_beyond_its_fade_or_outside() {
        let mut feathered = plain();
        feathered.feather = Some(0.2);
        let mut masked = plain();
        masked.mask = Some(Mask {
            u: (0.0, 0.5),
            v: (0.0, 1.0),
            feather: 0.05,
        });
        let layers = prepared(vec![feathered, masked]);
        let layers: Vec<&_> = layers.iter().collect();
        let with = |first: [[f32; 3]; 3], second: [[f32; 3]; 3]| {
            move |j: usize| if j == 0 { first } else { second }
        };
        let outside = nine(|_, _| -1.0);
        // The feathered layer at s = 0.05 ± 0.02: within its fade (0.1 either side of 0).
        let fading = nine(|x, _| 0.05 + 0.02 * x);
        assert_eq!(classify(&layers, with(fading, outside)), Classified::Hard);
        // Beyond its fade, and the masked layer outside: clear.
        let beyond = nine(|x, _| 0.2 + 0.02 * x);
        assert_eq!(classify(&layers, with(beyond, outside)), Classified::Clear);
        // The masked layer wholly inside: the mask may cut the box.
        let inside = nine(|_, _| 1.0);
        assert_eq!(classify(&layers, with(beyond, inside)), Classified::Hard);
        // The masked layer's edge across the box: hard.
        let across = nine(|x, _| 0.01 + 0.1 * x);
        assert_eq!(classify(&layers, with(beyond, across)), Classified::Hard);
    }

    #[test]
    fn a_smooth_edge_covers_the_box_about_the_centre_it_is_given() {
        // s = 0.03 − 0.1 x: the edge at x = 0.3, covering 0.8 of the box. Given s = 0 at the
        // centre instead, the edge passes through it: a half.
        let edge = SmoothEdge {
            layer: 0,
            quadratic: BoxQuadratic::through(&nine(|x, _| 0.03 - 0.1 * x)),
        };
        assert!((edge.coverage(0.03) - 0.8).abs() < 1e-5);
        assert!((edge.coverage(0.0) - 0.5).abs() < 1e-5);
    }
}
