//! Atomic file output: the content goes to a temporary file beside the target, which is renamed
//! over the target only when complete. A reader never sees half a file, and a failed write leaves
//! nothing behind.

use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

use thiserror::Error;

/// A file that could not be written.
#[derive(Debug, Error)]
#[error("cannot write {path}: {reason}")]
pub struct WriteError {
    pub path: String,
    pub reason: String,
}

/// The temporary file a write to `path` goes through: hidden, in the same directory (so the
/// rename is atomic), and named after the target and this process.
pub fn temporary_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map_or_else(Default::default, |n| n.to_string_lossy().into_owned());
    path.with_file_name(format!(".{name}.{}.tmp", std::process::id()))
}

/// Writes `path` through `write`, which fills a buffered temporary file; synced and renamed over
/// `path` on success, removed on failure.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<File>) -> Result<(), String>,
) -> Result<(), WriteError> {
    let temporary = temporary_path(path);
    let written = (|| -> Result<(), String> {
        let file = File::create(&temporary).map_err(|e| e.to_string())?;
        let mut out = BufWriter::new(file);
        write(&mut out)?;
        let file = out.into_inner().map_err(|e| e.to_string())?;
        file.sync_all().map_err(|e| e.to_string())?;
        std::fs::rename(&temporary, path).map_err(|e| e.to_string())
    })();
    if written.is_err() {
        // Best effort: the temporary file may not even exist.
        let _ = std::fs::remove_file(&temporary);
    }
    written.map_err(|reason| WriteError {
        path: path.display().to_string(),
        reason,
    })
}
