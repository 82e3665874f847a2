//! The triangle rasterizer: indexed triangles in homogeneous clip space in, a visibility buffer
//! out — per pixel the nearest triangle, its depth and the perspective-correct barycentrics of the
//! pixel centre on it.
//!
//! One call runs in three steps:
//! 1. every vertex is classified against the clip planes and projected once, snapped to a
//!    1/256-pixel grid (`setup`);
//! 2. in chunks of triangles, in parallel: triangles outside the view are culled, triangles
//!    crossing the near or far plane (or leaving the guard band) are clipped (`clip`), and each
//!    remaining triangle is set up as three integer edge functions, then binned to square tiles
//!    by its pixel bounding box (`bin`);
//! 3. tiles are rendered in parallel, each owning its pixels: per covered pixel centre a depth
//!    test, then per pixel one resolve of the winner's barycentrics (`tile`).
//!
//! Every value written is a function of the triangle list and the pixel alone — edge functions
//! are exact integers, depth and barycentrics are evaluated per pixel, and each tile meets its
//! triangles in input order — so the buffers are byte-identical for any thread count and tile
//! size.
//!
//! [`rasterize`] allocates per call; a [`Rasterizer`] keeps its working memory, and the buffer it
//! renders into, from one frame to the next.
//!
//! ```
//! use glam::Vec4;
//! use glint::render::raster::{rasterize, RasterOptions, Viewport};
//!
//! // One triangle over the whole 4 × 2 viewport (orthographic: w = 1); on screen its corners are
//! // (0, 2), (8, 2) and (0, −2) pixels.
//! let positions = [
//!     Vec4::new(-1.0, -1.0, 0.5, 1.0),
//!     Vec4::new(3.0, -1.0, 0.5, 1.0),
//!     Vec4::new(-1.0, 3.0, 0.5, 1.0),
//! ];
//! let viewport = Viewport { width: 4, height: 2 };
//! let (buffer, stats) = rasterize(viewport, &positions, &[[0, 1, 2]], &RasterOptions::default());
//! assert_eq!(stats.pixels_covered, 8);
//! // The centre (0.5, 1.5) of the bottom-left pixel is v0 + b1·(8, 0) + b2·(0, −4).
//! let hit = buffer.hit(0, 1).unwrap();
//! assert_eq!((hit.triangle, hit.depth), (0, 0.5));
//! assert_eq!(hit.barycentric, [0.0625, 0.125]);
//! ```

mod bin;
mod clip;
mod cut;
mod layer;
mod layer_copy;
#[cfg(test)]
mod layer_tests;
mod setup;
mod tile;
mod viewport;
mod visibility;

use std::ops::{Add, Mul, Range};

use glam::{DVec2, Vec4};
use rayon::prelude::*;

use crate::geom::Region;

use bin::{Bins, TileGrid};
use clip::{Planes, Verdict};
use setup::{Screen, ScreenVertex, TriangleSetup};
use tile::Scratch;

pub use cut::Cut;
pub use layer::Layer;
pub use layer_copy::LayerCopy;
pub use setup::{MAX_VIEWPORT_SIDE, SUBPIXEL_BITS};
pub use viewport::Viewport;
pub use visibility::{Hit, VisibilityBuffer};

use cut::Kept;

/// A vertex in homogeneous clip space (after the projection matrix): x, y in [−w, w] are on
/// screen, depth z in [0, w] (near plane z = 0, far plane z = w; glam's `Mat4::perspective_rh` /
/// `orthographic_rh` conventions), w > 0 in front of the camera.
pub type ClipVertex = Vec4;

/// How to run [`rasterize`]. The output does not depend on either setting.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RasterOptions {
    /// Worker threads; 0 runs in the current rayon pool (by default one thread per core).
    /// Any other count builds a pool for the call: to render many frames on a fixed number of
    /// threads, install your own pool once and pass 0.
    pub threads: usize,
    /// Side of the square tiles rendered in parallel, in pixels; 0 means
    /// [`RasterOptions::DEFAULT_TILE_SIZE`].
    pub tile_size: u32,
}

impl RasterOptions {
    pub const DEFAULT_TILE_SIZE: u32 = 64;
}

