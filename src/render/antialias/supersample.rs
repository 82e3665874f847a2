//! [`Stage::Supersample`](crate::render::Stage::Supersample): the pixels of a one-sample frame
//! that more samples could change, drawn again at K × K samples a tile at a time and averaged
//! into it.

use glam::{Mat4, Vec4};
use rayon::prelude::*;

use super::contrast::{pixels_to_supersample, DrawnRight};
use super::dilate::dilate;
use super::near_border::NearBorder;
use super::open_side::{beside_open_sides, open_sides};
use super::resolved::Resolved;
use super::seeded::{self, SeedInput};
use super::window::Window;
use crate::geom::PatchLibrary;
use crate::highlight::Footprint;
use crate::render::gbuffer::{Evaluate, GBuffer, EMPTY};
use crate::render::lines::LineImage;
use crate::render::neighbourhood::around;
use crate::render::probe::landed_depth;
use crate::render::raster::{Cut, RasterOptions, Rasterizer, Viewport, VisibilityBuffer};
use crate::render::scene::Scene;
use crate::render::settings::FrameMode;
use crate::render::shade::{shade, Edges, ShadeBuffers, Shaded};
use crate::render::tessellate::Mesh;
use crate::render::trim_cut::{MeshCut, Renumbered};
use crate::render::xtoon_tone::{self, Views};

/// Side of a tile in output pixels. A tile's samples, with its apron, are all a worker holds:
/// at 8 × 8 samples, 128 × 128 samples plus the apron. The marked pixels lie along edges, so
/// the samples rasterized grow with the edges' length times the tile's side: 16 pixels
/// rasterize half what 32 did, for a few more triangles binned twice (on the teapot's turntable
/// at 1280 × 720, the supersample stage 13 to 16 % faster).
pub const TILE: u32 = 16;

/// What the stage needs of the frame.
pub(in crate::render) struct SupersampleInput<'a> {
    pub library: &'a PatchLibrary,
    pub scene: &'a Scene<'a>,
    pub mesh: &'a Mesh,
    /// The mesh's vertices in the image's clip space.
    pub clip: &'a [Vec4],
    pub view_projection: Mat4,
    /// The samples' frames: the settings' (the one-sample G-buffer's may be interpolated).
    pub frames: FrameMode,
    /// Samples per pixel side.
    pub k: u32,
    /// The image in pixels.
    pub image: Viewport,
    /// Whether the X-Toon detail runs ahead of shading, and edge widths are taken.
    pub detail: bool,
    pub widths: bool,
    /// Per pixel, whether a highlight edge may cross it unseen by its colour (the edge-width
    /// stage's bound), when edge widths were taken.
    pub straddles: Option<&'a [bool]>,
    /// The one-sample G-buffer the highlights were shaded from.
    pub gbuffer: &'a GBuffer,
    /// Per texel of `gbuffer`, its footprint, when edge widths were taken.
    pub footprints: Option<&'a [Footprint]>,
    /// The frame's lines, when the scene draws them: a pixel they wholly ink is not drawn
    /// again.
    pub lines: Option<&'a LineImage>,
    /// Per texel of `gbuffer`, whether the one-sample pass drew its pixel's colour right
    /// (each edge clear of the box, or drawn across it at one sample: a band edge straight, a
    /// highlight edge smooth), when it classified them.
    pub drawn: Option<&'a [bool]>,
    /// Per pixel, whether the one-sample pass drew it right about a trim's rim (covered or
    /// not), when it looked for such pixels.
    pub drawn_pixels: Option<&'a [bool]>,
}

/// What the stage did.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(in crate::render) struct Done {
    /// Pixels drawn again at K × K samples.
    pub pixels: u64,
    /// NURBS frames evaluated for their samples (and the tiles' aprons); 0 with interpolated
    /// frames.
    pub frames: u64,
}

