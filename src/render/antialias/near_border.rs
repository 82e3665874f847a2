//! Where the sides of the patches' domains pass on screen: which pixels lie within a distance of
//! one, as the mesh's border pieces project.

use glam::{Vec2, Vec4};

use crate::math::distance_to_segment_f32;
use crate::render::raster::Viewport;
use crate::render::tessellate::Mesh;

/// Side of a cell of the grid the projected border pieces are binned in, in pixels.
const CELL: f32 = 32.0;

/// The clip-space `w` a border piece is cut at before it is projected: nothing nearer the eye
/// is seen.
const NEAREST_W: f32 = 1e-6;

/// The length in pixels below which a projected border piece is taken for a point: a collapsed
/// side (a pole), or a piece seen end-on.
const POINT_PIXELS: f32 = 1e-3;

/// The sides of the patches' domains on screen: the mesh's border pieces projected, each
/// binned in the cells of a [`CELL`]-pixel grid that lie within its reach of it.
pub(in crate::render) struct NearBorder {
    columns: usize,
    rows: usize,
    /// Per cell, the indices into `pieces` of those within `reach` of it.
    cells: Vec<Vec<u32>>,
    /// Each piece's end points in pixels (`y` down), and its reach.
    pieces: Vec<([Vec2; 2], f32)>,
}

impl NearBorder {
    /// Every piece of `mesh.borders` (a side of a patch's domain, whether or not another patch
    /// continues it, seen or hidden) and the point of every collapsed side (a pole: all its
    /// vertices at one position, so it has no pieces), through the vertices' clip-space
    /// positions `clip`, cut where it passes behind the eye and to `image` with its reach
    /// around it: `reach`, or `point_reach` for what projects to a point ([`POINT_PIXELS`]).
    /// A piece with an end that is not finite is not drawn by the rasterizer either, and is
    /// left out.
    #[must_use]
    pub fn new(
        mesh: &Mesh,
        clip: &[Vec4],
        image: Viewport,
        (reach, point_reach): (f32, f32),
    ) -> Self {
        let (w, h) = (image.width as f32, image.height as f32);
        let columns = (w / CELL).ceil().max(1.0) as usize;
        let rows = (h / CELL).ceil().max(1.0) as usize;
        let mut near = Self {
            columns,
            rows,
            cells: vec![Vec::new(); columns * rows],
            pieces: Vec::new(),
        };
        let to_pixels =
            |c: Vec4| Vec2::new((c.x / c.w + 1.0) * 0.5 * w, (1.0 - c.y / c.w) * 0.5 * h);
        let most = reach.max(point_reach);
        let bounds = (Vec2::splat(-most), Vec2::new(w + most, h + most));
        let mut add = |a: Vec4, b: Vec4| {
            let Some(piece) = project_cut(a, b, bounds, &to_pixels) else {
                return;
            };
            let reach = if piece[0].distance(piece[1]) < POINT_PIXELS {
                point_reach
            } else {
                reach
            };
            let index = near.pieces.len() as u32;
            near.pieces.push((piece, reach));
            let low = (piece[0].min(piece[1]) - reach) / CELL;
            let high = (piece[0].max(piece[1]) + reach) / CELL;
            let cell = |v: f32, most: usize| (v.floor().max(0.0) as usize).min(most - 1);
            for row in cell(low.y, rows)..=cell(high.y, rows) {
                for column in cell(low.x, columns)..=cell(high.x, columns) {
                    near.cells[row * columns + column].push(index);
                }
            }
        };
        let at = |v: u32| clip.get(v as usize).copied();
        for edge in &mesh.borders {
            if let (Some(a), Some(b)) = (at(edge.a), at(edge.b)) {
                add(a, b);
            }
        }
        // A collapsed side (a pole) has no pieces: its vertices are one point, taken once.
        for g in &mesh.grids {
            for side in g.sides().iter().filter(|s| s.len() > 1) {
                let position = |v: u32| mesh.positions.get(v as usize).copied();
                let first = position(side[0]);
                if side.iter().all(|&v| position(v) == first) {
                    if let Some(point) = at(side[0]) {
                        add(point, point);
                    }
                }
            }
        }
        near
    }

    /// Whether some side of a patch's domain passes within its reach of the centre of pixel
    /// `(x, y)`.
    #[must_use]
    pub fn at(&self, x: u32, y: u32) -> bool {
        let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
        let cell = |v: f32, most: usize| ((v / CELL) as usize).min(most - 1);
        let (column, row) = (cell(centre.x, self.columns), cell(centre.y, self.rows));
        self.cells[row * self.columns + column].iter().any(|&i| {
            let ([a, b], reach) = self.pieces[i as usize];
            distance_to_segment_f32(centre, a, b) <= reach
        })
    }
}

