//! The shot file, described field by field in `docs/shot-format.md`: serde types, loading with
//! includes, validation with file:line:col errors, and [`Shot::at`], the pure evaluation of
//! every track at a frame.

mod edit;
mod every_frame;
mod file;
#[cfg(test)]
pub(crate) mod fixtures;
mod frame_state;
mod glob;
mod highlight_point;
mod layer_axes;
mod library_at;
mod line_styles;
mod load;
mod moving_parts;
mod no_match;
mod orbit;
mod output;
mod params;
mod pin;
mod pose;
mod shape_hold;
mod source;
mod transform;
mod validated;
mod written;

pub use edit::{
    apply_edits, edit_layer, edit_text, frame_text, mask_text, number_text, op_text, param_paths,
    param_readings, parse_param_path, rounded_number_text, track_span, track_text, track_texts,
    value_text, CameraParam, DetailParam, EditError, HighlightRef, LayerEdit, LayerParam,
    LightParam, MaterialParam, OpParam, ParamPath, ParamPathError, ParamReading, ShadeParam,
    TrackEdit,
};
pub use file::{Aov, Preset, Selector};
pub use frame_state::FrameState;
pub use glob::matches as matches_patch;
pub use line_styles::LineFields;
pub use load::{load_shot, load_shot_text};
pub use orbit::{OrbitSpec, MAX_AZIMUTH_DEGREES, MAX_ELEVATION_DEGREES};
pub use output::{check_numbered, frame_path, resolve_path};
pub use transform::Placement;
pub use validated::{Instance, MaterialState, Shot};

/// The longest frame range a shot may have, and the most frames one frame list may name.
pub const MAX_FRAMES: i64 = 1_000_000;

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
