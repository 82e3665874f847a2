//! Rendering: camera, tessellation, rasterization, the G-buffer, shading and output.

pub mod camera;
pub mod raster;
pub mod tessellate;

use thiserror::Error;

/// A scene or setting the renderer cannot use.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum RenderError {
    #[error("camera: {0}")]
    Camera(String),
}
