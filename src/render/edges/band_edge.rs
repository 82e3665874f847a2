//! Tone-band edges for analytic anti-aliasing: per texel, how the edges of its cel ramp's
//! bands meet its pixel.

use rayon::prelude::*;

use super::settled::SettledTexels;
use crate::highlight::Footprint;
use crate::math::{BoxQuadratic, LevelCrossing};
use crate::render::gbuffer::{GBuffer, PIXELS_PER_JOB};
use crate::render::neighbourhood::one_patch_around;
use crate::render::scene::{Scene, Tone};
use crate::toon::CelRamp;

/// How a pixel's cel tone meets the edges of its ramp's bands.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(in crate::render) enum BandEdge {
    /// Its box lies inside one patch and no band edge crosses it: its centre's colour is the
    /// box's.
    Clear,
    /// A band edge crosses its box inside one patch, straight across it: the box takes the
    /// mean colour of a straight edge of `n·l` ([`CelRamp::shade_over_box`]) at the pixel's
    /// centre, with this footprint.
    Straight { n_dot_l: f32, footprint: Footprint },
    /// Neither: beside another patch, a silhouette or the image's edge, a band edge that bends
    /// over the pixel or jumps there (one part of a patch passing in front of another), or a
    /// tone that is not a cel ramp. Its tone is its centre's, hard, as without anti-aliasing.
    Hard,
}

impl BandEdge {
    /// Whether the pixel's tone is right as drawn: its box lies inside one patch, and every band
    /// edge crossing it is drawn as a straight edge.
    #[must_use]
    pub fn is_drawn(self) -> bool {
        match self {
            BandEdge::Clear | BandEdge::Straight { .. } => true,
            BandEdge::Hard => false,
        }
    }
}

/// The most of a pixel's area that a band edge drawn straight may misplace, by the bend of `n·l`
/// over the box ([`classify`]): a third of the sixteenth of a pixel by which 4 × 4 samples place
/// an edge.
pub(in crate::render) const STRAIGHT_AREA: f32 = 0.02;

/// The most the slope of `n·l` may change along itself from one pixel to the next, against
/// itself, for the quadratic to stand for `n·l` over the box: more is a jump, one part of a
/// patch in front of another, or the surface turning away toward a silhouette.
pub(in crate::render) const JUMP: f32 = 0.5;

/// Per texel of `gbuffer`, how its cel tone's band edges meet its pixel ([`classify`] of `n·l`
/// at the nine texels of its 3 × 3 neighbourhood), [`BandEdge::Hard`] where a neighbour is off
/// the image, uncovered or on another patch ([`one_patch_around`], `patches` per texel), or
/// the tone is not a cel ramp.
#[must_use]
pub(in crate::render) fn band_edges(
    gbuffer: &GBuffer,
    scene: &Scene,
    patches: &[u32],
) -> Vec<BandEdge> {
    // Per texel its n·l, side by side: the neighbours are looked up by it, and the texels
    // themselves are large.
    let n_dot_l: Vec<f32> = gbuffer
        .texels
        .par_iter()
        .with_min_len(PIXELS_PER_JOB)
        .map(|t| match &scene.looks[t.patch as usize].tone {
            Tone::Cel(_) => scene.tone_n_dot_l(t.patch, &t.frame, t.uv, t.position),
            Tone::XToon(_) => 0.0,
        })
        .collect();
    gbuffer
        .texels
        .par_iter()
        .with_min_len(PIXELS_PER_JOB)
        .map(|t| {
            let ramp = match &scene.looks[t.patch as usize].tone {
                Tone::Cel(ramp) => ramp,
                Tone::XToon(_) => return BandEdge::Hard,
            };
            match one_patch_around(gbuffer, patches, t) {
                Some(slots) => classify(ramp, &slots.map(|row| row.map(|k| n_dot_l[k]))),
                None => BandEdge::Hard,
            }
        })
        .collect()
}

/// Puts in each [`BandEdge::Straight`] of `edges` (per texel) the `n·l` of its texel's settled
/// frame, where `settled` has one.
pub(in crate::render) fn settle_straight_edges(
    edges: &mut [BandEdge],
    settled: &SettledTexels,
    scene: &Scene,
) {
    for (slot, t) in settled.iter() {
        if let BandEdge::Straight { n_dot_l, .. } = &mut edges[slot] {
            *n_dot_l = scene.tone_n_dot_l(t.patch, &t.frame, t.uv, t.position);
        }
    }
}

/// Whether no band edge of `ramp` reaches the box, from `n·l` at its 3 × 3 neighbourhood
/// ([`classify`]).
#[must_use]
pub(in crate::render) fn band_clear_of_box(ramp: &CelRamp, d: &[[f32; 3]; 3]) -> bool {
    classify(ramp, d) == BandEdge::Clear
}