/// Draws again, at `input.k × input.k` samples, each pixel of `shaded` (a one-sample image of
/// `input.image`'s size) whose colour or matte differs from a neighbour's, or that a highlight
/// edge may cross unseen ([`pixels_to_supersample`]), or where two patches end side by side
/// ([`beside_open_sides`]), and puts there the average of its samples: premultiplied colour
/// `α = mean(α_s)`, `rgb = mean(α_s rgb_s)/α`, and the mean matte and `N·H`.
///
/// A pixel the frame's lines wholly ink is left as it is, unless an AOV of the shading (the
/// matte, `N·H`) shows what lies under the lines.
///
/// The marked pixels are gathered in [`TILE`]-pixel tiles. Each tile is a [`Window`] of the
/// supersampled image with an [`APRON`] around it for the central differences of the edge
/// widths; only the triangles whose bounds reach the window are rasterized into it, each row
/// over the span of its samples that belong to marked pixels or lie within the apron of them,
/// and only those samples are kept: their G-buffer, detail, edge widths and shading are those of
/// the whole supersampled image at those samples. Memory is one tile per worker.
pub(in crate::render) fn supersample(input: &SupersampleInput, shaded: &mut Shaded) -> Done {
    let (w, h) = (input.image.width, input.image.height);
    let gbuffer = input.gbuffer;
    let drawn = input.drawn.map(|texels| DrawnRight {
        slot: &gbuffer.slot,
        texels,
        pixels: input.drawn_pixels,
    });
    // Where patches end side by side, a gap between them may be thinner than a pixel.
    let open = open_sides(input.mesh, input.library);
    let beside_open = open
        .iter()
        .flatten()
        .any(|&o| o)
        .then(|| beside_open_sides(gbuffer, input.library, &open, input.drawn));
    let also = match (input.straddles, beside_open) {
        (Some(straddles), Some(mut beside)) => {
            for (b, &s) in beside.iter_mut().zip(straddles) {
                *b |= s;
            }
            Some(beside)
        }
        (None, beside) => beside,
        (Some(_), None) => None,
    };
    let mut marked = pixels_to_supersample(
        &shaded.colour,
        shaded.matte.as_deref(),
        also.as_deref().or(input.straddles),
        drawn,
        w,
        h,
    );
    if let (Some(lines), None, None, None) =
        (input.lines, &shaded.matte, &shaded.n_dot_h, &shaded.n_dot_l)
    {
        for (p, m) in marked.iter_mut().enumerate().filter(|(_, m)| **m) {
            *m = !lines.hides(p);
        }
    }
    let pixels = marked.iter().filter(|&&m| m).count() as u64;
    if pixels == 0 {
        return Done::default();
    }
    let views = xtoon_tone::views(input.scene);
    let (mut marked, seeded) = split_seeded(input, marked);

    let (mut resolved, mut frames) = if seeded.is_empty() {
        (Vec::new(), 0)
    } else {
        let input = SeedInput {
            library: input.library,
            scene: input.scene,
            view_projection: input.view_projection,
            gbuffer: input.gbuffer,
            footprints: input.footprints,
            image: input.image,
            k: input.k,
        };
        let drawn = seeded::draw(&input, &views, &seeded, &mut seeded::Buffers::default());
        for &p in &drawn.failed {
            marked[p as usize] = true;
        }
        (drawn.resolved, drawn.frames)
    };
    let (tiles_x, tiles_y) = (w.div_ceil(TILE), h.div_ceil(TILE));
    let mut tile_marked = vec![false; (tiles_x * tiles_y) as usize];
    for (i, _) in marked.iter().enumerate().filter(|(_, &m)| m) {
        let (x, y) = (i as u32 % w, i as u32 / w);
        tile_marked[((y / TILE) * tiles_x + x / TILE) as usize] = true;
    }
    let bins = bin_triangles(input, &tile_marked, (tiles_x, tiles_y), APRON);
    let tiles: Vec<(u32, &Vec<u32>)> = (0..tiles_x * tiles_y)
        .zip(&bins)
        .filter(|&(t, _)| tile_marked[t as usize])
        .collect();
    let results: Vec<(Vec<Resolved>, u64)> = tiles
        .into_par_iter()
        .map_init(TileBuffers::default, |buffers, (t, bin)| {
            let (tx, ty) = (t % tiles_x, t / tiles_x);
            buffers.draw(input, &views, &marked, (tx, ty), APRON, bin)
        })
        .collect();
    for (tile, tile_frames) in results {
        frames += tile_frames;
        resolved.extend(tile);
    }
    for r in resolved {
        let p = r.pixel as usize;
        shaded.colour[p] = r.colour;
        if let Some(matte) = shaded.matte.as_mut() {
            matte[p] = r.matte;
        }
        if let Some(n_dot_h) = shaded.n_dot_h.as_mut() {
            n_dot_h[p] = r.n_dot_h;
        }
        if let Some(n_dot_l) = shaded.n_dot_l.as_mut() {
            n_dot_l[p] = r.n_dot_l;
        }
    }
    Done { pixels, frames }
}

