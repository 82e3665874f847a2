//! The shade stage: each texel's tone, then its patch's designed highlight, composited.

use glam::{Vec2, Vec3, Vec4};
use rayon::prelude::*;

use super::directions::{initial_half_vector, initial_half_vectors, view_lanes};
use super::edges::band_edge::BandEdge;
use super::edges::edge_width::SignedValues;
use super::edges::highlight_edge::{HighlightEdge, HighlightEdges};
use super::edges::settled::SettledTexels;
use super::gbuffer::{GBuffer, Texel, PIXELS_PER_JOB};
use super::scene::{Scene, Tone};
use super::xtoon_tone::{self, Views};
use crate::highlight::{ChunkScratch, Footprint, PointChunk, Shade};
use crate::math::{Lanes, LANES};
use crate::toon::ViewXToon;

/// The shaded image and what the stage did.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Shaded {
    /// Linear RGB with straight alpha (1 on surfaces, 0 on the background).
    pub colour: Vec<Vec4>,
    /// Final highlight coverage per pixel, when the scene asked for the matte.
    pub matte: Option<Vec<f32>>,
    /// `N·H` of the initial half vector per pixel (0 on the background), when asked for.
    pub n_dot_h: Option<Vec<f32>>,
    /// `N·L'` the tone reads per pixel (0 on the background), when asked for.
    pub n_dot_l: Option<Vec<f32>>,
    /// Pixels shaded.
    pub shaded: u64,
    /// Pixels on highlighted patches: the only ones a half vector was built for.
    pub highlighted: u64,
    /// Pixels on X-Toon patches (0 without X-Toon).
    pub xtoon: u64,
}

/// Per-texel results of the shade stage, kept from one frame to the next so that shading
/// allocates only the images it returns.
#[derive(Debug, Default)]
pub(super) struct ShadeBuffers {
    colour: Vec<Vec4>,
    /// Per texel, its highlight's coverage.
    coverage: Vec<f32>,
}

/// Shades every texel of `gbuffer`: `tone = ramp(N·L)`, or the X-Toon tone of its patch's
/// tone placed in the view (`views`), read from `ahead` when the detail stage computed it ahead
/// of shading; then on a patch with a highlight `H = normalize(L + V)`, the highlight
/// expression's coverage c and colour h, and `colour = (1 − c) tone + c h`.
///
/// With edge `widths` (analytic anti-aliasing,
/// [`edge_widths`](super::edges::edge_width::edge_widths)), each highlight edge covers the
/// pixel as a straight edge with the pixel's footprint of the signed inside value
/// `s = ε − ‖N − H'‖²/2` would ([`Footprint::coverage`]). Without them, edges are hard (the
/// look of Anjyo & Hiramitsu's stylized highlights, 2003), but where `highlights` (adaptive
/// anti-aliasing, [`highlight_edges`](super::edges::highlight_edge::highlight_edges)) has one
/// layer's edge crossing a pixel smoothly, which covers it as the quadratic of that layer's
/// `s` does. Likewise with `bands` ([`band_edges`](super::edges::band_edge::band_edges)), a cel
/// tone whose band edge crosses the pixel straight takes the box's mean colour
/// ([`CelRamp::shade_over_box`](crate::toon::CelRamp::shade_over_box)).
pub(super) fn shade(
    gbuffer: &GBuffer,
    scene: &Scene,
    views: &Views,
    ahead: Option<&[Vec3]>,
    edges: Edges<'_>,
    buffers: &mut ShadeBuffers,
) -> Shaded {
    let texels = gbuffer.texels.len();
    buffers.colour.resize(texels, Vec4::ZERO);
    buffers.coverage.resize(texels, 0.0);
    let counts = gbuffer
        .texels
        .par_chunks(PIXELS_PER_JOB)
        .zip(buffers.colour.par_chunks_mut(PIXELS_PER_JOB))
        .zip(buffers.coverage.par_chunks_mut(PIXELS_PER_JOB))
        .enumerate()
        .map_init(
            RunScratch::new,
            |scratch, (chunk, ((texels, colour), coverage))| {
                let first = chunk * PIXELS_PER_JOB;
                let range = first..first + texels.len();
                let edges = Edges {
                    widths: edges.widths.map(|w| &w[range.clone()]),
                    bands: edges.bands.map(|b| &b[range.clone()]),
                    highlights: edges.highlights,
                    settled: edges.settled,
                    signed: edges.signed,
                };
                let xtoon = XToonTones {
                    views,
                    ahead: ahead.map(|tones| &tones[range]),
                };
                let out = Out { colour, coverage };
                shade_texels(scene, (first, texels), edges, &xtoon, out, scratch)
            },
        )
        .reduce(Counts::default, Counts::add);
    let n_dot_h = scene.aovs.n_dot_h.then(|| {
        let values: Vec<f32> = gbuffer
            .texels
            .par_iter()
            .with_min_len(PIXELS_PER_JOB)
            .map(|t| t.frame.n.dot(initial_half_vector(scene, t)))
            .collect();
        gbuffer.gather(&values, 0.0)
    });
    let n_dot_l = scene.aovs.n_dot_l.then(|| {
        let values: Vec<f32> = gbuffer
            .texels
            .par_iter()
            .with_min_len(PIXELS_PER_JOB)
            .map(|t| scene.tone_n_dot_l(t.patch, &t.frame, t.uv, t.position))
            .collect();
        gbuffer.gather(&values, 0.0)
    });
    Shaded {
        colour: gbuffer.gather(&buffers.colour, Vec4::ZERO),
        matte: scene
            .aovs
            .matte
            .then(|| gbuffer.gather(&buffers.coverage, 0.0)),
        n_dot_h,
        n_dot_l,
        shaded: texels as u64,
        highlighted: counts.highlighted,
        xtoon: counts.xtoon,
    }
}

