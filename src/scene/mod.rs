//! The shot file (DESIGN §6): serde types, loading with includes, validation with
//! file:line:col errors, and [`Shot::at`], the pure evaluation of every track at a frame.

mod file;
mod glob;
mod load;
mod shot;

pub use file::{Aov, Preset, Selector};
pub use glob::matches as matches_patch;
pub use load::load_shot;
pub use shot::{resolve_path, FrameState, Instance, MaterialState, Shot};

use thiserror::Error;

/// A shot that cannot be rendered, with where the problem is written.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ShotError {
    /// A problem at a place in a file.
    #[error("{path}:{line}:{col}: {message}")]
    At {
        path: String,
        line: usize,
        col: usize,
        message: String,
    },
    /// A problem with a whole file (it cannot be read) or with no place in one.
    #[error("{path}: {message}")]
    File { path: String, message: String },
}
