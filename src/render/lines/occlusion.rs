//! Occlusion levels: how many surfaces lie between the eye and a point of a line, counted on
//! the mesh along the line of sight.
//!
//! The depth buffer holds only the nearest surface; a hidden line's level needs all of them.
//! The mesh's triangles are binned over the image once, and for each hidden point of a line the
//! line of sight from the eye to it is intersected with the triangles of its bin, each one it
//! passes through in front of the point (and kept by its patch's trim) counting once: a closed
//! body in front counts twice, its near and its far side.

use glam::{Mat4, Vec2, Vec3, Vec4};
use rayon::prelude::*;

use super::super::camera::{Camera, Projection};
use super::super::raster::Cut;
use super::super::tessellate::Mesh;
use super::super::trim_cut::MeshCut;
use super::screen::to_screen;
use crate::geom::{PatchLibrary, Region};

/// The side of a bin, in pixels.
const BIN: f32 = 16.0;

/// How much nearer than a point of a line, in pixel widths at its distance, a surface must be
/// to count as lying in front of it. Along a line found on the surface (a silhouette, a
/// border), the line of sight grazes the mesh it lies on, and the mesh about the line is
/// nearer by a fraction of the tessellation's error; a surface in front of the line lies
/// farther off than this.
const APART_PIXELS: f32 = 8.0;

/// The same, relative to the point's distance: a surface nearer by less than this is the
/// line's own (the depth test's own margin).
const RELATIVE_GAP: f32 = 1e-3;

/// The mesh's triangles, binned over the image, to count those in front of a point.
pub(crate) struct Occluders<'a> {
    mesh: &'a Mesh,
    cut: Option<MeshCut<'a>>,
    /// The inverse of the view-projection: a point of the image and its NDC depth to the world.
    to_world: Mat4,
    eye: Vec3,
    /// Whether the view is in perspective, from the eye, or orthographic, along `forward`.
    perspective: bool,
    forward: Vec3,
    /// The image in pixels.
    size: (u32, u32),
    /// The width of a pixel in world units at distance 1 (perspective), or everywhere
    /// (orthographic): `2 / (P₁₁ h)` for an image of `h` rows.
    pixel: f32,
    columns: usize,
    /// The triangles of bin `k`: `triangles[first[k]..first[k + 1]]`.
    first: Vec<u32>,
    triangles: Vec<u32>,
    /// Triangles reaching behind the eye, which no bin holds: tested everywhere.
    everywhere: Vec<u32>,
}

impl<'a> Occluders<'a> {
    /// The triangles of `mesh` (of `library`'s patches, whose trims they keep) seen through
    /// `camera` (`view_projection`) on an image of `size` pixels.
    #[must_use]
    pub fn new(
        (mesh, library): (&'a Mesh, &'a PatchLibrary),
        camera: &Camera,
        view_projection: Mat4,
        size: (u32, u32),
    ) -> Self {
        let columns = (size.0 as f32 / BIN).ceil().max(1.0) as usize;
        let rows = (size.1 as f32 / BIN).ceil().max(1.0) as usize;
        let project = |v: u32| {
            to_screen(
                view_projection * mesh.positions[v as usize].extend(1.0),
                size,
            )
        };
        // Per triangle, the bins its box on the image covers, `None` when it reaches behind
        // the eye, empty when it misses the image or is cut away.
        let cut = MeshCut::of(mesh, library);
        let boxes: Vec<Option<[usize; 4]>> = (0..mesh.triangles.len())
            .into_par_iter()
            .with_min_len(4096)
            .map(|t| {
                let cut_away = cut
                    .as_ref()
                    .is_some_and(|c| c.region(t as u32) == Region::Cut);
                if cut_away {
                    return Some([1, 0, 1, 0]);
                }
                let mut lo = Vec2::splat(f32::INFINITY);
                let mut hi = Vec2::splat(f32::NEG_INFINITY);
                for v in mesh.triangles[t] {
                    let (p, _) = project(v)?;
                    lo = lo.min(p);
                    hi = hi.max(p);
                }
                if hi.x < 0.0 || hi.y < 0.0 || lo.x > size.0 as f32 || lo.y > size.1 as f32 {
                    return Some([1, 0, 1, 0]);
                }
                let cell = |x: f32, n: usize| ((x / BIN).floor().max(0.0) as usize).min(n - 1);
                Some([
                    cell(lo.x, columns),
                    cell(hi.x, columns),
                    cell(lo.y, rows),
                    cell(hi.y, rows),
                ])
            })
            .collect();
        let mut first = vec![0u32; columns * rows + 1];
        let mut everywhere = Vec::new();
        let bins = |b: [usize; 4]| {
            (b[2]..=b[3]).flat_map(move |y| (b[0]..=b[1]).map(move |x| y * columns + x))
        };
        for (t, b) in boxes.iter().enumerate() {
            match b {
                Some(b) => bins(*b).for_each(|k| first[k + 1] += 1),
                None => everywhere.push(t as u32),
            }
        }
        for k in 0..columns * rows {
            first[k + 1] += first[k];
        }
        let mut filled = first.clone();
        let mut triangles = vec![0u32; first[columns * rows] as usize];
        for (t, b) in boxes.iter().enumerate() {
            if let Some(b) = b {
                for k in bins(*b) {
                    triangles[filled[k] as usize] = t as u32;
                    filled[k] += 1;
                }
            }
        }
        let aspect = size.0 as f32 / size.1.max(1) as f32;
        let projection = camera.projection_matrix(aspect);
        Self {
            mesh,
            cut,
            to_world: view_projection.inverse(),
            eye: camera.eye,
            perspective: matches!(camera.projection, Projection::Perspective { .. }),
            forward: camera.forward(),
            size,
            pixel: 2.0 / (projection.y_axis.y * size.1.max(1) as f32),
            columns,
            first,
            triangles,
            everywhere,
        }
    }

