//! The files of a rendered frame: the colour as an 8-bit sRGB RGBA PNG, each AOV as a PNG
//! beside it, and all of them as channels of one EXR for compositing.

use std::path::{Path, PathBuf};

use glam::Vec4;

use super::atomic::{Durability, WriteError};
use super::exr::write_exr;
use super::image_encoding::{
    colour_rgba8, depth16, grey8, heat_rgba8, normal_rgba8, patch_colours_rgba8, patch_ids16,
    uv_rgba8, HEAT_RANGE,
};
use super::png::{write_png_tagged, PngLayout};
use crate::render::RenderedFrame;

/// The names the AOV files beside a frame add to it ([`beside`]), every one there is.
pub const AOV_FILE_NAMES: [&str; 9] = [
    "matte", "patch_id", "patches", "depth", "normal", "uv", "n_dot_h", "n_dot_l", "outline",
];

/// The file beside the frame file `path` that holds its AOV `name`: `shot.0001.png` gives
/// `shot.0001.NAME.png`.
#[must_use]
pub fn beside(path: &Path, name: &str) -> PathBuf {
    let stem = path
        .file_stem()
        .map_or_else(Default::default, |s| s.to_string_lossy().into_owned());
    path.with_file_name(format!("{stem}.{name}.png"))
}

/// Writes the colour to `path` (PNG) and each AOV the frame holds beside it, named after it:
/// `shot.0001.png` gives `shot.0001.matte.png`, `.patch_id.png` (16-bit indices),
/// `.patches.png` (flat colours, the view of Figure 9 in Anjyo & Hiramitsu 2003), `.depth.png`
/// (16-bit), `.normal.png`, `.uv.png`, `.n_dot_h.png` (heat map), `.n_dot_l.png` (heat map
/// over [−1, 1]) and `.outline.png` (the lines
/// alone, sRGB with alpha). The colour is written last, so once it exists the whole frame does.
/// Returns the paths written.
pub fn write_pngs(frame: &RenderedFrame, path: &Path) -> Result<Vec<PathBuf>, WriteError> {
    write_pngs_with(frame, path, Durability::Synced)
}

/// [`write_pngs`], each file synced as `durability` says.
pub fn write_pngs_with(
    frame: &RenderedFrame,
    path: &Path,
    durability: Durability,
) -> Result<Vec<PathBuf>, WriteError> {
    write_pngs_tagged(frame, path, durability, &[])
}

/// [`write_pngs_with`], each file with a `tEXt` chunk for each `(keyword, text)` of `text`.
pub fn write_pngs_tagged(
    frame: &RenderedFrame,
    path: &Path,
    durability: Durability,
    text: &[(&str, &str)],
) -> Result<Vec<PathBuf>, WriteError> {
    let (w, h) = (frame.width, frame.height);
    let aov_file = |name: &str| beside(path, name);
    let a = &frame.aovs;
    let mut images: Vec<(PathBuf, PngLayout, Vec<u8>)> = Vec::new();
    if let Some(matte) = &a.matte {
        images.push((aov_file("matte"), PngLayout::Gray8, grey8(matte)));
    }
    if let Some(ids) = &a.patch_id {
        images.push((aov_file("patch_id"), PngLayout::Gray16, patch_ids16(ids)));
        images.push((
            aov_file("patches"),
            PngLayout::Rgba8,
            patch_colours_rgba8(ids),
        ));
    }
    if let Some(depth) = &a.depth {
        images.push((aov_file("depth"), PngLayout::Gray16, depth16(depth)));
    }
    if let Some(normal) = &a.normal {
        images.push((aov_file("normal"), PngLayout::Rgba8, normal_rgba8(normal)));
    }
    if let Some(uv) = &a.uv {
        images.push((aov_file("uv"), PngLayout::Rgba8, uv_rgba8(uv)));
    }
    if let Some(nh) = &a.n_dot_h {
        let alpha: Vec<f32> = frame.colour.iter().map(|c| c.w).collect();
        images.push((
            aov_file("n_dot_h"),
            PngLayout::Rgba8,
            heat_rgba8(nh, &alpha, HEAT_RANGE),
        ));
    }
    if let Some(nl) = &a.n_dot_l {
        let alpha: Vec<f32> = frame.colour.iter().map(|c| c.w).collect();
        // The whole range of N·L': the heat map's [1 − 2·1, 1].
        images.push((
            aov_file("n_dot_l"),
            PngLayout::Rgba8,
            heat_rgba8(nl, &alpha, 1.0),
        ));
    }
    if let Some(lines) = &a.outline {
        images.push((aov_file("outline"), PngLayout::Rgba8, colour_rgba8(lines)));
    }
    images.push((
        path.to_path_buf(),
        PngLayout::Rgba8,
        colour_rgba8(&frame.colour),
    ));
    let mut written = Vec::with_capacity(images.len());
    for (file, layout, pixels) in images {
        write_png_tagged(&file, (w, h), layout, &pixels, durability, text)?;
        written.push(file);
    }
    Ok(written)
}

/// Writes the frame as one EXR: linear `R G B A` and the AOVs as `matte.Y`, `patch_id.Y`
/// (−1 on the background), `depth.Z` (NDC, +∞ on the background), `normal.X/Y/Z`, `uv.U/V`,
/// `n_dot_h.Y`, `n_dot_l.Y` and `outline.R/G/B/A` (linear, straight alpha); a text attribute in its header for each `(name, text)` of `text`.
pub fn write_frame_exr(
    frame: &RenderedFrame,
    path: &Path,
    text: &[(&str, &str)],
) -> Result<(), WriteError> {
    let plane = |f: &dyn Fn(&Vec4) -> f32| frame.colour.iter().map(f).collect::<Vec<f32>>();
    let mut channels = vec![
        ("R".to_string(), plane(&|c| c.x)),
        ("G".to_string(), plane(&|c| c.y)),
        ("B".to_string(), plane(&|c| c.z)),
        ("A".to_string(), plane(&|c| c.w)),
    ];
    let a = &frame.aovs;
    if let Some(matte) = &a.matte {
        channels.push(("matte.Y".into(), matte.clone()));
    }
    if let Some(ids) = &a.patch_id {
        let ids = ids
            .iter()
            .map(|&i| if i == u32::MAX { -1.0 } else { i as f32 })
            .collect();
        channels.push(("patch_id.Y".into(), ids));
    }
    if let Some(depth) = &a.depth {
        channels.push(("depth.Z".into(), depth.clone()));
    }
    if let Some(normal) = &a.normal {
        channels.push(("normal.X".into(), normal.iter().map(|n| n.x).collect()));
        channels.push(("normal.Y".into(), normal.iter().map(|n| n.y).collect()));
        channels.push(("normal.Z".into(), normal.iter().map(|n| n.z).collect()));
    }
    if let Some(uv) = &a.uv {
        channels.push(("uv.U".into(), uv.iter().map(|t| t.x).collect()));
        channels.push(("uv.V".into(), uv.iter().map(|t| t.y).collect()));
    }
    if let Some(nh) = &a.n_dot_h {
        channels.push(("n_dot_h.Y".into(), nh.clone()));
    }
    if let Some(nl) = &a.n_dot_l {
        channels.push(("n_dot_l.Y".into(), nl.clone()));
    }
    if let Some(lines) = &a.outline {
        for (channel, name) in ["R", "G", "B", "A"].into_iter().enumerate() {
            channels.push((
                format!("outline.{name}"),
                lines.iter().map(|l| l[channel]).collect(),
            ));
        }
    }
    write_exr(path, frame.width, frame.height, channels, text)
}
