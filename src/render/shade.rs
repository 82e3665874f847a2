//! The shade pass: cel tone, then each patch's designed highlight, composited per pixel.

use glam::{Vec2, Vec3, Vec4};
use rayon::prelude::*;

use super::camera::Projection;
use super::gbuffer::{GBuffer, Texel, EMPTY, PIXELS_PER_JOB};
use super::scene::{Scene, Tone};
use super::stats::StageStats;
use super::xtoon;
use crate::highlight::{
    half_vector, ChunkScratch, Lanes, Light, LocalChunk, PreparedExpr, PreparedLayer, Shade, CHUNK,
};
use crate::toon::ViewXToon;

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

/// Per-texel results of the shade pass, kept from one frame to the next so that shading
/// allocates only the images it returns.
#[derive(Debug, Default)]
pub struct ShadeBuffers {
    colour: Vec<Vec4>,
    coverage: Vec<f32>,
}

/// Shades every covered pixel: `tone = ramp(N·L)`, or the X-Toon tone ([`xtoon`]),
/// then on a patch with a highlight `H = normalize(L + V)`, the highlight expression's coverage
/// c and colour h, and `colour = (1 − c) tone + c h`.
///
/// With `analytic_edges`, each highlight edge is smoothed over the pixel's footprint of the
/// signed inside value `s = ε − ‖N − H'‖²/2`: the width is `fwidth(s) = |∂s/∂x| + |∂s/∂y|`
/// from differences with the neighbouring pixels of the same patch, the largest over the
/// expression's layers. Without it, edges are hard (the paper's look).
pub fn shade(
    gbuffer: &GBuffer,
    scene: &Scene,
    analytic_edges: bool,
    buffers: &mut ShadeBuffers,
) -> Shaded {
    let detail = xtoon::detail(gbuffer, scene);
    // Highlights see the abstracted frames of X-Toon patches that ask for them.
    let gbuffer = detail.highlight_gbuffer.as_ref().unwrap_or(gbuffer);
    let widths = analytic_edges.then(|| edge_widths(gbuffer, scene));
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
                let range = chunk * PIXELS_PER_JOB..chunk * PIXELS_PER_JOB + texels.len();
                let widths = widths.as_ref().map(|w| &w[range.clone()]);
                let xtoon = XToonTones {
                    views: &detail.views,
                    ahead: (!detail.tones.is_empty()).then(|| &detail.tones[range]),
                };
                let out = Out { colour, coverage };
                shade_texels(scene, texels, widths, &xtoon, out, scratch)
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
    Shaded {
        colour: gbuffer.gather(&buffers.colour, Vec4::ZERO),
        matte: scene
            .aovs
            .matte
            .then(|| gbuffer.gather(&buffers.coverage, 0.0)),
        n_dot_h,
        shaded: texels as u64,
        highlighted: counts.highlighted,
        detail: StageStats {
            pixels: counts.xtoon,
            seconds: detail.ahead_seconds,
        },
    }
}

/// The cel tone `ramp(N·L)` at a point of `patch` with unit normal `n` (black on an X-Toon
/// patch, whose tone comes from [`XToonTones`]).
#[inline]
pub(super) fn cel_tone(scene: &Scene, patch: u32, position: Vec3, n: Vec3) -> Vec3 {
    match &scene.looks[patch as usize].tone {
        Tone::Cel(ramp) => ramp.shade(n.dot(scene.light.direction(position, n))),
        Tone::XToon(_) => Vec3::ZERO,
    }
}

/// Where the X-Toon tones of a run of texels come from: computed per texel from its patch's
/// tone placed in the view, or read from the pass that ran ahead of shading.
struct XToonTones<'a, 's> {
    views: &'a xtoon::Views<'s>,
    /// The tones of the run's texels, when they ran ahead.
    ahead: Option<&'a [Vec3]>,
}

// A piece of texels on one patch is one run of X-Toon tones, and view lanes hold either.
const _: () = assert!(CHUNK == crate::toon::RUN);

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

/// Blinn's half vector `normalize(L + V)` at a texel: the highlight vector before any operation.
fn initial_half_vector(scene: &Scene, t: &Texel) -> Vec3 {
    let n = t.frame.n;
    half_vector(
        scene.light.direction(t.position, n),
        scene.camera.toward_eye(t.position),
        n,
    )
}

