//! Editing a shot or look file's text by parameter path: a track's value or keys, a highlight
//! layer's structure, each edit made in place with every other byte kept.

mod edit_text;
mod error;
mod layer_edit;
mod layer_text;
mod number_text;
mod outline_edit;
mod param_path;
mod param_range;
mod param_readings;
mod param_sites;
mod query;
mod read;
mod resolve;
mod track_edit;
mod track_line;
mod track_splice;

pub use edit_text::{apply_edits, edit_text};
pub use error::EditError;
pub use layer_edit::{edit_layer, LayerEdit};
pub use layer_text::{mask_text, op_text};
pub use number_text::{frame_text, number_text, rounded_number_text, value_text};
pub use param_path::{
    CameraParam, DetailParam, HighlightRef, LayerParam, LightParam, MaterialParam, OpParam,
    ParamPath, ParamPathError, ShadeParam,
};
pub use param_readings::{param_readings, ParamReading};
pub use query::{param_paths, track_span, track_text, track_texts};
pub use resolve::parse_param_path;
pub use track_edit::TrackEdit;