impl Default for RasterOptions {
    fn default() -> Self {
        Self {
            threads: 0,
            tile_size: Self::DEFAULT_TILE_SIZE,
        }
    }
}

/// Counts from one [`rasterize`] call.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct RasterStats {
    /// Triangles in the input list.
    pub triangles_in: usize,
    /// Triangles skipped for an index out of range or a NaN or infinite vertex coordinate.
    pub triangles_invalid: usize,
    /// Triangles that reached no pixel centre's bounding box: outside the view frustum, behind
    /// the camera, zero-area after snapping, or between pixel centres; and triangles a
    /// [`Cut`] cuts away whole.
    pub triangles_culled: usize,
    /// Triangles clipped against the near or far plane or the guard band (culled ones included
    /// when nothing of them remained).
    pub triangles_clipped: usize,
    /// Triangles rasterized, counting each triangle of a clipped polygon.
    pub triangles_rasterized: usize,
    /// Pixel centres covered, summed over triangles (≥ `pixels_covered`; the ratio is the
    /// overdraw).
    pub fragments: u64,
    /// Pixels with a triangle in the output.
    pub pixels_covered: u64,
}

impl Add for RasterStats {
    type Output = Self;

    fn add(self, other: Self) -> Self {
        Self {
            triangles_in: self.triangles_in + other.triangles_in,
            triangles_invalid: self.triangles_invalid + other.triangles_invalid,
            triangles_culled: self.triangles_culled + other.triangles_culled,
            triangles_clipped: self.triangles_clipped + other.triangles_clipped,
            triangles_rasterized: self.triangles_rasterized + other.triangles_rasterized,
            fragments: self.fragments + other.fragments,
            pixels_covered: self.pixels_covered + other.pixels_covered,
        }
    }
}

/// Interpolates a vertex attribute at barycentrics `b = (b1, b2)` from the visibility buffer:
/// `a0·(1 − b1 − b2) + a1·b1 + a2·b2`. The barycentrics are already perspective-correct, so this
/// is the perspective-correct value.
pub fn interpolate<T>(b: [f32; 2], a0: T, a1: T, a2: T) -> T
where
    T: Mul<f32, Output = T> + Add<Output = T>,
{
    a0 * (1.0 - b[0] - b[1]) + a1 * b[0] + a2 * b[1]
}

/// Triangles set up per parallel job; the output does not depend on it.
const CHUNK_TRIANGLES: usize = 1024;

/// Rasterizes the indexed triangles `triangles` (each indexing `positions`) into a visibility
/// buffer of `viewport`'s size. Both windings are drawn (no back-face culling). Triangles are
/// clipped to the near and far planes (z = 0 and z = w); their parts beside or above the view
/// are cut by the viewport. A pixel is covered when its centre is inside the triangle, on an
/// edge under the top-left rule. Triangles with an index out of range or a NaN or infinite
/// coordinate are skipped and counted.
///
/// Allocates the buffer and working memory for the call; a frame loop can reuse both with
/// [`Rasterizer::rasterize_into`].
///
/// # Panics
/// If a viewport side exceeds [`MAX_VIEWPORT_SIDE`] or there are `u32::MAX` triangles or more.
pub fn rasterize(
    viewport: Viewport,
    positions: &[ClipVertex],
    triangles: &[[u32; 3]],
    options: &RasterOptions,
) -> (VisibilityBuffer, RasterStats) {
    let mut buffer = VisibilityBuffer::default();
    let stats =
        Rasterizer::new().rasterize_into(viewport, positions, triangles, options, &mut buffer);
    (buffer, stats)
}

/// The working memory of [`rasterize`] — projected vertices, set-up and binned triangles —
/// kept from one call to the next, so that rendering frame after frame allocates (and
/// page-faults) nothing once the sizes have settled.
#[derive(Debug, Default)]
pub struct Rasterizer {
    vertices: Vec<Vertex>,
    chunks: Vec<Chunk>,
}

