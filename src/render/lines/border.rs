//! Borders and creases: the pieces of the patches' domain boundaries that are drawn — a
//! boundary no patch continues, a seam where two patches meet at an angle, a seam the
//! silhouette runs along, and (when asked) every seam between two patches.

use glam::Mat4;
use rayon::prelude::*;

use super::super::camera::Camera;
use super::super::scene::Outlines;
use super::super::tessellate::{BorderEdge, Mesh};
use super::contour::{screen_length, EyeSide, LONGEST_PIECE_PIXELS};
use super::piece::{LineKind, Piece};
use crate::geom::PatchLibrary;

/// Over this band of angles (degrees) around the crease angle, a crease fades in: its opacity
/// runs from 0 at `crease − ½ band` to 1 at `crease + ½ band`, so that a crease whose angle
/// (or whose threshold) changes smoothly never appears or vanishes at once.
pub(crate) const CREASE_BAND_DEGREES: f32 = 10.0;

/// Below this angle (degrees) between the normals on the two sides, a seam is smooth: the
/// silhouette crosses it like any other curve of the surface, and is found on each side.
const SMOOTH_DEGREES: f64 = 1.0;

/// The opacity of a crease whose sides' normals turn by `angle` degrees against the crease
/// angle `crease`: `clamp((angle − crease) / band + ½, 0, 1)`.
#[must_use]
pub(crate) fn crease_opacity(angle: f32, crease: f32) -> f32 {
    ((angle - crease) / CREASE_BAND_DEGREES + 0.5).clamp(0.0, 1.0)
}

/// The boundary pieces of `mesh` that `outlines` draws, each on the surface's boundary curve:
/// a piece longer than [`LONGEST_PIECE_PIXELS`] on the `size` image is cut evenly in (u, v)
/// and its points evaluated on the patch. What is drawn:
///
/// - a boundary no other patch continues: a [`LineKind::Border`];
/// - a seam where the eye sees one side's front and the other's back (`g` of opposite signs
///   at both ends, the normals apart by more than [`SMOOTH_DEGREES`]): a silhouette;
/// - a seam between two patches, with patch borders on: a border;
/// - otherwise a seam whose normals turn by more than the crease angle (less the half band):
///   a crease, with [`crease_opacity`] of the mean angle at its two ends.
#[must_use]
pub(crate) fn borders_and_creases(
    mesh: &Mesh,
    library: &PatchLibrary,
    camera: &Camera,
    view_projection: Mat4,
    size: (u32, u32),
    outlines: &Outlines,
) -> Vec<Piece> {
    let facing = EyeSide::of(camera);
    mesh.borders
        .par_iter()
        .with_min_len(256)
        .flat_map_iter(|edge| {
            let kind = classify(mesh, facing, outlines, edge);
            kind.map(|kind| {
                let surface = &library.patches[edge.patch as usize].surface;
                pieces(mesh, surface, edge, kind, view_projection, size)
            })
            .into_iter()
            .flatten()
        })
        .collect()
}

fn classify(
    mesh: &Mesh,
    facing: EyeSide,
    outlines: &Outlines,
    edge: &BorderEdge,
) -> Option<(LineKind, f32)> {
    let Some((a2, b2, other)) = edge.across else {
        return Some((LineKind::Border, 1.0));
    };
    let normal = |v: u32| mesh.normals[v as usize].as_dvec3();
    let angle = |v: u32, w: u32| {
        normal(v)
            .dot(normal(w))
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees()
    };
    let (at_a, at_b) = (angle(edge.a, a2), angle(edge.b, b2));
    let folds = |v: u32, w: u32| facing.at_vertex(mesh, v) * facing.at_vertex(mesh, w) < 0.0;
    if folds(edge.a, a2) && folds(edge.b, b2) && at_a.min(at_b) > SMOOTH_DEGREES {
        return Some((LineKind::Silhouette, 1.0));
    }
    if outlines.patch_borders && other != edge.patch {
        return Some((LineKind::Border, 1.0));
    }
    let opacity = crease_opacity((0.5 * (at_a + at_b)) as f32, outlines.crease_degrees);
    (opacity > 0.0).then_some((LineKind::Crease, opacity))
}

/// The boundary from vertex `a` to `b` of `edge` as pieces no longer than
/// [`LONGEST_PIECE_PIXELS`] on the image, their ends on the surface.
fn pieces(
    mesh: &Mesh,
    surface: &crate::geom::NurbsSurface,
    edge: &BorderEdge,
    (kind, opacity): (LineKind, f32),
    view_projection: Mat4,
    size: (u32, u32),
) -> Vec<Piece> {
    let position = |v: u32| mesh.positions[v as usize];
    let uv = |v: u32| mesh.uvs[v as usize].as_dvec2();
    let (pa, pb) = (position(edge.a), position(edge.b));
    let length = screen_length(view_projection, size, pa.as_dvec3(), pb.as_dvec3());
    let n = (length / LONGEST_PIECE_PIXELS).ceil().clamp(1.0, 64.0) as u32;
    let at = |k: u32| {
        if k == 0 {
            return (pa.as_dvec3(), pa);
        }
        if k == n {
            return (pb.as_dvec3(), pb);
        }
        let t = f64::from(k) / f64::from(n);
        let p = uv(edge.a).lerp(uv(edge.b), t);
        let on_mesh = pa.lerp(pb, t as f32);
        let point = surface.point(p.x, p.y);
        (
            if point.is_finite() {
                point
            } else {
                on_mesh.as_dvec3()
            },
            on_mesh,
        )
    };
    let points: Vec<_> = (0..=n).map(at).collect();
    points
        .windows(2)
        .map(|w| Piece {
            ends: [w[0].0, w[1].0],
            on_mesh: [w[0].1, w[1].1],
            opacity,
            kind,
        })
        .collect()
}
