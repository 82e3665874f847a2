//! A contact sheet: equal tiles in a grid, each with a caption in a strip beneath it, the tile's
//! pixels copied unchanged.

use image::{Rgba, RgbaImage};

use super::text::{draw_label, fit_text, label_size, LabelStyle};
use crate::render::MAX_SIDE;

/// The most tiles one sheet holds.
pub const MAX_TILES: usize = 64;

/// The space between cells and around the sheet, in pixels.
pub const SHEET_GAP: u32 = 4;

/// The sheet's colour between cells.
pub const SHEET_BACKGROUND: Rgba<u8> = Rgba([48, 48, 52, 255]);

/// Where the tiles and captions of a sheet go.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SheetLayout {
    pub tiles: usize,
    pub columns: u32,
    pub rows: u32,
    /// Each tile's `(width, height)`.
    pub tile: (u32, u32),
    pub caption: LabelStyle,
}

/// A sheet that cannot be laid out.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum SheetError {
    #[error("a sheet needs at least one tile")]
    NoTiles,
    #[error("{count} tiles are more than the {MAX_TILES} a sheet holds; make fewer variants or frames, or several sheets")]
    TooManyTiles { count: usize },
    #[error("--columns must be at least 1")]
    NoColumns,
    #[error("the sheet would be {width}×{height} pixels, over the {MAX_SIDE} a side may have; use smaller tiles or another number of columns")]
    TooLarge { width: u64, height: u64 },
}

impl SheetLayout {
    /// The layout of `tiles` tiles of `tile` size in `columns` columns (default
    /// `⌈√tiles⌉`, the grid nearest a square), with `rows = ⌈tiles / columns⌉`. Captions are
    /// drawn at scale 2 when every one of `captions` fits the tile's width at it, else at
    /// scale 1 (cut to fit). The sheet is `columns·(w + gap) + gap` wide and
    /// `rows·(h + caption + gap) + gap` high, at most [`MAX_SIDE`] each way.
    pub fn new(
        captions: &[String],
        tile: (u32, u32),
        columns: Option<u32>,
    ) -> Result<Self, SheetError> {
        let tiles = captions.len();
        if tiles == 0 {
            return Err(SheetError::NoTiles);
        }
        if tiles > MAX_TILES {
            return Err(SheetError::TooManyTiles { count: tiles });
        }
        let columns = match columns {
            Some(0) => return Err(SheetError::NoColumns),
            Some(n) => n,
            None => (tiles as f64).sqrt().ceil() as u32,
        };
        let rows = tiles.div_ceil(columns as usize) as u32;
        let large = LabelStyle::dark_on_light(2);
        let fits = captions.iter().all(|c| label_size(c, &large).0 <= tile.0);
        let caption = LabelStyle::dark_on_light(if fits { 2 } else { 1 });
        let layout = Self {
            tiles,
            columns,
            rows,
            tile,
            caption,
        };
        let (width, height) = layout.size_u64();
        if width > u64::from(MAX_SIDE) || height > u64::from(MAX_SIDE) {
            return Err(SheetError::TooLarge { width, height });
        }
        Ok(layout)
    }

    /// The height of the caption strip under each tile.
    #[must_use]
    pub fn caption_height(&self) -> u32 {
        label_size("", &self.caption).1
    }

    fn size_u64(&self) -> (u64, u64) {
        let gap = u64::from(SHEET_GAP);
        (
            u64::from(self.columns) * (u64::from(self.tile.0) + gap) + gap,
            u64::from(self.rows)
                * (u64::from(self.tile.1) + u64::from(self.caption_height()) + gap)
                + gap,
        )
    }

    /// The sheet's `(width, height)`.
    #[must_use]
    pub fn size(&self) -> (u32, u32) {
        let (w, h) = self.size_u64();
        (w as u32, h as u32)
    }

    /// The top-left pixel of tile `index`, counted along rows from the top left.
    #[must_use]
    pub fn tile_origin(&self, index: usize) -> (u32, u32) {
        let (column, row) = (index as u32 % self.columns, index as u32 / self.columns);
        (
            SHEET_GAP + column * (self.tile.0 + SHEET_GAP),
            SHEET_GAP + row * (self.tile.1 + self.caption_height() + SHEET_GAP),
        )
    }
}

/// A sheet being filled tile by tile.
pub struct Sheet {
    layout: SheetLayout,
    image: RgbaImage,
}

impl Sheet {
    /// An empty sheet of `layout`.
    #[must_use]
    pub fn new(layout: SheetLayout) -> Self {
        let (width, height) = layout.size();
        Self {
            layout,
            image: RgbaImage::from_pixel(width, height, SHEET_BACKGROUND),
        }
    }

