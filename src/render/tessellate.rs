//! Tessellation: each patch becomes a grid mesh whose vertices carry the patch, (u, v) and the
//! exact frame there. Neighbouring patches are sampled alike along the edges they share and their
//! edge vertices welded to the same coordinates, so the mesh is watertight.

use std::collections::HashMap;
use std::sync::Arc;

use glam::{DVec3, Mat4, Vec2, Vec3};
use rayon::prelude::*;
use serde::Deserialize;

use super::FastMap;
use crate::geom::{GridEvaluator, KnotVector, NamedPatch, NurbsSurface, PatchLibrary, Region};

/// How finely patches are cut into triangles.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Density {
    /// A fixed number of segments per knot span in each direction.
    PerSpan { u: u32, v: u32 },
    /// Enough segments that the flat triangles stay within `pixels` of the surface on screen
    /// (estimated from the projected control net), at most [`MAX_SEGMENTS_PER_SPAN`] per span.
    ScreenTolerance { pixels: f32 },
}

impl std::fmt::Display for Density {
    /// `span N` (or `span UxV`), or `tol P px`.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Density::PerSpan { u, v } if u == v => write!(f, "span {u}"),
            Density::PerSpan { u, v } => write!(f, "span {u}x{v}"),
            Density::ScreenTolerance { pixels } => write!(f, "tol {pixels} px"),
        }
    }
}

/// The most segments per knot span an adaptive density chooses.
pub const MAX_SEGMENTS_PER_SPAN: u32 = 64;

/// Triangles with per-vertex surface data, in f32 world space.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    pub positions: Vec<Vec3>,
    pub normals: Vec<Vec3>,
    /// The unit tangent du of each vertex's frame (dv = N × du).
    pub tangents_u: Vec<Vec3>,
    /// Each vertex's (u, v) on its patch.
    pub uvs: Vec<Vec2>,
    pub triangles: Vec<[u32; 3]>,
    /// The patch (index in the library) of each triangle.
    pub triangle_patch: Vec<u32>,
    /// Per patch, where its grid of vertices sits in the mesh.
    pub grids: Vec<PatchGrid>,
    /// Every piece of a patch's domain boundary between two neighbouring vertices, once
    /// ([`boundary_edges`]).
    pub borders: Vec<BorderEdge>,
    /// Where each triangle lies on its patch's trim — wholly kept, wholly cut away, or crossed
    /// by a trim loop — decided per grid cell by the cell's (u, v) rectangle
    /// ([`Trim::region`](crate::geom::Trim::region)); empty when no patch is trimmed.
    pub triangle_region: Vec<Region>,
}

impl Mesh {
    /// The mesh's point at `(u, v)` on patch `patch`: in the grid cell holding it, on the cell's
    /// triangle holding it, by barycentric coordinates in (u, v) (linear over a triangle, since
    /// a cell is a rectangle in (u, v)); `(u, v)` outside the domain is taken at its nearest
    /// cell.
    #[must_use]
    pub fn point_on(&self, patch: u32, uv: glam::DVec2) -> Vec3 {
        let g = self.grids[patch as usize];
        let u_at = |i: u32| f64::from(self.uvs[g.vertex(i, 0) as usize].x);
        let v_at = |j: u32| f64::from(self.uvs[g.vertex(0, j) as usize].y);
        // The cell [i, i + 1] with u_at(i) ≤ u, clamped to the grid.
        let cell = |n: u32, at: &dyn Fn(u32) -> f64, x: f64| {
            let (mut lo, mut hi) = (0, n.saturating_sub(1).max(1));
            while hi - lo > 1 {
                let mid = (lo + hi) / 2;
                if at(mid) <= x {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            lo.min(n.saturating_sub(2))
        };
        let (i, j) = (cell(g.nu, &u_at, uv.x), cell(g.nv, &v_at, uv.y));
        let (u0, u1, v0, v1) = (u_at(i), u_at(i + 1), v_at(j), v_at(j + 1));
        let s = ((uv.x - u0) / (u1 - u0)).clamp(0.0, 1.0) as f32;
        let t = ((uv.y - v0) / (v1 - v0)).clamp(0.0, 1.0) as f32;
        let p = |i: u32, j: u32| self.positions[g.vertex(i, j) as usize];
        let (a, c) = (p(i, j), p(i + 1, j + 1));
        // [(i, j), (i+1, j), (i+1, j+1)] below the diagonal s = t, [(i, j), (i+1, j+1), (i, j+1)]
        // above it.
        if s >= t {
            a + (p(i + 1, j) - a) * (s - t) + (c - a) * t
        } else {
            a + (c - a) * s + (p(i, j + 1) - a) * (t - s)
        }
    }
}

/// One patch's vertices in the mesh: an `nu × nv` grid from `first`, vertex `(i, j)` (the i-th
/// u sample, the j-th v sample) at `first + i nv + j`. Each grid cell `(i, j)` is cut into the
/// triangles `[(i, j), (i+1, j), (i+1, j+1)]` and `[(i, j), (i+1, j+1), (i, j+1)]`, in that
/// order, from triangle `2 Σ (cells of the patches before) + 2 (i (nv − 1) + j)`
/// ([`PatchGrid::triangle`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PatchGrid {
    pub first: u32,
    pub nu: u32,
    pub nv: u32,
    /// The patch's first triangle in the mesh: `2 Σ (cells of the patches before)`.
    pub first_triangle: u32,
}

impl PatchGrid {
    /// The vertex `(i, j)`.
    #[inline]
    #[must_use]
    pub fn vertex(&self, i: u32, j: u32) -> u32 {
        self.first + i * self.nv + j
    }