/// The marked pixels split in two: those left to the rasterized tiles, as a mask, and those the
/// seeded path draws ([`seeded::draw`]), as a list. The seeded path takes a marked pixel when
/// frames are refined (it refines its samples' (u, v) from the points around them),
/// nothing runs ahead of shading (the X-Toon detail reads a neighbourhood of samples), and its
/// neighbourhood shows the surfaces to start from ([`seeded::seedable`]).
fn split_seeded(input: &SupersampleInput, mut marked: Vec<bool>) -> (Vec<bool>, Vec<u32>) {
    let (w, h) = (input.image.width as usize, input.image.height as usize);
    let samples = u64::from(input.image.width * input.k) * u64::from(input.image.height * input.k);
    if input.frames != FrameMode::Refined || input.detail || samples > u64::from(u32::MAX) {
        return (marked, Vec::new());
    }
    let near_border = NearBorder::new(
        input.mesh,
        input.clip,
        input.image,
        (seeded::BORDER_PIXELS, seeded::POLE_PIXELS),
    );
    let seeded: Vec<u32> = (0..w * h)
        .into_par_iter()
        .filter(|&p| marked[p] && seeded::seedable(input.gbuffer, input.scene, &near_border, p))
        .map(|p| p as u32)
        .collect();
    for &p in &seeded {
        marked[p as usize] = false;
    }
    (marked, seeded)
}

/// Samples around a tile that its samples' results depend on: one, for the central
/// differences of the edge widths.
const APRON: u32 = 1;

/// Per tile of the `tiles` grid that is marked, the triangles whose screen bounds reach its
/// window (with `apron`), in mesh order; empty for the others. A triangle with a vertex at or
/// behind the eye goes to every marked tile (the rasterizer clips it).
fn bin_triangles(
    input: &SupersampleInput,
    marked: &[bool],
    (tiles_x, tiles_y): (u32, u32),
    apron: u32,
) -> Vec<Vec<u32>> {
    let side = (TILE * input.k) as f32;
    let (sw, sh) = (
        (input.image.width * input.k) as f32,
        (input.image.height * input.k) as f32,
    );
    let a = apron as f32;
    let ranges: Vec<Option<[u32; 4]>> = input
        .mesh
        .triangles
        .par_iter()
        .with_min_len(4096)
        .map(|tri| {
            let c = tri.map(|v| input.clip.get(v as usize).copied().unwrap_or(Vec4::NAN));
            if c.iter().any(|c| !c.is_finite()) {
                return None;
            }
            if c.iter().any(|c| c.w <= 1e-6) {
                return Some([0, tiles_x - 1, 0, tiles_y - 1]);
            }
            let xs = c.map(|c| (c.x / c.w + 1.0) * 0.5 * sw);
            let ys = c.map(|c| (1.0 - c.y / c.w) * 0.5 * sh);
            let (x0, x1) = (xs[0].min(xs[1]).min(xs[2]), xs[0].max(xs[1]).max(xs[2]));
            let (y0, y1) = (ys[0].min(ys[1]).min(ys[2]), ys[0].max(ys[1]).max(ys[2]));
            if x1 + a < 0.0 || y1 + a < 0.0 || x0 - a > sw || y0 - a > sh {
                return None;
            }
            let tile = |v: f32, most: u32| ((v / side).floor().max(0.0) as u32).min(most - 1);
            Some([
                tile(x0 - a, tiles_x),
                tile(x1 + a, tiles_x),
                tile(y0 - a, tiles_y),
                tile(y1 + a, tiles_y),
            ])
        })
        .collect();
    let mut bins = vec![Vec::new(); marked.len()];
    for (t, range) in ranges.iter().enumerate() {
        let Some([tx0, tx1, ty0, ty1]) = *range else {
            continue;
        };
        for ty in ty0..=ty1 {
            for tx in tx0..=tx1 {
                let i = (ty * tiles_x + tx) as usize;
                if marked[i] {
                    bins[i].push(t as u32);
                }
            }
        }
    }
    bins
}

/// A worker's memory for drawing one tile after another.
#[derive(Default)]
struct TileBuffers {
    vertices: Vec<u32>,
    clip: Vec<Vec4>,
    triangles: Vec<[u32; 3]>,
    rasterizer: Rasterizer,
    visibility: VisibilityBuffer,
    gbuffer: GBuffer,
    shading: ShadeBuffers,
    /// Per sample of the window, whether it is drawn on.
    drawn: Vec<bool>,
    /// Per sample of the window, how much of its frame the G-buffer evaluates.
    evaluate: Vec<Evaluate>,
    /// Scratch for [`dilate`].
    dilating: (Vec<bool>, Vec<u32>),
    /// Per row of the window, the span of its samples drawn on.
    spans: Vec<(u32, u32)>,
    /// Per sample of the window, whether [`grow`] covered it.
    grown: Vec<bool>,
}