impl Rasterizer {
    /// A rasterizer holding no memory yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// [`rasterize`] into `buffer`, which is resized to the viewport and overwritten, reusing its
    /// memory and this rasterizer's.
    ///
    /// # Panics
    /// As [`rasterize`].
    pub fn rasterize_into(
        &mut self,
        viewport: Viewport,
        positions: &[ClipVertex],
        triangles: &[[u32; 3]],
        options: &RasterOptions,
        buffer: &mut VisibilityBuffer,
    ) -> RasterStats {
        self.rasterize_cut_into(viewport, positions, triangles, None, options, buffer)
    }

    /// [`Rasterizer::rasterize_into`] drawing only what `cut` keeps of the triangles: those it
    /// cuts away whole are culled, and a pixel of one it crosses is drawn only where it keeps
    /// the pixel's centre. A pixel cut away is not written, so the nearest surface behind it
    /// shows.
    ///
    /// # Panics
    /// As [`rasterize`].
    pub fn rasterize_cut_into(
        &mut self,
        viewport: Viewport,
        positions: &[ClipVertex],
        triangles: &[[u32; 3]],
        cut: Option<&dyn Cut>,
        options: &RasterOptions,
        buffer: &mut VisibilityBuffer,
    ) -> RasterStats {
        self.rasterize_rows_into(viewport, positions, triangles, cut, None, options, buffer)
    }

    /// [`Rasterizer::rasterize_cut_into`] testing, in each row `y` of the viewport, only the
    /// pixels `rows[y].0 .. rows[y].1` (an empty range tests none): the others are left empty.
    /// A pixel tested is drawn as the whole viewport would draw it, since the depth test is
    /// the pixel's own; what is left out costs nothing but the triangles' set-up.
    ///
    /// # Panics
    /// As [`rasterize`], and if `rows` is given with a length other than the viewport's
    /// height.
    #[allow(clippy::too_many_arguments)]
    pub fn rasterize_rows_into(
        &mut self,
        viewport: Viewport,
        positions: &[ClipVertex],
        triangles: &[[u32; 3]],
        cut: Option<&dyn Cut>,
        rows: Option<&[(u32, u32)]>,
        options: &RasterOptions,
        buffer: &mut VisibilityBuffer,
    ) -> RasterStats {
        if let Some(rows) = rows {
            assert_eq!(
                rows.len(),
                viewport.height as usize,
                "one range of pixels per row"
            );
        }
        assert!(
            viewport.width <= MAX_VIEWPORT_SIDE && viewport.height <= MAX_VIEWPORT_SIDE,
            "viewport {}×{} exceeds {MAX_VIEWPORT_SIDE} pixels a side",
            viewport.width,
            viewport.height
        );
        assert!(
            triangles.len() < u32::MAX as usize,
            "u32::MAX marks empty pixels"
        );
        let tile_size = match options.tile_size {
            0 => RasterOptions::DEFAULT_TILE_SIZE,
            size => size,
        };
        in_pool(options.threads, || {
            buffer.resize(viewport);
            if viewport.width == 0 || viewport.height == 0 {
                return RasterStats {
                    triangles_in: triangles.len(),
                    triangles_culled: triangles.len(),
                    ..RasterStats::default()
                };
            }
            let drawn = Drawn {
                ranges: None,
                over: None,
                clamp: true,
            };
            self.rasterize_in_pool(
                viewport,
                positions,
                triangles,
                (cut, rows),
                (drawn, None),
                tile_size,
                buffer,
            )
            .0
        })
    }

    /// [`Rasterizer::rasterize_cut_into`] of only the triangles whose indices lie in `ranges`
    /// (ascending, not overlapping, within the list), into `layer`: what they show, to be drawn
    /// over by the others ([`Rasterizer::rasterize_over_into`]).
    ///
    /// # Panics
    /// As [`rasterize`], and if a range is out of order or beyond the list.
    pub fn rasterize_layer_into(
        &mut self,
        viewport: Viewport,
        positions: &[ClipVertex],
        (triangles, ranges): (&[[u32; 3]], &[Range<u32>]),
        cut: Option<&dyn Cut>,
        layer: &mut Layer,
    ) -> RasterStats {
        let drawn = Drawn {
            ranges: Some(ranges),
            over: None,
            clamp: false,
        };
        let buffer = layer.buffer_mut();
        let (stats, _) =
            self.rasterize_ranges(viewport, positions, triangles, cut, (drawn, None), buffer);
        stats
    }