/// How the bands of `ramp` meet a pixel from `n·l` at its 3 × 3 neighbourhood (`d[y][x]`, the
/// pixel at `d[1][1]`), one surface across it, taken as the quadratic through the nine
/// ([`BoxQuadratic`]):
///
/// - no threshold within its [reach](BoxQuadratic::reach) of `d`: [`BandEdge::Clear`];
/// - else, where the edge of the nearest threshold crosses the box straight, misplaced by
///   less than [`STRAIGHT_AREA`] of the pixel and with the slope changing by at most [`JUMP`]
///   of itself ([`BoxQuadratic::crossing`]): [`BandEdge::Straight`] with `d` and the footprint
///   `(|g_x|, |g_y|)`;
/// - else (a bend, or a jump: one part of the patch in front of another) [`BandEdge::Hard`].
#[must_use]
fn classify(ramp: &CelRamp, d: &[[f32; 3]; 3]) -> BandEdge {
    let q = BoxQuadratic::through(d);
    let reach = q.reach();
    if !(reach.is_finite() && q.centre.is_finite()) {
        return BandEdge::Hard;
    }
    if ramp
        .uniform_between(q.centre - reach, q.centre + reach)
        .is_some()
    {
        return BandEdge::Clear;
    }
    let Some(threshold) = ramp.nearest_threshold(q.centre) else {
        return BandEdge::Hard;
    };
    match q.crossing(threshold, STRAIGHT_AREA, JUMP) {
        Some(LevelCrossing::Straight) => BandEdge::Straight {
            n_dot_l: q.centre,
            footprint: Footprint {
                x: q.gx.abs(),
                y: q.gy.abs(),
            },
        },
        Some(LevelCrossing::Bent) | None => BandEdge::Hard,
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::render::fixtures::nine;

    fn ramp() -> CelRamp {
        CelRamp::two_tone(Vec3::ZERO, Vec3::ONE, 0.1)
    }

    #[test]
    fn a_straight_edge_across_the_box_is_drawn_with_its_slopes() {
        // n·l = 0.12 − 0.03 x + 0.01 y: the threshold 0.1 is 0.02 away, the box reaches 0.02.
        let d = nine(|x, y| 0.12 - 0.03 * x + 0.01 * y);
        match classify(&ramp(), &d) {
            BandEdge::Straight {
                n_dot_l,
                footprint: f,
            } => {
                assert!(
                    (f.x - 0.03).abs() < 1e-6 && (f.y - 0.01).abs() < 1e-6,
                    "{f:?}"
                );
                assert_eq!(n_dot_l, d[1][1]);
            }
            other => panic!("{other:?}"),
        }
        // One pixel farther on, the box no longer reaches the edge.
        let d = nine(|x, y| 0.15 - 0.03 * x + 0.01 * y);
        assert_eq!(classify(&ramp(), &d), BandEdge::Clear);
    }

    #[test]
    fn a_bend_or_a_jump_over_the_box_is_hard() {
        // Curving along the slope, with the edge 0.4 px from the centre: the curve moves it by
        // c 0.4²/(2 · 0.01), 0.0032 of the pixel for c = 0.0004, 0.032 for c = 0.004.
        let along = |c: f32| nine(move |x, _| 0.096 + 0.01 * x + 0.5 * c * x * x);
        assert!(matches!(
            classify(&ramp(), &along(0.0004)),
            BandEdge::Straight { .. }
        ));
        assert_eq!(classify(&ramp(), &along(0.004)), BandEdge::Hard);
        // Bending across the slope: on average c/(24 · 0.01) of the pixel, 0.004 for
        // c = 0.001, 0.033 for c = 0.008.
        let across = |c: f32| nine(move |x, y| 0.1 + 0.01 * y + 0.5 * c * x * x);
        assert!(matches!(
            classify(&ramp(), &across(0.001)),
            BandEdge::Straight { .. }
        ));
        assert_eq!(classify(&ramp(), &across(0.008)), BandEdge::Hard);
        // One column lies on a part of the patch far behind: n·l jumps there.
        let jump = nine(|x, _| if x > 0.5 { 0.9 } else { 0.1 + 0.01 * x });
        assert_eq!(classify(&ramp(), &jump), BandEdge::Hard);
        // Not finite: hard.
        let nan = nine(|x, _| if x > 0.5 { f32::NAN } else { 0.1 });
        assert_eq!(classify(&ramp(), &nan), BandEdge::Hard);
    }

    #[test]
    fn the_curved_reach_finds_an_edge_the_slopes_alone_miss() {
        // A saddle, flat along the centre row and column, that rises past the threshold toward
        // two corners of the box (0.05 + 0.3 · ¼ = 0.125 there): no slope, all bend.
        let d = nine(|x, y| 0.05 + 0.3 * x * y);
        assert!(d[1][1] < 0.1 && d[1][2] == d[1][0] && d[2][1] == d[0][1]);
        assert_eq!(classify(&ramp(), &d), BandEdge::Hard);
    }
}
