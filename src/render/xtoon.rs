//! The X-Toon detail pass: on patches with an X-Toon tone, each texel's shading normal, detail
//! and texture colour, before the shade pass composites highlights over them.

use glam::Vec3;
use rayon::prelude::*;

use super::gbuffer::{facing_frame, GBuffer, Texel, PIXELS_PER_JOB};
use super::scene::{Scene, Tone};
use super::stats::{timed, StageStats};
use crate::toon::{SurfacePoint, ViewXToon, XToonShade};

/// What the detail pass made.
#[derive(Debug, Default)]
pub(super) struct Detail {
    /// Per texel, the X-Toon tone on X-Toon patches (zero on the others); empty when no patch
    /// has an X-Toon tone.
    pub tones: Vec<Vec3>,
    /// The G-buffer with the abstracted frame on every texel of a patch whose designed
    /// highlight uses it; None when no patch's does.
    pub highlight_gbuffer: Option<GBuffer>,
    /// Pixels: texels on X-Toon patches.
    pub stats: StageStats,
}

/// Runs the X-Toon tone of every texel on an X-Toon patch. Does nothing (and reports zero)
/// when no patch has one.
pub(super) fn detail(gbuffer: &GBuffer, scene: &Scene) -> Detail {
    let (eye, forward) = (scene.camera.eye, scene.camera.forward());
    let views: Vec<Option<ViewXToon>> = scene
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
    let ((tones, highlight_gbuffer, pixels), seconds) = timed(|| {
        let shade = |t: &Texel| {
            views[t.patch as usize]
                .as_ref()
                .map(|v| shade_texel(v, scene, t))
        };
        let mut tones = vec![Vec3::ZERO; gbuffer.texels.len()];
        if !abstract_highlights.contains(&true) {
            let pixels = gbuffer
                .texels
                .par_chunks(PIXELS_PER_JOB)
                .zip(tones.par_chunks_mut(PIXELS_PER_JOB))
                .map(|(texels, tones)| {
                    let mut count = 0;
                    for (t, tone) in texels.iter().zip(tones) {
                        if let Some(s) = shade(t) {
                            *tone = s.colour;
                            count += 1;
                        }
                    }
                    count
                })
                .sum();
            return (tones, None, pixels);
        }
        let mut texels = gbuffer.texels.clone();
        let pixels = texels
            .par_chunks_mut(PIXELS_PER_JOB)
            .zip(tones.par_chunks_mut(PIXELS_PER_JOB))
            .map(|(texels, tones)| {
                let mut count = 0;
                for (t, tone) in texels.iter_mut().zip(tones) {
                    if let Some(s) = shade(t) {
                        *tone = s.colour;
                        count += 1;
                        if abstract_highlights[t.patch as usize] {
                            t.frame = facing_frame(s.normal, t.frame.du, s.normal);
                        }
                    }
                }
                count
            })
            .sum();
        let highlight_gbuffer = GBuffer {
            width: gbuffer.width,
            height: gbuffer.height,
            slot: gbuffer.slot.clone(),
            texels,
        };
        (tones, Some(highlight_gbuffer), pixels)
    });
    Detail {
        tones,
        highlight_gbuffer,
        stats: StageStats { pixels, seconds },
    }
}

/// The X-Toon tone at a texel, seen from the scene's camera and lit by its light.
#[inline]
fn shade_texel(view: &ViewXToon, scene: &Scene, t: &Texel) -> XToonShade {
    let n = t.frame.n;
    let point = SurfacePoint {
        position: t.position,
        normal: n,
        patch: t.patch as usize,
        uv: t.uv,
    };
    view.shade(
        &point,
        || scene.camera.toward_eye(t.position),
        scene.light.direction(t.position, n),
    )
}
