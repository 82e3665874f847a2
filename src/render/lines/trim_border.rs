//! Trim borders: where a trimmed patch's trim loops cut its surface, drawn as borders.

use glam::{DVec2, DVec3, Mat4, Vec2, Vec3};
use rayon::prelude::*;

use super::super::tessellate::Mesh;
use super::contour::LONGEST_PIECE_PIXELS;
use super::piece::Piece;
use super::screen::to_screen;
use crate::geom::{NurbsSurface, PatchLibrary};
use crate::render::line_style::{LineKind, LineStyle};

/// How far, in pixels, a loop's points may lie from the straight piece drawn past them.
const FLAT_PIXELS: f32 = 0.02;

/// The pieces along the trim edges of every trimmed patch whose style draws borders: each run of
/// a loop that cuts the surface (its segments along the domain's sides left out,
/// [`Trim::edges`](crate::geom::Trim::edges)), its ends on the surface. Consecutive segments
/// are drawn as one piece while it stays within [`FLAT_PIXELS`] of the points it passes (on the
/// mesh, as seen on the `size` image) and no longer than [`LONGEST_PIECE_PIXELS`]; a longer
/// segment is cut evenly in (u, v). The pieces of a loop share their ends exactly, so they chain
/// into one line.
#[must_use]
pub(crate) fn trim_borders(
    mesh: &Mesh,
    library: &PatchLibrary,
    view_projection: Mat4,
    size: (u32, u32),
    styles: &[LineStyle],
) -> Vec<Piece> {
    library
        .patches
        .par_iter()
        .enumerate()
        .filter(|(k, p)| p.trim.is_some() && styles[*k].draws(LineKind::Border))
        .flat_map_iter(|(k, patch)| {
            let trim = patch.trim.as_deref().expect("filtered to trimmed patches");
            let on = OnPatch {
                mesh,
                patch: k as u32,
                surface: &patch.surface,
                view_projection,
                size,
            };
            let mut pieces = Vec::new();
            for run in runs(trim.edges()) {
                on.run(&run, &mut pieces);
            }
            pieces
        })
        .collect()
}

/// The segments `edges` joined into runs of points where one segment ends where the next begins.
fn runs(edges: impl Iterator<Item = [DVec2; 2]>) -> Vec<Vec<DVec2>> {
    let mut runs: Vec<Vec<DVec2>> = Vec::new();
    for [a, b] in edges {
        match runs.last_mut() {
            Some(run) if run.last() == Some(&a) => run.push(b),
            _ => runs.push(vec![a, b]),
        }
    }
    runs
}

/// A point of a trim edge: on the mesh, and there on the image (None behind the eye). The
/// mesh lies within the tessellation's tolerance of the surface, which is all the choice of
/// pieces needs; the surface is evaluated at the pieces' ends alone.
#[derive(Clone, Copy)]
struct Point {
    uv: DVec2,
    mesh: Vec3,
    screen: Option<Vec2>,
}

/// What drawing one patch's trim edges needs.
struct OnPatch<'a> {
    mesh: &'a Mesh,
    patch: u32,
    surface: &'a NurbsSurface,
    view_projection: Mat4,
    size: (u32, u32),
}

impl OnPatch<'_> {
    fn point(&self, uv: DVec2) -> Point {
        let mesh = self.mesh.point_on(self.patch, uv);
        let screen = to_screen(self.view_projection * mesh.extend(1.0), self.size).map(|(p, _)| p);
        Point { uv, mesh, screen }
    }

    /// The surface's point at `p`, or the mesh's where the surface has none.
    fn on_surface(&self, p: &Point) -> DVec3 {
        let surface = self.surface.point(p.uv.x, p.uv.y);
        if surface.is_finite() {
            surface
        } else {
            p.mesh.as_dvec3()
        }
    }

    /// The pieces along the run of (u, v) points `run`.
    fn run(&self, run: &[DVec2], pieces: &mut Vec<Piece>) {
        let points: Vec<Point> = run.iter().map(|&uv| self.point(uv)).collect();
        let mut start = 0;
        let mut from = self.on_surface(&points[0]);
        while start + 1 < points.len() {
            // The farthest point the piece from `start` may reach.
            let mut end = start + 1;
            while end + 1 < points.len() && self.straight(&points[start..=end + 1]) {
                end += 1;
            }
            from = self.cut((points[start], from), points[end], pieces);
            start = end;
        }
    }

    /// Whether the chord from the first of `points` to the last is at most
    /// [`LONGEST_PIECE_PIXELS`] long and passes within [`FLAT_PIXELS`] of every point between.
    fn straight(&self, points: &[Point]) -> bool {
        let ends = (points[0].screen, points[points.len() - 1].screen);
        let (Some(a), Some(b)) = ends else {
            return false;
        };
        let d = b - a;
        let length = d.length();
        length <= LONGEST_PIECE_PIXELS
            && points[1..points.len() - 1].iter().all(|p| {
                p.screen.is_some_and(|q| {
                    let off = if length > 0.0 {
                        (q - a).perp_dot(d).abs() / length
                    } else {
                        q.distance(a)
                    };
                    off <= FLAT_PIXELS
                })
            })
    }

    /// The piece from `a` (with its point on the surface) to `b`, cut evenly in (u, v) into
    /// pieces no longer than [`LONGEST_PIECE_PIXELS`] on the image; returns `b` on the surface.
    fn cut(&self, (a, on_a): (Point, DVec3), b: Point, pieces: &mut Vec<Piece>) -> DVec3 {
        let length = match (a.screen, b.screen) {
            (Some(p), Some(q)) => p.distance(q),
            _ => 0.0,
        };
        let n = (length / LONGEST_PIECE_PIXELS).ceil().clamp(1.0, 64.0) as u32;
        let (mut from, mut from_mesh) = (on_a, a.mesh);
        for i in 1..=n {
            let to = if i == n {
                b
            } else {
                self.point(a.uv.lerp(b.uv, f64::from(i) / f64::from(n)))
            };
            let on_to = self.on_surface(&to);
            pieces.push(Piece {
                ends: [from, on_to],
                on_mesh: [from_mesh, to.mesh],
                opacity: 1.0,
                kind: LineKind::Border,
                open: true,
                patches: [self.patch; 2],
            });
            (from, from_mesh) = (on_to, to.mesh);
        }
        from
    }
}