    /// The triangles whose indices lie in `ranges` (ascending, not overlapping, within the list)
    /// drawn over `layer`, the visibility of other triangles of the same list made by
    /// [`Rasterizer::rasterize_layer_into`] for the same viewport, positions of its triangles
    /// and cut. The buffer is byte for byte the one [`Rasterizer::rasterize_cut_into`] makes of
    /// the layer's triangles and these together: the depth test keeps, per pixel, the nearest
    /// fragment and on equal depth the lower triangle index, whatever the order they are drawn
    /// in. The statistics count the triangles in `ranges` alone, the pixels covered by either.
    ///
    /// # Panics
    /// As [`Rasterizer::rasterize_layer_into`], and if the layer is not of `viewport`'s size.
    pub fn rasterize_over_into(
        &mut self,
        viewport: Viewport,
        positions: &[ClipVertex],
        triangles: (&[[u32; 3]], &[Range<u32>]),
        over: (Option<&dyn Cut>, &Layer),
        buffer: &mut VisibilityBuffer,
    ) -> RasterStats {
        let mut copy = LayerCopy::default();
        self.rasterize_over_keeping(viewport, positions, triangles, over, (buffer, &mut copy))
    }

    /// [`Rasterizer::rasterize_over_into`] into a `buffer` that `copy` describes: the record
    /// of the last draw into it over a layer ([`LayerCopy`]), which the buffer is as that draw
    /// left it. The tiles that draw copied from this same layer, where no triangle is drawn
    /// now, are left as they are (they hold what copying them again would write); `copy` is
    /// then this draw's record. The buffer is byte for byte the one
    /// [`Rasterizer::rasterize_over_into`] makes: pass [`LayerCopy::default`] for a buffer of
    /// unknown content, and [`LayerCopy::forget`] a record whose buffer was written otherwise.
    ///
    /// # Panics
    /// As [`Rasterizer::rasterize_over_into`].
    pub fn rasterize_over_keeping(
        &mut self,
        viewport: Viewport,
        positions: &[ClipVertex],
        (triangles, ranges): (&[[u32; 3]], &[Range<u32>]),
        (cut, layer): (Option<&dyn Cut>, &Layer),
        (buffer, copy): (&mut VisibilityBuffer, &mut LayerCopy),
    ) -> RasterStats {
        let over = layer.buffer();
        assert!(
            over.width == viewport.width && over.height == viewport.height,
            "the layer is of the viewport's size"
        );
        if buffer.width != viewport.width || buffer.height != viewport.height {
            copy.forget();
        }
        let drawn = Drawn {
            ranges: Some(ranges),
            over: Some(over),
            clamp: true,
        };
        let (stats, tiles) = self.rasterize_ranges(
            viewport,
            positions,
            triangles,
            cut,
            (drawn, Some((layer, &*copy))),
            buffer,
        );
        copy.record(layer, viewport, tiles);
        stats
    }