    /// The first of the two triangles of cell `(i, j)`: `first_triangle + 2 (i (nv − 1) + j)`.
    #[inline]
    #[must_use]
    pub fn triangle(&self, i: u32, j: u32) -> u32 {
        self.first_triangle + 2 * (i * (self.nv - 1) + j)
    }

    /// The vertices along the four sides of the domain in turn: `v = v0`, `u = u1`, `v = v1`,
    /// `u = u0`.
    #[must_use]
    pub fn sides(&self) -> [Vec<u32>; 4] {
        let (nu, nv) = (self.nu, self.nv);
        [
            (0..nu).map(|i| self.vertex(i, 0)).collect(),
            (0..nv).map(|j| self.vertex(nu - 1, j)).collect(),
            (0..nu).map(|i| self.vertex(i, nv - 1)).collect(),
            (0..nv).map(|j| self.vertex(0, j)).collect(),
        ]
    }
}

/// A piece of a patch's domain boundary between two neighbouring mesh vertices `a` and `b`
/// (of patch `patch`), and the vertices at the same two positions on the patch across it, when
/// another piece of boundary (of another patch, or of the same patch on a closed surface) runs
/// there.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BorderEdge {
    pub patch: u32,
    pub a: u32,
    pub b: u32,
    /// `(a', b')` at the positions of `a` and `b`, and their patch.
    pub across: Option<(u32, u32, u32)>,
}

impl BorderEdge {
    /// The patch across the piece: the one that continues it, or its own when none does.
    #[must_use]
    pub fn patch_across(&self) -> u32 {
        self.across.map_or(self.patch, |(_, _, other)| other)
    }
}

/// Segments per knot span of one patch, along u and along v.
pub type Segments = (u32, u32);

/// Tessellates a library, keeping the last mesh while the segment counts stay the same.
#[derive(Debug)]
pub struct Tessellator {
    library: Arc<PatchLibrary>,
    /// Classes of (patch, direction) that must be cut alike: `class[2 p + d]`, d = 0 for u.
    class: Vec<usize>,
    cached: Option<(Vec<Segments>, Mesh)>,
    /// A mesh no longer drawn, whose memory the next mesh made is written into.
    spare: Option<Mesh>,
    /// Per patch, its grid in the cached mesh: a mesh rebuilt because some patches' counts
    /// changed evaluates those patches alone.
    patch_frames: Vec<PatchFrames>,
    /// How many meshes have been made: what identifies the cached one.
    generation: u64,
    /// How many patches' grids the last mesh made evaluated (the others' were kept).
    evaluated: usize,
}

/// One patch's grid of vertices, as evaluated: the segments it was cut with, the parameters of
/// its rows and columns and, row by row, each vertex's point, normal and unit tangent along u;
/// on a trimmed patch, also where each cell of the grid lies on its trim, row by row.
#[derive(Debug, Default, PartialEq)]
struct PatchFrames {
    segments: Segments,
    us: Vec<f64>,
    vs: Vec<f64>,
    points: Vec<DVec3>,
    normals: Vec<Vec3>,
    tangents_u: Vec<Vec3>,
    regions: Vec<Region>,
}

impl PatchFrames {
    /// Makes each of `patch_frames` (one per patch of `library`) that of its `segments`,
    /// evaluating only those cut otherwise before; returns how many were evaluated.
    fn refresh(patch_frames: &mut [Self], library: &PatchLibrary, segments: &[Segments]) -> usize {
        patch_frames
            .par_iter_mut()
            .zip(&library.patches)
            .zip(segments)
            .map(|((evaluated, patch), &cut)| {
                let stale = evaluated.segments != cut || evaluated.points.is_empty();
                if stale {
                    *evaluated = Self::of(patch, cut);
                }
                usize::from(stale)
            })
            .sum()
    }

    /// The grid of `patch` cut with `(seg_u, seg_v)` segments per span.
    fn of(patch: &NamedPatch, (seg_u, seg_v): Segments) -> Self {
        let surface = &patch.surface;
        let us = span_samples(surface.knots_u(), seg_u);
        let vs = span_samples(surface.knots_v(), seg_v);
        let grid = GridEvaluator::new(surface, &us, &vs);
        let count = us.len() * vs.len();
        let mut evaluated = Self {
            segments: (seg_u, seg_v),
            points: Vec::with_capacity(count),
            normals: Vec::with_capacity(count),
            tangents_u: Vec::with_capacity(count),
            regions: Vec::new(),
            us,
            vs,
        };
        for f in (0..evaluated.us.len()).flat_map(|i| grid.row_frames(i)) {
            evaluated.points.push(f.point);
            evaluated.normals.push(f.normal.as_vec3());
            evaluated.tangents_u.push(f.du.as_vec3());
        }
        if let Some(trim) = &patch.trim {
            let (us, vs) = (&evaluated.us, &evaluated.vs);
            evaluated.regions = us
                .windows(2)
                .flat_map(|u| {
                    vs.windows(2).map(move |v| {
                        trim.region(glam::DVec2::new(u[0], v[0]), glam::DVec2::new(u[1], v[1]))
                    })
                })
                .collect();
        }
        evaluated
    }
}