/// The unit vectors V from each of up to [`CHUNK`] `texels` toward the eye
/// ([`Camera::toward_eye`]) into `out`, side by side: under perspective `eye − p` for all, then
/// all normalized at once ([`Lanes::normalize`]), with the same values as texel by texel.
///
/// [`Camera::toward_eye`]: super::Camera::toward_eye
#[inline]
pub(super) fn view_lanes(scene: &Scene, texels: &[Texel], out: &mut Lanes) {
    let n = texels.len();
    match scene.camera.projection {
        Projection::Perspective { .. } => {
            towards(scene.camera.eye, texels, out);
            out.normalize(n, |k, _| scene.camera.toward_eye(texels[k].position));
        }
        Projection::Orthographic { .. } => out.fill(n, scene.camera.toward_eye(Vec3::ZERO)),
    }
}

/// The unit vectors L from each of up to [`CHUNK`] `texels` toward the light
/// ([`Light::direction`]) into `out`, side by side as [`view_lanes`] does, with the same
/// values as texel by texel.
#[inline]
pub(super) fn light_lanes(scene: &Scene, texels: &[Texel], out: &mut Lanes) {
    let n = texels.len();
    match scene.light {
        Light::Directional { towards: l } => out.fill(n, l),
        Light::Point { position } => {
            towards(position, texels, out);
            out.normalize(n, |k, _| {
                scene.light.direction(texels[k].position, texels[k].frame.n)
            });
        }
    }
}

/// The vector from each of `texels` to the point `to`, into `out`.
#[inline]
fn towards(to: Vec3, texels: &[Texel], out: &mut Lanes) {
    for (k, t) in texels.iter().enumerate() {
        out.set(k, to - t.position);
    }
}

