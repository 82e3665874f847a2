//! Writing rendered frames: the colour as 8-bit sRGB RGBA PNG, each AOV as its own PNG, and
//! all of them as channels of one EXR for compositing.

use std::path::{Path, PathBuf};

use glam::{Vec2, Vec3, Vec4};

use super::renderer::RenderedFrame;
use crate::formats::atomic::WriteError;
use crate::formats::exr::write_exr;
use crate::formats::png::{write_png, PngLayout};

/// Writes the colour to `path` (PNG) and each AOV the frame holds beside it, named after it:
/// `shot.0001.png` gives `shot.0001.matte.png`, `.patch_id.png` (16-bit indices),
/// `.patches.png` (flat colours, the paper's Figure 9 view), `.depth.png` (16-bit),
/// `.normal.png`, `.uv.png` and `.n_dot_h.png` (heat map). The colour is written last, so once
/// it exists the whole frame does. Returns the paths written.
pub fn write_pngs(frame: &RenderedFrame, path: &Path) -> Result<Vec<PathBuf>, WriteError> {
    let (w, h) = (frame.width, frame.height);
    let beside = |name: &str| -> PathBuf {
        let stem = path
            .file_stem()
            .map_or_else(Default::default, |s| s.to_string_lossy().into_owned());
        path.with_file_name(format!("{stem}.{name}.png"))
    };
    let a = &frame.aovs;
    let mut images: Vec<(PathBuf, PngLayout, Vec<u8>)> = Vec::new();
    if let Some(matte) = &a.matte {
        images.push((beside("matte"), PngLayout::Gray8, grey8(matte)));
    }
    if let Some(ids) = &a.patch_id {
        images.push((beside("patch_id"), PngLayout::Gray16, patch_ids16(ids)));
        images.push((
            beside("patches"),
            PngLayout::Rgba8,
            patch_colours_rgba8(ids),
        ));
    }
    if let Some(depth) = &a.depth {
        images.push((beside("depth"), PngLayout::Gray16, depth16(depth)));
    }
    if let Some(normal) = &a.normal {
        images.push((beside("normal"), PngLayout::Rgba8, normal_rgba8(normal)));
    }
    if let Some(uv) = &a.uv {
        images.push((beside("uv"), PngLayout::Rgba8, uv_rgba8(uv)));
    }
    if let Some(nh) = &a.n_dot_h {
        let alpha: Vec<f32> = frame.colour.iter().map(|c| c.w).collect();
        images.push((
            beside("n_dot_h"),
            PngLayout::Rgba8,
            heat_rgba8(nh, &alpha, HEAT_RANGE),
        ));
    }
    images.push((
        path.to_path_buf(),
        PngLayout::Rgba8,
        colour_rgba8(&frame.colour),
    ));
    let mut written = Vec::with_capacity(images.len());
    for (file, layout, pixels) in images {
        write_png(&file, w, h, layout, &pixels)?;
        written.push(file);
    }
    Ok(written)
}

/// The `N·H` span the heat map shows below 1: a highlight of ε up to this is in view.
pub const HEAT_RANGE: f32 = 0.1;

/// Writes the frame as one EXR: linear `R G B A` and the AOVs as `matte.Y`, `patch_id.Y`
/// (−1 on the background), `depth.Z` (NDC, +∞ on the background), `normal.X/Y/Z`, `uv.U/V` and
/// `n_dot_h.Y`.
pub fn write_frame_exr(frame: &RenderedFrame, path: &Path) -> Result<(), WriteError> {
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
    write_exr(path, frame.width, frame.height, channels)
}