impl Tessellator {
    /// Finds the edges the library's patches share (once) and starts with an empty cache.
    pub fn new(library: impl Into<Arc<PatchLibrary>>) -> Self {
        let library = library.into();
        Self {
            class: direction_classes(&library),
            patch_frames: (0..library.patches.len())
                .map(|_| PatchFrames::default())
                .collect(),
            library,
            cached: None,
            spare: None,
            generation: 0,
            evaluated: 0,
        }
    }

    /// Draws `library` from now on: the same model as this tessellator's, with the patches
    /// `moved` marks (one flag per patch) moved or deformed. Their grids are evaluated again at
    /// the next mesh; every other patch's grid is kept. The edges found shared stay those of
    /// the first library.
    pub fn repose(&mut self, library: Arc<PatchLibrary>, moved: &[bool]) {
        for (frames, _) in self.patch_frames.iter_mut().zip(moved).filter(|(_, &m)| m) {
            *frames = PatchFrames::default();
        }
        if moved.iter().any(|&m| m) {
            self.spare = self.cached.take().map(|(_, mesh)| mesh);
        }
        self.library = library;
    }

    /// How many patches' grids the last mesh made was evaluated for; the rest were kept from
    /// earlier meshes.
    #[must_use]
    pub fn evaluated(&self) -> usize {
        self.evaluated
    }

    /// The mesh for `density`, seen through `view_projection` on a `width × height` image (used
    /// by the adaptive density only). Returns whether it had to be rebuilt.
    pub fn mesh(
        &mut self,
        density: Density,
        view_projection: Mat4,
        width: u32,
        height: u32,
    ) -> (&Mesh, bool) {
        let segments = self.segments(density, view_projection, width, height);
        self.mesh_of(segments)
    }

    /// The mesh of `segments` per span for every patch (as [`Tessellator::segments`] gives
    /// them): the cached one when they are its own. Returns whether it had to be rebuilt.
    pub fn mesh_of(&mut self, segments: Vec<Segments>) -> (&Mesh, bool) {
        let rebuilt = !matches!(&self.cached, Some((s, _)) if *s == segments);
        if rebuilt {
            // The grids of the patches whose counts changed, in parallel; the others' are kept.
            self.evaluated = PatchFrames::refresh(&mut self.patch_frames, &self.library, &segments);
            let spare = self.cached.take().map(|(_, mesh)| mesh);
            let spare = spare.or_else(|| self.spare.take()).unwrap_or_default();
            let mesh = build_mesh(&self.library, &self.patch_frames, spare);
            self.cached = Some((segments, mesh));
            self.generation += 1;
        }
        let (_, mesh) = self.cached.as_ref().expect("the cache was just filled");
        (mesh, rebuilt)
    }

    /// How many vertices [`Tessellator::mesh`] would make for these arguments
    /// ([`vertex_count`]), without making them.
    #[must_use]
    pub fn vertices(
        &self,
        density: Density,
        view_projection: Mat4,
        width: u32,
        height: u32,
    ) -> u64 {
        vertex_count(
            &self.library,
            &self.segments(density, view_projection, width, height),
        )
    }

    /// Which mesh [`Tessellator::mesh`] last made, counting from 1: what depends on the mesh
    /// alone may be kept while this stays the same.
    #[must_use]
    pub fn generation(&self) -> u64 {
        self.generation
    }

    /// The mesh last made by [`Tessellator::mesh`], if any.
    #[must_use]
    pub fn cached_mesh(&self) -> Option<&Mesh> {
        self.cached.as_ref().map(|(_, mesh)| mesh)
    }

    /// Segments per span for every patch: the density's own choice, then the largest within
    /// each class of directions that share edges, so shared edges are sampled alike.
    pub fn segments(
        &self,
        density: Density,
        view_projection: Mat4,
        width: u32,
        height: u32,
    ) -> Vec<Segments> {
        let wanted: Vec<Segments> = self
            .library
            .patches
            .iter()
            .map(|p| match density {
                Density::PerSpan { u, v } => (u.max(1), v.max(1)),
                Density::ScreenTolerance { pixels } => {
                    screen_segments(&p.surface, view_projection, width, height, pixels)
                }
            })
            .collect();
        let mut largest: HashMap<usize, u32> = HashMap::new();
        for (node, &class) in self.class.iter().enumerate() {
            let (u, v) = wanted[node / 2];
            let n = if node % 2 == 0 { u } else { v };
            let entry = largest.entry(class).or_insert(n);
            *entry = (*entry).max(n);
        }
        (0..wanted.len())
            .map(|p| (largest[&self.class[2 * p]], largest[&self.class[2 * p + 1]]))
            .collect()
    }
}

