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
    size: (u32, u32),
    layout: PngLayout,
    pixels: &[u8],
    durability: Durability,
) -> Result<(), WriteError> {
    write_png_tagged(path, size, layout, pixels, durability, &[])
}

/// [`write_png_with`] with a `tEXt` chunk for each `(keyword, text)` of `text` (Latin-1, a
/// keyword of 1 to 79 characters), written before the pixels so that a reader finds it without
/// decoding them ([`try_read_png_text`]). Without text, the `image` crate's encoder writes it.
pub fn write_png_tagged(
    path: &Path,
    (width, height): (u32, u32),
    layout: PngLayout,
    pixels: &[u8],
    durability: Durability,
    text: &[(&str, &str)],
) -> Result<(), WriteError> {
    let error = |reason: String| WriteError {
        path: path.display().to_string(),
        reason,
    };
    let (color, depth, bytes_per_pixel) = match layout {
        PngLayout::Rgba8 => (png::ColorType::Rgba, png::BitDepth::Eight, 4),
        PngLayout::Gray8 => (png::ColorType::Grayscale, png::BitDepth::Eight, 1),
        PngLayout::Gray16 => (png::ColorType::Grayscale, png::BitDepth::Sixteen, 2),
    };
    let expected = width as usize * height as usize * bytes_per_pixel;
    if pixels.len() != expected {
        return Err(error(format!(
            "{} bytes of pixels for a {width}×{height} {layout:?} image, which needs {expected}",
            pixels.len()
        )));
    }
    if text.is_empty() {
        return write_untagged(path, (width, height), layout, pixels, durability);
    }
    write_atomically_with(path, durability, |out| {
        let mut encoder = png::Encoder::new(out, width, height);
        encoder.set_color(color);
        encoder.set_depth(depth);
        encoder.set_compression(png::Compression::Balanced);
        encoder.set_filter(png::Filter::Adaptive);
        for (keyword, value) in text {
            encoder
                .add_text_chunk((*keyword).to_string(), (*value).to_string())
                .map_err(|e| e.to_string())?;
        }
        // 16-bit samples are big-endian in PNG, as `pixels` holds them.
        let mut writer = encoder.write_header().map_err(|e| e.to_string())?;
        writer.write_image_data(pixels).map_err(|e| e.to_string())?;
        writer.finish().map_err(|e| e.to_string())
    })
}

/// The image written by the `image` crate's PNG encoder.
fn write_untagged(
    path: &Path,
    (width, height): (u32, u32),
    layout: PngLayout,
    pixels: &[u8],
    durability: Durability,
) -> Result<(), WriteError> {
    let color = match layout {
        PngLayout::Rgba8 => ExtendedColorType::Rgba8,
        PngLayout::Gray8 => ExtendedColorType::L8,
        PngLayout::Gray16 => ExtendedColorType::L16,
    };
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

/// The text of the PNG file at `path` under `keyword` (its first `tEXt` chunk of that name
/// before the pixels): `Ok(None)` when it has none, `Err` when the file cannot be read as a PNG.
pub fn try_read_png_text(path: &Path, keyword: &str) -> Result<Option<String>, String> {
    let file = std::fs::File::open(path).map_err(|e| e.to_string())?;
    let decoder = png::Decoder::new(std::io::BufReader::new(file));
    let reader = decoder.read_info().map_err(|e| e.to_string())?;
    Ok(reader
        .info()
        .uncompressed_latin1_text
        .iter()
        .find(|chunk| chunk.keyword == keyword)
        .map(|chunk| chunk.text.clone()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn untagged_images_have_the_image_crate_s_bytes_and_tags_read_back() {
        let dir = tempfile::tempdir().unwrap();
        let (w, h) = (7u32, 5u32);
        let pixels: Vec<u8> = (0..w * h * 4).map(|i| (i * 37 % 251) as u8).collect();
        let path = dir.path().join("a.png");
        write_png(&path, w, h, PngLayout::Rgba8, &pixels).unwrap();
        let mut expected = Vec::new();
        PngEncoder::new(&mut expected)
            .write_image(&pixels, w, h, ExtendedColorType::Rgba8)
            .unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), expected);
        assert_eq!(try_read_png_text(&path, "glint:fingerprint"), Ok(None));

        let tagged = dir.path().join("b.png");
        let tags = [("glint:fingerprint", "0123abcd"), ("Software", "glint")];
        write_png_tagged(
            &tagged,
            (w, h),
            PngLayout::Rgba8,
            &pixels,
            Durability::Synced,
            &tags,
        )
        .unwrap();
        assert_eq!(
            try_read_png_text(&tagged, "glint:fingerprint"),
            Ok(Some("0123abcd".to_string()))
        );
        let decoded = image::open(&tagged).unwrap().to_rgba8().into_raw();
        assert_eq!(decoded, pixels);
        let grey: Vec<u8> = (0..w * h * 2).map(|i| (i * 53 % 256) as u8).collect();
        let deep = dir.path().join("d.png");
        write_png_tagged(
            &deep,
            (w, h),
            PngLayout::Gray16,
            &grey,
            Durability::Synced,
            &tags,
        )
        .unwrap();
        let read = image::open(&deep).unwrap().to_luma16().into_raw();
        let expected: Vec<u16> = grey
            .chunks(2)
            .map(|b| u16::from_be_bytes([b[0], b[1]]))
            .collect();
        assert_eq!(read, expected, "16-bit samples stay big-endian");
        std::fs::write(dir.path().join("c.png"), b"not a png").unwrap();
        assert!(try_read_png_text(&dir.path().join("c.png"), "x").is_err());
    }

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