    /// Copies `tile` (of the layout's tile size; a larger one is cut, a smaller one leaves the
    /// rest of its cell as it was) into cell `index` unchanged, and draws `caption` in the strip
    /// under it, cut to the tile's width.
    pub fn put(&mut self, index: usize, tile: &RgbaImage, caption: &str) {
        let (x0, y0) = self.layout.tile_origin(index);
        let (w, h) = self.layout.tile;
        for y in 0..h.min(tile.height()) {
            for x in 0..w.min(tile.width()) {
                self.image.put_pixel(x0 + x, y0 + y, *tile.get_pixel(x, y));
            }
        }
        let style = self.layout.caption;
        let text = fit_text(caption, w, &style);
        draw_label(
            &mut self.image,
            &text,
            (i64::from(x0), i64::from(y0 + h)),
            &style,
        );
    }

    /// The finished sheet.
    #[must_use]
    pub fn into_image(self) -> RgbaImage {
        self.image
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn captions(n: usize) -> Vec<String> {
        (1..=n).map(|i| format!("frame {i}")).collect()
    }

    #[test]
    fn the_default_grid_is_near_square_and_holds_every_tile() {
        for (n, columns, rows) in [
            (1, 1, 1),
            (2, 2, 1),
            (3, 2, 2),
            (5, 3, 2),
            (9, 3, 3),
            (10, 4, 3),
        ] {
            let layout = SheetLayout::new(&captions(n), (40, 30), None).unwrap();
            assert_eq!((layout.columns, layout.rows), (columns, rows), "{n} tiles");
        }
        let layout = SheetLayout::new(&captions(5), (40, 30), Some(5)).unwrap();
        assert_eq!((layout.columns, layout.rows), (5, 1));
    }

    #[test]
    fn cells_do_not_overlap_and_fill_the_sheet() {
        let layout = SheetLayout::new(&captions(5), (40, 30), Some(2)).unwrap();
        let caption = layout.caption_height();
        assert_eq!(layout.size(), (2 * 44 + 4, 3 * (30 + caption + 4) + 4));
        assert_eq!(layout.tile_origin(0), (4, 4));
        assert_eq!(layout.tile_origin(1), (48, 4));
        assert_eq!(layout.tile_origin(2), (4, 4 + 30 + caption + 4));
        let (w, h) = layout.size();
        let (x, y) = layout.tile_origin(4);
        assert!(x + 40 + 4 <= w && y + 30 + caption + 4 == h);
    }

    #[test]
    fn tiles_are_copied_unchanged_with_their_caption_beneath() {
        let layout = SheetLayout::new(&captions(2), (40, 30), None).unwrap();
        let mut sheet = Sheet::new(layout);
        let tile = RgbaImage::from_fn(40, 30, |x, y| Rgba([x as u8, y as u8, 7, (x * y) as u8]));
        sheet.put(1, &tile, "frame 2");
        let image = sheet.into_image();
        let (x0, y0) = layout.tile_origin(1);
        for y in 0..30 {
            for x in 0..40 {
                assert_eq!(image.get_pixel(x0 + x, y0 + y), tile.get_pixel(x, y));
            }
        }
        let caption = (0..layout.caption_height())
            .flat_map(|y| (0..40).map(move |x| (x, y)))
            .filter(|&(x, y)| *image.get_pixel(x0 + x, y0 + 30 + y) == layout.caption.ink)
            .count();
        assert!(caption > 20, "{caption}");
        // Cell 0 was not filled: background.
        let (x0, y0) = layout.tile_origin(0);
        assert_eq!(*image.get_pixel(x0 + 5, y0 + 5), SHEET_BACKGROUND);
    }

    #[test]
    fn captions_too_wide_for_scale_two_are_drawn_at_scale_one() {
        let short = SheetLayout::new(&captions(2), (320, 180), None).unwrap();
        assert_eq!(short.caption.scale, 2);
        let long = vec!["alpha=0.25 beta=0.125 gamma=3".to_string()];
        let layout = SheetLayout::new(&long, (320, 180), None).unwrap();
        assert_eq!(layout.caption.scale, 1);
    }

    #[test]
    fn sheets_past_the_limits_are_refused() {
        assert_eq!(
            SheetLayout::new(&captions(65), (8, 8), None),
            Err(SheetError::TooManyTiles { count: 65 })
        );
        assert_eq!(
            SheetLayout::new(&[], (8, 8), None),
            Err(SheetError::NoTiles)
        );
        assert_eq!(
            SheetLayout::new(&captions(2), (8, 8), Some(0)),
            Err(SheetError::NoColumns)
        );
        assert!(matches!(
            SheetLayout::new(&captions(4), (9000, 100), None),
            Err(SheetError::TooLarge { .. })
        ));
    }
}