/// The vertices of `library`'s mesh cut with `segments` per span: per patch
/// `(spans_u · n_u + 1)(spans_v · n_v + 1)`.
#[must_use]
pub fn vertex_count(library: &PatchLibrary, segments: &[Segments]) -> u64 {
    library
        .patches
        .iter()
        .zip(segments)
        .map(|(p, &(n_u, n_v))| {
            let side = |spans: usize, n: u32| (spans as u64).saturating_mul(u64::from(n)) + 1;
            side(p.surface.knots_u().span_count(), n_u)
                .saturating_mul(side(p.surface.knots_v().span_count(), n_v))
        })
        .fold(0u64, u64::saturating_add)
}

/// Parameters cutting each knot span of `knots` into `segments` equal parts, every knot inside
/// the domain and both ends included exactly, once.
fn span_samples(knots: &KnotVector, segments: u32) -> Vec<f64> {
    let (start, end) = knots.domain();
    let mut breaks: Vec<f64> = knots
        .knots()
        .iter()
        .copied()
        .filter(|&k| k > start && k < end)
        .collect();
    breaks.dedup();
    breaks.insert(0, start);
    breaks.push(end);
    let n = segments as usize;
    let mut samples = vec![start];
    for span in breaks.windows(2) {
        let (a, b) = (span[0], span[1]);
        samples.extend((1..n).map(|k| a + (b - a) * (k as f64 / n as f64)));
        samples.push(b);
    }
    samples
}

/// Segments per span so that, on screen, a linear piece deviates from the surface by at most
/// `tolerance` pixels. For a Bezier curve of degree p cut into n pieces the deviation is at most
/// `p (p − 1) max‖Δ²P‖ / (8 n²)` (second differences of the control points), so
/// `n = ⌈sqrt(p (p − 1) max‖Δ²P‖ / (8 tol))⌉`, taken per direction over the projected net.
fn screen_segments(
    surface: &NurbsSurface,
    view_projection: Mat4,
    width: u32,
    height: u32,
    tolerance: f32,
) -> Segments {
    let (count_u, count_v) = (surface.count_u(), surface.count_v());
    let half = Vec2::new(width as f32, height as f32) * 0.5;
    let mut on_screen = Vec::with_capacity(count_u * count_v);
    for i in 0..count_u {
        for j in 0..count_v {
            let p = view_projection * surface.control_point(i, j).0.as_vec3().extend(1.0);
            if p.w <= 1e-6 {
                // Behind the eye: no estimate, cut as finely as allowed.
                return (MAX_SEGMENTS_PER_SPAN, MAX_SEGMENTS_PER_SPAN);
            }
            on_screen.push(Vec2::new(p.x, p.y) / p.w * half);
        }
    }
    let at = |i: usize, j: usize| on_screen[i * count_v + j];
    let second_difference = |along_u: bool| -> f32 {
        let (n, m) = if along_u {
            (count_u, count_v)
        } else {
            (count_v, count_u)
        };
        let mut largest = 0.0f32;
        for line in 0..m {
            for k in 1..n.saturating_sub(1) {
                let p = |k: usize| if along_u { at(k, line) } else { at(line, k) };
                largest = largest.max((p(k + 1) - 2.0 * p(k) + p(k - 1)).length());
            }
        }
        largest
    };
    let count = |degree: usize, d2: f32| -> u32 {
        let p = degree as f32;
        let n = (p * (p - 1.0) * d2 / (8.0 * tolerance.max(1e-3)))
            .sqrt()
            .ceil();
        (n as u32).clamp(if degree > 1 { 2 } else { 1 }, MAX_SEGMENTS_PER_SPAN)
    };
    (
        count(surface.knots_u().degree(), second_difference(true)),
        count(surface.knots_v().degree(), second_difference(false)),
    )
}

/// The points along edge `edge` of a patch's domain (0: v = v0, 1: u = u1, 2: v = v1,
/// 3: u = u0), at `n + 1` evenly spaced parameters.
fn edge_points(surface: &NurbsSurface, edge: usize, n: usize) -> Vec<DVec3> {
    let d = surface.domain();
    (0..=n)
        .map(|k| {
            let t = k as f64 / n as f64;
            let (s, r) = match edge {
                0 => (t, 0.0),
                1 => (1.0, t),
                2 => (t, 1.0),
                _ => (0.0, t),
            };
            let (u, v) = d.lerp(s, r);
            surface.point(u, v)
        })
        .collect()
}

/// The model's extent from the world origin (at least 1): the scale for "equal" positions.
fn model_scale(library: &PatchLibrary) -> f64 {
    library
        .patches
        .iter()
        .flat_map(|p| edge_points(&p.surface, 0, 2))
        .fold(1.0f64, |m, p| m.max(p.abs().max_element()))
}

/// Union-find classes over the nodes (patch, direction): two patches that share an edge put the
/// directions that edge runs along into one class.
fn direction_classes(library: &PatchLibrary) -> Vec<usize> {
    direction_classes_counted(library).0
}

