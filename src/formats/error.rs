//! Why a file could not be read, with where in it the problem is.

use thiserror::Error;

use super::{ron_location, ron_paths};

/// A file that could not be read, with where in it the problem is.
#[derive(Debug, Error)]
pub enum FormatError {
    #[error("{path}: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
    #[error("{path}:{line}:{col}: {message}")]
    Ron {
        path: String,
        line: usize,
        col: usize,
        message: String,
    },
    #[error("{path}:{line}:{col}: {message}")]
    Usd {
        path: String,
        line: usize,
        col: usize,
        message: String,
    },
    #[error("{path}:{line}: {message}")]
    Bpt {
        path: String,
        line: usize,
        message: String,
    },
    #[error("{path}: {message}")]
    Image { path: String, message: String },
    /// The file as a whole cannot be read as text (not a regular file, too large).
    #[error("{path}: cannot read the file: {message}")]
    File { path: String, message: String },
    #[error(
        "{path}: unknown patch file type; use .ron (a patch library), .bpt (Bezier patches) or .usda (USD text)"
    )]
    UnknownKind { path: String },
    #[error(
        "{path} names the parts of a model, it is not one; give the model it is beside ({model})"
    )]
    PartsFile { path: String, model: String },
}

impl FormatError {
    /// A RON error in `text` (shown as `shown`) at the value `path` leads to, or at the
    /// deepest value on it that is written.
    #[must_use]
    pub fn ron_at(text: &str, shown: &str, path: &[ron_paths::Step], message: String) -> Self {
        let offset = ron_paths::locate_or_nearest(text, path);
        let (line, col) = ron_location::position_of(text, offset);
        FormatError::Ron {
            path: shown.into(),
            line,
            col,
            message,
        }
    }
}