/// Per texel, what the shade stage knows of the pixel's box for analytic anti-aliasing: the
/// footprints of the highlight's edges, or which of them cross the box smoothly, and how the
/// tone's band edges meet it (`None`: hard).
#[derive(Clone, Copy, Debug)]
pub(super) struct Edges<'a> {
    /// Every texel's footprint (analytic anti-aliasing).
    pub widths: Option<&'a [Footprint]>,
    pub bands: Option<&'a [BandEdge]>,
    /// Without `widths`, how the highlight's edges meet each texel's box: one crossing it
    /// smoothly is drawn from its quadratic about its settled texel where there is one
    /// (adaptive anti-aliasing). For the whole G-buffer, by slot.
    pub highlights: Option<&'a HighlightEdges>,
    pub settled: Option<&'a SettledTexels>,
    /// Without `widths`, each highlight layer's signed value at each texel, found before
    /// (for the whole G-buffer, by slot): the hard shades are taken from them.
    pub signed: Option<&'a SignedValues<'a>>,
}

impl Edges<'_> {
    /// Whether the hard highlight shades are taken from `signed` (no half vector is built for
    /// them): without `widths`, where the signed values were found before.
    fn hard_from_signed(&self) -> bool {
        self.widths.is_none() && self.signed.is_some()
    }
}

/// The cel tone `ramp(N·L)` of the scene's light L at a point of `patch` with unit normal `n`
/// (black on an X-Toon patch, whose tone comes from [`XToonTones`]): the tone of a scene with no
/// designed light ([`Scene::has_designed_light`]), which needs no surface frame.
#[inline]
pub(super) fn cel_tone(scene: &Scene, patch: u32, position: Vec3, n: Vec3) -> Vec3 {
    match &scene.looks[patch as usize].tone {
        Tone::Cel(ramp) => ramp.shade(n.dot(scene.light.direction(position, n))),
        Tone::XToon(_) => Vec3::ZERO,
    }
}

/// The cel tone of texel `t`: `ramp(N·L')` of the light its patch's tone reads
/// ([`Scene::tone_n_dot_l`]), black on an X-Toon patch.
#[inline]
fn texel_cel_tone(scene: &Scene, t: &Texel) -> Vec3 {
    match &scene.looks[t.patch as usize].tone {
        Tone::Cel(ramp) => ramp.shade(scene.tone_n_dot_l(t.patch, &t.frame, t.uv, t.position)),
        Tone::XToon(_) => Vec3::ZERO,
    }
}

