//! Writing a frame's files so that a farm can retry anywhere: stale temporaries of killed runs
//! cleared, every file written atomically, the colour last.

use std::io::Write as _;
use std::path::{Path, PathBuf};

use super::fingerprint::{Fingerprint, FINGERPRINT_KEY};
use crate::formats::atomic::{
    remove_stale_temporaries, write_atomically_with, Durability, WriteError,
};
use crate::formats::svg::svg_document;
use crate::formats::{beside, write_frame_exr, write_pngs_tagged, AOV_FILE_NAMES};
use crate::render::{RenderedFrame, VectorLines};

/// Which files a frame has beside its colour PNG and its AOVs' PNGs.
#[derive(Clone, Copy, Debug)]
pub(super) struct FrameFiles {
    /// The EXR of every image (when there are AOVs).
    pub exr: bool,
    /// The lines as strokes, `NAME.svg`.
    pub svg: bool,
}

/// Writes `image` to `path` and its AOVs beside it: stale temporaries of earlier, killed runs
/// removed, of every file a frame can have; the EXR and the SVG (as `files` asks) and the AOV
/// PNGs first, the colour PNG last, so that once the colour exists the whole frame does; the
/// PNGs and the SVG synced as `durability` says; each file stamped with `fingerprint`
/// ([`FINGERPRINT_KEY`]). Returns the paths written.
pub(super) fn write_frame(
    image: &RenderedFrame,
    path: &Path,
    files: FrameFiles,
    durability: Durability,
    fingerprint: Option<&Fingerprint>,
) -> Result<Vec<PathBuf>, WriteError> {
    let tag: Vec<(&str, &str)> = fingerprint
        .map(|f| (FINGERPRINT_KEY, f.0.as_str()))
        .into_iter()
        .collect();
    let exr_path = path.with_extension("exr");
    clear_stale_temporaries(path)?;
    let mut written = Vec::new();
    if files.exr {
        write_frame_exr(image, &exr_path, &tag)?;
        written.push(exr_path);
    }
    if files.svg {
        let svg_path = path.with_extension("svg");
        let empty = VectorLines {
            size: (image.width, image.height),
            ..VectorLines::default()
        };
        let document = svg_document(image.lines.as_deref().unwrap_or(&empty), &tag);
        write_atomically_with(&svg_path, durability, |out| {
            out.write_all(document.as_bytes())
                .map_err(|e| e.to_string())
        })?;
        written.push(svg_path);
    }
    written.extend(write_pngs_tagged(image, path, durability, &tag)?);
    Ok(written)
}

/// Removes the stale temporaries of earlier, killed runs beside every file the frame at `path`
/// can have: its colour PNG, its EXR, its SVG and each AOV's PNG.
pub(super) fn clear_stale_temporaries(path: &Path) -> Result<(), WriteError> {
    let exr_path = path.with_extension("exr");
    let svg_path = path.with_extension("svg");
    let aov_paths = AOV_FILE_NAMES.map(|name| beside(path, name));
    let targets = [path, exr_path.as_path(), svg_path.as_path()]
        .into_iter()
        .chain(aov_paths.iter().map(PathBuf::as_path));
    for target in targets {
        remove_stale_temporaries(target).map_err(|e| WriteError {
            path: target.display().to_string(),
            reason: format!("cannot clear old temporary files beside it: {e}"),
        })?;
    }
    Ok(())
}

/// Makes the folder of `path` and checks that a file can be created in it.
pub(super) fn check_writable(path: &Path) -> Result<(), String> {
    let folder = match path.parent() {
        Some(f) if !f.as_os_str().is_empty() => f.to_path_buf(),
        _ => PathBuf::from("."),
    };
    std::fs::create_dir_all(&folder)
        .map_err(|e| format!("cannot create the output folder {}: {e}", folder.display()))?;
    let probe = folder.join(format!(".glint-write-check.{}.tmp", std::process::id()));
    std::fs::write(&probe, b"").map_err(|e| {
        format!(
            "cannot write in the output folder {}: {e}",
            folder.display()
        )
    })?;
    let _ = std::fs::remove_file(&probe);
    Ok(())
}
