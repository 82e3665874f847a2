//! Rendering one tile: the depth test over the pixel centres each binned triangle covers, then
//! one resolve per pixel that writes the winner's index, depth and barycentrics.

use super::bin::TileGrid;
use super::cut::Kept;
use super::setup::{PixelRect, TriangleSetup};
use super::visibility::VisibilityBuffer;

/// The pixels of one tile in the frame buffers, as one slice per pixel row.
pub(super) struct TileTarget<'a> {
    /// Index of the tile in its grid.
    pub index: usize,
    rect: PixelRect,
    depth: Vec<&'a mut [f32]>,
    triangle: Vec<&'a mut [u32]>,
    barycentric: Vec<&'a mut [[f32; 2]]>,
}

/// Splits `buffer` into the tiles of `grid`, which each own their pixels.
pub(super) fn tile_targets<'a>(
    buffer: &'a mut VisibilityBuffer,
    grid: &TileGrid,
) -> Vec<TileTarget<'a>> {
    let width = buffer.width as usize;
    let depth = split_rows(&mut buffer.depth, width, grid);
    let triangle = split_rows(&mut buffer.triangle, width, grid);
    let barycentric = split_rows(&mut buffer.barycentric, width, grid);
    depth
        .into_iter()
        .zip(triangle)
        .zip(barycentric)
        .enumerate()
        .map(|(index, ((depth, triangle), barycentric))| TileTarget {
            index,
            rect: grid.rect(index),
            depth,
            triangle,
            barycentric,
        })
        .collect()
}

/// For each tile of `grid`, its row slices of the row-major image `data` of width `width`.
fn split_rows<'a, T>(data: &'a mut [T], width: usize, grid: &TileGrid) -> Vec<Vec<&'a mut [T]>> {
    let mut tiles: Vec<Vec<&mut [T]>> = (0..grid.len()).map(|_| Vec::new()).collect();
    for (y, row) in data.chunks_mut(width).enumerate() {
        let first = y / grid.size() * grid.columns();
        for (column, piece) in row.chunks_mut(grid.size()).enumerate() {
            tiles[first + column].push(piece);
        }
    }
    tiles
}

/// Per-tile working memory, reused from tile to tile: the nearest depth so far and the triangle
/// that has it, row-major over the tile.
pub(super) struct Scratch<'s> {
    depth: Vec<f32>,
    /// The triangle index of the nearest fragment so far, `u32::MAX` where none.
    index: Vec<u32>,
    winner: Vec<Option<&'s TriangleSetup>>,
}

impl Scratch<'_> {
    pub(super) fn new() -> Self {
        Self {
            depth: Vec::new(),
            index: Vec::new(),
            winner: Vec::new(),
        }
    }

    /// Empties the scratch for a tile of `pixels` pixels, or with `over`, starts it at what
    /// `over` holds over the tile's rectangle `rect` (its row width `width`).
    fn reset(&mut self, pixels: usize, over: Option<&VisibilityBuffer>, rect: &PixelRect) {
        self.winner.clear();
        self.winner.resize(pixels, None);
        self.depth.clear();
        self.index.clear();
        match over {
            None => {
                self.depth.resize(pixels, f32::INFINITY);
                self.index.resize(pixels, u32::MAX);
            }
            Some(over) => {
                let stride = over.width as usize;
                for y in rect.y0..=rect.y1 {
                    let start = y as usize * stride + rect.x0 as usize;
                    let end = y as usize * stride + rect.x1 as usize + 1;
                    self.depth.extend_from_slice(&over.depth[start..end]);
                    self.index.extend_from_slice(&over.triangle[start..end]);
                }
            }
        }
    }
}

/// What rendering a tile counted.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct TileCounts {
    /// Pixel centres covered, summed over triangles.
    pub fragments: u64,
    /// Pixels with a triangle.
    pub pixels: u64,
    /// Whether the tile holds the pixels of the layer drawn over, copied with no triangle
    /// drawn over them.
    pub copied: bool,
}

