//! Tone-band edges for analytic anti-aliasing: per texel, how the edges of its cel ramp's
//! bands meet its pixel.

use glam::Mat4;
use rayon::prelude::*;

use super::gbuffer::{Evaluate, GBuffer, Texel, EMPTY, PIXELS_PER_JOB};
use super::scene::{Scene, Tone};
use super::settings::FrameMode;
use crate::highlight::Footprint;
use crate::toon::CelRamp;

/// How a pixel's cel tone meets the edges of its ramp's bands.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum BandEdge {
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
pub(super) const STRAIGHT_AREA: f32 = 0.02;

/// The most the slope of `n·l` may change along itself from one pixel to the next, against
/// itself, for the quadratic to stand for `n·l` over the box: more is a jump, one part of a
/// patch in front of another, or the surface turning away toward a silhouette.
const JUMP: f32 = 0.5;

/// Per texel of `gbuffer`, how its cel tone's band edges meet its pixel ([`classify`] of `n·l`
/// at the nine texels of its 3 × 3 neighbourhood), [`BandEdge::Hard`] where a neighbour is off
/// the image, uncovered or on another patch, or the tone is not a cel ramp.
#[must_use]
pub(super) fn band_edges(gbuffer: &GBuffer, scene: &Scene) -> Vec<BandEdge> {
    // Per texel its patch and n·l, side by side: the neighbours are looked up by them, and the
    // texels themselves are large.
    let seen: Vec<(u32, f32)> = gbuffer
        .texels
        .par_iter()
        .with_min_len(PIXELS_PER_JOB)
        .map(|t| {
            let n_dot_l = match &scene.looks[t.patch as usize].tone {
                Tone::Cel(_) => {
                    let n = t.frame.n;
                    n.dot(scene.light.direction(t.position, n))
                }
                Tone::XToon(_) => 0.0,
            };
            (t.patch, n_dot_l)
        })
        .collect();
    let (w, h) = (gbuffer.width as usize, gbuffer.height as usize);
    gbuffer
        .texels
        .par_iter()
        .with_min_len(PIXELS_PER_JOB)
        .map(|t| {
            let ramp = match &scene.looks[t.patch as usize].tone {
                Tone::Cel(ramp) => ramp,
                Tone::XToon(_) => return BandEdge::Hard,
            };
            let i = t.pixel as usize;
            let (x, y) = (i % w, i / w);
            if x == 0 || y == 0 || x + 1 >= w || y + 1 >= h {
                return BandEdge::Hard;
            }
            let mut values = [[0.0f32; 3]; 3];
            for (dy, row) in values.iter_mut().enumerate() {
                for (dx, value) in row.iter_mut().enumerate() {
                    let slot = gbuffer.slot[(y + dy - 1) * w + x + dx - 1];
                    if slot == EMPTY {
                        return BandEdge::Hard;
                    }
                    let (patch, n_dot_l) = seen[slot as usize];
                    if patch != t.patch {
                        return BandEdge::Hard;
                    }
                    *value = n_dot_l;
                }
            }
            classify(ramp, &values)
        })
        .collect()
}

/// Puts in each [`BandEdge::Straight`] of `edges` (per texel of `gbuffer`) the `n·l` of its
/// texel's frame evaluated in `mode` ([`GBuffer::evaluate_frames`]): where the G-buffer holds
/// interpolated frames and the settings ask for better ones, the pixels a band edge crosses at
/// one sample take their colour from where the edge is, a small part of a pixel from where
/// the interpolated normals put it (the slopes stay the interpolated ones: an error in them
/// moves the edge by its distance from the centre times their relative error). Returns the
/// frames evaluated.
pub(super) fn settle_straight_edges(
    edges: &mut [BandEdge],
    gbuffer: &GBuffer,
    scene: &Scene,
    view_projection: Mat4,
    mode: FrameMode,
) -> u64 {
    let straight = |e: &BandEdge| matches!(e, BandEdge::Straight { .. });
    let mut texels: Vec<Texel> = edges
        .iter()
        .zip(&gbuffer.texels)
        .filter(|(e, _)| straight(e))
        .map(|(_, t)| *t)
        .collect();
    let frames = GBuffer::evaluate_frames(
        &mut texels,
        scene.library,
        &scene.camera,
        view_projection,
        (gbuffer.width, gbuffer.height),
        mode,
        Evaluate::Full,
    );
    for (edge, t) in edges.iter_mut().filter(|e| straight(e)).zip(&texels) {
        if let BandEdge::Straight { n_dot_l, .. } = edge {
            let n = t.frame.n;
            *n_dot_l = n.dot(scene.light.direction(t.position, n));
        }
    }
    frames
}