/// [`direction_classes`], and how many pairs of edges it compared point by point.
///
/// Edges are found through a hash of their end points, not by comparing every pair of
/// patches: an edge is filed under the grid cell of each end (cells twice the tolerance wide),
/// and an edge is compared only with the edges filed in the 27 cells around its first point,
/// which hold every edge that can match it forwards or backwards. The work is linear in the
/// number of edges, with a constant for the edges that meet at one corner.
fn direction_classes_counted(library: &PatchLibrary) -> (Vec<usize>, usize) {
    const SAMPLES: usize = 8;
    let mut parent: Vec<usize> = (0..2 * library.patches.len()).collect();
    fn root(parent: &mut [usize], mut x: usize) -> usize {
        while parent[x] != x {
            parent[x] = parent[parent[x]];
            x = parent[x];
        }
        x
    }
    let tolerance = 1e-9 * model_scale(library);
    let cell_size = 2.0 * tolerance;
    let cell = |p: DVec3| (p / cell_size).floor().as_i64vec3();
    let edges: Vec<Vec<Vec<DVec3>>> = library
        .patches
        .iter()
        .map(|p| {
            (0..4)
                .map(|e| edge_points(&p.surface, e, SAMPLES))
                .collect()
        })
        .collect();
    let collapsed = |points: &[DVec3]| {
        points
            .iter()
            .all(|p| (*p - points[0]).length() <= tolerance)
    };
    let mut filed: FastMap<glam::I64Vec3, Vec<(usize, usize)>> = FastMap::default();
    for (patch, patch_edges) in edges.iter().enumerate() {
        for (edge, points) in patch_edges.iter().enumerate() {
            if collapsed(points) {
                continue; // a collapsed edge is a point, shared with nothing
            }
            let (first, last) = (cell(points[0]), cell(points[SAMPLES]));
            filed.entry(first).or_default().push((patch, edge));
            if last != first {
                filed.entry(last).or_default().push((patch, edge));
            }
        }
    }
    let same = |a: &[DVec3], b: &[DVec3]| {
        let forward = a
            .iter()
            .zip(b)
            .all(|(p, q)| (*p - *q).length() <= tolerance);
        forward
            || a.iter()
                .zip(b.iter().rev())
                .all(|(p, q)| (*p - *q).length() <= tolerance)
    };
    let mut compared = 0;
    let mut candidates = Vec::new();
    for (a, patch_edges) in edges.iter().enumerate() {
        for (ea, pa) in patch_edges.iter().enumerate() {
            if collapsed(pa) {
                continue;
            }
            let centre = cell(pa[0]);
            candidates.clear();
            for dx in -1..=1 {
                for dy in -1..=1 {
                    for dz in -1..=1 {
                        let near = centre + glam::I64Vec3::new(dx, dy, dz);
                        if let Some(list) = filed.get(&near) {
                            candidates.extend(list.iter().filter(|&&(b, _)| b > a));
                        }
                    }
                }
            }
            // An edge filed under both its ends can be found twice.
            candidates.sort_unstable();
            candidates.dedup();
            for &(b, eb) in &candidates {
                compared += 1;
                if same(pa, &edges[b][eb]) {
                    // Edges 0 and 2 run along u (direction 0), 1 and 3 along v.
                    let (x, y) = (
                        root(&mut parent, 2 * a + ea % 2),
                        root(&mut parent, 2 * b + eb % 2),
                    );
                    parent[x] = y;
                }
            }
        }
    }
    let classes = (0..parent.len()).map(|x| root(&mut parent, x)).collect();
    (classes, compared)
}

