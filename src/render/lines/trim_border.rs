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

#[cfg(test)]
mod tests {
    use std::f64::consts::TAU;
    use std::sync::Arc;

    use super::super::super::camera::looking;
    use super::super::super::tessellate::{Density, Tessellator};
    use super::*;
    use crate::geom::{shapes, NamedPatch, Trim};

    #[test]
    fn a_hole_s_loop_is_drawn_once_around_on_the_surface_and_the_domain_s_sides_are_not() {
        // The square of side 2 in z = 0 (x = 2u − 1, y = 2v − 1), with a 64-sided hole of
        // radius ¼ in (u, v) about its middle: radius ½ about the origin.
        let sides = 64;
        let corners = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
        let outer: Vec<DVec2> = corners.iter().map(|&(u, v)| DVec2::new(u, v)).collect();
        let hole: Vec<DVec2> = (0..sides)
            .map(|k| {
                let angle = -TAU * f64::from(k) / f64::from(sides);
                DVec2::new(0.5, 0.5) + 0.25 * DVec2::from_angle(angle)
            })
            .collect();
        let mut square = NamedPatch::new("square", shapes::plane(2.0, 2.0).unwrap());
        let domain = square.surface.domain();
        square.trim = Some(Arc::new(Trim::new(vec![outer, hole], domain).unwrap()));
        let library = Arc::new(PatchLibrary::new(vec![square]));
        let camera = looking(Vec3::new(0.0, -1.0, 4.0), Vec3::ZERO, Vec3::Z);
        let view_projection = camera.view_projection(1.0);
        let mut tessellator = Tessellator::new(Arc::clone(&library));
        let (mesh, _) = tessellator.mesh(Density::PerSpan { u: 8, v: 8 }, view_projection, 64, 64);
        let style = LineStyle::new(1.0, Vec3::ZERO);
        let pieces = trim_borders(mesh, &library, view_projection, (64, 64), &[style]);
        assert!(!pieces.is_empty());
        // On the hole's sides: between the radius of their middles and of their corners.
        let inner = 0.5 * (std::f64::consts::PI / f64::from(sides)).cos();
        for piece in &pieces {
            assert_eq!(
                (piece.kind, piece.open, piece.patches),
                (LineKind::Border, true, [0, 0])
            );
            for end in piece.ends {
                let r = end.truncate().length();
                assert!(end.z == 0.0 && r > inner - 1e-9 && r < 0.5 + 1e-9, "{end}");
            }
        }
        // One closed line, end to start, as long as the hole's sides.
        for (piece, next) in pieces.iter().zip(pieces.iter().cycle().skip(1)) {
            assert_eq!(piece.ends[1], next.ends[0]);
        }
        let length: f64 = pieces.iter().map(|p| p.ends[0].distance(p.ends[1])).sum();
        let sides_length = f64::from(sides) * (TAU / f64::from(sides) / 2.0).sin();
        assert!(
            (length / sides_length - 1.0).abs() < 1e-4,
            "{length} {sides_length}"
        );
        // A style that draws no borders draws none of it.
        let mut no_borders = style;
        no_borders.kinds = crate::render::line_style::LineKinds {
            border: false,
            ..crate::render::line_style::LineKinds::DEFAULT
        };
        assert!(trim_borders(mesh, &library, view_projection, (64, 64), &[no_borders]).is_empty());
    }
}
