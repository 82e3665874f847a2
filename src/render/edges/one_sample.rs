//! The edges at one sample: how the edges of the tone's bands, of the highlights and of the
//! trims meet each pixel, whether the pixel is drawn right at one sample, and the highlight's
//! edge widths ([`Stage::EdgeWidths`], [`Stage::TrimEdges`]).

use glam::Mat4;
use rayon::prelude::*;

use super::band_edge::{band_edges, settle_straight_edges, BandEdge};
use super::edge_width::{edge_widths_of, signed_values, EdgeWidths, SignedValues};
use super::highlight_edge::{highlight_edges, HighlightEdge, HighlightEdges};
use super::settled::SettledTexels;
use super::trim_edge::TrimEdges;
use crate::render::gbuffer::{GBuffer, EMPTY, PIXELS_PER_JOB};
use crate::render::neighbourhood::around;
use crate::render::scene::{Scene, Tone};
use crate::render::settings::{Antialias, FrameMode};
use crate::render::shade::Edges;
#[cfg(doc)]
use crate::render::Stage;

/// What [`Stage::EdgeWidths`] finds per texel.
#[derive(Default)]
pub(in crate::render) struct OneSampleEdges<'s> {
    /// Each highlight layer's signed value, on a frame with highlights: the shade stage's, for
    /// the texels it shades with hard edges.
    pub signed: Option<SignedValues<'s>>,
    /// The highlight's edge widths, on a frame with highlights.
    pub widths: Option<EdgeWidths>,
    /// How the tone's band edges meet the pixel, on a frame with banded cel ramps.
    pub bands: Option<Vec<BandEdge>>,
    /// How the highlight's edges meet the pixel, on a frame with highlights under adaptive
    /// anti-aliasing.
    pub highlights: Option<HighlightEdges>,
    /// Whether the pixel's colour is right as drawn at one sample, under adaptive
    /// anti-aliasing ([`drawn`]).
    pub drawn: Option<Vec<bool>>,
    /// Where the G-buffer's frames are interpolated, the texels the one-sample pass draws its
    /// edges from, with the settings' frames: the centres of the pixels a band edge crosses
    /// straight, and the neighbourhoods of those a highlight edge crosses smoothly.
    pub settled: SettledTexels,
    /// The pixels about the rims of trims drawn right at one sample, under adaptive
    /// anti-aliasing on a frame with trimmed patches
    /// ([`find_trim_edges`](super::trim_edge::find_trim_edges)).
    pub trims: Option<TrimEdges>,
    /// The patch of each texel, side by side: the neighbours are looked up by patch, and the
    /// texels themselves are large.
    pub patches: Vec<u32>,
}

impl OneSampleEdges<'_> {
    /// What the one-sample shading takes of them under `antialias`: under analytic
    /// anti-aliasing the highlight footprints of every pixel; under adaptive anti-aliasing the
    /// highlight edges that cross a pixel smoothly alone, since a pixel any other highlight
    /// edge crosses is drawn again at k × k samples, each with its own footprint (hard edges
    /// there mark only the pixels the edges cross, where analytic ones also mark their
    /// neighbours, which a partly covered pixel beside them differs from).
    #[must_use]
    pub(in crate::render) fn shading(&self, antialias: Antialias) -> Edges<'_> {
        let adaptive = match antialias {
            Antialias::Adaptive(_) => true,
            Antialias::None | Antialias::Analytic | Antialias::Supersample(_) => false,
        };
        Edges {
            widths: self
                .widths
                .as_ref()
                .filter(|_| !adaptive)
                .map(|w| w.footprints.as_slice()),
            bands: self.bands.as_deref(),
            highlights: self.highlights.as_ref(),
            settled: Some(&self.settled),
            signed: self.signed.as_ref(),
        }
    }
}

impl<'s> OneSampleEdges<'s> {
    /// [`Stage::EdgeWidths`] up to the widths: per texel, how the tone's band edges meet the
    /// pixel; under `adaptive` anti-aliasing also how the highlight's edges meet it and whether
    /// it is [`drawn`] right at one sample. With `settle`, the view-projection and the
    /// settings' frames where the G-buffer's are interpolated, the texels the straight band
    /// edges and smooth highlight edges are drawn from are evaluated again in those frames
    /// ([`SettledTexels`]). Returns the frames evaluated; the widths are taken once
    /// [`Stage::TrimEdges`] has drawn what it draws ([`take_widths`](Self::take_widths)).
    #[must_use]
    pub(in crate::render) fn find(
        gbuffer: &GBuffer,
        scene: &'s Scene,
        adaptive: bool,
        settle: Option<(Mat4, FrameMode)>,
    ) -> (Self, u64) {
        let mut frames = 0;
        let patches = patches_of(gbuffer);
        let signed = scene
            .has_highlights()
            .then(|| signed_values(gbuffer, scene));
        let mut highlights = signed
            .as_ref()
            .filter(|_| adaptive)
            .map(|s| highlight_edges(gbuffer, s, &patches));
        let mut bands = scene
            .has_band_edges()
            .then(|| band_edges(gbuffer, scene, &patches));
        let settled = match settle {
            Some((view_projection, mode)) => {
                // The centres of the pixels a band edge crosses straight, and the
                // neighbourhoods of those a highlight edge crosses smoothly.
                let mut picked = vec![false; gbuffer.texels.len()];
                for (pick, band) in picked.iter_mut().zip(bands.iter().flatten()) {
                    *pick = matches!(band, BandEdge::Straight { .. });
                }
                for slot in highlights.iter().flat_map(|h| h.neighbourhoods(gbuffer)) {
                    picked[slot] = true;
                }
                let (settled, evaluated) =
                    SettledTexels::evaluate(gbuffer, scene, view_projection, mode, &picked);
                frames = evaluated;
                if let Some(bands) = &mut bands {
                    settle_straight_edges(bands, &settled, scene);
                }
                if let (Some(highlights), Some(signed)) = (&mut highlights, &signed) {
                    highlights.settle(gbuffer, scene, signed, &settled);
                }
                settled
            }
            None => SettledTexels::default(),
        };
        let drawn = adaptive.then(|| {
            let kinds = highlights.as_ref().map(|h| h.kinds.as_slice());
            drawn(gbuffer, scene, bands.as_deref(), kinds)
        });
        let edges = Self {
            signed,
            widths: None,
            bands,
            highlights,
            drawn,
            settled,
            trims: None,
            patches,
        };
        (edges, frames)
    }

