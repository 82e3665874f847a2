//! The plan of a frame (DESIGN §1): what the scene and settings call for, compiled before any
//! stage runs. A stage or channel the plan leaves out does not run, and
//! [`RenderStats`](super::RenderStats) shows it.

use super::scene::{Aovs, Scene, Tone};
use super::settings::{FrameMode, Settings};

/// Where the shade pass finds the surface at each pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Surfaces {
    /// The G-buffer: per covered pixel its patch, (u, v), position and shading frame.
    Texels,
    /// The visibility buffer alone: the vertex normal interpolated at the pixel, which is all
    /// the cel tone over `N·L` needs when frames are interpolated. No G-buffer is built.
    Visibility,
}

/// The stages one frame runs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Plan {
    pub surfaces: Surfaces,
    /// Some patch has a highlight: half vectors are built for its pixels.
    pub highlights: bool,
    pub outlines: bool,
    /// Some AOV is asked for.
    pub aovs: bool,
}

impl Plan {
    /// The plan for `scene` under `settings`. The G-buffer is built unless the only effect is
    /// the cel tone over interpolated frames: highlights need the frame's tangents and (u, v),
    /// outlines and AOVs read neighbouring or stored texels, X-Toon reads each texel's position
    /// and frame, and exact or refined frames are evaluated per texel.
    pub fn new(scene: &Scene, settings: &Settings) -> Self {
        let highlights = scene.looks.iter().any(|look| look.highlight.is_some());
        let outlines = scene.outlines.is_some();
        let aovs = scene.aovs != Aovs::default();
        let xtoon = scene
            .looks
            .iter()
            .any(|look| matches!(look.tone, Tone::XToon(_)));
        let tone_only = !highlights && !outlines && !aovs && !xtoon;
        let surfaces = if tone_only && settings.frames == FrameMode::Interpolated {
            Surfaces::Visibility
        } else {
            Surfaces::Texels
        };
        Self {
            surfaces,
            highlights,
            outlines,
            aovs,
        }
    }
}
