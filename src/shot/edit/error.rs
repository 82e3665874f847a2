//! Why an edit of a file's text cannot be made, as one line placed in the file.

use std::fmt;
use std::path::Path;

use super::number_text::frame_text;
use super::param_path::ParamPath;
use crate::shot::ShotError;

/// Why a track could not be edited. Each is one line; [`EditError::in_file`] places it in the
/// file edited.
#[derive(Clone, Debug, PartialEq)]
pub enum EditError {
    /// The text is not a shot or look file that reads.
    Parse {
        line: usize,
        col: usize,
        message: String,
    },
    /// The path names no track of the file.
    BadPath {
        /// The path as written.
        written: String,
        /// Why it names no track.
        reason: String,
        /// The valid path of the file closest to it as written.
        nearest: Option<ParamPath>,
    },
    /// The value is not one the track can take (the wrong number of components, not finite, a
    /// direction of no length).
    BadValue {
        path: ParamPath,
        line: usize,
        col: usize,
        reason: String,
    },
    /// The frame is not a finite number.
    BadFrame { frame: f64 },
    /// A key to delete that the track does not have.
    NoKey {
        path: ParamPath,
        line: usize,
        col: usize,
        frame: f64,
        /// The frames of the keys it has.
        frames: Vec<f64>,
    },
    /// The edit could not be made as asked without changing more than the track (the text is
    /// not written as expected, or does not read back as intended); nothing is written.
    Unchecked {
        path: ParamPath,
        line: usize,
        col: usize,
        reason: String,
    },
}

impl EditError {
    /// The 1-based line and column the error is about, where it has one: the track's value (or
    /// the deepest value written on its path).
    #[must_use]
    pub fn place(&self) -> Option<(usize, usize)> {
        match self {
            EditError::Parse { line, col, .. }
            | EditError::BadValue { line, col, .. }
            | EditError::NoKey { line, col, .. }
            | EditError::Unchecked { line, col, .. } => Some((*line, *col)),
            EditError::BadPath { .. } | EditError::BadFrame { .. } => None,
        }
    }

    /// The sentence that says what is wrong, without the place.
    #[must_use]
    pub fn message(&self) -> String {
        match self {
            EditError::Parse { message, .. } => message.clone(),
            EditError::BadPath {
                written,
                reason,
                nearest: Some(near),
            } => format!("`{written}`: {reason}; the nearest valid path is `{near}`"),
            EditError::BadPath {
                written,
                reason,
                nearest: None,
            } => format!("`{written}`: {reason}"),
            EditError::BadValue { path, reason, .. } => format!("{path}: {reason}"),
            EditError::BadFrame { frame } => format!("the frame {frame} is not a finite number"),
            EditError::NoKey {
                path,
                frame,
                frames,
                ..
            } => format!(
                "{path} has no key at frame {}; {}",
                frame_text(*frame),
                keys_message(frames)
            ),
            EditError::Unchecked { path, reason, .. } => {
                format!("{path}: {reason}; the file is left as it is")
            }
        }
    }

    /// The error placed in the file at `file`: `FILE:LINE:COL: message`, or `FILE: message`.
    #[must_use]
    pub fn in_file(&self, file: &Path) -> ShotError {
        let path = file.display().to_string();
        let message = self.message();
        match self.place() {
            Some((line, col)) => ShotError::At {
                path,
                line,
                col,
                message,
            },
            None => ShotError::File { path, message },
        }
    }
}

impl fmt::Display for EditError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some((line, col)) = self.place() {
            write!(f, "{line}:{col}: ")?;
        }
        f.write_str(&self.message())
    }
}

impl std::error::Error for EditError {}

fn keys_message(frames: &[f64]) -> String {
    if frames.is_empty() {
        return "it is a constant, with no keys".to_string();
    }
    let frames: Vec<String> = frames.iter().map(|&f| frame_text(f)).collect();
    format!("its keys are at frames {}", frames.join(", "))
}
