//! The shade pass: cel tone, then each patch's designed highlight, composited per pixel.

use glam::{Vec2, Vec3, Vec4};
use rayon::prelude::*;

use super::gbuffer::{GBuffer, Texel, EMPTY, PIXELS_PER_JOB};
use super::scene::{Scene, Tone};
use super::stats::StageStats;
use super::xtoon;
use crate::highlight::{half_vector, PreparedExpr, PreparedLayer, Shade, TangentFrame};

/// The shaded image and what the pass did.
#[derive(Clone, Debug, PartialEq)]
pub struct Shaded {
    /// Linear RGB with straight alpha (1 on surfaces, 0 on the background).
    pub colour: Vec<Vec4>,
    /// Final highlight coverage per pixel, when the scene asked for the matte.
    pub matte: Option<Vec<f32>>,
    /// `N·H` of the initial half vector per pixel (0 on the background), when asked for.
    pub n_dot_h: Option<Vec<f32>>,
    /// Pixels shaded.
    pub shaded: u64,
    /// Pixels on highlighted patches: the only ones a half vector was built for.
    pub highlighted: u64,
    /// The X-Toon detail pass: pixels on X-Toon patches (0 without X-Toon) and its time.
    pub detail: StageStats,
}

/// Shades every covered pixel: `tone = ramp(N·L)`, or the X-Toon tone from the detail pass,
/// then on a patch with a highlight `H = normalize(L + V)`, the highlight expression's coverage
/// c and colour h, and `colour = (1 − c) tone + c h`.
///
/// With `analytic_edges`, each highlight edge is smoothed over the pixel's footprint of the
/// signed inside value `s = ε − ‖N − H'‖²/2`: the width is `fwidth(s) = |∂s/∂x| + |∂s/∂y|`
/// from differences with the neighbouring pixels of the same patch, the largest over the
/// expression's layers. Without it, edges are hard (the paper's look).
pub fn shade(gbuffer: &GBuffer, scene: &Scene, analytic_edges: bool) -> Shaded {
    let detail = xtoon::detail(gbuffer, scene);
    // Highlights see the abstracted frames of X-Toon patches that ask for them.
    let gbuffer = detail.highlight_gbuffer.as_ref().unwrap_or(gbuffer);
    // Per texel: the half vector, on highlighted patches only.
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
    let widths = analytic_edges.then(|| edge_widths(gbuffer, scene, &half_vectors));
    let shades: Vec<Shade> = gbuffer
        .texels
        .par_chunks(PIXELS_PER_JOB)
        .zip(half_vectors.par_chunks(PIXELS_PER_JOB))
        .enumerate()
        .flat_map_iter(|(chunk, (texels, hs))| {
            let widths = widths
                .as_ref()
                .map(|w| &w[chunk * PIXELS_PER_JOB..][..texels.len()]);
            highlight_chunk(scene, texels, hs, widths)
        })
        .collect();
    let results: Vec<(Vec4, f32)> = gbuffer
        .texels
        .par_iter()
        .zip(&shades)
        .enumerate()
        .with_min_len(PIXELS_PER_JOB)
        .map(|(k, (t, shade))| {
            let tone = match &scene.looks[t.patch as usize].tone {
                Tone::Cel(ramp) => {
                    let n = t.frame.n;
                    ramp.shade(n.dot(scene.light.direction(t.position, n)))
                }
                Tone::XToon(_) => detail.tones[k],
            };
            let colour: Vec3 = tone.lerp(shade.colour, shade.coverage);
            (colour.extend(1.0), shade.coverage)
        })
        .collect();
    let n_dot_h = scene.aovs.n_dot_h.then(|| {
        let values: Vec<f32> = gbuffer
            .texels
            .par_iter()
            .with_min_len(PIXELS_PER_JOB)
            .map(|t| t.frame.n.dot(initial_half_vector(scene, t)))
            .collect();
        gbuffer.gather(&values, 0.0)
    });
    let colours: Vec<Vec4> = results.iter().map(|r| r.0).collect();
    let colour = gbuffer.gather(&colours, Vec4::ZERO);
    let matte = scene.aovs.matte.then(|| {
        let coverage: Vec<f32> = results.iter().map(|r| r.1).collect();
        gbuffer.gather(&coverage, 0.0)
    });
    Shaded {
        colour,
        matte,
        n_dot_h,
        shaded: gbuffer.texels.len() as u64,
        highlighted: half_vectors.iter().filter(|h| h.is_some()).count() as u64,
        detail: detail.stats,
    }
}

/// Blinn's half vector `normalize(L + V)` at a texel: the highlight vector before any operation.
fn initial_half_vector(scene: &Scene, t: &Texel) -> Vec3 {
    let n = t.frame.n;
    half_vector(
        scene.light.direction(t.position, n),
        scene.camera.toward_eye(t.position),
        n,
    )
}

/// No highlight: nothing to composite.
const NO_HIGHLIGHT: Shade = Shade {
    coverage: 0.0,
    colour: Vec3::ZERO,
};

/// The highlight shade of each texel of a chunk (in pixel order), given its half vectors (on
/// highlighted patches) and, for analytic edges, its edge widths. Runs of texels on one patch go
/// through the expression's batch evaluation; with per-pixel widths, one by one.
fn highlight_chunk(
    scene: &Scene,
    texels: &[Texel],
    half_vectors: &[Option<Vec3>],
    widths: Option<&[f32]>,
) -> Vec<Shade> {
    let mut out = vec![NO_HIGHLIGHT; texels.len()];
    let mut start = 0;
    while start < texels.len() {
        let patch = texels[start].patch;
        let end = texels[start..]
            .iter()
            .position(|t| t.patch != patch)
            .map_or(texels.len(), |n| start + n);
        if let Some(expr) = &scene.looks[patch as usize].highlight {
            let run = &texels[start..end];
            let hs: Vec<Vec3> = half_vectors[start..end]
                .iter()
                .map(|h| h.expect("highlighted patches have half vectors"))
                .collect();
            match widths {
                Some(widths) => {
                    for (k, t) in run.iter().enumerate() {
                        out[start + k] = expr.eval(&t.frame, t.uv, hs[k], widths[start + k]);
                    }
                }
                None => {
                    let frames: Vec<TangentFrame> = run.iter().map(|t| t.frame).collect();
                    let uvs: Vec<Vec2> = run.iter().map(|t| t.uv).collect();
                    expr.eval_many(&frames, &uvs, &hs, 0.0, &mut out[start..end]);
                }
            }
        }
        start = end;
    }
    out
}

/// The layers of an expression, left to right.
fn layers(expr: &PreparedExpr) -> Vec<&PreparedLayer> {
    match expr {
        PreparedExpr::Layer(layer) => vec![layer],
        PreparedExpr::Combine(_, a, b) => {
            let mut all = layers(a);
            all.extend(layers(b));
            all
        }
    }
}

/// Per texel, the largest `fwidth(s)` over the layers of its patch's highlight (0 without one).
/// Differences are taken forward, or backward at the edge of the patch or image.
fn edge_widths(gbuffer: &GBuffer, scene: &Scene, half_vectors: &[Option<Vec3>]) -> Vec<f32> {
    let layer_lists: Vec<Vec<&PreparedLayer>> = scene
        .looks
        .iter()
        .map(|look| look.highlight.as_ref().map_or_else(Vec::new, layers))
        .collect();
    let most = layer_lists.iter().map(Vec::len).max().unwrap_or(0);
    // signed[k * most + j]: layer j's signed value at texel k.
    let signed: Vec<f32> = gbuffer
        .texels
        .par_iter()
        .zip(half_vectors)
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
