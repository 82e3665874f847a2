//! Validation of X-Toon parameters, with messages that name the parameter, its value and the
//! allowed range.

use thiserror::Error;

use super::abstraction::{Abstraction, MAX_ITERATIONS};
use crate::param::ParamError;

/// Why an X-Toon description, texture or abstracted shape cannot be used.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum XToonError {
    /// A parameter that is not finite or outside its range.
    #[error(transparent)]
    Param(#[from] ParamError),
    /// A smoothed shape with an iteration count outside its range.
    #[error(
        "smoothing iterations is {iterations}, outside the allowed range [1, {MAX_ITERATIONS}]; \
         the normals are averaged over a radius of half the control-net spacing times √iterations"
    )]
    Iterations {
        /// The count given.
        iterations: u32,
    },
    /// A 2D toon texture that cannot be sampled.
    #[error("toon texture: {0}")]
    Texture(String),
    /// A model whose abstracted shape cannot be built.
    #[error("abstracted shape: {0}")]
    Shape(String),
    /// A shape detail prepared with a shape built for another abstraction.
    #[error("the shape detail asks for {wanted:?}, but the shape given was built for {built:?}")]
    ShapeMismatch {
        /// The abstraction the description names.
        wanted: Abstraction,
        /// The abstraction the built shape is of.
        built: Abstraction,
    },
}