/// [`initial_half_vector`] at each of up to [`CHUNK`] `texels` into `out`, given their view
/// vectors `view`, side by side: the light vectors ([`light_lanes`]) and the normalized sums
/// each in loops over one coordinate array at a time, with the same values as texel by texel.
fn initial_half_vectors(scene: &Scene, texels: &[Texel], view: &Lanes, out: &mut [Vec3]) {
    let n = texels.len();
    let mut sum = Lanes::default();
    light_lanes(scene, texels, &mut sum);
    // H = normalize(L + V).
    for k in 0..n {
        sum.set(k, sum.get(k) + view.get(k));
    }
    sum.normalize(n, |k, _| initial_half_vector(scene, &texels[k]));
    for (k, h) in out.iter_mut().enumerate() {
        *h = sum.get(k);
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

/// The inputs and results of the tone and the highlight expression for up to [`CHUNK`] texels
/// of one patch, kept by each worker from one run to the next.
struct RunScratch {
    /// The view vectors of the run, filled when its tone or highlight reads them.
    view: Lanes,
    tone: xtoon::ToneScratch,
    half_vectors: [Vec3; CHUNK],
    /// The half vectors in the texels' frames.
    initial: LocalChunk,
    uvs: [Vec2; CHUNK],
    expr: ChunkScratch,
    shades: [Shade; CHUNK],
}

impl RunScratch {
    fn new() -> Self {
        Self {
            view: Lanes::default(),
            tone: xtoon::ToneScratch::default(),
            half_vectors: [Vec3::ZERO; CHUNK],
            initial: LocalChunk::default(),
            uvs: [Vec2::ZERO; CHUNK],
            expr: ChunkScratch::default(),
            shades: [NO_HIGHLIGHT; CHUNK],
        }
    }
}

/// Shades `texels` (in pixel order) into `out`, given their edge widths for analytic edges.
/// Runs of texels on one patch go through the highlight expression together, [`CHUNK`] at a
/// time; with per-pixel widths, one by one. Their tones are computed first, in a loop of their
/// own with the X-Toon tone inlined whole into it, rather than called texel by texel.
fn shade_texels(
    scene: &Scene,
    texels: &[Texel],
    widths: Option<&[f32]>,
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
        // them.
        let reads_view = scene.looks[patch].highlight.is_some()
            || (xtoon.ahead.is_none() && view.is_some_and(ViewXToon::uses_view));
        for piece in run.chunks(CHUNK) {
            let range = start..start + piece.len();
            let widths = widths.map(|w| &w[range.clone()]);
            if reads_view {
                view_lanes(scene, piece, &mut scratch.view);
            }
            let mut tones = [Vec3::ZERO; CHUNK];
            let tones = &mut tones[..piece.len()];
            match (view, xtoon.ahead) {
                (None, _) => {
                    for (tone, t) in tones.iter_mut().zip(piece) {
                        *tone = cel_tone(scene, t.patch, t.position, t.frame.n);
                    }
                }
                (Some(_), Some(ahead)) => tones.copy_from_slice(&ahead[range.clone()]),
                (Some(view), None) => {
                    xtoon::shade_texels(
                        view,
                        scene,
                        piece,
                        &scratch.view,
                        &mut scratch.tone,
                        tones,
                    );
                }
            }
            let shades = highlight(scene, piece, widths, scratch);
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

/// The highlight shades of up to [`CHUNK`] texels on one patch, or `None` when the patch has no
/// highlight (no half vector is built then).
fn highlight<'s>(
    scene: &Scene,
    texels: &[Texel],
    widths: Option<&[f32]>,
    scratch: &'s mut RunScratch,
) -> Option<&'s [Shade]> {
    let expr = scene.looks[texels[0].patch as usize].highlight.as_ref()?;
    let n = texels.len();
    let hs = &mut scratch.half_vectors[..n];
    initial_half_vectors(scene, texels, &scratch.view, hs);
    let shades = &mut scratch.shades[..n];
    match widths {
        Some(widths) => {
            for (k, (shade, t)) in shades.iter_mut().zip(texels).enumerate() {
                *shade = expr.eval(&t.frame, t.uv, hs[k], widths[k]);
            }
        }
        None => {
            scratch.initial.set(n, |k| texels[k].frame.to_local(hs[k]));
            for (uv, t) in scratch.uvs.iter_mut().zip(texels) {
                *uv = t.uv;
            }
            let uvs = &scratch.uvs[..n];
            expr.eval_chunk(&scratch.initial, uvs, 0.0, &mut scratch.expr, shades);
        }
    }
    Some(shades)
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
fn edge_widths(gbuffer: &GBuffer, scene: &Scene) -> Vec<f32> {
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
        .map(|look| look.highlight.as_ref().map_or_else(Vec::new, layers))
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::PatchLibrary;
    use crate::highlight::TangentFrame;
    use crate::render::scene::Aovs;
    use crate::render::Camera;

    /// Texels at scattered points, one of them on the eye and one on the point light.
    fn texels(eye: Vec3, light: Vec3) -> Vec<Texel> {
        (0..CHUNK)
            .map(|k| {
                let a = k as f32 * 0.7;
                let position = match k {
                    3 => eye,
                    5 => light,
                    _ => Vec3::new(a.cos(), a.sin(), 0.1 * a) * (1.0 + 0.3 * a),
                };
                let n = Vec3::new(a.sin(), 0.3, a.cos()).normalize();
                let du = n.any_orthonormal_vector();
                Texel {
                    pixel: k as u32,
                    depth: 0.5,
                    patch: 0,
                    uv: Vec2::ZERO,
                    position,
                    frame: TangentFrame::new(du, n.cross(du), n),
                }
            })
            .collect()
    }

    #[test]
    fn half_vectors_side_by_side_equal_those_texel_by_texel() {
        let library = PatchLibrary::default();
        let eye = Vec3::new(0.5, -6.0, 2.0);
        let light_at = Vec3::new(-3.0, 2.0, 5.0);
        let lights = [
            Light::Directional {
                towards: Vec3::new(0.3, -0.6, 0.75).normalize(),
            },
            Light::Point { position: light_at },
            // Straight behind every point seen by the orthographic camera: L + V vanishes.
            Light::Directional { towards: Vec3::Y },
        ];
        let projections = [
            Projection::Perspective {
                fov_y_degrees: 40.0,
            },
            Projection::Orthographic { height: 4.0 },
        ];
        let texels = texels(eye, light_at);
        for light in lights {
            for projection in projections {
                let scene = Scene {
                    library: &library,
                    looks: Vec::new(),
                    camera: Camera {
                        eye,
                        target: eye + Vec3::Y,
                        up: Vec3::Z,
                        projection,
                        near: 0.1,
                        far: 100.0,
                    },
                    light,
                    outlines: None,
                    aovs: Aovs::default(),
                };
                let mut side_by_side = [Vec3::ZERO; CHUNK];
                let mut view = Lanes::default();
                view_lanes(&scene, &texels, &mut view);
                initial_half_vectors(&scene, &texels, &view, &mut side_by_side);
                for (t, h) in texels.iter().zip(side_by_side) {
                    let one = initial_half_vector(&scene, t);
                    assert!(h.is_finite(), "{light:?} {projection:?}: {h}");
                    assert_eq!(
                        h.to_array().map(f32::to_bits),
                        one.to_array().map(f32::to_bits)
                    );
                }
            }
        }
    }
}
