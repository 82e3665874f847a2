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
        let pixels = gbuffer
            .texels
            .par_iter()
            .with_min_len(PIXELS_PER_JOB)
            .filter(|t| views[t.patch as usize].is_some())
            .count() as u64;
        if !abstract_highlights.contains(&true) {
            let tones = gbuffer
                .texels
                .par_iter()
                .with_min_len(PIXELS_PER_JOB)
                .map(|t| shade(t).map_or(Vec3::ZERO, |s| s.colour))
                .collect();
            return (tones, None, pixels);
        }
        let (tones, texels): (Vec<Vec3>, Vec<Texel>) = gbuffer
            .texels
            .par_iter()
            .with_min_len(PIXELS_PER_JOB)
            .map(|t| match shade(t) {
                Some(s) if abstract_highlights[t.patch as usize] => {
                    let frame = facing_frame(s.normal, t.frame.du, s.normal);
                    (s.colour, Texel { frame, ..*t })
                }
                s => (s.map_or(Vec3::ZERO, |s| s.colour), *t),
            })
            .unzip();
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
        scene.camera.toward_eye(t.position),
        scene.light.direction(t.position, n),
    )
}
