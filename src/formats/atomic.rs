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

/// Whether a written file is synced to the disk before it is renamed into place.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Durability {
    /// Synced first: once the file exists under its name it survives a crash or power cut —
    /// what a render farm's frames need.
    #[default]
    Synced,
    /// Renamed without waiting for the disk: still whole or absent for any reader, but a power
    /// cut may lose it — for previews that are made again at the next save.
    Unsynced,
}

/// Writes `path` through `write`, which fills a buffered temporary file; synced and renamed over
/// `path` on success, removed on failure.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut BufWriter<File>) -> Result<(), String>,
) -> Result<(), WriteError> {
    write_atomically_with(path, Durability::Synced, write)
}

/// [`write_atomically`] with the sync before the rename as `durability` says.
pub fn write_atomically_with(
    path: &Path,
    durability: Durability,
    write: impl FnOnce(&mut BufWriter<File>) -> Result<(), String>,
) -> Result<(), WriteError> {
    let temporary = temporary_path(path);
    let written = (|| -> Result<(), String> {
        let file = File::create(&temporary).map_err(|e| e.to_string())?;
        let mut out = BufWriter::new(file);
        write(&mut out)?;
        let file = out.into_inner().map_err(|e| e.to_string())?;
        match durability {
            Durability::Synced => file.sync_all().map_err(|e| e.to_string())?,
            Durability::Unsynced => {}
        }
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

/// Removes the temporary files earlier writes to `path` left behind when their process was
/// killed (`.NAME.PID.tmp` beside it). Returns how many were removed.
pub fn remove_stale_temporaries(path: &Path) -> std::io::Result<usize> {
    let (Some(folder), Some(name)) = (path.parent(), path.file_name()) else {
        return Ok(0);
    };
    let folder = if folder.as_os_str().is_empty() {
        Path::new(".")
    } else {
        folder
    };
    let prefix = format!(".{}.", name.to_string_lossy());
    let mut removed = 0;
    let entries = match std::fs::read_dir(folder) {
        Ok(entries) => entries,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(0),
        Err(e) => return Err(e),
    };
    for entry in entries {
        let entry = entry?;
        let file = entry.file_name().to_string_lossy().into_owned();
        let pid = file
            .strip_prefix(&prefix)
            .and_then(|rest| rest.strip_suffix(".tmp"));
        if pid.is_some_and(|p| !p.is_empty() && p.bytes().all(|b| b.is_ascii_digit())) {
            std::fs::remove_file(entry.path())?;
            removed += 1;
        }
    }
    Ok(removed)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unsynced_writes_are_whole_and_leave_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("frame.png");
        for (durability, text) in [
            (Durability::Unsynced, "first"),
            (Durability::Synced, "second"),
        ] {
            write_atomically_with(&path, durability, |out| {
                std::io::Write::write_all(out, text.as_bytes()).map_err(|e| e.to_string())
            })
            .unwrap();
            assert_eq!(std::fs::read_to_string(&path).unwrap(), text);
        }
        let failed = write_atomically_with(&path, Durability::Unsynced, |_| Err("no".into()));
        assert!(failed.is_err());
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "second");
        let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(names.len(), 1, "only the target is left");
    }

    #[test]
    fn stale_temporaries_of_one_target_go_and_nothing_else() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("shot.0001.png");
        for name in [
            ".shot.0001.png.123.tmp",
            ".shot.0001.png.99.tmp",
            ".shot.0002.png.123.tmp",
            ".shot.0001.png.x.tmp",
            "shot.0001.png",
        ] {
            std::fs::write(dir.path().join(name), b"x").unwrap();
        }
        assert_eq!(remove_stale_temporaries(&target).unwrap(), 2);
        let mut left: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        left.sort();
        assert_eq!(
            left,
            [
                ".shot.0001.png.x.tmp",
                ".shot.0002.png.123.tmp",
                "shot.0001.png"
            ]
        );
    }
}