/// Renders `triangles` (in ascending input order) into the tile `target`, in each row `y` of
/// the image only the pixels `rows[y].0 .. rows[y].1` when `rows` is given.
///
/// With `over`, the tile starts as `over` holds it (a [`Layer`](super::Layer) of other
/// triangles, depth unclamped) instead of empty; with `clamp`, depth is written clamped to
/// [0, 1]. A tile over which no triangle is drawn is `over`'s pixels copied, and with `copied`,
/// the pixels covered where the tile already holds that copy ([`LayerCopy`]), it is left as it
/// is.
///
/// Depth test: a fragment replaces the stored one when nearer, or at equal depth when of a
/// lower triangle index, so that per pixel the least `(depth, index)` wins whatever order the
/// triangles are drawn in (in ascending order, as here, the second case never arises but over
/// a layer); pieces of one clipped triangle meet in their clipping order.
///
/// [`LayerCopy`]: super::LayerCopy
pub(super) fn render_tile<'s>(
    target: TileTarget<'_>,
    triangles: impl Iterator<Item = &'s TriangleSetup>,
    (cut, rows): Kept<'_>,
    (over, clamp, copied): (Option<&VisibilityBuffer>, bool, Option<u64>),
    scratch: &mut Scratch<'s>,
) -> TileCounts {
    let width = (target.rect.x1 - target.rect.x0 + 1) as usize;
    let mut triangles = triangles.peekable();
    if let (Some(over), None) = (over, triangles.peek()) {
        let pixels = copied.unwrap_or_else(|| copy_over(target, width, over, clamp));
        return TileCounts {
            fragments: 0,
            pixels,
            copied: true,
        };
    }
    scratch.reset(width * target.depth.len(), over, &target.rect);
    let fragments = triangles
        .map(|setup| draw(setup, &target.rect, width, (cut, rows), scratch))
        .sum();
    let pixels = resolve(target, width, scratch, (over, clamp));
    TileCounts {
        fragments,
        pixels,
        copied: false,
    }
}

/// The depth test over the pixels of `tile` (row width `width`) that `setup` covers, stepping
/// the edge functions incrementally: `E(x + 1, y) = E(x, y) + step_x`,
/// `E(x, y + 1) = E(x, y) + step_y`. A pixel centre is covered when every biased edge value is
/// non-negative, i.e. when their bitwise or is. A pixel of a [`TriangleSetup::tested`]
/// triangle that would win is drawn only when `cut` keeps it. With `rows`, a row `y` is
/// tested only over `rows[y].0 .. rows[y].1`, the edge values started where that range starts:
/// `E(x₀, y) = E(r.x₀, y) + (x₀ − r.x₀) step_x`. Returns the number of covered pixel centres.
fn draw<'s>(
    setup: &'s TriangleSetup,
    tile: &PixelRect,
    width: usize,
    (cut, rows): Kept<'_>,
    scratch: &mut Scratch<'s>,
) -> u64 {
    let cut = cut.filter(|_| setup.tested);
    let r = setup.rect.intersection(tile);
    if r.is_empty() {
        return 0;
    }
    let [e0, e1, e2] = &setup.edges;
    let (dx, dy) = (
        i64::from(r.x0 - setup.rect.x0),
        i64::from(r.y0 - setup.rect.y0),
    );
    let mut row = [e0.at(dx, dy), e1.at(dx, dy), e2.at(dx, dy)];
    let mut fragments = 0;
    for y in r.y0..=r.y1 {
        let (x0, x1) = match rows {
            None => (r.x0, r.x1),
            Some(rows) => {
                let (a, b) = rows[y as usize];
                (r.x0.max(a as i32), r.x1.min(b as i32 - 1))
            }
        };
        if x0 > x1 {
            row[0] += e0.step_y;
            row[1] += e1.step_y;
            row[2] += e2.step_y;
            continue;
        }
        let skipped = i64::from(x0 - r.x0);
        let start = (y - tile.y0) as usize * width + (x0 - tile.x0) as usize;
        let span = (x1 - x0 + 1) as usize;
        let depth = &mut scratch.depth[start..start + span];
        let index = &mut scratch.index[start..start + span];
        let winner = &mut scratch.winner[start..start + span];
        let mut e = [
            row[0] + skipped * e0.step_x,
            row[1] + skipped * e1.step_x,
            row[2] + skipped * e2.step_x,
        ];
        let mut entered = false;
        let pixels = depth.iter_mut().zip(index).zip(winner);
        for (x, ((stored, stored_index), won)) in (x0..).zip(pixels) {
            if (e[0] | e[1] | e[2]) >= 0 {
                entered = true;
                fragments += 1;
                let z = setup.depth_at(e);
                let nearer = z < *stored
                    || (z == *stored
                        && *stored_index != u32::MAX
                        && setup.triangle < *stored_index);
                if nearer && cut.is_none_or(|c| c.keeps(setup.triangle, setup.barycentric(x, y))) {
                    *stored = z;
                    *stored_index = setup.triangle;
                    *won = Some(setup);
                }
            } else if entered {
                // A triangle is convex: its pixels in a row are contiguous.
                break;
            }
            e[0] += e0.step_x;
            e[1] += e1.step_x;
            e[2] += e2.step_x;
        }
        row[0] += e0.step_y;
        row[1] += e1.step_y;
        row[2] += e2.step_y;
    }
    fragments
}