/// The cel tone of texel `t` over its pixel's box: [`texel_cel_tone`], or where a band edge crosses
/// the box straight, the box's mean colour about the edge's `n·l` at the centre ([`CelRamp::shade_over_box`](crate::toon::CelRamp::shade_over_box)).
#[inline]
fn cel_tone_over_box(scene: &Scene, t: &Texel, edge: BandEdge) -> Vec3 {
    match (&scene.looks[t.patch as usize].tone, edge) {
        (Tone::Cel(ramp), BandEdge::Straight { n_dot_l, footprint }) => {
            ramp.shade_over_box(n_dot_l, footprint.x, footprint.y)
        }
        (_, BandEdge::Clear | BandEdge::Hard | BandEdge::Straight { .. }) => {
            texel_cel_tone(scene, t)
        }
    }
}

/// Where the X-Toon tones of a run of texels come from: computed per texel from its patch's
/// tone placed in the view, or read from the pass that ran ahead of shading.
struct XToonTones<'a, 's> {
    views: &'a Views<'s>,
    /// The tones of the run's texels, when they ran ahead.
    ahead: Option<&'a [Vec3]>,
}

/// What the shade pass counted.
#[derive(Clone, Copy, Debug, Default)]
struct Counts {
    /// Texels on highlighted patches.
    highlighted: u64,
    /// Texels on X-Toon patches.
    xtoon: u64,
}

impl Counts {
    fn add(self, other: Self) -> Self {
        Self {
            highlighted: self.highlighted + other.highlighted,
            xtoon: self.xtoon + other.xtoon,
        }
    }
}

/// No highlight: nothing to composite.
const NO_HIGHLIGHT: Shade = Shade {
    coverage: 0.0,
    colour: Vec3::ZERO,
};

/// Where the shade of a run of texels goes: colour and highlight coverage per texel.
struct Out<'a> {
    colour: &'a mut [Vec4],
    coverage: &'a mut [f32],
}

/// The inputs and results of the tone and the highlight expression for up to [`LANES`] texels
/// of one patch, kept by each worker from one run to the next.
struct RunScratch {
    /// The view vectors of the run, filled when its tone or highlight reads them.
    view: Lanes,
    tone: xtoon_tone::ToneScratch,
    half_vectors: [Vec3; LANES],
    /// The texels' frames and half vectors.
    points: PointChunk,
    uvs: [Vec2; LANES],
    expr: ChunkScratch,
    shades: [Shade; LANES],
}

impl RunScratch {
    fn new() -> Self {
        Self {
            view: Lanes::default(),
            tone: xtoon_tone::ToneScratch::default(),
            half_vectors: [Vec3::ZERO; LANES],
            points: PointChunk::default(),
            uvs: [Vec2::ZERO; LANES],
            expr: ChunkScratch::default(),
            shades: [NO_HIGHLIGHT; LANES],
        }
    }
}

/// Shades `texels` (in pixel order) into `out`, given their edges for analytic anti-aliasing.
/// Runs of texels on one patch go through the highlight expression together, [`LANES`] at a
/// time; with per-pixel widths, one by one. Their tones are computed first, in a loop of their
/// own with the X-Toon tone inlined whole into it, rather than called texel by texel.
fn shade_texels(
    scene: &Scene,
    (first, texels): (usize, &[Texel]),
    edges: Edges<'_>,
    xtoon: &XToonTones,
    out: Out<'_>,
    scratch: &mut RunScratch,
) -> Counts {
    let mut counts = Counts::default();
    let mut start = 0;
    for run in texels.chunk_by(|a, b| a.patch == b.patch) {
        let patch = run[0].patch as usize;
        let view = xtoon.views.get(patch).and_then(Option::as_ref);
        // The view vectors are computed once for the tone and the highlight, if either reads
        // them (the highlight does unless its shades come from signed values found before).
        let reads_view = (scene.looks[patch].highlight.is_some() && !edges.hard_from_signed())
            || (xtoon.ahead.is_none() && view.is_some_and(ViewXToon::uses_view));
        for piece in run.chunks(LANES) {
            let range = start..start + piece.len();
            let widths = edges.widths.map(|w| &w[range.clone()]);
            let smooth = edges.highlights.map(|h| (first + start, h));
            let signed = edges.signed.map(|s| (first + start, s));
            if reads_view {
                view_lanes(scene, piece, &mut scratch.view);
            }
            let mut tones = [Vec3::ZERO; LANES];
            let tones = &mut tones[..piece.len()];
            match (view, xtoon.ahead) {
                (None, _) => {
                    for (k, (tone, t)) in tones.iter_mut().zip(piece).enumerate() {
                        let edge = edges.bands.map_or(BandEdge::Hard, |b| b[start + k]);
                        *tone = cel_tone_over_box(scene, t, edge);
                    }
                }
                (Some(_), Some(ahead)) => tones.copy_from_slice(&ahead[range.clone()]),
                (Some(view), None) => {
                    xtoon_tone::shade_texels(
                        view,
                        scene,
                        piece,
                        &scratch.view,
                        &mut scratch.tone,
                        tones,
                    );
                }
            }
            let found = Found {
                smooth,
                settled: edges.settled,
                signed,
            };
            let shades = highlight(scene, piece, widths, found, scratch);
            let len = piece.len() as u64;
            counts.highlighted += if shades.is_some() { len } else { 0 };
            counts.xtoon += if view.is_some() { len } else { 0 };
            for (k, &tone) in tones.iter().enumerate() {
                let shade = shades.map_or(NO_HIGHLIGHT, |s| s[k]);
                out.colour[start + k] = tone.lerp(shade.colour, shade.coverage).extend(1.0);
                out.coverage[start + k] = shade.coverage;
            }
            start = range.end;
        }
    }
    counts
}