    /// How many surfaces lie in front of the point at `pixel` on the image with NDC depth `z`,
    /// counted up to `most + 1`: the triangles the line of sight to it passes through nearer
    /// than it by [`APART_PIXELS`] pixel widths and [`RELATIVE_GAP`] of its distance, where
    /// their patches' trims keep them. `most + 1` also for a point off the image or whose
    /// place cannot be had.
    #[must_use]
    pub fn in_front(&self, pixel: Vec2, z: f32, most: u32) -> u32 {
        let beyond = most.saturating_add(1);
        let (w, h) = (self.size.0 as f32, self.size.1 as f32);
        if !(pixel.x >= 0.0 && pixel.y >= 0.0 && pixel.x < w && pixel.y < h) {
            return beyond;
        }
        let ndc = Vec4::new(2.0 * pixel.x / w - 1.0, 1.0 - 2.0 * pixel.y / h, z, 1.0);
        let world = self.to_world * ndc;
        let point = world.truncate() / world.w;
        if !point.is_finite() {
            return beyond;
        }
        // The line of sight as `point + s · toward`, s from 0 at the point to 1 at the eye (at
        // the plane through the eye square to the view, under orthographic projection).
        let (toward, distance, pixel_width) = if self.perspective {
            let d = self.eye - point;
            let distance = d.length();
            (d, distance, self.pixel * distance)
        } else {
            let distance = (point - self.eye).dot(self.forward).max(0.0);
            (-self.forward * distance, distance, self.pixel)
        };
        let apart = (APART_PIXELS * pixel_width).max(RELATIVE_GAP * distance);
        let least = if distance > 0.0 {
            apart / distance
        } else {
            1.0
        };
        let bin = (pixel.y / BIN) as usize * self.columns + (pixel.x / BIN) as usize;
        let listed = &self.triangles[self.first[bin] as usize..self.first[bin + 1] as usize];
        let mut count = 0;
        for &t in listed.iter().chain(&self.everywhere) {
            if self.crosses(t, point, toward, least) {
                count += 1;
                if count >= beyond {
                    break;
                }
            }
        }
        count
    }

    /// Whether the segment `origin + s · toward`, `s ∈ (least, 1)`, passes through triangle `t`
    /// where its patch's trim keeps it (Möller–Trumbore: `s = (e₂ · q) / (e₁ · p)` with
    /// `p = toward × e₂`, `q = (origin − a) × e₁`, and barycentrics `b₁ = (origin − a)·p / det`,
    /// `b₂ = toward · q / det`).
    fn crosses(&self, t: u32, origin: Vec3, toward: Vec3, least: f32) -> bool {
        let [a, b, c] = self.mesh.triangles[t as usize].map(|v| self.mesh.positions[v as usize]);
        let (e1, e2) = (b - a, c - a);
        let p = toward.cross(e2);
        let det = e1.dot(p);
        if det.abs() <= f32::EPSILON * e1.length() * e2.length() * toward.length() {
            return false;
        }
        let inverse = 1.0 / det;
        let from_a = origin - a;
        let b1 = from_a.dot(p) * inverse;
        if !(0.0..=1.0).contains(&b1) {
            return false;
        }
        let q = from_a.cross(e1);
        let b2 = toward.dot(q) * inverse;
        if b2 < 0.0 || b1 + b2 > 1.0 {
            return false;
        }
        let s = e2.dot(q) * inverse;
        if !(s > least && s < 1.0) {
            return false;
        }
        match &self.cut {
            Some(cut) => match cut.region(t) {
                Region::Kept => true,
                Region::Cut => false,
                Region::Both => cut.keeps(t, [b1, b2]),
            },
            None => true,
        }
    }
}
