//! A file read for a shot (the shot or an include): its text, and errors placed where a value
//! is written in it.

use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;

use super::ShotError;
use crate::formats::ron_location::{explain_at, position_of};
use crate::formats::ron_paths::{locate_or_nearest, Step};
use crate::formats::text_file::{read_text, TextError};

/// A file read for the shot: its path, its name as shown in messages, its folder and its text.
pub(super) struct Source {
    pub path: PathBuf,
    pub shown: String,
    pub folder: PathBuf,
    text: String,
}

impl Source {
    pub fn read(path: &Path) -> Result<Self, ShotError> {
        let shown = path.display().to_string();
        let text = read_text(path).map_err(|e| match e {
            TextError::Io(e) => ShotError::File {
                path: shown.clone(),
                message: format!("cannot read the file: {e}"),
            },
            e @ (TextError::NotAFile | TextError::TooLarge) => ShotError::File {
                path: shown.clone(),
                message: format!("cannot read the file: {e}"),
            },
            TextError::NotUtf8 { line, col } => ShotError::At {
                path: shown.clone(),
                line,
                col,
                message: "the file is not UTF-8 text: these bytes do not read as UTF-8".to_string(),
            },
        })?;
        Ok(Self::new(path, text))
    }

    /// The file at `path` as if it held `text`.
    pub fn new(path: &Path, text: String) -> Self {
        Self {
            path: path.to_path_buf(),
            shown: path.display().to_string(),
            folder: path.parent().map(Path::to_path_buf).unwrap_or_default(),
            text,
        }
    }

    /// An error at the value `path` leads to (a map entry: at its key), or at the deepest
    /// value on the way that is written, when the rest is left to its default.
    pub fn error_at(&self, path: &[Step], message: impl Into<String>) -> ShotError {
        let (line, col) = position_of(&self.text, locate_or_nearest(&self.text, path));
        ShotError::At {
            path: self.shown.clone(),
            line,
            col,
            message: message.into(),
        }
    }

    /// Parses the text as `T`, with errors placed where they are written.
    pub fn parse<T: DeserializeOwned>(&self) -> Result<T, ShotError> {
        let options = ron::Options::default()
            .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
        options.from_str(&self.text).map_err(|e| {
            let (at, message) =
                explain_at(&self.text, &e.code, (e.span.start.line, e.span.start.col));
            ShotError::At {
                path: self.shown.clone(),
                line: at.0,
                col: at.1,
                message,
            }
        })
    }
}