/// What the edge-width stage found of a run of texels' highlight, each by the first texel's
/// slot and then per slot of the G-buffer.
#[derive(Clone, Copy)]
struct Found<'a> {
    /// How each texel's highlight edges meet its box.
    smooth: Option<(usize, &'a HighlightEdges)>,
    /// The texels evaluated again in the settings' frames.
    settled: Option<&'a SettledTexels>,
    /// Each layer's signed value at each texel.
    signed: Option<(usize, &'a SignedValues<'a>)>,
}

/// The highlight shades of up to [`LANES`] texels on one patch, or `None` when the patch has no
/// highlight (no half vector is built then): with `widths`, each with its footprint; else hard,
/// from the signed values `found` where it has them, but where `found.smooth` has an edge
/// crossing the box smoothly, with that edge's cover of the box
/// ([`SmoothEdge::coverage`](super::edges::highlight_edge::SmoothEdge::coverage)) about the `s`
/// of the texel's settled copy where there is one.
fn highlight<'s>(
    scene: &Scene,
    texels: &[Texel],
    widths: Option<&[Footprint]>,
    found: Found<'_>,
    scratch: &'s mut RunScratch,
) -> Option<&'s [Shade]> {
    let expr = scene.looks[texels[0].patch as usize].highlight.as_ref()?;
    let n = texels.len();
    let shades = &mut scratch.shades[..n];
    match (widths, found.signed) {
        (Some(widths), _) => {
            let hs = &mut scratch.half_vectors[..n];
            initial_half_vectors(scene, texels, &scratch.view, hs);
            for (k, (shade, t)) in shades.iter_mut().zip(texels).enumerate() {
                *shade = expr.eval(&t.frame, t.uv, hs[k], widths[k]);
            }
        }
        (None, Some((first, signed))) => {
            for (k, (shade, t)) in shades.iter_mut().zip(texels).enumerate() {
                *shade = expr.eval_signed(signed.of(first + k), t.uv, Footprint::HARD);
            }
        }
        (None, None) => {
            let hs = &mut scratch.half_vectors[..n];
            initial_half_vectors(scene, texels, &scratch.view, hs);
            scratch.points.set(n, |k| (texels[k].frame, hs[k]));
            for (uv, t) in scratch.uvs.iter_mut().zip(texels) {
                *uv = t.uv;
            }
            let uvs = &scratch.uvs[..n];
            expr.eval_chunk(
                &scratch.points,
                uvs,
                Footprint::HARD,
                &mut scratch.expr,
                shades,
            );
        }
    }
    if let (None, Some((first, edges))) = (widths, found.smooth) {
        for (k, shade) in shades.iter_mut().enumerate() {
            let slot = first + k;
            match edges.kinds[slot] {
                HighlightEdge::Smooth => {
                    let Some(edge) = edges.smooth(slot) else {
                        continue;
                    };
                    let t = found
                        .settled
                        .and_then(|s| s.get(slot))
                        .unwrap_or(&texels[k]);
                    let h = initial_half_vector(scene, t);
                    let cover = |s: f32| edge.coverage(s);
                    *shade = expr.eval_with_edge(&t.frame, t.uv, h, edge.layer, &cover);
                }
                HighlightEdge::Clear | HighlightEdge::Hard => {}
            }
        }
    }
    Some(shades)
}
