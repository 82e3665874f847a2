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
/// rename is atomic), and named after the target, this machine and this process
/// (`.NAME.HOST.PID.tmp`), so that a writer knows its own and can tell whether another's is
/// still being written ([`remove_stale_temporaries`]).
pub fn temporary_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map_or_else(Default::default, |n| n.to_string_lossy().into_owned());
    path.with_file_name(format!(
        ".{name}.{}.{}.tmp",
        host_token(),
        std::process::id()
    ))
}

/// This machine's name: the kernel's (Linux), or `HOSTNAME`/`COMPUTERNAME`, or `unknown`.
#[must_use]
pub fn host_name() -> String {
    std::fs::read_to_string("/proc/sys/kernel/hostname")
        .ok()
        .map(|h| h.trim().to_string())
        .filter(|h| !h.is_empty())
        .or_else(|| std::env::var("HOSTNAME").ok())
        .or_else(|| std::env::var("COMPUTERNAME").ok())
        .unwrap_or_else(|| "unknown".to_string())
}

/// The host name as it goes into a temporary's name: letters, digits and `-` only.
fn host_token() -> String {
    host_name()
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '-'
            }
        })
        .collect()
}

/// Whether the process `pid` of this machine is still running: `/proc/PID` exists (Linux).
/// Where that cannot be known, every other process counts as running, so that no temporary
/// another writer may still need is taken from it.
fn is_running(pid: u32) -> bool {
    if pid == std::process::id() {
        return true;
    }
    if Path::new("/proc/self").exists() {
        Path::new(&format!("/proc/{pid}")).exists()
    } else {
        true
    }
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
    if let Ok(meta) = std::fs::metadata(path) {
        if !meta.is_file() {
            return Err(WriteError {
                path: path.display().to_string(),
                reason: "something that is not a regular file is there (a folder, a device); \
                         glint replaces only regular files"
                    .to_string(),
            });
        }
    }
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
/// killed: `.NAME.HOST.PID.tmp` beside it (or `.NAME.PID.tmp`, as older versions named them)
/// whose process, on this machine, is no longer running. A temporary of a running process — a
/// retry of the same frame still at work — is left to it, and so is one from another machine,
/// whose processes cannot be seen from here. Returns how many were removed.
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
    let here = host_token();
    let mut removed = 0;
    let entries = match std::fs::read_dir(folder) {
        Ok(entries) => entries,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(0),
        Err(e) => return Err(e),
    };
    for entry in entries {
        let entry = entry?;
        let file = entry.file_name().to_string_lossy().into_owned();
        let Some(rest) = file
            .strip_prefix(&prefix)
            .and_then(|r| r.strip_suffix(".tmp"))
        else {
            continue;
        };
        let (host, pid) = match rest.rsplit_once('.') {
            Some((host, pid)) => (host, pid),
            None => (here.as_str(), rest),
        };
        let Ok(pid) = pid.parse::<u32>() else {
            continue;
        };
        if host != here || is_running(pid) {
            continue;
        }
        match std::fs::remove_file(entry.path()) {
            Ok(()) => removed += 1,
            // Its writer renamed it into place meanwhile.
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => {}
            Err(e) => return Err(e),
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
        // A process that has ended, and this one, which is running.
        let mut child = std::process::Command::new("true").spawn().unwrap();
        child.wait().unwrap();
        let (dead, alive, host) = (child.id(), std::process::id(), host_token());
        let names = [
            format!(".shot.0001.png.{host}.{dead}.tmp"),
            format!(".shot.0001.png.{dead}.tmp"),
            format!(".shot.0001.png.{host}.{alive}.tmp"),
            format!(".shot.0001.png.other-machine.{dead}.tmp"),
            format!(".shot.0002.png.{host}.{dead}.tmp"),
            ".shot.0001.png.x.tmp".to_string(),
            "shot.0001.png".to_string(),
        ];
        for name in &names {
            std::fs::write(dir.path().join(name), b"x").unwrap();
        }
        assert_eq!(remove_stale_temporaries(&target).unwrap(), 2);
        let mut left: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        left.sort();
        let mut kept = names[2..].to_vec();
        kept.sort();
        assert_eq!(
            left, kept,
            "a running writer's, another machine's and other targets' stay"
        );
    }

    #[test]
    fn only_regular_files_are_replaced() {
        let dir = tempfile::tempdir().unwrap();
        let folder = dir.path().join("frame.png");
        std::fs::create_dir(&folder).unwrap();
        let e = write_atomically(&folder, |_| Ok(())).unwrap_err();
        assert!(e.to_string().contains("not a regular file"), "{e}");
        assert!(folder.is_dir());
        if Path::new("/dev/null").exists() {
            let e = write_atomically(Path::new("/dev/null"), |_| Ok(())).unwrap_err();
            assert!(e.to_string().contains("not a regular file"), "{e}");
        }
    }
}
