//! A shot or look file's text read for editing, its problems as edit errors at their place.

use super::error::EditError;
use super::param_sites::ParsedFile;
use crate::shot::ShotError;

/// The text read as a shot or look file.
pub(super) fn read_file(text: &str) -> Result<ParsedFile, EditError> {
    ParsedFile::parse(text).map_err(|e| match e {
        ShotError::At {
            line, col, message, ..
        } => EditError::Parse { line, col, message },
        ShotError::File { message, .. } => EditError::Parse {
            line: 1,
            col: 1,
            message,
        },
    })
}
