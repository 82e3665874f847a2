//! A line of text drawn onto an RGBA image in a box of its own, for labels that stay legible
//! over any picture.
//!
//! The glyphs are the public-domain 8 × 8 bitmap font of the `font8x8` crate, drawn at a whole
//! scale (each font pixel a `scale × scale` square): crisp at any size, no font file to ship,
//! and the same pixels on every machine.

use font8x8::{UnicodeFonts, BASIC_FONTS, GREEK_FONTS, LATIN_FONTS};
use image::{Rgba, RgbaImage};

/// The font's glyph cell, in font pixels: every glyph is this wide and high.
pub const GLYPH_SIDE: u32 = 8;

/// How a label is drawn: its glyphs' scale and colours, and the box around them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct LabelStyle {
    /// Image pixels per font pixel (≥ 1).
    pub scale: u32,
    /// The glyphs' colour.
    pub ink: Rgba<u8>,
    /// The box's colour, drawn under the glyphs.
    pub background: Rgba<u8>,
    /// Image pixels of box around the glyphs on every side.
    pub padding: u32,
}

impl LabelStyle {
    /// Dark ink on a light, opaque box with 2 pixels of padding, at `scale`.
    #[must_use]
    pub fn dark_on_light(scale: u32) -> Self {
        Self {
            scale,
            ink: Rgba([20, 20, 24, 255]),
            background: Rgba([250, 250, 246, 255]),
            padding: 2,
        }
    }
}

/// A rectangle of image pixels: `x..x + width` by `y..y + height`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelRect {
    pub x: i64,
    pub y: i64,
    pub width: u32,
    pub height: u32,
}

impl PixelRect {
    /// Whether pixel `(x, y)` lies in the rectangle.
    #[must_use]
    pub fn contains(&self, x: i64, y: i64) -> bool {
        (self.x..self.x + i64::from(self.width)).contains(&x)
            && (self.y..self.y + i64::from(self.height)).contains(&y)
    }

    /// Whether the two rectangles share a pixel.
    #[must_use]
    pub fn overlaps(&self, other: &PixelRect) -> bool {
        self.x < other.x + i64::from(other.width)
            && other.x < self.x + i64::from(self.width)
            && self.y < other.y + i64::from(other.height)
            && other.y < self.y + i64::from(self.height)
    }

    /// The rectangle of this size centred on pixel `(cx, cy)` (the extra pixel of an even side
    /// to the left and top), moved by the least amount that puts it inside a `width × height`
    /// image; a rectangle larger than the image is put at its left or top edge.
    #[must_use]
    pub fn centred_inside(
        size: (u32, u32),
        (cx, cy): (i64, i64),
        (width, height): (u32, u32),
    ) -> Self {
        let fit = |centre: i64, side: u32, room: u32| {
            let start = centre - i64::from(side) / 2;
            start.min(i64::from(room) - i64::from(side)).max(0)
        };
        PixelRect {
            x: fit(cx, size.0, width),
            y: fit(cy, size.1, height),
            width: size.0,
            height: size.1,
        }
    }
}

/// The 8 × 8 glyph of `c`, one byte a row from the top, bit `i` the `i`-th pixel from the left;
/// `?` for a character the font does not have.
#[must_use]
fn glyph(c: char) -> [u8; 8] {
    BASIC_FONTS
        .get(c)
        .or_else(|| LATIN_FONTS.get(c))
        .or_else(|| GREEK_FONTS.get(c))
        .or_else(|| BASIC_FONTS.get('?'))
        .unwrap_or([0; 8])
}

/// The size of `text`'s box: `(8·scale·chars + 2·padding, 8·scale + 2·padding)`.
#[must_use]
pub fn label_size(text: &str, style: &LabelStyle) -> (u32, u32) {
    let chars = u32::try_from(text.chars().count()).unwrap_or(u32::MAX);
    let cell = GLYPH_SIDE * style.scale;
    (
        cell.saturating_mul(chars).saturating_add(2 * style.padding),
        cell + 2 * style.padding,
    )
}