    /// Takes the trim edges of [`Stage::TrimEdges`]: the pixels about the rims of trimmed
    /// patches they draw right are [`drawn`] right.
    pub(in crate::render) fn add_trims(&mut self, gbuffer: &GBuffer, trims: TrimEdges) {
        if let Some(drawn) = &mut self.drawn {
            for (&slot, _) in gbuffer.slot.iter().zip(&trims.drawn).filter(|(_, &d)| d) {
                if slot != EMPTY {
                    drawn[slot as usize] = true;
                }
            }
        }
        self.trims = Some(trims);
    }

    /// The rest of [`Stage::EdgeWidths`]: per texel, the highlight's edge width over the
    /// pixel's footprint, on a frame with highlights.
    pub(in crate::render) fn take_widths(&mut self, gbuffer: &GBuffer) {
        // Under adaptive anti-aliasing the widths serve the samples of the pixels that are
        // not drawn (started from the texels around them) and mark those a highlight may
        // cross unseen: they are wanted only beside such pixels.
        let wanted = self
            .drawn
            .as_ref()
            .map(|drawn| beside_undrawn(gbuffer, drawn));
        self.widths = self
            .signed
            .as_ref()
            .map(|s| edge_widths_of(gbuffer, s, &self.patches, wanted.as_deref()));
    }
}

/// The patch of each texel of `gbuffer`, side by side.
#[must_use]
fn patches_of(gbuffer: &GBuffer) -> Vec<u32> {
    gbuffer.texels.iter().map(|t| t.patch).collect()
}

/// Per texel of `gbuffer`, whether some texel of its 3 × 3 neighbourhood is not `drawn` (per
/// texel): the neighbourhoods of the few texels that are not, marked from each. A texel beside
/// an uncovered pixel is never drawn right, so it marks itself.
#[must_use]
fn beside_undrawn(gbuffer: &GBuffer, drawn: &[bool]) -> Vec<bool> {
    let size = (gbuffer.width as usize, gbuffer.height as usize);
    let mut beside = vec![false; drawn.len()];
    for (t, _) in gbuffer.texels.iter().zip(drawn).filter(|(_, &d)| !d) {
        for n in around(t.pixel as usize, size) {
            let slot = gbuffer.slot[n];
            if slot != EMPTY {
                beside[slot as usize] = true;
            }
        }
    }
    beside
}

/// Per texel of `gbuffer`, whether its pixel's colour is right as drawn at one sample: its box
/// lies inside one patch, its tone is a cel ramp whose band edges are clear of the box or
/// cross it straight (any cel ramp without `bands`), its highlight's edges are clear of the box
/// or cross it smoothly (any highlight without `highlights`), and not both a band edge and a
/// highlight edge cross it. More samples would not change such a pixel; at least one of `bands`
/// and `highlights` is given, each of which sees whether the box lies inside one patch.
#[must_use]
fn drawn(
    gbuffer: &GBuffer,
    scene: &Scene,
    bands: Option<&[BandEdge]>,
    highlights: Option<&[HighlightEdge]>,
) -> Vec<bool> {
    gbuffer
        .texels
        .par_iter()
        .enumerate()
        .with_min_len(PIXELS_PER_JOB)
        .map(|(k, t)| {
            let band = match bands {
                Some(bands) => bands[k],
                None => match scene.looks[t.patch as usize].tone {
                    Tone::Cel(_) => BandEdge::Clear,
                    Tone::XToon(_) => BandEdge::Hard,
                },
            };
            let highlight = highlights.map_or(HighlightEdge::Clear, |h| h[k]);
            let both = matches!(
                (band, highlight),
                (BandEdge::Straight { .. }, HighlightEdge::Smooth)
            );
            band.is_drawn() && highlight.is_drawn() && !both
        })
        .collect()
}