/// The piece from clip-space `a` to `b` in pixels (`to_pixels`), cut at `w = NEAREST_W` where
/// it passes behind the eye and to `bounds`; `None` where nothing of it is left, or an end is
/// not finite (the rasterizer draws nothing there either).
fn project_cut(
    mut a: Vec4,
    mut b: Vec4,
    bounds: (Vec2, Vec2),
    to_pixels: &impl Fn(Vec4) -> Vec2,
) -> Option<[Vec2; 2]> {
    if !(a.is_finite() && b.is_finite()) || (a.w <= NEAREST_W && b.w <= NEAREST_W) {
        return None;
    }
    if a.w < NEAREST_W || b.w < NEAREST_W {
        let t = (NEAREST_W - a.w) / (b.w - a.w);
        let cut = a + (b - a) * t;
        if a.w < NEAREST_W {
            a = cut;
        } else {
            b = cut;
        }
    }
    clip_to_box(to_pixels(a), to_pixels(b), bounds)
}

/// The part of the segment from `a` to `b` inside the box `(low, high)`, by Liang–Barsky: the
/// `t ∈ [0, 1]` of `a + t (b − a)` within each slab; `None` where none is.
#[must_use]
fn clip_to_box(a: Vec2, b: Vec2, (low, high): (Vec2, Vec2)) -> Option<[Vec2; 2]> {
    let d = b - a;
    let (mut t0, mut t1) = (0.0f32, 1.0f32);
    for (p, q) in [
        (-d.x, a.x - low.x),
        (d.x, high.x - a.x),
        (-d.y, a.y - low.y),
        (d.y, high.y - a.y),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
            continue;
        }
        let r = q / p;
        if p < 0.0 {
            t0 = t0.max(r);
        } else {
            t1 = t1.min(r);
        }
    }
    (t0 <= t1).then(|| [a + d * t0, a + d * t1])
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::geom::Domain;
    use crate::render::fixtures::{self, ball_library, mesh_in_view};
    use crate::render::Camera;

    #[test]
    fn the_pixels_near_a_sphere_s_seam_and_poles_are_those_its_true_sides_pass_near() {
        // The sphere's domain sides are its seam (a meridian) and its two poles. From above the
        // equator and turned so that the seam runs across the front, over the top and past
        // the silhouette, each pixel is near a side exactly when the sides themselves, dense
        // points of the surface projected, pass within the reach of its centre.
        let library = ball_library();
        let (width, height, reach) = (96u32, 96u32, 3.0f32);
        let camera = Camera {
            eye: Vec3::new(2.5, -4.0, 2.0),
            ..fixtures::camera()
        };
        let (mesh, view_projection, clip) = mesh_in_view(&library, &camera, (width, height), 0.05);
        let mesh = &mesh;
        let near = NearBorder::new(mesh, &clip, Viewport { width, height }, (reach, reach));

        let surface = &library.patches[0].surface;
        let Domain { u, v } = surface.domain();
        let n = 4000;
        let along = |a: (f64, f64), k: usize| a.0 + (a.1 - a.0) * k as f64 / n as f64;
        let sides: Vec<Vec2> = (0..=n)
            .flat_map(|k| {
                [
                    (u.0, along(v, k)),
                    (u.1, along(v, k)),
                    (along(u, k), v.0),
                    (along(u, k), v.1),
                ]
            })
            .map(|(a, b)| {
                let c = view_projection * surface.point(a, b).as_vec3().extend(1.0);
                Vec2::new(
                    (c.x / c.w + 1.0) * 0.5 * width as f32,
                    (1.0 - c.y / c.w) * 0.5 * height as f32,
                )
            })
            .collect();
        let (mut near_count, mut far_count) = (0, 0);
        for y in 0..height {
            for x in 0..width {
                let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                let truth = sides
                    .iter()
                    .map(|p| p.distance(centre))
                    .fold(f32::INFINITY, f32::min);
                // Points 4000 to a side are a hair apart; the mesh's chords are within 0.05 px.
                if truth < reach - 0.2 {
                    assert!(near.at(x, y), "({x}, {y}) is {truth} px from a side");
                    near_count += 1;
                } else if truth > reach + 0.2 {
                    assert!(!near.at(x, y), "({x}, {y}) is {truth} px from every side");
                    far_count += 1;
                }
            }
        }
        // The view shows both: a seam across the image, and most of the image away from it.
        assert!(
            near_count > 300 && far_count > 5000,
            "{near_count} {far_count}"
        );
    }

    #[test]
    fn a_segment_is_cut_to_the_box_or_dropped_when_it_misses_it() {
        let bounds = (Vec2::ZERO, Vec2::new(10.0, 10.0));
        let cut = clip_to_box(Vec2::new(-5.0, 5.0), Vec2::new(15.0, 5.0), bounds).unwrap();
        assert_eq!(cut, [Vec2::new(0.0, 5.0), Vec2::new(10.0, 5.0)]);
        let inside = [Vec2::new(1.0, 2.0), Vec2::new(3.0, 4.0)];
        assert_eq!(clip_to_box(inside[0], inside[1], bounds), Some(inside));
        assert_eq!(
            clip_to_box(Vec2::new(-5.0, 12.0), Vec2::new(15.0, 30.0), bounds),
            None
        );
        // Parallel to a side and outside it.
        assert_eq!(
            clip_to_box(Vec2::new(-1.0, 0.0), Vec2::new(-1.0, 10.0), bounds),
            None
        );
    }
}