/// How the bands of `ramp` meet a pixel from `n·l` at its 3 × 3 neighbourhood (`d[y][x]`, the
/// pixel at `d[1][1]`), one surface across it. Over the box, `n·l` is taken as the quadratic
/// through the nine: slope `g = ((d₊ₓ − d₋ₓ)/2, (d₊ᵧ − d₋ᵧ)/2)` and second differences
/// `c_xx = d₊ₓ + d₋ₓ − 2d`, `c_yy` likewise, `c_xy = (d₊₊ − d₊₋ − d₋₊ + d₋₋)/4`. Within the box
/// (`|x|, |y| ≤ ½`) its linear part moves by at most `(|g_x| + |g_y|)/2` and its quadratic part
/// by at most `(|c_xx| + |c_yy|)/8 + |c_xy|/4`:
///
/// - no threshold within that reach of `d`: [`BandEdge::Clear`];
/// - else, where drawing the edge of the nearest threshold `t` straight misplaces less than
///   [`STRAIGHT_AREA`] of the pixel: [`BandEdge::Straight`] with `d` and the footprint
///   `(|g_x|, |g_y|)`.
///   With `c_gg` and `c_pp` the second derivatives along `g` and across it, the straight edge
///   lies at `r = (t − d)/‖g‖` along `g`; the curvature along `g` moves it by `c_gg r²/(2‖g‖)`,
///   and the bend across `g` (`c_pp x²/(2‖g‖)` at `x` along the edge) takes the mean of that
///   over the box's width, `c_pp/(24‖g‖)`; and the slope changes along itself by at most
///   [`JUMP`] of itself from one pixel to the next (`|c_gg| ≤ JUMP ‖g‖`);
/// - else (a bend, or a jump: one part of the patch in front of another) [`BandEdge::Hard`].
#[must_use]
fn classify(ramp: &CelRamp, d: &[[f32; 3]; 3]) -> BandEdge {
    let centre = d[1][1];
    let (gx, gy) = (0.5 * (d[1][2] - d[1][0]), 0.5 * (d[2][1] - d[0][1]));
    let cxx = d[1][2] + d[1][0] - 2.0 * centre;
    let cyy = d[2][1] + d[0][1] - 2.0 * centre;
    let cxy = 0.25 * (d[2][2] - d[2][0] - d[0][2] + d[0][0]);
    let bend = 0.125 * (cxx.abs() + cyy.abs()) + 0.25 * cxy.abs();
    let reach = 0.5 * (gx.abs() + gy.abs()) + bend;
    if !(reach.is_finite() && centre.is_finite()) {
        return BandEdge::Hard;
    }
    if ramp
        .uniform_between(centre - reach, centre + reach)
        .is_some()
    {
        return BandEdge::Clear;
    }
    let slope2 = gx * gx + gy * gy;
    let slope = slope2.sqrt();
    let Some(threshold) = ramp.nearest_threshold(centre) else {
        return BandEdge::Hard;
    };
    if slope2 <= 0.0 {
        return BandEdge::Hard;
    }
    let along = (gx * gx * cxx + 2.0 * gx * gy * cxy + gy * gy * cyy) / slope2;
    let across = (gy * gy * cxx - 2.0 * gx * gy * cxy + gx * gx * cyy) / slope2;
    let r = (threshold - centre) / slope;
    let misplaced = (0.5 * along.abs() * r * r + across.abs() / 24.0) / slope;
    if misplaced <= STRAIGHT_AREA && along.abs() <= JUMP * slope {
        BandEdge::Straight {
            n_dot_l: centre,
            footprint: Footprint {
                x: gx.abs(),
                y: gy.abs(),
            },
        }
    } else {
        BandEdge::Hard
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;

    fn ramp() -> CelRamp {
        CelRamp::two_tone(Vec3::ZERO, Vec3::ONE, 0.1)
    }

    /// `f` at the nine centres around the pixel.
    fn around(f: impl Fn(f32, f32) -> f32) -> [[f32; 3]; 3] {
        std::array::from_fn(|y| std::array::from_fn(|x| f(x as f32 - 1.0, y as f32 - 1.0)))
    }

    #[test]
    fn a_straight_edge_across_the_box_is_drawn_with_its_slopes() {
        // n·l = 0.12 − 0.03 x + 0.01 y: the threshold 0.1 is 0.02 away, the box reaches 0.02.
        let d = around(|x, y| 0.12 - 0.03 * x + 0.01 * y);
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
        let d = around(|x, y| 0.15 - 0.03 * x + 0.01 * y);
        assert_eq!(classify(&ramp(), &d), BandEdge::Clear);
    }

    #[test]
    fn a_bend_or_a_jump_over_the_box_is_hard() {
        // Curving along the slope, with the edge 0.4 px from the centre: the curve moves it by
        // c 0.4²/(2 · 0.01), 0.0032 of the pixel for c = 0.0004, 0.032 for c = 0.004.
        let along = |c: f32| around(move |x, _| 0.096 + 0.01 * x + 0.5 * c * x * x);
        assert!(matches!(
            classify(&ramp(), &along(0.0004)),
            BandEdge::Straight { .. }
        ));
        assert_eq!(classify(&ramp(), &along(0.004)), BandEdge::Hard);
        // Bending across the slope: on average c/(24 · 0.01) of the pixel, 0.004 for
        // c = 0.001, 0.033 for c = 0.008.
        let across = |c: f32| around(move |x, y| 0.1 + 0.01 * y + 0.5 * c * x * x);
        assert!(matches!(
            classify(&ramp(), &across(0.001)),
            BandEdge::Straight { .. }
        ));
        assert_eq!(classify(&ramp(), &across(0.008)), BandEdge::Hard);
        // One column lies on a part of the patch far behind: n·l jumps there.
        let jump = around(|x, _| if x > 0.5 { 0.9 } else { 0.1 + 0.01 * x });
        assert_eq!(classify(&ramp(), &jump), BandEdge::Hard);
        // Not finite: hard.
        let nan = around(|x, _| if x > 0.5 { f32::NAN } else { 0.1 });
        assert_eq!(classify(&ramp(), &nan), BandEdge::Hard);
    }

    #[test]
    fn the_curved_reach_finds_an_edge_the_slopes_alone_miss() {
        // A saddle, flat along the centre row and column, that rises past the threshold toward
        // two corners of the box (0.05 + 0.3 · ¼ = 0.125 there): no slope, all bend.
        let d = around(|x, y| 0.05 + 0.3 * x * y);
        assert!(d[1][1] < 0.1 && d[1][2] == d[1][0] && d[2][1] == d[0][1]);
        assert_eq!(classify(&ramp(), &d), BandEdge::Hard);
    }
}
