//! Reading 2D toon textures from PNG: sRGB-encoded pixels decoded to linear RGB.

use std::path::Path;

use glam::Vec3;
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
    let image = image::load_from_memory_with_format(&bytes, ImageFormat::Png)
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

/// The inverse sRGB transfer function of an encoded value in [0, 1]:
/// `c / 12.92` up to 0.04045, `((c + 0.055) / 1.055)^2.4` above.
#[must_use]
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.040_45 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_decoding_matches_its_reference_points() {
        assert_eq!(srgb_to_linear(0.0), 0.0);
        assert!((srgb_to_linear(1.0) - 1.0).abs() < 1e-6);
        // sRGB 128/255 is linear 0.2159.
        assert!((srgb_to_linear(128.0 / 255.0) - 0.2159).abs() < 1e-4);
        // Both branches meet at the threshold.
        let t = 0.040_45;
        assert!((t / 12.92 - ((t + 0.055) / 1.055_f32).powf(2.4)).abs() < 1e-6);
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
