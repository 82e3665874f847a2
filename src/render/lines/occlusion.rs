//! Occlusion levels: how many surfaces lie between the eye and a point of a line, counted on
//! the mesh along the line of sight.
//!
//! The depth buffer holds only the nearest surface; a hidden line's level needs all of them.
//! The mesh's triangles are binned over the image once, and for each hidden point of a line the
//! line of sight from the eye to it is intersected with the triangles of its bin, each surface
//! it passes through in front of the point (where its patch's trim keeps it) counting once: a
//! closed body in front counts twice, its near and its far side.

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

/// Crossings of the line of sight this close, as fractions of the way from the point to the
/// eye, are one surface's: the triangles about an edge or a vertex it passes through, or two
/// patches at their seam.
const SAME_CROSSING: f32 = 1e-5;

/// The most crossings one line of sight keeps apart; past them, each counts as a surface.
const MOST_HITS: usize = 64;

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
    /// Per triangle, its box on the image, `[x0, y0, x1, y1]` (empty for one no bin holds): a
    /// point outside it is not tested against the triangle.
    bounds: Vec<[f32; 4]>,
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
        // Each vertex on the image once (None behind the eye): a vertex is shared by about six
        // triangles.
        let on_image: Vec<Option<Vec2>> = mesh
            .positions
            .par_iter()
            .with_min_len(4096)
            .map(|p| to_screen(view_projection * p.extend(1.0), size).map(|(q, _)| q))
            .collect();
        // Per triangle, the bins its box on the image covers, `None` when it reaches behind
        // the eye, empty when it misses the image or is cut away.
        let cut = MeshCut::of(mesh, library);
        const NONE: (Option<[usize; 4]>, [f32; 4]) = (Some([1, 0, 1, 0]), [f32::NAN; 4]);
        let (boxes, bounds): (Vec<Option<[usize; 4]>>, Vec<[f32; 4]>) = (0..mesh.triangles.len())
            .into_par_iter()
            .with_min_len(4096)
            .map(|t| {
                let cut_away = cut
                    .as_ref()
                    .is_some_and(|c| c.region(t as u32) == Region::Cut);
                if cut_away {
                    return NONE;
                }
                let mut lo = Vec2::splat(f32::INFINITY);
                let mut hi = Vec2::splat(f32::NEG_INFINITY);
                for v in mesh.triangles[t] {
                    let Some(p) = on_image[v as usize] else {
                        // Behind the eye: tested everywhere.
                        return (
                            None,
                            [
                                f32::NEG_INFINITY,
                                f32::NEG_INFINITY,
                                f32::INFINITY,
                                f32::INFINITY,
                            ],
                        );
                    };
                    lo = lo.min(p);
                    hi = hi.max(p);
                }
                if hi.x < 0.0 || hi.y < 0.0 || lo.x > size.0 as f32 || lo.y > size.1 as f32 {
                    return NONE;
                }
                let cell = |x: f32, n: usize| ((x / BIN).floor().max(0.0) as usize).min(n - 1);
                (
                    Some([
                        cell(lo.x, columns),
                        cell(hi.x, columns),
                        cell(lo.y, rows),
                        cell(hi.y, rows),
                    ]),
                    // Widened a little, so that rounding never leaves out a point on an edge.
                    [lo.x - 0.01, lo.y - 0.01, hi.x + 0.01, hi.y + 0.01],
                )
            })
            .unzip();
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
            bounds,
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
        // Where along the line of sight it crosses triangles: a line of sight through an edge
        // or a vertex crosses every triangle there at once, and one surface is counted once.
        let mut hits = [0.0f32; MOST_HITS];
        let mut found = 0usize;
        let mut more = 0u32;
        for &t in listed.iter().chain(&self.everywhere) {
            let [x0, y0, x1, y1] = self.bounds[t as usize];
            if !(pixel.x >= x0 && pixel.x <= x1 && pixel.y >= y0 && pixel.y <= y1) {
                continue;
            }
            if let Some(s) = self.crosses(t, point, toward, least) {
                match hits.get_mut(found) {
                    Some(slot) => {
                        *slot = s;
                        found += 1;
                    }
                    None => more += 1,
                }
            }
        }
        let hits = &mut hits[..found];
        hits.sort_unstable_by(f32::total_cmp);
        let surfaces = hits
            .iter()
            .enumerate()
            .filter(|&(k, &s)| k == 0 || s - hits[k - 1] > SAME_CROSSING)
            .count() as u32;
        (surfaces + more).min(beyond)
    }

    /// Where the segment `origin + s · toward`, `s ∈ (least, 1)`, passes through triangle `t`
    /// and its patch's trim keeps it, its `s` (Möller–Trumbore: `s = (e₂ · q) / (e₁ · p)` with
    /// `p = toward × e₂`, `q = (origin − a) × e₁`, and barycentrics `b₁ = (origin − a)·p / det`,
    /// `b₂ = toward · q / det`); None where it does not.
    fn crosses(&self, t: u32, origin: Vec3, toward: Vec3, least: f32) -> Option<f32> {
        let [a, b, c] = self.mesh.triangles[t as usize].map(|v| self.mesh.positions[v as usize]);
        let (e1, e2) = (b - a, c - a);
        let p = toward.cross(e2);
        let det = e1.dot(p);
        if det.abs() <= f32::EPSILON * e1.length() * e2.length() * toward.length() {
            return None;
        }
        let inverse = 1.0 / det;
        let from_a = origin - a;
        let b1 = from_a.dot(p) * inverse;
        if !(0.0..=1.0).contains(&b1) {
            return None;
        }
        let q = from_a.cross(e1);
        let b2 = toward.dot(q) * inverse;
        if b2 < 0.0 || b1 + b2 > 1.0 {
            return None;
        }
        let s = e2.dot(q) * inverse;
        if !(s > least && s < 1.0) {
            return None;
        }
        let kept = match &self.cut {
            Some(cut) => match cut.region(t) {
                Region::Kept => true,
                Region::Cut => false,
                Region::Both => cut.keeps(t, [b1, b2]),
            },
            None => true,
        };
        kept.then_some(s)
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::{DVec2, DVec3};

    use super::*;
    use crate::geom::{shapes, NamedPatch, Trim};
    use crate::render::tessellate::{Density, Tessellator};

    /// A square plate of side 2 about (0, 0, z), square to the z axis.
    fn plate(z: f64) -> NamedPatch {
        let p = |x: f64, y: f64| DVec3::new(x, y, z);
        NamedPatch {
            name: format!("plate{z}"),
            trim: None,
            surface: shapes::bezier(
                1,
                1,
                &[
                    vec![p(-1.0, -1.0), p(-1.0, 1.0)],
                    vec![p(1.0, -1.0), p(1.0, 1.0)],
                ],
            )
            .unwrap(),
        }
    }

    #[test]
    fn the_surfaces_in_front_of_a_point_are_counted_where_their_trims_keep_them() {
        // Three plates above the origin, seen from above; the middle one with a square hole
        // over the middle of its domain.
        let mut holed = plate(2.0);
        let domain = holed.surface.domain();
        let at = |s: f64, t: f64| {
            let (u, v) = (domain.u, domain.v);
            DVec2::new(u.0 + s * (u.1 - u.0), v.0 + t * (v.1 - v.0))
        };
        let outer = vec![at(0., 0.), at(1., 0.), at(1., 1.), at(0., 1.), at(0., 0.)];
        let hole = vec![
            at(0.3, 0.3),
            at(0.3, 0.7),
            at(0.7, 0.7),
            at(0.7, 0.3),
            at(0.3, 0.3),
        ];
        holed.trim = Some(Arc::new(Trim::new(vec![outer, hole], domain).unwrap()));
        let library = Arc::new(PatchLibrary {
            patches: vec![plate(1.0), holed, plate(3.0)],
            groups: Vec::new(),
        });
        let camera = Camera {
            eye: Vec3::new(0.0, 0.0, 10.0),
            target: Vec3::ZERO,
            up: Vec3::Y,
            projection: Projection::Perspective {
                fov_y_degrees: 30.0,
            },
            near: 0.1,
            far: 100.0,
        };
        let size = (256, 256);
        let view_projection = camera.view_projection(1.0);
        let mut tessellator = Tessellator::new(Arc::clone(&library));
        let (mesh, _) =
            tessellator.mesh(Density::PerSpan { u: 6, v: 6 }, view_projection, 256, 256);
        let occluders = Occluders::new((mesh, &library), &camera, view_projection, size);
        let count = |p: Vec3, most: u32| {
            let (pixel, z) = to_screen(view_projection * p.extend(1.0), size).unwrap();
            occluders.in_front(pixel, z, most)
        };
        // Under the middle, through the hole: the top plate alone; under a corner, all three
        // (the middle lies on a vertex of each plate's mesh, the corner does not).
        assert_eq!(count(Vec3::ZERO, 8), 2);
        assert_eq!(
            count(Vec3::new(0.0, 0.0, 1.0), 8),
            1,
            "the plate it lies on does not count"
        );
        assert_eq!(count(Vec3::new(0.8, 0.8, 0.0), 8), 3);
        assert_eq!(count(Vec3::new(0.8, 0.8, 2.5), 8), 1);
        // Counted up to one past the most asked for.
        assert_eq!(count(Vec3::new(0.8, 0.8, 0.0), 1), 2);
        // Beside the plates, nothing.
        assert_eq!(count(Vec3::new(1.5, 0.0, 0.0), 8), 0);
    }
}
