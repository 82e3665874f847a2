//! A text file replaced in place by an editor of it: atomically, where a link leads, with its
//! permissions kept, and a read-only file refused.

use std::io::Write;
use std::path::Path;

use super::atomic::{write_atomically, WriteError};

/// Replaces the file at `file` (the file a link leads to, if it is one) with `text`, atomically,
/// keeping its permissions; a read-only file is refused and left as it is.
pub fn replace_text(file: &Path, text: &str) -> Result<(), WriteError> {
    let fail = |reason: String| WriteError {
        path: file.display().to_string(),
        reason,
    };
    let target = std::fs::canonicalize(file).map_err(|e| fail(e.to_string()))?;
    let permissions = std::fs::metadata(&target)
        .map_err(|e| fail(e.to_string()))?
        .permissions();
    if permissions.readonly() {
        return Err(fail("it is read-only; it is left as it is".to_string()));
    }
    write_atomically(&target, |out| {
        out.write_all(text.as_bytes()).map_err(|e| e.to_string())
    })?;
    std::fs::set_permissions(&target, permissions).map_err(|e| fail(e.to_string()))
}
