//! The X-Toon tone of texels: each patch's tone placed in the frame's view, and the tone of a
//! run of texels on one patch — computed by the shade stage as it goes or, when a designed
//! highlight is evaluated in the abstracted frame, by the detail stage ahead of it.

use glam::Vec3;
use rayon::prelude::*;

use super::directions::{tone_light_lanes, view_lanes};
use super::facing::facing_frame;
use super::gbuffer::{GBuffer, Texel, PIXELS_PER_JOB};
use super::scene::{Scene, Tone};
use crate::math::{Lanes, LANES};
use crate::toon::{PointRun, ViewXToon};

/// Each patch's X-Toon tone placed in a frame's view: `None` on cel patches, empty when no
/// patch has an X-Toon tone.
pub(super) type Views<'s> = Vec<Option<ViewXToon<'s>>>;

/// Places every X-Toon tone of `scene` in its view (empty when no patch has an X-Toon tone).
pub(super) fn views<'s>(scene: &'s Scene) -> Views<'s> {
    let (eye, forward) = (scene.camera.eye, scene.camera.forward());
    let views: Views = scene
        .looks
        .iter()
        .map(|look| match &look.tone {
            Tone::XToon(tone) => Some(tone.in_view(eye, forward)),
            Tone::Cel(_) => None,
        })
        .collect();
    if views.iter().all(Option::is_none) {
        return Vec::new();
    }
    views
}

/// What the detail stage computes ahead of shading.
#[derive(Debug)]
pub(super) struct XToonDetail {
    /// Per texel, the X-Toon tone (zero on cel patches).
    pub tones: Vec<Vec3>,
    /// The G-buffer with the abstracted frame on every texel of a patch whose designed
    /// highlight uses it: the frames the highlights see.
    pub gbuffer: GBuffer,
    /// How many texels were toned: those on a patch with an X-Toon tone.
    pub toned: u64,
}

/// The detail stage: the X-Toon tone of every texel of `gbuffer` on a patch with a view, and
/// the abstracted frames of the patches whose designed highlight uses them.
pub(super) fn detail(gbuffer: &GBuffer, scene: &Scene, views: &Views) -> XToonDetail {
    let abstract_highlights: Vec<bool> = scene
        .looks
        .iter()
        .map(|look| {
            look.highlight.is_some()
                && matches!(&look.tone, Tone::XToon(tone) if tone.abstracts_highlights())
        })
        .collect();
    let mut tones = vec![Vec3::ZERO; gbuffer.texels.len()];
    let mut texels = gbuffer.texels.clone();
    let toned = texels
        .par_chunks_mut(PIXELS_PER_JOB)
        .zip(tones.par_chunks_mut(PIXELS_PER_JOB))
        .map(|(texels, tones)| {
            let mut toned = 0;
            let mut scratch = ToneScratch::default();
            let mut view_vectors = Lanes::default();
            let mut start = 0;
            for run in texels.chunk_by_mut(|a, b| a.patch == b.patch) {
                let patch = run[0].patch as usize;
                let range = start..start + run.len();
                start = range.end;
                let Some(view) = views.get(patch).and_then(Option::as_ref) else {
                    continue;
                };
                toned += run.len() as u64;
                for (piece, tones) in run.chunks_mut(LANES).zip(tones[range].chunks_mut(LANES)) {
                    if view.uses_view() {
                        view_lanes(scene, piece, &mut view_vectors);
                    }
                    let shading =
                        shade_texels(view, scene, piece, &view_vectors, &mut scratch, tones);
                    if abstract_highlights[patch] {
                        for (k, t) in piece.iter_mut().enumerate() {
                            let n = shading.get(k);
                            t.frame = facing_frame(n, t.frame.du, n);
                        }
                    }
                }
            }
            toned
        })
        .sum();
    XToonDetail {
        tones,
        gbuffer: GBuffer {
            width: gbuffer.width,
            height: gbuffer.height,
            slot: gbuffer.slot.clone(),
            texels,
        },
        toned,
    }
}

/// What [`shade_texels`] works in, kept by each worker from one run to the next.
#[derive(Debug, Default)]
pub(super) struct ToneScratch {
    points: PointRun,
    light: Lanes,
    abstracted: Lanes,
}

/// The X-Toon tones of up to [`LANES`] `texels` of one patch, whose tone is `view`, into
/// `colour`: seen along their view vectors `views` (read only when the tone
/// [uses them](ViewXToon::uses_view)) and lit by the light their tone reads (the scene's, or
/// their patch's designed light: [`tone_light_lanes`]). Returns their shading
/// normals.
#[inline(always)]
pub(super) fn shade_texels<'a>(
    view: &ViewXToon,
    scene: &Scene,
    texels: &[Texel],
    views: &Lanes,
    scratch: &'a mut ToneScratch,
    colour: &mut [Vec3],
) -> &'a Lanes {
    let points = &mut scratch.points;
    (points.len, points.patch) = (texels.len(), texels[0].patch as usize);
    for (k, t) in texels.iter().enumerate() {
        points.set(k, t.position, t.frame.n, t.uv);
    }
    tone_light_lanes(scene, texels, &mut scratch.light);
    view.shade_run(
        &scratch.points,
        views,
        &scratch.light,
        &mut scratch.abstracted,
        colour,
    )
}
