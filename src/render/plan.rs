//! The plan of a frame: which stages the scene and settings call for, decided before any stage
//! runs. A stage the plan leaves out does not run, and [`RenderStats`](super::RenderStats)
//! shows it.

use super::scene::{Aovs, Scene, Tone};
use super::settings::{Antialias, FrameMode, Settings};
use super::stage::Stage;

/// Where the shade stage finds the surface at each pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Surfaces {
    /// The G-buffer: per covered pixel its patch, (u, v), position and shading frame.
    Texels,
    /// The visibility buffer alone: the vertex normal interpolated at the pixel, which is all
    /// the cel tone over `N·L` needs when frames are interpolated. No G-buffer is built.
    Visibility,
}

/// The stages one frame runs: the one place that decides them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Plan {
    /// Where the shade stage reads the surface.
    pub surfaces: Surfaces,
    /// Per stage in [`Stage::ALL`] order, whether it runs.
    runs: [bool; Stage::COUNT],
}

impl Plan {
    /// The plan for `scene` under `settings`:
    ///
    /// - tessellation, rasterization and shading always run;
    /// - the G-buffer is built unless the only effect is the cel tone over interpolated frames:
    ///   highlights need the frame's tangents and (u, v), outlines and AOVs read neighbouring or
    ///   stored texels, X-Toon reads each texel's position and frame, and exact or refined
    ///   frames are evaluated per texel;
    /// - the X-Toon detail runs as a stage of its own only when some patch's designed highlight
    ///   is evaluated in its X-Toon tone's abstracted frame (the highlights then need every
    ///   abstracted frame before they start);
    /// - edge widths only under analytic anti-aliasing on a frame with highlights;
    /// - outlines and AOVs when the scene asks for them, the resolve under supersampling.
    #[must_use]
    pub fn new(scene: &Scene, settings: &Settings) -> Self {
        let highlights = scene.looks.iter().any(|look| look.highlight.is_some());
        let outlines = scene.outlines.is_some();
        let aovs = scene.aovs != Aovs::default();
        let xtoon = scene
            .looks
            .iter()
            .any(|look| matches!(look.tone, Tone::XToon(_)));
        let abstracted_highlights = scene.looks.iter().any(|look| {
            look.highlight.is_some()
                && matches!(&look.tone, Tone::XToon(tone) if tone.abstracts_highlights())
        });
        let tone_only = !highlights && !outlines && !aovs && !xtoon;
        let surfaces = if tone_only && settings.frames == FrameMode::Interpolated {
            Surfaces::Visibility
        } else {
            Surfaces::Texels
        };
        let texels = surfaces == Surfaces::Texels;
        let runs = Stage::ALL.map(|stage| match stage {
            Stage::Tessellate | Stage::Rasterize | Stage::Shade => true,
            Stage::GBuffer => texels,
            Stage::Detail => texels && abstracted_highlights,
            Stage::EdgeWidths => texels && highlights && settings.antialias == Antialias::Analytic,
            Stage::Outline => outlines,
            Stage::Aov => aovs,
            Stage::Resolve => settings.samples_per_side() > 1,
        });
        Self { surfaces, runs }
    }

    /// Whether `stage` runs.
    #[must_use]
    pub fn runs(&self, stage: Stage) -> bool {
        self.runs[stage.index()]
    }

    /// The stages that run, in pipeline order.
    pub fn stages(&self) -> impl Iterator<Item = Stage> + '_ {
        Stage::ALL.into_iter().filter(|&stage| self.runs(stage))
    }
}
