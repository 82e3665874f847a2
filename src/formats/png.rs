//! PNG output (8-bit RGBA, 8- and 16-bit grey), written atomically.

use std::path::Path;

use image::codecs::png::PngEncoder;
use image::{ExtendedColorType, ImageEncoder};

use super::atomic::{write_atomically_with, Durability, WriteError};

/// The pixel layouts glint writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PngLayout {
    /// 8-bit RGBA, 4 bytes a pixel.
    Rgba8,
    /// 8-bit grey, 1 byte a pixel.
    Gray8,
    /// 16-bit grey, 2 bytes a pixel, big-endian.
    Gray16,
}

/// Writes `pixels` (rows top to bottom, in `layout`) as a PNG at `path`, atomically and synced.
pub fn write_png(
    path: &Path,
    width: u32,
    height: u32,
    layout: PngLayout,
    pixels: &[u8],
) -> Result<(), WriteError> {
    write_png_with(path, (width, height), layout, pixels, Durability::Synced)
}

/// [`write_png`] of a `(width, height)` image, synced as `durability` says.
pub fn write_png_with(
    path: &Path,
    (width, height): (u32, u32),
    layout: PngLayout,
    pixels: &[u8],
    durability: Durability,
) -> Result<(), WriteError> {
    let error = |reason: String| WriteError {
        path: path.display().to_string(),
        reason,
    };
    let (color, bytes_per_pixel) = match layout {
        PngLayout::Rgba8 => (ExtendedColorType::Rgba8, 4),
        PngLayout::Gray8 => (ExtendedColorType::L8, 1),
        PngLayout::Gray16 => (ExtendedColorType::L16, 2),
    };
    let expected = width as usize * height as usize * bytes_per_pixel;
    if pixels.len() != expected {
        return Err(error(format!(
            "{} bytes of pixels for a {width}×{height} {layout:?} image, which needs {expected}",
            pixels.len()
        )));
    }
    // The encoder takes 16-bit samples in native byte order and writes them big-endian, as PNG
    // stores them.
    let native: Vec<u8>;
    let pixels = match layout {
        PngLayout::Gray16 => {
            native = pixels
                .chunks_exact(2)
                .flat_map(|b| u16::from_be_bytes([b[0], b[1]]).to_ne_bytes())
                .collect();
            &native
        }
        PngLayout::Rgba8 | PngLayout::Gray8 => pixels,
    };
    write_atomically_with(path, durability, |out| {
        PngEncoder::new(out)
            .write_image(pixels, width, height, color)
            .map_err(|e| e.to_string())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_a_png_that_decodes_to_the_same_pixels_and_leaves_no_temporary() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.png");
        let pixels: Vec<u8> = (0..4 * 3 * 2).map(|i| i as u8 * 10).collect();
        write_png(&path, 3, 2, PngLayout::Rgba8, &pixels).unwrap();
        let decoded = image::open(&path).unwrap().to_rgba8();
        assert_eq!(decoded.as_raw(), &pixels);
        let names: Vec<_> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, ["a.png"]);
    }

    #[test]
    fn sixteen_bit_samples_given_big_endian_decode_to_their_values() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("g.png");
        let values: [u16; 3] = [21, 0x0102, 65_535];
        let bytes: Vec<u8> = values.iter().flat_map(|v| v.to_be_bytes()).collect();
        write_png(&path, 3, 1, PngLayout::Gray16, &bytes).unwrap();
        let decoded = image::open(&path).unwrap().to_luma16();
        assert_eq!(decoded.as_raw(), &values);
    }

    #[test]
    fn an_unwritable_path_is_an_error_naming_it_and_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("missing-dir").join("a.png");
        let e = write_png(&path, 1, 1, PngLayout::Gray8, &[0]).unwrap_err();
        assert!(e.to_string().contains("missing-dir"), "{e}");
        // Wrong buffer size: the encoder refuses, and no file or temporary remains.
        let path = dir.path().join("b.png");
        assert!(write_png(&path, 2, 2, PngLayout::Gray8, &[0]).is_err());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }
}