/// The longest start of `text` whose box is at most `width` wide, ending in `..` when cut;
/// `text` itself when it fits.
#[must_use]
pub fn fit_text(text: &str, width: u32, style: &LabelStyle) -> String {
    if label_size(text, style).0 <= width {
        return text.to_owned();
    }
    let cell = GLYPH_SIDE * style.scale;
    let room = (width.saturating_sub(2 * style.padding) / cell) as usize;
    let kept: String = text.chars().take(room.saturating_sub(2)).collect();
    if room >= 2 {
        format!("{kept}..")
    } else {
        kept
    }
}

/// Draws `text` on one line in its box with the box's top-left corner at `(x, y)`: the box
/// ([`label_size`]) filled with the background, then the glyphs' pixels in ink, each font
/// pixel a `scale × scale` square. What falls outside the image is left out. Returns the box.
pub fn draw_label(
    image: &mut RgbaImage,
    text: &str,
    (x, y): (i64, i64),
    style: &LabelStyle,
) -> PixelRect {
    draw_block(image, &[text], (x, y), style)
}

/// The size of a block of `lines`, one under another in one box: the widest line's box
/// ([`label_size`]) wide and `lines · 8·scale + 2·padding` high.
#[must_use]
pub fn block_size(lines: &[&str], style: &LabelStyle) -> (u32, u32) {
    let width = lines
        .iter()
        .map(|line| label_size(line, style).0)
        .max()
        .unwrap_or(2 * style.padding);
    let rows = u32::try_from(lines.len()).unwrap_or(u32::MAX);
    (
        width,
        (GLYPH_SIDE * style.scale)
            .saturating_mul(rows)
            .saturating_add(2 * style.padding),
    )
}

/// Draws `lines` one under another in one box ([`block_size`]) with its top-left corner at
/// `(x, y)`, as [`draw_label`] draws one. Returns the box.
pub fn draw_block(
    image: &mut RgbaImage,
    lines: &[&str],
    (x, y): (i64, i64),
    style: &LabelStyle,
) -> PixelRect {
    let (width, height) = block_size(lines, style);
    let rect = PixelRect {
        x,
        y,
        width,
        height,
    };
    let mut put = |px: i64, py: i64, colour: Rgba<u8>| {
        if let (Ok(px), Ok(py)) = (u32::try_from(px), u32::try_from(py)) {
            if px < image.width() && py < image.height() {
                image.put_pixel(px, py, colour);
            }
        }
    };
    for py in y..y + i64::from(height) {
        for px in x..x + i64::from(width) {
            put(px, py, style.background);
        }
    }
    let scale = i64::from(style.scale);
    let cell = i64::from(GLYPH_SIDE) * scale;
    let (left, top) = (x + i64::from(style.padding), y + i64::from(style.padding));
    for (line_index, line) in lines.iter().enumerate() {
        let line_top = top + line_index as i64 * cell;
        for (i, c) in line.chars().enumerate() {
            let glyph_left = left + i as i64 * cell;
            for (row, bits) in glyph(c).iter().enumerate() {
                for column in 0..8 {
                    if bits & (1 << column) == 0 {
                        continue;
                    }
                    let (gx, gy) = (glyph_left + column * scale, line_top + row as i64 * scale);
                    for dy in 0..scale {
                        for dx in 0..scale {
                            put(gx + dx, gy + dy, style.ink);
                        }
                    }
                }
            }
        }
    }
    rect
}

#[cfg(test)]
mod tests {
    use super::*;

    const PAPER: Rgba<u8> = Rgba([10, 120, 200, 255]);

    fn paper(width: u32, height: u32) -> RgbaImage {
        RgbaImage::from_pixel(width, height, PAPER)
    }

    #[test]
    fn a_label_changes_exactly_the_pixels_inside_its_box() {
        let style = LabelStyle::dark_on_light(2);
        let mut image = paper(80, 40);
        let rect = draw_label(&mut image, "lid 24", (5, 7), &style);
        assert_eq!((rect.width, rect.height), (6 * 16 + 4, 16 + 4));
        for (x, y, p) in image.enumerate_pixels() {
            let inside = rect.contains(i64::from(x), i64::from(y));
            assert_eq!(*p != PAPER, inside, "pixel ({x}, {y})");
        }
    }

