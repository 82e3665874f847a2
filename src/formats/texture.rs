//! Reading 2D toon textures from PNG: sRGB-encoded pixels decoded to linear RGB.

use std::path::Path;

use glam::Vec3;

use super::srgb::srgb_to_linear;
use image::ImageFormat;

use super::FormatError;
use crate::toon::ToonTexture;

/// Reads the PNG at `path` as a 2D toon texture: column 0 is `n·l = −1`, the top row D = 1.
/// Colours are sRGB-encoded (as a paint program shows them) and decoded to linear RGB; alpha is
/// ignored. Grey, 16-bit and palette images are read as their RGB colours.
pub fn read_toon_texture(path: &Path) -> Result<ToonTexture, FormatError> {
    let shown = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|source| FormatError::Io {
        path: shown.clone(),
        source,
    })?;
    toon_texture_from_png(&bytes, &shown)
}

/// A toon texture from the bytes of a PNG file, as [`read_toon_texture`] reads it; `shown`
/// names the file in errors.
pub fn toon_texture_from_png(bytes: &[u8], shown: &str) -> Result<ToonTexture, FormatError> {
    let shown = shown.to_string();
    let image = image::load_from_memory_with_format(bytes, ImageFormat::Png)
        .map_err(|e| FormatError::Image {
            path: shown.clone(),
            message: e.to_string(),
        })?
        .to_rgb8();
    let (width, height) = image.dimensions();
    toon_texture_from_srgb8(width as usize, height as usize, image.as_raw()).map_err(|e| {
        FormatError::Image {
            path: shown,
            message: e.to_string(),
        }
    })
}

/// A toon texture from sRGB-encoded RGB8 pixels, rows from the top: each channel decoded with
/// [`srgb_to_linear`].
pub fn toon_texture_from_srgb8(
    width: usize,
    height: usize,
    rgb: &[u8],
) -> Result<ToonTexture, crate::toon::XToonError> {
    let texels = rgb
        .chunks_exact(3)
        .map(|p| Vec3::from_array([p[0], p[1], p[2]].map(|c| srgb_to_linear(f32::from(c) / 255.0))))
        .collect();
    ToonTexture::new(width, height, texels)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pixels_are_decoded_from_srgb_to_linear() {
        // Encoded 0, 128, 188 and 255 of 255 are linear 0, 0.215861, 0.502886 and 1
        // (IEC 61966-2-1); one texel per channel order, rows from the top.
        let t = toon_texture_from_srgb8(2, 1, &[0, 128, 255, 188, 0, 128]).unwrap();
        let close = |a: Vec3, b: [f32; 3]| (a - Vec3::from_array(b)).abs().max_element() < 1e-5;
        assert!(
            close(t.texel(0, 0), [0.0, 0.215_861, 1.0]),
            "{}",
            t.texel(0, 0)
        );
        assert!(
            close(t.texel(1, 0), [0.502_886, 0.0, 0.215_861]),
            "{}",
            t.texel(1, 0)
        );
    }

    #[test]
    fn unreadable_files_name_the_path() {
        let dir = tempfile::tempdir().unwrap();
        let missing = dir.path().join("missing.png");
        assert!(read_toon_texture(&missing)
            .unwrap_err()
            .to_string()
            .contains("missing.png"));
        let garbage = dir.path().join("garbage.png");
        std::fs::write(&garbage, b"not a png").unwrap();
        let e = read_toon_texture(&garbage).unwrap_err().to_string();
        assert!(e.starts_with(&garbage.display().to_string()), "{e}");
    }
}