    /// The checks and pool of [`Rasterizer::rasterize_rows_into`] for a draw of some ranges of
    /// triangles, with what the buffer holds of the layer drawn over (`copy`); returns the
    /// counts and, per tile, the pixels covered where it is the layer's copy.
    fn rasterize_ranges(
        &mut self,
        viewport: Viewport,
        positions: &[ClipVertex],
        triangles: &[[u32; 3]],
        cut: Option<&dyn Cut>,
        (drawn, copy): (Drawn<'_>, Option<(&Layer, &LayerCopy)>),
        buffer: &mut VisibilityBuffer,
    ) -> (RasterStats, Vec<Option<u64>>) {
        assert!(
            viewport.width <= MAX_VIEWPORT_SIDE && viewport.height <= MAX_VIEWPORT_SIDE,
            "viewport {}×{} exceeds {MAX_VIEWPORT_SIDE} pixels a side",
            viewport.width,
            viewport.height
        );
        assert!(
            triangles.len() < u32::MAX as usize,
            "u32::MAX marks empty pixels"
        );
        let mut end = 0;
        for range in drawn.ranges.unwrap_or_default() {
            assert!(
                range.start >= end && range.start <= range.end,
                "ranges ascend without overlap"
            );
            assert!(
                range.end as usize <= triangles.len(),
                "ranges within the list"
            );
            end = range.end;
        }
        buffer.resize(viewport);
        if viewport.width == 0 || viewport.height == 0 {
            return (RasterStats::default(), Vec::new());
        }
        let tile_size = RasterOptions::DEFAULT_TILE_SIZE;
        let kept = (cut, None);
        let copied = copy.map(|(layer, copy)| (layer, copy, viewport));
        self.rasterize_in_pool(
            viewport,
            positions,
            triangles,
            kept,
            (drawn, copied),
            tile_size,
            buffer,
        )
    }

    #[allow(clippy::too_many_arguments)]
    fn rasterize_in_pool(
        &mut self,
        viewport: Viewport,
        positions: &[ClipVertex],
        triangles: &[[u32; 3]],
        (cut, rows): Kept<'_>,
        (drawn, copy): (Drawn<'_>, Option<(&Layer, &LayerCopy, Viewport)>),
        tile_size: u32,
        buffer: &mut VisibilityBuffer,
    ) -> (RasterStats, Vec<Option<u64>>) {
        let screen = Screen::new(viewport.width, viewport.height);
        let (guard_x, guard_y) = screen.guard_band();
        let planes = Planes::new(guard_x, guard_y);
        positions
            .par_iter()
            .map(|p| Vertex::new(*p, &planes, &screen))
            .collect_into_vec(&mut self.vertices);
        let input = SetupInput {
            positions,
            vertices: &self.vertices,
            planes,
            screen,
            cut,
        };
        let grid = TileGrid::new(screen.bounds, tile_size);
        let all = 0..triangles.len() as u32;
        let whole = std::slice::from_ref(&all);
        let runs: Vec<(u32, &[[u32; 3]])> = drawn
            .ranges
            .unwrap_or(whole)
            .iter()
            .flat_map(|range| {
                let run = &triangles[range.start as usize..range.end as usize];
                (range.start..)
                    .step_by(CHUNK_TRIANGLES)
                    .zip(run.chunks(CHUNK_TRIANGLES))
            })
            .collect();
        self.chunks.resize_with(runs.len(), Chunk::default);
        self.chunks
            .par_iter_mut()
            .zip(runs.par_iter())
            .for_each(|(chunk, &(first, run))| {
                chunk.set_up(&input, &grid, run, first);
            });

        let chunks = &self.chunks;
        let counts: Vec<tile::TileCounts> = tile::tile_targets(buffer, &grid)
            .into_par_iter()
            .map_init(Scratch::new, |scratch, target| {
                let index = target.index;
                let binned = chunks.iter().flat_map(|chunk| {
                    chunk
                        .bins
                        .tile(index)
                        .iter()
                        .map(|&i| &chunk.setups[i as usize])
                });
                let copied =
                    copy.and_then(|(layer, copy, viewport)| copy.copied(layer, viewport, index));
                tile::render_tile(
                    target,
                    binned,
                    (cut, rows),
                    (drawn.over, drawn.clamp, copied),
                    scratch,
                )
            })
            .collect();
        let stats = chunks
            .iter()
            .fold(RasterStats::default(), |s, c| s + c.stats);
        let stats = RasterStats {
            fragments: counts.iter().map(|c| c.fragments).sum(),
            pixels_covered: counts.iter().map(|c| c.pixels).sum(),
            ..stats
        };
        let tiles = counts
            .iter()
            .map(|c| c.copied.then_some(c.pixels))
            .collect();
        (stats, tiles)
    }
}

/// Which triangles a call draws, over what, and how it writes depth.
#[derive(Clone, Copy)]
struct Drawn<'a> {
    /// The indices of the triangles drawn; None: all of them.
    ranges: Option<&'a [Range<u32>]>,
    /// What other triangles show, drawn over ([`Layer`]'s buffer).
    over: Option<&'a VisibilityBuffer>,
    /// Whether depth is written clamped to [0, 1], as a visibility buffer holds it, or as
    /// computed, as a [`Layer`] keeps it for the depth test of the triangles drawn over it.
    clamp: bool,
}

/// Runs `job` in a new pool of `threads` threads, or in the current pool when `threads` is 0 (or
/// a pool cannot be started).
fn in_pool<R: Send>(threads: usize, job: impl FnOnce() -> R + Send) -> R {
    if threads == 0 {
        return job();
    }
    match rayon::ThreadPoolBuilder::new().num_threads(threads).build() {
        Ok(pool) => pool.install(job),
        Err(_) => job(),
    }
}

/// A vertex classified against the clip planes and projected.
#[derive(Clone, Copy, Debug)]
struct Vertex {
    outcode: u16,
    /// Meaningful only when the vertex is inside all clip planes; triangles with a vertex
    /// outside one are clipped from their clip-space positions instead.
    screen: ScreenVertex,
}

impl Vertex {
    fn new(p: ClipVertex, planes: &Planes, screen: &Screen) -> Self {
        let p = p.as_dvec4();
        Self {
            outcode: planes.outcode(p),
            screen: screen.project(p),
        }
    }
}

/// What setting up a triangle needs to know about the frame.
struct SetupInput<'a> {
    positions: &'a [ClipVertex],
    vertices: &'a [Vertex],
    planes: Planes,
    screen: Screen,
    cut: Option<&'a dyn Cut>,
}