/// The sRGB transfer function of a linear value in [0, 1]:
/// `12.92 c` below 0.0031308, `1.055 c^(1/2.4) − 0.055` above.
pub fn linear_to_srgb(c: f32) -> f32 {
    let c = c.clamp(0.0, 1.0);
    if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

fn byte(v: f32) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// RGBA8: sRGB-encoded colour, linear straight alpha.
pub fn colour_rgba8(colour: &[Vec4]) -> Vec<u8> {
    colour
        .iter()
        .flat_map(|c| {
            [
                byte(linear_to_srgb(c.x)),
                byte(linear_to_srgb(c.y)),
                byte(linear_to_srgb(c.z)),
                byte(c.w),
            ]
        })
        .collect()
}

/// Grey8: a value in [0, 1] per pixel (the highlight matte).
pub fn grey8(values: &[f32]) -> Vec<u8> {
    values.iter().map(|&v| byte(v)).collect()
}

/// A distinct flat colour for each patch index (hues spaced by the golden angle), transparent
/// where no patch is: the patch-id debug view.
pub fn patch_colours_rgba8(ids: &[u32]) -> Vec<u8> {
    ids.iter()
        .flat_map(|&id| {
            if id == u32::MAX {
                return [0, 0, 0, 0];
            }
            let hue = (id as f32 * 0.618_034).fract() * 6.0;
            let x = 1.0 - (hue % 2.0 - 1.0).abs();
            let (r, g, b) = match hue as u32 {
                0 => (1.0, x, 0.0),
                1 => (x, 1.0, 0.0),
                2 => (0.0, 1.0, x),
                3 => (0.0, x, 1.0),
                4 => (x, 0.0, 1.0),
                _ => (1.0, 0.0, x),
            };
            [
                byte(0.25 + 0.7 * r),
                byte(0.25 + 0.7 * g),
                byte(0.25 + 0.7 * b),
                255,
            ]
        })
        .collect()
}

/// Grey16 (big-endian): the patch index itself, 65535 where no patch is.
pub fn patch_ids16(ids: &[u32]) -> Vec<u8> {
    ids.iter()
        .flat_map(|&id| (id.min(65_535) as u16).to_be_bytes())
        .collect()
}

/// Grey16 (big-endian): NDC depth in [0, 1], 65535 on the background.
pub fn depth16(depth: &[f32]) -> Vec<u8> {
    depth
        .iter()
        .flat_map(|&d| ((d.clamp(0.0, 1.0) * 65_535.0).round() as u16).to_be_bytes())
        .collect()
}

/// RGBA8: a unit normal as `0.5 n + 0.5`, transparent where it is zero (background).
pub fn normal_rgba8(normals: &[Vec3]) -> Vec<u8> {
    normals
        .iter()
        .flat_map(|n| {
            let c = *n * 0.5 + 0.5;
            let alpha = if *n == Vec3::ZERO { 0 } else { 255 };
            [byte(c.x), byte(c.y), byte(c.z), alpha]
        })
        .collect()
}

/// RGBA8: a heat map of `N·H` over [1 − 2 `range`, 1]: blue far from the highlight through green
/// and yellow to red at `N·H = 1`; values below the range are blue. `alpha` per pixel (the
/// colour's coverage) keeps the background transparent.
pub fn heat_rgba8(n_dot_h: &[f32], alpha: &[f32], range: f32) -> Vec<u8> {
    n_dot_h
        .iter()
        .zip(alpha)
        .flat_map(|(&x, &a)| {
            let t = ((x - (1.0 - 2.0 * range)) / (2.0 * range)).clamp(0.0, 1.0);
            // Blue (0) → cyan → green → yellow → red (1).
            let (r, g, b) = match (t * 4.0) as u32 {
                0 => (0.0, 4.0 * t, 1.0),
                1 => (0.0, 1.0, 2.0 - 4.0 * t),
                2 => (4.0 * t - 2.0, 1.0, 0.0),
                _ => (1.0, (4.0 - 4.0 * t).max(0.0), 0.0),
            };
            [byte(r), byte(g), byte(b), byte(a)]
        })
        .collect()
}

/// RGBA8: (u, v) as red and green.
pub fn uv_rgba8(uvs: &[Vec2]) -> Vec<u8> {
    uvs.iter()
        .flat_map(|uv| [byte(uv.x), byte(uv.y), 0, 255])
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_encoding_matches_its_reference_points() {
        assert_eq!(linear_to_srgb(0.0), 0.0);
        assert!((linear_to_srgb(1.0) - 1.0).abs() < 1e-6);
        // Linear 0.2159 is sRGB 0.502, 128 of 255.
        assert_eq!(byte(linear_to_srgb(0.2159)), 128);
        assert_eq!(
            colour_rgba8(&[Vec4::new(1.0, 0.0, 2.0, 0.5)]),
            [255, 0, 255, 128]
        );
    }

    #[test]
    fn heat_map_runs_from_blue_to_red_over_its_range() {
        let values = [1.0, 1.0 - 2.0 * HEAT_RANGE, -1.0, 1.0 - HEAT_RANGE];
        let c = heat_rgba8(&values, &[1.0, 1.0, 0.0, 1.0], HEAT_RANGE);
        assert_eq!(c[0..4], [255, 0, 0, 255]);
        assert_eq!(c[4..8], [0, 0, 255, 255]);
        assert_eq!(c[8..12], [0, 0, 255, 0]);
        assert_eq!(c[12..16], [0, 255, 0, 255]);
    }

    #[test]
    fn patch_colours_differ_between_neighbouring_ids() {
        let c = patch_colours_rgba8(&[0, 1, 2, u32::MAX]);
        assert_ne!(c[0..4], c[4..8]);
        assert_ne!(c[4..8], c[8..12]);
        assert_eq!(c[12..16], [0, 0, 0, 0]);
    }
}
