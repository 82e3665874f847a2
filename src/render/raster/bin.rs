//! Square tiles over the viewport, and binning set-up triangles to the tiles their pixel
//! bounding boxes overlap.

use super::setup::{PixelRect, TriangleSetup};

/// The viewport cut into `size × size` tiles (smaller at the right and bottom borders), numbered
/// row by row.
#[derive(Clone, Debug)]
pub(super) struct TileGrid {
    size: u32,
    columns: u32,
    rows: u32,
    screen: PixelRect,
    /// Tile column of each pixel column and tile row of each pixel row, looked up rather than
    /// divided for every binned triangle.
    column_of: Vec<u32>,
    row_of: Vec<u32>,
}

impl TileGrid {
    pub(super) fn new(screen: PixelRect, size: u32) -> Self {
        let (width, height) = ((screen.x1 + 1) as u32, (screen.y1 + 1) as u32);
        Self {
            size,
            columns: width.div_ceil(size),
            rows: height.div_ceil(size),
            screen,
            column_of: (0..width).map(|x| x / size).collect(),
            row_of: (0..height).map(|y| y / size).collect(),
        }
    }

    /// Number of tiles.
    pub(super) fn len(&self) -> usize {
        self.columns as usize * self.rows as usize
    }

    /// Tile side in pixels.
    pub(super) fn size(&self) -> usize {
        self.size as usize
    }

    /// Tiles per row.
    pub(super) fn columns(&self) -> usize {
        self.columns as usize
    }

    /// The pixels of tile `index`.
    pub(super) fn rect(&self, index: usize) -> PixelRect {
        let size = i64::from(self.size);
        let column = (index % self.columns as usize) as i64;
        let row = (index / self.columns as usize) as i64;
        let (x0, y0) = (column * size, row * size);
        // Tile origins lie inside the screen, so they fit in i32; far ends are clamped to it.
        PixelRect {
            x0: x0 as i32,
            y0: y0 as i32,
            x1: (x0 + size - 1).min(i64::from(self.screen.x1)) as i32,
            y1: (y0 + size - 1).min(i64::from(self.screen.y1)) as i32,
        }
    }

    /// The tiles overlapping `rect`, a non-empty rectangle inside the screen.
    fn covering(&self, rect: &PixelRect) -> impl Iterator<Item = usize> {
        let columns = self.columns as usize;
        let column = |x: i32| self.column_of[x as usize] as usize;
        let row = |y: i32| self.row_of[y as usize] as usize;
        let (c0, c1) = (column(rect.x0), column(rect.x1));
        (row(rect.y0)..=row(rect.y1)).flat_map(move |r| (c0..=c1).map(move |c| r * columns + c))
    }
}

/// For each tile, the indices of the set-up triangles overlapping it, in ascending order (a
/// counting sort: count per tile, prefix sums, fill).
#[derive(Clone, Debug, Default)]
pub(super) struct Bins {
    /// `items[start[t]..start[t + 1]]` is tile `t`'s list.
    start: Vec<usize>,
    items: Vec<u32>,
}

impl Bins {
    /// Bins `setups` to the tiles of `grid`, replacing what the bins held.
    pub(super) fn fill(&mut self, grid: &TileGrid, setups: &[TriangleSetup]) {
        let start = &mut self.start;
        start.clear();
        start.resize(grid.len() + 1, 0);
        for setup in setups {
            for tile in grid.covering(&setup.rect) {
                start[tile + 1] += 1;
            }
        }
        for t in 0..grid.len() {
            start[t + 1] += start[t];
        }
        let mut next = start.clone();
        self.items.clear();
        self.items.resize(start[grid.len()], 0);
        for (index, setup) in setups.iter().enumerate() {
            for tile in grid.covering(&setup.rect) {
                self.items[next[tile]] = index as u32;
                next[tile] += 1;
            }
        }
    }

    /// Indices of the set-up triangles overlapping tile `tile`, ascending.
    pub(super) fn tile(&self, tile: usize) -> &[u32] {
        &self.items[self.start[tile]..self.start[tile + 1]]
    }
}