/// A run of consecutive input triangles, set up and binned.
#[derive(Debug, Default)]
struct Chunk {
    setups: Vec<TriangleSetup>,
    bins: Bins,
    stats: RasterStats,
}

impl Chunk {
    /// Sets up `triangles`, the first of which has index `first`, and bins them, replacing what
    /// the chunk held.
    fn set_up(
        &mut self,
        input: &SetupInput<'_>,
        grid: &TileGrid,
        triangles: &[[u32; 3]],
        first: u32,
    ) {
        self.setups.clear();
        self.stats = RasterStats {
            triangles_in: triangles.len(),
            ..RasterStats::default()
        };
        for (index, corners) in (first..).zip(triangles) {
            input.set_up(index, corners, &mut self.setups, &mut self.stats);
        }
        self.stats.triangles_rasterized = self.setups.len();
        self.bins.fill(grid, &self.setups);
    }
}

impl SetupInput<'_> {
    /// Culls, clips and sets up triangle `index` with vertex indices `corners`, appending what
    /// is left of it to `out` and counting the outcome in `stats`.
    fn set_up(
        &self,
        index: u32,
        corners: &[u32; 3],
        out: &mut Vec<TriangleSetup>,
        stats: &mut RasterStats,
    ) {
        let Some(vertices) = self.vertices_of(corners) else {
            stats.triangles_invalid += 1;
            return;
        };
        let tested = match self.cut.map_or(Region::Kept, |c| c.region(index)) {
            Region::Kept => false,
            Region::Both => true,
            Region::Cut => {
                stats.triangles_culled += 1;
                return;
            }
        };
        let before = out.len();
        match clip::classify(vertices.map(|v| v.outcode)) {
            Verdict::Invalid => {
                stats.triangles_invalid += 1;
                return;
            }
            Verdict::Outside => {}
            Verdict::Inside => {
                let bary = [DVec2::ZERO, DVec2::X, DVec2::Y];
                let v = std::array::from_fn(|i| (vertices[i].screen, bary[i]));
                out.extend(TriangleSetup::new(v, index, &self.screen));
            }
            Verdict::Clip(planes) => {
                stats.triangles_clipped += 1;
                let v = corners.map(|i| self.positions[i as usize].as_dvec4());
                let polygon = clip::clip_triangle(v, &self.planes, planes);
                out.extend(polygon.fan().filter_map(|t| {
                    let t = t.map(|p| (self.screen.project(p.pos), p.bary));
                    TriangleSetup::new(t, index, &self.screen)
                }));
            }
        }
        stats.triangles_culled += usize::from(out.len() == before);
        for setup in &mut out[before..] {
            setup.tested = tested;
        }
    }

    /// The three vertices of a triangle, or `None` if an index is out of range.
    fn vertices_of(&self, corners: &[u32; 3]) -> Option<[Vertex; 3]> {
        let v = |i: u32| self.vertices.get(i as usize).copied();
        Some([v(corners[0])?, v(corners[1])?, v(corners[2])?])
    }
}