/// The grid meshes of all patches (their `patch_frames`), with boundary vertices at equal
/// positions welded to one f32 value, and, when a patch is trimmed, where each triangle lies on
/// its trim.
///
/// A boundary vertex takes the value of the first boundary vertex, in patch order and within a
/// patch row by row, whose point rounds to the same multiple of the welding quantum. Only that
/// choice is made in order, over the boundary vertices alone; each patch's vertices and
/// triangles are then written in parallel into arrays of their final size (the mesh is rebuilt
/// whenever a patch moves), `spare`'s memory reused: every value of the mesh is written, so
/// what `spare` held does not matter, and a mesh made frame after frame neither allocates nor
/// touches fresh pages.
fn build_mesh(library: &PatchLibrary, patch_frames: &[PatchFrames], spare: Mesh) -> Mesh {
    let trimmed = library.patches.iter().any(|p| p.trim.is_some());
    let vertex_counts: Vec<usize> = patch_frames
        .iter()
        .map(|f| f.us.len() * f.vs.len())
        .collect();
    let triangle_counts: Vec<usize> = patch_frames
        .iter()
        .map(|f| 2 * f.us.len().saturating_sub(1) * f.vs.len().saturating_sub(1))
        .collect();
    let vertices: usize = vertex_counts.iter().sum();
    let triangles: usize = triangle_counts.iter().sum();
    let quantum = 1e-9 * model_scale(library);
    let key_of = |point: DVec3| (point / quantum).round().as_i64vec3().to_array();
    let border: Vec<Vec<([i64; 3], Vec3)>> = patch_frames
        .par_iter()
        .map(|f| {
            let (nu, nv) = (f.us.len(), f.vs.len());
            f.points
                .iter()
                .enumerate()
                .filter(|(k, _)| {
                    let (i, j) = (k / nv, k % nv);
                    i == 0 || j == 0 || i + 1 == nu || j + 1 == nv
                })
                .map(|(_, point)| (key_of(*point), point.as_vec3()))
                .collect()
        })
        .collect();
    // Per patch, the welded value of each of its boundary vertices, row by row.
    let mut first_at: FastMap<[i64; 3], Vec3> =
        FastMap::with_capacity_and_hasher(border.iter().map(Vec::len).sum(), Default::default());
    let welded: Vec<Vec<Vec3>> = border
        .into_iter()
        .map(|patch| {
            patch
                .into_iter()
                .map(|(key, position)| *first_at.entry(key).or_insert(position))
                .collect()
        })
        .collect();
    let mut mesh = Mesh {
        positions: sized(spare.positions, vertices, Vec3::ZERO),
        normals: sized(spare.normals, vertices, Vec3::ZERO),
        tangents_u: sized(spare.tangents_u, vertices, Vec3::ZERO),
        uvs: sized(spare.uvs, vertices, Vec2::ZERO),
        triangles: sized(spare.triangles, triangles, [0; 3]),
        triangle_patch: sized(spare.triangle_patch, triangles, 0),
        grids: spare.grids,
        triangle_region: sized(
            spare.triangle_region,
            if trimmed { triangles } else { 0 },
            Region::Kept,
        ),
        borders: Vec::new(),
    };
    mesh.grids.clear();
    let (mut first, mut first_triangle) = (0, 0);
    for (f, (&n, &t)) in patch_frames
        .iter()
        .zip(vertex_counts.iter().zip(&triangle_counts))
    {
        mesh.grids.push(PatchGrid {
            first: first as u32,
            nu: f.us.len() as u32,
            nv: f.vs.len() as u32,
            first_triangle: first_triangle as u32,
        });
        first += n;
        first_triangle += t;
    }
    let region_counts: Vec<usize> = triangle_counts
        .iter()
        .map(|&t| if trimmed { t } else { 0 })
        .collect();
    let out = split_by(&mut mesh.positions, &vertex_counts)
        .into_iter()
        .zip(split_by(&mut mesh.normals, &vertex_counts))
        .zip(split_by(&mut mesh.tangents_u, &vertex_counts))
        .zip(split_by(&mut mesh.uvs, &vertex_counts))
        .zip(split_by(&mut mesh.triangles, &triangle_counts))
        .zip(split_by(&mut mesh.triangle_patch, &triangle_counts))
        .zip(split_by(&mut mesh.triangle_region, &region_counts))
        .map(|((((((p, n), t), uv), tri), tp), r)| (p, n, t, uv, tri, tp, r))
        .collect::<Vec<_>>();
    out.into_par_iter()
        .zip(patch_frames.par_iter())
        .zip(library.patches.par_iter())
        .zip(mesh.grids.par_iter())
        .zip(welded.par_iter())
        .enumerate()
        .for_each(
            |(patch_index, ((((out, evaluated), patch), grid), welded))| {
                let (positions, normals, tangents, uvs, tris, triangle_patch, regions_out) = out;
                let PatchFrames {
                    us,
                    vs,
                    points,
                    normals: patch_normals,
                    tangents_u,
                    regions,
                    ..
                } = evaluated;
                let (nu, nv) = (us.len(), vs.len());
                let mut welded = welded.iter();
                for (k, (point, (position, uv))) in points
                    .iter()
                    .zip(positions.iter_mut().zip(uvs.iter_mut()))
                    .enumerate()
                {
                    let (i, j) = (k / nv, k % nv);
                    *position = if i == 0 || j == 0 || i + 1 == nu || j + 1 == nv {
                        *welded.next().expect("one welded value per boundary vertex")
                    } else {
                        point.as_vec3()
                    };
                    *uv = Vec2::new(us[i] as f32, vs[j] as f32);
                }
                normals.copy_from_slice(patch_normals);
                tangents.copy_from_slice(tangents_u);
                triangle_patch.fill(patch_index as u32);
                let index = |i: usize, j: usize| grid.first + (i * nv + j) as u32;
                let cells = (0..nu.saturating_sub(1))
                    .flat_map(|i| (0..nv.saturating_sub(1)).map(move |j| (i, j)));
                for ((i, j), pair) in cells.zip(tris.chunks_exact_mut(2)) {
                    let (a, b, c, d) = (
                        index(i, j),
                        index(i + 1, j),
                        index(i + 1, j + 1),
                        index(i, j + 1),
                    );
                    pair[0] = [a, b, c];
                    pair[1] = [a, c, d];
                }
                if patch.trim.is_some() {
                    for (region, pair) in regions.iter().zip(regions_out.chunks_exact_mut(2)) {
                        pair.fill(*region);
                    }
                } else {
                    regions_out.fill(Region::Kept);
                }
            },
        );
    mesh.borders = boundary_edges(&mesh.positions, &mesh.grids);
    mesh
}

/// `values` holding `len` values: those it held first, then `fill`. Its memory is kept.
fn sized<T: Clone>(mut values: Vec<T>, len: usize, fill: T) -> Vec<T> {
    values.truncate(len);
    values.resize(len, fill);
    values
}