/// Rings of samples grown outward from the mesh's coverage under refined frames.
const GROWN_RINGS: usize = 2;

/// Covers, [`GROWN_RINGS`] times, each drawn empty sample beside a covered one with that
/// neighbour's triangle and barycentrics, and marks it in `grown` (one flag per sample).
///
/// A tessellated surface's silhouette is a polygon of chords, inside the true one on a convex
/// outline by up to the tessellation's sag. Refined frames move each sample's (u, v) onto its
/// ray, so a sample just outside the mesh, started from its neighbour's (u, v), lands on the
/// surface if its ray hits it there; [`TileBuffers::grown_hits`] keeps those and drops the rest.
fn grow(visibility: &mut VisibilityBuffer, drawn: &[bool], grown: &mut Vec<bool>) {
    let (w, h) = (visibility.width as usize, visibility.height as usize);
    grown.clear();
    grown.resize(w * h, false);
    let mut ring = Vec::new();
    for _ in 0..GROWN_RINGS {
        ring.clear();
        for (i, _) in drawn.iter().enumerate().filter(|(_, &d)| d) {
            if visibility.triangle[i] != EMPTY {
                continue;
            }
            let neighbour = around(i, (w, h)).find(|&j| visibility.triangle[j] != EMPTY);
            if let Some(j) = neighbour {
                ring.push((i, j));
            }
        }
        for &(i, j) in &ring {
            visibility.triangle[i] = visibility.triangle[j];
            visibility.barycentric[i] = visibility.barycentric[j];
            visibility.depth[i] = visibility.depth[j];
            grown[i] = true;
        }
    }
}

impl TileBuffers {
    /// Per texel, whether to keep it: every texel the mesh covers, and a grown one whose
    /// refined surface point projects (through `to_screen`, the window's view-projection) within
    /// [`HIT_SAMPLES`](crate::render::probe::HIT_SAMPLES) of its sample's centre — its ray hits
    /// the surface — on a part of its patch the patch's trim keeps, and whose depth is then set
    /// from that point.
    fn grown_hits(&mut self, to_screen: Mat4, width: u32, library: &PatchLibrary) -> Vec<bool> {
        let size = (width, self.gbuffer.height);
        self.gbuffer
            .texels
            .iter_mut()
            .map(|t| {
                if !self.grown[t.pixel as usize] {
                    return true;
                }
                let patch = &library.patches[t.patch as usize];
                if !patch.keeps(f64::from(t.uv.x), f64::from(t.uv.y)) {
                    // On a part the patch's trim cuts away: the ray passes through.
                    return false;
                }
                let landed = landed_depth(to_screen, t.position, t.pixel, size);
                if let Some(depth) = landed {
                    t.depth = depth;
                }
                landed.is_some()
            })
            .collect()
    }

