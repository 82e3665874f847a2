//! Readers and writers of files: RON patch libraries, `.bpt` Bezier patches, USD text layers
//! (with their time samples), 2D toon textures, and the PNG and EXR files of rendered frames.

pub mod atomic;
mod bpt;
mod error;
pub mod exr;
mod frame_files;
pub mod image_encoding;
mod parse_ron;
pub mod parts;
mod patch_ron;
pub mod png;
pub mod replace_text;
pub mod ron_location;
pub mod ron_paths;
mod srgb;
pub mod svg;
pub mod text_file;
mod texture;
mod usd;

use std::path::Path;

use crate::geom::PatchLibrary;

pub use bpt::parse_bpt;
pub use error::FormatError;
pub use frame_files::{
    beside, write_frame_exr, write_pngs, write_pngs_tagged, write_pngs_with, AOV_FILE_NAMES,
};
pub use patch_ron::parse_patch_ron;
pub use srgb::{linear_to_srgb, srgb_to_linear};
pub use texture::{read_toon_texture, toon_texture_from_png, toon_texture_from_srgb8};
pub use usd::{
    parse_usda, parse_usda_motion, TimeCodes, UsdMotion, DEFAULT_TIME_CODES_PER_SECOND,
    MAX_PATCHES as MAX_USD_PATCHES, MAX_SAMPLES as MAX_USD_SAMPLES,
};

/// A model as read, with how its patches move when the file animates them.
#[derive(Clone, Debug)]
pub struct Model {
    pub library: PatchLibrary,
    /// Some for a USD layer (text, or binary with `usd-binary`) whose time samples move a
    /// patch; None otherwise.
    pub motion: Option<UsdMotion>,
}

impl Model {
    /// A model that does not move.
    #[must_use]
    pub fn still(library: PatchLibrary) -> Self {
        Self {
            library,
            motion: None,
        }
    }
}

/// A reader of a model's text (`text`, shown in errors as `shown`): its library and, for a USD
/// layer, its motion.
type ReadText = fn(&str, &str) -> Result<(PatchLibrary, Option<UsdMotion>), FormatError>;

/// A `.usd`, `.usdc` or `.usdz` file at `path`: a `.usd` that is text is read as `.usda`; a
/// binary layer through the `usd-binary` feature, or refused with the conversion to run.
fn load_binary_usd(path: &Path, kind: Option<&str>, shown: String) -> Result<Model, FormatError> {
    let head = std::fs::File::open(path)
        .and_then(|mut f| {
            let mut head = [0u8; 8];
            let n = std::io::Read::read(&mut f, &mut head)?;
            Ok(head[..n].to_vec())
        })
        .map_err(|source| FormatError::Io {
            path: shown.clone(),
            source,
        })?;
    if head.starts_with(b"#usda") && kind == Some("usd") {
        let text = text_file::read_text(path).map_err(|e| FormatError::File {
            path: shown.clone(),
            message: e.to_string(),
        })?;
        let (library, motion) = parse_usda_motion(&text, &shown)?;
        return Ok(Model { library, motion });
    }
    let convert = format!(
        "convert it to text with usdcat, from the usd-core Python package: usdcat --flatten {} -o model.usda",
        path.display()
    );
    if kind == Some("usdz") {
        return Err(FormatError::File {
            path: shown,
            message: format!("glint does not open .usdz packages; {convert}"),
        });
    }
    #[cfg(feature = "usd-binary")]
    {
        let _ = convert;
        let (library, motion) = usd::read_usdc_motion(path, &shown)?;
        Ok(Model { library, motion })
    }
    #[cfg(not(feature = "usd-binary"))]
    Err(FormatError::File {
        path: shown,
        message: format!(
            "this glint reads USD as text (.usda), built without the `usd-binary` feature; {convert}"
        ),
    })
}

/// Loads a model: a RON patch library (`.ron`), Bezier patches (`.bpt`) or a USD layer
/// (`.usda`; `.usd` and `.usdc` too with the `usd-binary` feature), by extension. A USD
/// layer's time-sampled values are read at their earliest samples.
pub fn load_patches(path: &Path) -> Result<PatchLibrary, FormatError> {
    Ok(load_model(path)?.library)
}

/// Loads a model like [`load_patches`], keeping a USD layer's time samples: its motion is
/// Some when they move a patch.
pub fn load_model(path: &Path) -> Result<Model, FormatError> {
    let shown = path.display().to_string();
    let kind = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    if let Some(model) = parts::model_of_parts_file(path) {
        return Err(FormatError::PartsFile {
            path: shown,
            model: model.display().to_string(),
        });
    }
    let parse: ReadText = match kind.as_deref() {
        Some("ron") => |text, shown| Ok((parse_patch_ron(text, shown)?, None)),
        Some("bpt") => |text, shown| Ok((parse_bpt(text, shown)?, None)),
        Some("usda") => parse_usda_motion,
        Some("usd" | "usdc" | "usdz") => return load_binary_usd(path, kind.as_deref(), shown),
        _ => return Err(FormatError::UnknownKind { path: shown }),
    };
    let text = text_file::read_text(path).map_err(|e| match e {
        text_file::TextError::Io(source) => FormatError::Io {
            path: shown.clone(),
            source,
        },
        e @ (text_file::TextError::NotAFile | text_file::TextError::TooLarge) => {
            FormatError::File {
                path: shown.clone(),
                message: e.to_string(),
            }
        }
        text_file::TextError::NotUtf8 { line, col } => FormatError::Ron {
            path: shown.clone(),
            line,
            col,
            message: "the file is not UTF-8 text: these bytes do not read as UTF-8".to_string(),
        },
    })?;
    let (mut library, motion) = parse(&text, &shown)?;
    let parts = parts::parts_file(path);
    if parts.is_file() {
        let more = parts::read_parts_file(&parts, &library.patches, &library.groups)?;
        library.groups.extend(more);
    }
    Ok(Model { library, motion })
}
