//! Why a highlight, a band edge or a surface point cannot be placed where it was asked for.

use thiserror::Error;

use super::JobError;

/// Why a highlight cannot be placed at a pixel.
#[derive(Debug, Error)]
pub enum PlaceError {
    /// The position lies outside the image.
    #[error("pixel ({x}, {y}) is outside the {width}×{height} image")]
    OutsideImage {
        x: f64,
        y: f64,
        width: u32,
        height: u32,
    },
    /// No patch is drawn at the pixel.
    #[error("pixel ({x}, {y}) at frame {frame} shows no patch of the model")]
    OffModel { x: f64, y: f64, frame: f64 },
    /// The patch under the pixel has no designed highlight, or not the one asked for.
    #[error("{0}")]
    NoHighlight(String),
    /// The layer asked for does not exist, has no translation, or is pinned.
    #[error("{0}")]
    Layer(String),
    /// The surface point asked for is not on the model: no such patch, or (u, v) outside its
    /// domain.
    #[error("{0}")]
    NoPoint(String),
    /// A band edge cannot be placed by a shade entry: the patch has none (or not the one asked
    /// for), the entry has no translation, the patch's tone has no such band, or no translation
    /// reaches the point.
    #[error("{0}")]
    Shade(String),
    /// The frame could not be read or rendered.
    #[error(transparent)]
    Job(#[from] JobError),
}

impl PlaceError {
    /// Whether the input is at fault (exit code 2), not the work.
    #[must_use]
    pub fn is_bad_input(&self) -> bool {
        match self {
            PlaceError::OutsideImage { .. }
            | PlaceError::OffModel { .. }
            | PlaceError::NoHighlight(_)
            | PlaceError::Layer(_)
            | PlaceError::NoPoint(_)
            | PlaceError::Shade(_) => true,
            PlaceError::Job(e) => e.is_bad_input(),
        }
    }
}
