//! The X-Toon detail work: on patches with an X-Toon tone, each texel's shading normal, detail
//! and texture colour.
//!
//! The shade pass computes the tone as it goes, a run of texels on one patch at a time, while
//! the texels are at hand. Only when some patch's designed highlight uses the abstracted frame
//! does the tone run as a pass of its own, ahead of shading: the highlights (and their analytic
//! edge widths) then need every texel's abstracted frame before they start.

use glam::Vec3;
use rayon::prelude::*;

use super::gbuffer::{facing_frame, GBuffer, Texel, PIXELS_PER_JOB};
use super::scene::{Scene, Tone};
use super::shade::{light_lanes, view_lanes};
use super::stats::timed;
use crate::highlight::Lanes;
use crate::toon::{PointRun, ViewXToon, RUN};

/// Each patch's X-Toon tone placed in a frame's view: `None` on cel patches, empty when no
/// patch has an X-Toon tone.
pub(super) type Views<'s> = Vec<Option<ViewXToon<'s>>>;

/// What the shade pass needs of the X-Toon tones of a frame.
#[derive(Debug, Default)]
pub(super) struct Detail<'s> {
    pub views: Views<'s>,
    /// Per texel, the X-Toon tone (zero on cel patches), when it ran ahead of the shade pass;
    /// empty otherwise.
    pub tones: Vec<Vec3>,
    /// The G-buffer with the abstracted frame on every texel of a patch whose designed
    /// highlight uses it; None when no patch's does.
    pub highlight_gbuffer: Option<GBuffer>,
    /// The time of the pass ahead of shading (0 when it did not run).
    pub ahead_seconds: f64,
}

/// Places every X-Toon tone of `scene` in its view, and runs the tones ahead of the shade pass
/// when a highlight uses the abstracted frame. Does nothing when no patch has an X-Toon tone.
pub(super) fn detail<'s>(gbuffer: &GBuffer, scene: &'s Scene) -> Detail<'s> {
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
        return Detail::default();
    }
    let abstract_highlights: Vec<bool> = scene
        .looks
        .iter()
        .map(|look| {
            look.highlight.is_some()
                && matches!(&look.tone, Tone::XToon(tone) if tone.abstracts_highlights())
        })
        .collect();
    if !abstract_highlights.contains(&true) {
        return Detail {
            views,
            ..Detail::default()
        };
    }
    let ((tones, highlight_gbuffer), ahead_seconds) = timed(|| {
        let mut tones = vec![Vec3::ZERO; gbuffer.texels.len()];
        let mut texels = gbuffer.texels.clone();
        texels
            .par_chunks_mut(PIXELS_PER_JOB)
            .zip(tones.par_chunks_mut(PIXELS_PER_JOB))
            .for_each(|(texels, tones)| {
                let mut scratch = ToneScratch::default();
                let mut view_vectors = Lanes::default();
                let mut start = 0;
                for run in texels.chunk_by_mut(|a, b| a.patch == b.patch) {
                    let patch = run[0].patch as usize;
                    let range = start..start + run.len();
                    start = range.end;
                    let Some(view) = &views[patch] else {
                        continue;
                    };
                    for (piece, tones) in run.chunks_mut(RUN).zip(tones[range].chunks_mut(RUN)) {
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
            });
        let highlight_gbuffer = GBuffer {
            width: gbuffer.width,
            height: gbuffer.height,
            slot: gbuffer.slot.clone(),
            texels,
            edge_surfaces: Vec::new(),
        };
        (tones, Some(highlight_gbuffer))
    });
    Detail {
        views,
        tones,
        highlight_gbuffer,
        ahead_seconds,
    }
}

/// What [`shade_texels`] works in, kept by each worker from one run to the next.
#[derive(Debug, Default)]
pub(super) struct ToneScratch {
    points: PointRun,
    light: Lanes,
    abstracted: Lanes,
}

/// The X-Toon tones of up to [`RUN`] `texels` of one patch, whose tone is `view`, into
/// `colour`: seen along their view vectors `views` (read only when the tone
/// [uses them](ViewXToon::uses_view)) and lit by the scene's light. Returns their shading
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
    light_lanes(scene, texels, &mut scratch.light);
    view.shade_run(
        &scratch.points,
        views,
        &scratch.light,
        &mut scratch.abstracted,
        colour,
    )
}