/// `slice` cut into consecutive pieces of `lengths` (which sum to at most its length).
fn split_by<'a, T>(mut slice: &'a mut [T], lengths: &[usize]) -> Vec<&'a mut [T]> {
    lengths
        .iter()
        .map(|&n| {
            let (head, tail) = std::mem::take(&mut slice).split_at_mut(n);
            slice = tail;
            head
        })
        .collect()
}

/// The pieces of every patch's domain boundary, each between two neighbouring vertices of its
/// grid, paired with the piece at the same two positions across it. Boundary vertices are
/// welded, so two pieces that meet have bit-identical end points; pieces of zero length (a
/// collapsed edge) are left out. A piece met from two sides is listed once, from the first.
#[must_use]
pub fn boundary_edges(positions: &[Vec3], grids: &[PatchGrid]) -> Vec<BorderEdge> {
    let key = |v: u32| positions[v as usize].to_array().map(f32::to_bits);
    // At most one piece per pair of neighbouring boundary vertices: sized once, not grown.
    let most: usize = grids
        .iter()
        .map(|g| 2 * (g.nu as usize + g.nv as usize).saturating_sub(2))
        .sum();
    let mut pieces: Vec<BorderEdge> = Vec::with_capacity(most);
    let mut seen: FastMap<([u32; 3], [u32; 3]), usize> =
        FastMap::with_capacity_and_hasher(most, Default::default());
    for (patch, g) in grids.iter().enumerate() {
        for side in &g.sides() {
            for pair in side.windows(2) {
                let (a, b) = (pair[0], pair[1]);
                let (ka, kb) = (key(a), key(b));
                if ka == kb {
                    continue;
                }
                let unordered = if ka < kb { (ka, kb) } else { (kb, ka) };
                match seen.get(&unordered) {
                    Some(&k) if pieces[k].across.is_none() && pieces[k].a != a => {
                        let first = &mut pieces[k];
                        let (fa, _) = (key(first.a), key(first.b));
                        first.across = Some(if fa == ka {
                            (a, b, patch as u32)
                        } else {
                            (b, a, patch as u32)
                        });
                    }
                    Some(_) => {}
                    None => {
                        seen.insert(unordered, pieces.len());
                        pieces.push(BorderEdge {
                            patch: patch as u32,
                            a,
                            b,
                            across: None,
                        });
                    }
                }
            }
        }
    }
    pieces
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{shapes, NamedPatch};

    #[test]
    fn span_samples_hit_every_knot_and_cut_spans_evenly() {
        let knots = KnotVector::new(vec![0.0, 0.0, 0.0, 0.3, 1.0, 1.0, 1.0], 2, 4).unwrap();
        let s = span_samples(&knots, 3);
        assert_eq!(s.len(), 7);
        assert_eq!((s[0], s[3], s[6]), (0.0, 0.3, 1.0));
        assert!((s[1] - 0.1).abs() < 1e-15 && (s[5] - (0.3 + 0.7 * 2.0 / 3.0)).abs() < 1e-15);
    }

    #[test]
    fn adaptive_density_grows_with_size_on_screen_and_shrinks_with_tolerance() {
        let sphere = shapes::sphere(DVec3::ZERO, 1.0).unwrap();
        let view = |distance: f32| {
            Mat4::perspective_rh(0.7, 1.0, 0.1, 100.0)
                * Mat4::look_at_rh(Vec3::new(0.0, -distance, 0.0), Vec3::ZERO, Vec3::Z)
        };
        let near = screen_segments(&sphere, view(3.0), 512, 512, 0.5);
        let far = screen_segments(&sphere, view(30.0), 512, 512, 0.5);
        let coarse = screen_segments(&sphere, view(3.0), 512, 512, 4.0);
        assert!(near.0 > far.0 && near.1 > far.1, "{near:?} {far:?}");
        assert!(near.0 > coarse.0, "{near:?} {coarse:?}");
        assert!(far.0 >= 2 && near.0 <= MAX_SEGMENTS_PER_SPAN);
    }

    #[test]
    fn shared_edges_are_found_by_hashing_not_by_comparing_every_pair() {
        // A square grid of side × side bilinear tiles: each inner edge is shared by two tiles,
        // so the u directions of a column and the v directions of a row form classes.
        let grid = |side: usize| {
            let s = 1.0 / side as f64;
            let patches = (0..side * side)
                .map(|k| {
                    let (x, y) = ((k / side) as f64 * s, (k % side) as f64 * s);
                    let p = |dx: f64, dy: f64| DVec3::new(x + dx, y + dy, 0.0);
                    NamedPatch {
                        name: format!("t{k}"),
                        trim: None,
                        surface: shapes::bezier(
                            1,
                            1,
                            &[vec![p(0.0, 0.0), p(0.0, s)], vec![p(s, 0.0), p(s, s)]],
                        )
                        .unwrap(),
                    }
                })
                .collect();
            PatchLibrary {
                patches,
                groups: Vec::new(),
            }
        };
        for side in [3, 10] {
            let (classes, _) = direction_classes_counted(&grid(side));
            let distinct: std::collections::HashSet<_> = classes.iter().collect();
            // u runs along x: tiles with the same y-index share their v = const edges, so their
            // u directions join; one class per row of u directions and per column of v.
            assert_eq!(distinct.len(), 2 * side, "side {side}");
        }
        // Ten times the tiles, about ten times the comparisons (a pairwise search would do a
        // hundred times as many).
        let (_, small) = direction_classes_counted(&grid(20));
        let (_, large) = direction_classes_counted(&grid(63));
        assert!(small > 0);
        assert!(
            large <= 12 * small,
            "{small} comparisons for 400 tiles, {large} for 3969"
        );
    }

    /// A unit sphere and a torus, untrimmed.
    fn sphere_and_torus() -> PatchLibrary {
        PatchLibrary {
            patches: vec![
                NamedPatch {
                    name: "sphere".into(),
                    trim: None,
                    surface: shapes::sphere(DVec3::ZERO, 1.0).unwrap(),
                },
                NamedPatch {
                    name: "torus".into(),
                    trim: None,
                    surface: shapes::torus(2.0, 0.5).unwrap(),
                },
            ],
            groups: Vec::new(),
        }
    }

    #[test]
    fn the_vertex_count_is_the_mesh_s() {
        let library = sphere_and_torus();
        for segments in [vec![(1, 1), (1, 1)], vec![(3, 5), (7, 2)]] {
            let patch_frames: Vec<PatchFrames> = library
                .patches
                .iter()
                .zip(&segments)
                .map(|(p, &cut)| PatchFrames::of(p, cut))
                .collect();
            let mesh = build_mesh(&library, &patch_frames, Mesh::default());
            assert_eq!(
                vertex_count(&library, &segments),
                mesh.positions.len() as u64
            );
        }
    }

    #[test]
    fn a_mesh_rebuilt_evaluates_only_the_patches_cut_otherwise_and_equals_a_fresh_one() {
        let library = sphere_and_torus();
        let fresh = |segments: &[Segments]| {
            let mut patch_frames: Vec<PatchFrames> =
                (0..2).map(|_| PatchFrames::default()).collect();
            assert_eq!(
                PatchFrames::refresh(&mut patch_frames, &library, segments),
                2
            );
            patch_frames
        };
        let mut kept = fresh(&[(3, 2), (4, 4)]);
        // The torus cut otherwise, then both, then neither.
        for (segments, evaluated) in [
            (vec![(3, 2), (5, 4)], 1),
            (vec![(2, 2), (5, 3)], 2),
            (vec![(2, 2), (5, 3)], 0),
        ] {
            assert_eq!(
                PatchFrames::refresh(&mut kept, &library, &segments),
                evaluated
            );
            let again = fresh(&segments);
            assert_eq!(kept, again);
            assert_eq!(
                build_mesh(&library, &kept, Mesh::default()),
                build_mesh(&library, &again, Mesh::default())
            );
        }
    }

    #[test]
    fn a_mesh_made_in_a_spare_s_memory_is_the_mesh_made_afresh() {
        // The sphere trimmed by a hole, so that the mesh has trim regions, and the torus not.
        let mut library = sphere_and_torus();
        let domain = library.patches[0].surface.domain();
        let at = |s: f64, t: f64| {
            let (u, v) = (domain.u, domain.v);
            glam::DVec2::new(u.0 + s * (u.1 - u.0), v.0 + t * (v.1 - v.0))
        };
        let outer = vec![at(0., 0.), at(1., 0.), at(1., 1.), at(0., 1.), at(0., 0.)];
        let hole = vec![
            at(0.2, 0.2),
            at(0.2, 0.8),
            at(0.8, 0.8),
            at(0.8, 0.2),
            at(0.2, 0.2),
        ];
        let trim = crate::geom::Trim::new(vec![outer, hole], domain).unwrap();
        library.patches[0].trim = Some(Arc::new(trim));
        let frames = |segments: &[Segments]| {
            let mut patch_frames: Vec<PatchFrames> =
                (0..2).map(|_| PatchFrames::default()).collect();
            PatchFrames::refresh(&mut patch_frames, &library, segments);
            patch_frames
        };
        // Spares larger and smaller than the mesh, holding values no mesh has.
        for len in [5, 100_000] {
            let spare = Mesh {
                positions: vec![Vec3::NAN; len],
                normals: vec![Vec3::NAN; len],
                tangents_u: vec![Vec3::NAN; len],
                uvs: vec![Vec2::NAN; len],
                triangles: vec![[u32::MAX; 3]; len],
                triangle_patch: vec![u32::MAX; len],
                grids: vec![
                    PatchGrid {
                        first: 7,
                        nu: 7,
                        nv: 7,
                        first_triangle: 7
                    };
                    3
                ],
                borders: Vec::new(),
                triangle_region: vec![Region::Cut; len],
            };
            let patch_frames = frames(&[(8, 8), (4, 4)]);
            let fresh = build_mesh(&library, &patch_frames, Mesh::default());
            assert!(fresh.triangle_region.contains(&Region::Cut));
            assert!(fresh.triangle_region.contains(&Region::Kept));
            assert_eq!(
                build_mesh(&library, &patch_frames, spare),
                fresh,
                "spare of {len}"
            );
        }
    }
}