/// Writes every pixel of the tile (rows `width` wide) into the frame buffers as `over` holds
/// it, a covered pixel's depth with `clamp` clamped to [0, 1]: what [`resolve`] writes where no triangle is
/// drawn over `over`. Returns the number of pixels with a triangle.
fn copy_over(
    mut target: TileTarget<'_>,
    width: usize,
    over: &VisibilityBuffer,
    clamp: bool,
) -> u64 {
    let mut pixels = 0;
    let stride = over.width as usize;
    let rows = target
        .depth
        .iter_mut()
        .zip(&mut target.triangle)
        .zip(&mut target.barycentric);
    for (dy, ((depth, triangle), barycentric)) in rows.enumerate() {
        let start = (target.rect.y0 as usize + dy) * stride + target.rect.x0 as usize;
        let from = start..start + width;
        triangle.copy_from_slice(&over.triangle[from.clone()]);
        barycentric.copy_from_slice(&over.barycentric[from.clone()]);
        let from = &over.depth[from];
        if clamp {
            // A select a pixel, not a branch, so that the loop runs in vector lanes.
            for ((z, &was), &t) in depth.iter_mut().zip(from).zip(&**triangle) {
                *z = if t == u32::MAX {
                    was
                } else {
                    was.clamp(0.0, 1.0)
                };
            }
        } else {
            depth.copy_from_slice(from);
        }
        pixels += triangle
            .iter()
            .map(|&t| u64::from(t != u32::MAX))
            .sum::<u64>();
    }
    pixels
}

/// Writes every pixel of the tile into the frame buffers: the winner's index, depth (with
/// `clamp`, clamped to [0, 1] against rounding) and barycentrics, what `over` holds there
/// where no triangle drawn won over it, or the empty values; returns the number of pixels
/// with a winner.
fn resolve(
    mut target: TileTarget<'_>,
    width: usize,
    scratch: &Scratch<'_>,
    (over, clamp): (Option<&VisibilityBuffer>, bool),
) -> u64 {
    let clamped = |z: f32| if clamp { z.clamp(0.0, 1.0) } else { z };
    let mut pixels = 0;
    let rows = target
        .depth
        .iter_mut()
        .zip(&mut target.triangle)
        .zip(&mut target.barycentric);
    for (dy, ((depth, triangle), barycentric)) in rows.enumerate() {
        let y = target.rect.y0 + dy as i32;
        let start = dy * width;
        let winners = &scratch.winner[start..start + width];
        for (dx, winner) in winners.iter().enumerate() {
            (depth[dx], triangle[dx], barycentric[dx]) = match winner {
                Some(setup) => {
                    pixels += 1;
                    (
                        clamped(scratch.depth[start + dx]),
                        setup.triangle,
                        setup.barycentric(target.rect.x0 + dx as i32, y),
                    )
                }
                None => match over {
                    Some(over) if scratch.index[start + dx] != u32::MAX => {
                        pixels += 1;
                        let i = y as usize * over.width as usize + (target.rect.x0 as usize + dx);
                        (
                            clamped(over.depth[i]),
                            over.triangle[i],
                            over.barycentric[i],
                        )
                    }
                    _ => (f32::INFINITY, u32::MAX, [0.0; 2]),
                },
            };
        }
    }
    pixels
}