    #[test]
    fn glyphs_are_ink_on_the_box_and_differ_from_letter_to_letter() {
        let style = LabelStyle::dark_on_light(1);
        let mut image = paper(40, 12);
        draw_label(&mut image, "IO", (0, 0), &style);
        let cell = |i: u32| -> Vec<bool> {
            (0..8)
                .flat_map(|y| (0..8).map(move |x| (x, y)))
                .map(|(x, y)| *image.get_pixel(2 + 8 * i + x, 2 + y) == style.ink)
                .collect()
        };
        let (i, o) = (cell(0), cell(1));
        // Each glyph has ink and box between its strokes, and the two letters differ.
        for g in [&i, &o] {
            let inked = g.iter().filter(|&&on| on).count();
            assert!(inked > 6 && inked < 40, "{inked}");
        }
        assert_ne!(i, o);
        // The padding is all box.
        assert!((0..12).all(|y| *image.get_pixel(0, y) == style.background));
    }

    #[test]
    fn scale_two_draws_each_font_pixel_as_a_square() {
        let mut one = paper(12, 12);
        let mut two = paper(20, 20);
        draw_label(&mut one, "A", (0, 0), &LabelStyle::dark_on_light(1));
        draw_label(&mut two, "A", (0, 0), &LabelStyle::dark_on_light(2));
        for y in 0..16 {
            for x in 0..16 {
                assert_eq!(
                    two.get_pixel(2 + x, 2 + y),
                    one.get_pixel(2 + x / 2, 2 + y / 2)
                );
            }
        }
    }

    #[test]
    fn a_block_stacks_lines_as_labels_in_one_box() {
        let style = LabelStyle::dark_on_light(1);
        let mut block = paper(40, 30);
        let rect = draw_block(&mut block, &["ab", "wxyz"], (1, 1), &style);
        assert_eq!((rect.width, rect.height), (4 * 8 + 4, 2 * 8 + 4));
        let mut first = paper(40, 30);
        draw_label(&mut first, "ab", (1, 1), &style);
        let mut second = paper(40, 30);
        draw_label(&mut second, "wxyz", (1, 9), &style);
        for (x, y, p) in block.enumerate_pixels() {
            let expected = if (3..11).contains(&y) && (3..19).contains(&x) {
                *first.get_pixel(x, y)
            } else if (11..19).contains(&y) && (3..35).contains(&x) {
                *second.get_pixel(x, y)
            } else if rect.contains(i64::from(x), i64::from(y)) {
                style.background
            } else {
                PAPER
            };
            assert_eq!(*p, expected, "pixel ({x}, {y})");
        }
    }

    #[test]
    fn a_label_past_the_edge_is_clipped_not_wrapped() {
        let style = LabelStyle::dark_on_light(1);
        let mut image = paper(10, 10);
        let rect = draw_label(&mut image, "wide label", (-3, 6), &style);
        assert_eq!((rect.x, rect.y), (-3, 6));
        for (x, y, p) in image.enumerate_pixels() {
            assert_eq!(*p != PAPER, y >= 6, "pixel ({x}, {y})");
        }
    }

    #[test]
    fn boxes_are_centred_then_kept_inside_the_image() {
        let image = (100, 50);
        let r = PixelRect::centred_inside((20, 10), (50, 25), image);
        assert_eq!((r.x, r.y), (40, 20));
        let r = PixelRect::centred_inside((20, 10), (2, 49), image);
        assert_eq!((r.x, r.y), (0, 40));
        assert!(r.contains(2, 49));
        let r = PixelRect::centred_inside((20, 10), (99, 0), image);
        assert_eq!((r.x, r.y), (80, 0));
        let r = PixelRect::centred_inside((200, 10), (50, 25), image);
        assert_eq!(r.x, 0);
        assert!(r.overlaps(&PixelRect {
            x: 199,
            y: 29,
            width: 5,
            height: 5
        }));
        assert!(!r.overlaps(&PixelRect {
            x: 200,
            y: 20,
            width: 5,
            height: 5
        }));
    }

    #[test]
    fn text_too_wide_is_cut_with_dots() {
        let style = LabelStyle::dark_on_light(1);
        assert_eq!(fit_text("alpha=0.2", 100, &style), "alpha=0.2");
        // 8 px a character and 2 px of padding each side: 44 px hold 5 characters.
        assert_eq!(fit_text("alpha=0.2", 44, &style), "alp..");
        assert!(label_size(&fit_text("alpha=0.2", 44, &style), &style).0 <= 44);
    }
}