    /// The marked pixels of tile `(tx, ty)` drawn at K × K samples from the triangles `bin`,
    /// and the NURBS frames evaluated.
    fn draw(
        &mut self,
        input: &SupersampleInput,
        views: &Views,
        marked: &[bool],
        (tx, ty): (u32, u32),
        apron: u32,
        bin: &[u32],
    ) -> (Vec<Resolved>, u64) {
        let (k, image) = (input.k, input.image);
        let full = Viewport {
            width: image.width * k,
            height: image.height * k,
        };
        let (px0, py0) = (tx * TILE, ty * TILE);
        let (px1, py1) = (
            (px0 + TILE).min(image.width),
            (py0 + TILE).min(image.height),
        );
        let (x0, y0) = (
            (px0 * k).saturating_sub(apron),
            (py0 * k).saturating_sub(apron),
        );
        let (x1, y1) = (
            (px1 * k + apron).min(full.width),
            (py1 * k + apron).min(full.height),
        );
        let window = Window {
            x: x0,
            y: y0,
            width: x1 - x0,
            height: y1 - y0,
            full,
        };
        let to_window = window.clip_from_image();

        // The tile's own vertex list: the bin's vertices, sorted, in the window's clip space.
        let mesh = input.mesh;
        self.vertices.clear();
        self.vertices
            .extend(bin.iter().flat_map(|&t| mesh.triangles[t as usize]));
        self.vertices.sort_unstable();
        self.vertices.dedup();
        self.clip.clear();
        self.clip.extend(
            self.vertices
                .iter()
                .map(|&v| to_window * input.clip[v as usize]),
        );
        let local = |v: u32| self.vertices.binary_search(&v).unwrap_or(0) as u32;
        self.triangles.clear();
        self.triangles
            .extend(bin.iter().map(|&t| mesh.triangles[t as usize].map(local)));
        let options = RasterOptions {
            threads: 0,
            ..RasterOptions::default()
        };
        let mesh_cut = MeshCut::of(mesh, input.library);
        let cut = mesh_cut.as_ref().map(|cut| Renumbered {
            cut,
            triangles: bin,
        });
        // Only the samples of marked pixels, and those within the apron of them (the edge
        // widths' central differences), are drawn on; each row is rasterized over the span
        // from its first such sample to its last.
        let (ww, wh) = (window.width, window.height);
        let (wu, hu) = (ww as usize, wh as usize);
        self.drawn.clear();
        self.drawn.extend((0..wh).flat_map(|y| {
            let row = ((y + y0) / k * image.width) as usize;
            (0..ww).map(move |x| marked[row + ((x + x0) / k) as usize])
        }));
        let (rows, counts) = &mut self.dilating;
        dilate(&mut self.drawn, (wu, hu), apron as usize, (rows, counts));
        self.spans.clear();
        self.spans.extend(self.drawn.chunks(wu).map(|row| {
            let first = row.iter().position(|&d| d);
            let last = row.iter().rposition(|&d| d);
            match (first, last) {
                (Some(a), Some(b)) => (a as u32, b as u32 + 1),
                _ => (0, 0),
            }
        }));
        self.rasterizer.rasterize_rows_into(
            window.viewport(),
            &self.clip,
            &self.triangles,
            cut.as_ref().map(|c| c as &dyn Cut),
            Some(&self.spans),
            &options,
            &mut self.visibility,
        );
        self.evaluate.clear();
        self.evaluate.extend(self.drawn.iter().map(|&d| {
            if d {
                Evaluate::Full
            } else {
                Evaluate::Mesh
            }
        }));
        for (t, &drawn) in self.visibility.triangle.iter_mut().zip(&self.drawn) {
            if *t != EMPTY {
                *t = if drawn { bin[*t as usize] } else { EMPTY };
            }
        }
        if input.frames == FrameMode::Refined {
            grow(&mut self.visibility, &self.drawn, &mut self.grown);
            for (e, _) in self
                .evaluate
                .iter_mut()
                .zip(&self.grown)
                .filter(|(_, &g)| g)
            {
                *e = Evaluate::Probe;
            }
        } else {
            self.grown.clear();
        }

        let scene = input.scene;
        let frames = self.gbuffer.fill(
            &self.visibility,
            mesh,
            input.library,
            &scene.camera,
            to_window * input.view_projection,
            input.frames,
            Some(&self.evaluate),
        );
        if !self.grown.is_empty() {
            let to_screen = to_window * input.view_projection;
            let keep = self.grown_hits(to_screen, window.width, input.library);
            self.gbuffer.retain(&keep);
        }
        let detailed = input
            .detail
            .then(|| xtoon_tone::detail(&self.gbuffer, scene, views));
        let gbuffer = detailed.as_ref().map_or(&self.gbuffer, |a| &a.gbuffer);
        let widths = input
            .widths
            .then(|| crate::render::edges::edge_width::edge_widths(gbuffer, scene).footprints);
        let tones = detailed.as_ref().map(|a| a.tones.as_slice());
        let samples = shade(
            gbuffer,
            scene,
            views,
            tones,
            Edges {
                widths: widths.as_deref(),
                bands: None,
                highlights: None,
                settled: None,
                signed: None,
            },
            &mut self.shading,
        );

        let mut resolved = Vec::new();
        for py in py0..py1 {
            for px in px0..px1 {
                let pixel = py * image.width + px;
                if !marked[pixel as usize] {
                    continue;
                }
                let (sx0, sy0) = (px * k - x0, py * k - y0);
                let indices =
                    (0..k * k).map(|s| ((sy0 + s / k) * window.width + sx0 + s % k) as usize);
                resolved.push(Resolved::average(pixel, &samples, indices));
            }
        }
        (resolved, frames)
    }
}
