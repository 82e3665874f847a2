//! Whether a frame's files on disk are whole and current: each expected file (the colour PNG, an
//! AOV's PNGs, the EXR, the SVG) a regular file that decodes, of the shot's size, stamped with the
//! frame's fingerprint.

use std::path::{Path, PathBuf};

use super::fingerprint::{Fingerprint, FINGERPRINT_KEY};
use super::RenderJob;
use crate::formats::beside;
use crate::formats::exr::try_read_exr_text;
use crate::formats::png::try_read_png_text;
use crate::formats::svg::try_read_svg;
use crate::shot::Aov;

/// How closely to look at a frame's files.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scrutiny {
    /// Regular files whose stamp is the frame's fingerprint (a header read each): what
    /// `--skip-existing` trusts, the files being written atomically.
    Stamp,
    /// Also decoded whole, and of the shot's size: what `glint verify` checks.
    Decode,
}

/// What is wrong with one file of a frame.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum FileProblem {
    /// It does not exist.
    Missing,
    /// Something that is not a regular file is in its place (a folder, a device).
    NotAFile,
    /// It cannot be decoded (truncated, not an image).
    Broken(String),
    /// It decodes to another size than the shot's.
    WrongSize { found: (u32, u32) },
    /// It was made from other inputs than the current ones (or carries no fingerprint).
    Stale,
}

impl FileProblem {
    /// The problem in a few words.
    #[must_use]
    pub fn describe(&self, expected: (u32, u32)) -> String {
        match self {
            FileProblem::Missing => "missing".to_string(),
            FileProblem::NotAFile => "not a regular file".to_string(),
            FileProblem::Broken(reason) => format!("does not decode ({reason})"),
            FileProblem::WrongSize { found } => format!(
                "{}×{} instead of {}×{}",
                found.0, found.1, expected.0, expected.1
            ),
            FileProblem::Stale => "made from other inputs than the shot's now".to_string(),
        }
    }
}

/// The files an AOV is written to beside a frame's colour, by the name they add to it.
#[must_use]
pub fn aov_file_names(aov: Aov) -> &'static [&'static str] {
    match aov {
        Aov::Matte => &["matte"],
        Aov::PatchId => &["patch_id", "patches"],
        Aov::Depth => &["depth"],
        Aov::Normal => &["normal"],
        Aov::Uv => &["uv"],
        Aov::NDotH => &["n_dot_h"],
        Aov::NDotL => &["n_dot_l"],
        Aov::Outline => &["outline"],
    }
}

impl RenderJob {
    /// Every file frame `frame` is written to: the colour PNG, each AOV's PNGs beside it and,
    /// with AOVs, the EXR.
    #[must_use]
    pub fn frame_files(&self, frame: i64) -> Vec<PathBuf> {
        let colour = self.frame_path(frame);
        let mut files = vec![colour.clone()];
        for &aov in &self.shot().aovs {
            files.extend(aov_file_names(aov).iter().map(|name| beside(&colour, name)));
        }
        if !self.shot().aovs.is_empty() {
            files.push(colour.with_extension("exr"));
        }
        if self.overrides.svg {
            files.push(colour.with_extension("svg"));
        }
        files
    }

    /// The problems of frame `frame`'s files, looked at as `scrutiny` says: empty when the frame
    /// is whole and current.
    #[must_use]
    pub fn frame_problems(&self, frame: i64, scrutiny: Scrutiny) -> Vec<(PathBuf, FileProblem)> {
        let expected = self.fingerprint(frame);
        let size = (self.settings().width, self.settings().height);
        self.frame_files(frame)
            .into_iter()
            .filter_map(|file| {
                check_file(&file, expected.as_ref(), size, scrutiny).map(|problem| (file, problem))
            })
            .collect()
    }
}

/// What is wrong with the file at `path`, if anything.
fn check_file(
    path: &Path,
    expected: Option<&Fingerprint>,
    size: (u32, u32),
    scrutiny: Scrutiny,
) -> Option<FileProblem> {
    let meta = match std::fs::symlink_metadata(path) {
        Ok(meta) => meta,
        Err(_) => return Some(FileProblem::Missing),
    };
    let regular = meta.is_file() || (meta.file_type().is_symlink() && path.is_file());
    if !regular {
        return Some(FileProblem::NotAFile);
    }
    let is_exr = path.extension().is_some_and(|e| e == "exr");
    if path.extension().is_some_and(|e| e == "svg") {
        return check_svg(path, expected, size);
    }
    let stamp = if is_exr {
        try_read_exr_text(path, FINGERPRINT_KEY)
    } else {
        try_read_png_text(path, FINGERPRINT_KEY)
    };
    let stamp = match stamp {
        Ok(stamp) => stamp,
        Err(reason) => return Some(FileProblem::Broken(reason)),
    };
    if scrutiny == Scrutiny::Decode {
        let found = if is_exr {
            decode_exr(path)
        } else {
            image::open(path)
                .map(|image| (image.width(), image.height()))
                .map_err(|e| e.to_string())
        };
        match found {
            Err(reason) => return Some(FileProblem::Broken(reason)),
            Ok(found) if found != size => return Some(FileProblem::WrongSize { found }),
            Ok(_) => {}
        }
    }
    match (stamp, expected) {
        (Some(stamp), Some(expected)) if stamp == expected.0 => None,
        _ => Some(FileProblem::Stale),
    }
}

/// What is wrong with the SVG at `path`, a regular file: it is read whole whatever the
/// scrutiny (it holds its stamp as text, and is small beside the frame's images).
fn check_svg(path: &Path, expected: Option<&Fingerprint>, size: (u32, u32)) -> Option<FileProblem> {
    let text = match std::fs::read_to_string(path) {
        Ok(text) => text,
        Err(e) => return Some(FileProblem::Broken(e.to_string())),
    };
    match try_read_svg(&text, FINGERPRINT_KEY) {
        Err(reason) => Some(FileProblem::Broken(reason)),
        Ok((found, _)) if found != size => Some(FileProblem::WrongSize { found }),
        Ok((_, Some(stamp))) if expected.is_some_and(|e| e.0 == stamp) => None,
        Ok(_) => Some(FileProblem::Stale),
    }
}

/// The size of the EXR at `path`, after reading all its pixels.
fn decode_exr(path: &Path) -> Result<(u32, u32), String> {
    let image = exr::prelude::read_all_flat_layers_from_file(path).map_err(|e| e.to_string())?;
    let layer = image.layer_data.first().ok_or("no layer")?;
    let size = layer.size;
    Ok((size.0 as u32, size.1 as u32))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formats::AOV_FILE_NAMES;

    #[test]
    fn every_aov_s_files_are_among_those_a_frame_can_have() {
        let mut names: Vec<&str> = Aov::ALL
            .iter()
            .flat_map(|&a| aov_file_names(a).iter().copied())
            .collect();
        names.sort_unstable();
        let mut all = AOV_FILE_NAMES.to_vec();
        all.sort_unstable();
        assert_eq!(names, all);
    }
}
