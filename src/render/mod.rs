//! Rendering: camera, tessellation, rasterization, the G-buffer, shading and output.
//!
//! A frame runs tessellate (cached) ▸ rasterize ▸ G-buffer ▸ shade (X-Toon detail ▸ tone ▸
//! highlight) ▸ outlines ▸ resolve; a stage the scene does not use does not run, and
//! [`RenderStats`] shows it.

pub mod camera;
mod gbuffer;
mod outline;
pub mod output;
mod plan;
pub mod raster;
mod renderer;
mod scene;
mod settings;
mod shade;
mod stats;
pub mod tessellate;
mod visibility_shade;
mod xtoon;

pub use camera::{Camera, Projection};
pub use gbuffer::{facing_frame, GBuffer, Texel};
pub use renderer::{AovImages, RenderedFrame, Renderer};
pub use scene::{Aovs, Outlines, PatchLook, Scene, Tone};
pub use settings::{Antialias, FrameMode, Settings};
pub use stats::{RenderStats, StageStats};

use thiserror::Error;

/// A scene or setting the renderer cannot use.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum RenderError {
    #[error("camera: {0}")]
    Camera(String),
    #[error("settings: {0}")]
    Settings(String),
    #[error("scene: {0}")]
    Scene(String),
}
