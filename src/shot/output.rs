//! Where a shot's frames are written: output patterns with a run of `#` for the frame number,
//! and paths relative to the file that names them.

use std::path::{Path, PathBuf};

/// `pattern` with its last run of `#` replaced by `frame`, zero-padded to the run's length
/// (a pattern without `#` is returned as it is).
pub fn frame_path(pattern: &Path, frame: i64) -> PathBuf {
    let text = pattern.to_string_lossy();
    let Some(end) = text.rfind('#').map(|i| i + 1) else {
        return pattern.to_path_buf();
    };
    let start = text[..end].trim_end_matches('#').len();
    let width = end - start;
    let number = if frame < 0 {
        format!(
            "-{:0width$}",
            frame.unsigned_abs(),
            width = width.saturating_sub(1)
        )
    } else {
        format!("{frame:0width$}")
    };
    PathBuf::from(format!("{}{number}{}", &text[..start], &text[end..]))
}

/// `base` joined with `path` (kept as it is when absolute), with `name/..` pairs removed, so
/// that messages show `out/a.png` rather than `shots/../out/a.png`.
pub fn resolve_path(base: &Path, path: &Path) -> PathBuf {
    let mut clean = PathBuf::new();
    for part in base.join(path).components() {
        match part {
            std::path::Component::CurDir => {}
            std::path::Component::ParentDir
                if matches!(
                    clean.components().next_back(),
                    Some(std::path::Component::Normal(_))
                ) =>
            {
                clean.pop();
            }
            other => clean.push(other),
        }
    }
    clean
}

/// Checks that `pattern` names a file of its own for each of `frames` frames: with more than
/// one frame, it must have a run of `#` for the frame number.
pub fn check_numbered(pattern: &Path, frames: usize) -> Result<(), String> {
    if frames > 1 && frame_path(pattern, 0) == frame_path(pattern, 1) {
        return Err(format!(
            "the output pattern {} has no `#` for the frame number, so every frame would overwrite the same file; write e.g. \"out/shot.####.png\"",
            pattern.display()
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_numbers_fill_the_last_run_of_hashes() {
        let p = |s: &str, f| frame_path(Path::new(s), f).display().to_string();
        assert_eq!(p("out/shot.####.png", 7), "out/shot.0007.png");
        assert_eq!(p("out/shot.##.png", 123), "out/shot.123.png");
        assert_eq!(p("out#/s.#.png", 5), "out#/s.5.png");
        assert_eq!(p("out/s.####.png", -3), "out/s.-003.png");
        assert_eq!(p("out/still.png", 3), "out/still.png");
    }

    #[test]
    fn a_pattern_without_a_frame_number_serves_one_frame_only() {
        assert!(check_numbered(Path::new("out/still.png"), 1).is_ok());
        let e = check_numbered(Path::new("out/still.png"), 2).unwrap_err();
        assert!(e.contains("out/still.png") && e.contains("no `#`"), "{e}");
        assert!(check_numbered(Path::new("out/s.#.png"), 1000).is_ok());
    }

    #[test]
    fn resolved_paths_lose_their_detours() {
        let r = |a: &str, b: &str| resolve_path(Path::new(a), Path::new(b));
        assert_eq!(r("shots", "../out/a.png"), Path::new("out/a.png"));
        assert_eq!(r("shots/x", "./../../out"), Path::new("out"));
        assert_eq!(r("", "../out"), Path::new("../out"));
        assert_eq!(r("shots", "/abs/out"), Path::new("/abs/out"));
    }
}
