//! Borders and creases: the pieces of the patches' domain boundaries that are drawn — a
//! boundary no patch continues, a seam where two patches meet at an angle, a seam the
//! silhouette runs along, and (when asked) every seam between two patches — on what the
//! patches' trims keep of them.

use glam::Mat4;
use rayon::prelude::*;

use super::super::camera::Camera;
use super::super::scene::Outlines;
use super::super::tessellate::{BorderEdge, Mesh};
use super::contour::{screen_length, EyeSide, LONGEST_PIECE_PIXELS};
use super::piece::Piece;
use crate::geom::PatchLibrary;
use crate::render::line_style::{LineKind, LineStyle};

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

/// The boundary pieces of `mesh` that `outlines` and the patches' `styles` draw, each on the
/// surface's boundary curve: a piece longer than [`LONGEST_PIECE_PIXELS`] on the `size` image
/// is cut evenly in (u, v) and its points evaluated on the patch. What is drawn:
///
/// - a boundary no other patch continues: a [`LineKind::Border`];
/// - a seam where the eye sees one side's front and the other's back (`g` of opposite signs
///   at both ends, the normals apart by more than [`SMOOTH_DEGREES`]): a silhouette;
/// - a seam between two patches of different materials (`materials`, per patch; none differ
///   when it is empty), where either side draws material borders: a material border;
/// - a seam between two patches, with patch borders on: a border;
/// - otherwise a seam whose normals turn by more than the crease angle (less the half band):
///   a crease, with [`crease_opacity`] of the mean angle at its two ends.
///
/// Where a trim cuts the boundary away on one side, what the other side keeps of it is a
/// border; where both sides cut it away, nothing is drawn ([`sides_kept`]).
#[must_use]
pub(crate) fn borders_and_creases(
    mesh: &Mesh,
    library: &PatchLibrary,
    camera: &Camera,
    view_projection: Mat4,
    size: (u32, u32),
    (outlines, styles, materials): (&Outlines, &[LineStyle], &[u32]),
) -> Vec<Piece> {
    let facing = EyeSide::of(camera);
    let drawn = |patch: u32, kind: LineKind| styles[patch as usize].draws(kind);
    mesh.borders
        .par_iter()
        .with_min_len(256)
        .flat_map_iter(|edge| {
            let surface = &library.patches[edge.patch as usize].surface;
            // `open`: nothing continues the surface past the piece.
            let draw =
                |span: (f64, f64), kind: Option<(LineKind, f32)>, patches: [u32; 2], open| {
                    kind.filter(|&(kind, _)| drawn(patches[0], kind) || drawn(patches[1], kind))
                        .map(|(kind, opacity)| {
                            pieces(
                                mesh,
                                surface,
                                edge,
                                span,
                                (kind, opacity, open),
                                patches,
                                view_projection,
                                size,
                            )
                        })
                        .into_iter()
                        .flatten()
                };
            let whole = [edge.patch, edge.patch_across()];
            sides_kept(mesh, library, edge)
                .into_iter()
                .flat_map(move |(span, here, across)| match (here, across) {
                    (true, true) => {
                        let kind = classify(mesh, facing, (outlines, styles, materials), edge);
                        draw(span, kind, whole, edge.across.is_none())
                    }
                    // What a trim leaves of the boundary on one side only is an open border.
                    (true, false) => {
                        draw(span, Some((LineKind::Border, 1.0)), [edge.patch; 2], true)
                    }
                    (false, true) => {
                        let other = edge.patch_across();
                        draw(span, Some((LineKind::Border, 1.0)), [other; 2], true)
                    }
                    (false, false) => draw(span, None, whole, false),
                })
                .collect::<Vec<_>>()
        })
        .collect()
}

/// The boundary piece `edge` cut where the trims of the patches on its two sides start or stop
/// keeping it: per part, its interval of the piece's parameter (0 at `a`, 1 at `b`) and whether
/// the patch on each side keeps it there (where nothing continues the piece, the side across
/// keeps what this side keeps). An untrimmed piece is one part, kept on both sides.
fn sides_kept(
    mesh: &Mesh,
    library: &PatchLibrary,
    edge: &BorderEdge,
) -> Vec<((f64, f64), bool, bool)> {
    let uv = |v: u32| mesh.uvs[v as usize].as_dvec2();
    let kept = |patch: u32, a: u32, b: u32| {
        library.patches[patch as usize]
            .trim
            .as_ref()
            .map(|t| t.kept_spans(uv(a), uv(b)))
    };
    let here = kept(edge.patch, edge.a, edge.b);
    let across = edge.across.and_then(|(a, b, other)| kept(other, a, b));
    if here.is_none() && across.is_none() {
        return vec![((0.0, 1.0), true, true)];
    }
    let inside = |spans: &Option<Vec<(f64, f64)>>, t: f64| {
        spans
            .as_ref()
            .is_none_or(|s| s.iter().any(|&(t0, t1)| t0 <= t && t <= t1))
    };
    let mut cuts: Vec<f64> = [0.0, 1.0]
        .into_iter()
        .chain(
            here.iter()
                .chain(&across)
                .flatten()
                .flat_map(|&(t0, t1)| [t0, t1]),
        )
        .collect();
    cuts.sort_by(f64::total_cmp);
    cuts.dedup();
    cuts.windows(2)
        .filter(|w| w[1] > w[0])
        .map(|w| {
            let middle = 0.5 * (w[0] + w[1]);
            let kept_here = inside(&here, middle);
            // Nothing continues the piece: no side across keeps what this side cuts away.
            let kept_across = match edge.across {
                Some(_) => inside(&across, middle),
                None => kept_here,
            };
            ((w[0], w[1]), kept_here, kept_across)
        })
        .collect()
}

fn classify(
    mesh: &Mesh,
    facing: EyeSide,
    (outlines, styles, materials): (&Outlines, &[LineStyle], &[u32]),
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
    let material = |patch: u32| materials.get(patch as usize).copied().unwrap_or(0);
    let draws_material = |patch: u32| styles[patch as usize].draws(LineKind::MaterialBorder);
    if material(edge.patch) != material(other)
        && (draws_material(edge.patch) || draws_material(other))
    {
        return Some((LineKind::MaterialBorder, 1.0));
    }
    if outlines.patch_borders && other != edge.patch {
        return Some((LineKind::Border, 1.0));
    }
    let opacity = crease_opacity((0.5 * (at_a + at_b)) as f32, outlines.crease_degrees);
    (opacity > 0.0).then_some((LineKind::Crease, opacity))
}

/// The part `[t0, t1]` of the boundary from vertex `a` to `b` of `edge` (on `patches`) as
/// pieces no longer than [`LONGEST_PIECE_PIXELS`] on the image, their ends on the surface.
#[allow(clippy::too_many_arguments)]
fn pieces(
    mesh: &Mesh,
    surface: &crate::geom::NurbsSurface,
    edge: &BorderEdge,
    (t0, t1): (f64, f64),
    (kind, opacity, open): (LineKind, f32, bool),
    patches: [u32; 2],
    view_projection: Mat4,
    size: (u32, u32),
) -> Vec<Piece> {
    let position = |v: u32| mesh.positions[v as usize];
    let uv = |v: u32| mesh.uvs[v as usize].as_dvec2();
    let (pa, pb) = (position(edge.a), position(edge.b));
    let length =
        (t1 - t0) as f32 * screen_length(view_projection, size, pa.as_dvec3(), pb.as_dvec3());
    let n = (length / LONGEST_PIECE_PIXELS).ceil().clamp(1.0, 64.0) as u32;
    let at = |k: u32| {
        let t = t0 + (t1 - t0) * f64::from(k) / f64::from(n);
        if t <= 0.0 {
            return (pa.as_dvec3(), pa);
        }
        if t >= 1.0 {
            return (pb.as_dvec3(), pb);
        }
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
            open,
            patches,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use glam::{DVec2, DVec3, Vec3};

    use super::*;
    use crate::geom::{shapes, NamedPatch, Trim};
    use crate::render::camera::looking;
    use crate::render::tessellate::{Density, Tessellator};

    /// Black outlines 2 px wide with crease angle `crease`, without patch borders.
    fn outlines(crease: f32) -> Outlines {
        Outlines {
            width: 2.0,
            colour: Vec3::ZERO,
            crease_degrees: crease,
            patch_borders: false,
        }
    }

    /// The borders and creases of `mesh` seen by `camera` on a 64 × 64 image, every patch in
    /// the outlines' style ([`outlines`] with crease angle `crease`).
    fn outlined(mesh: &Mesh, library: &PatchLibrary, camera: &Camera, crease: f32) -> Vec<Piece> {
        let outlines = outlines(crease);
        let styles = vec![outlines.style(); library.patches.len()];
        borders_and_creases(
            mesh,
            library,
            camera,
            camera.view_projection(1.0),
            (64, 64),
            (&outlines, &styles, &[]),
        )
    }

    /// Two unit squares hinged along the y axis, the second turned up by `degrees`.
    fn hinge(degrees: f64) -> PatchLibrary {
        let (s, c) = degrees.to_radians().sin_cos();
        let flat = |x: f64, y: f64| DVec3::new(x, y, 0.0);
        let raised = |r: f64, y: f64| DVec3::new(r * c, y, r * s);
        let square = |p: [[DVec3; 2]; 2]| {
            shapes::bezier(1, 1, &[vec![p[0][0], p[0][1]], vec![p[1][0], p[1][1]]]).unwrap()
        };
        PatchLibrary {
            patches: vec![
                NamedPatch {
                    name: "flat".into(),
                    trim: None,
                    surface: square([
                        [flat(-1.0, 0.0), flat(-1.0, 1.0)],
                        [flat(0.0, 0.0), flat(0.0, 1.0)],
                    ]),
                },
                NamedPatch {
                    name: "raised".into(),
                    trim: None,
                    surface: square([
                        [raised(0.0, 0.0), raised(0.0, 1.0)],
                        [raised(1.0, 0.0), raised(1.0, 1.0)],
                    ]),
                },
            ],
            groups: Vec::new(),
        }
    }

    #[test]
    fn a_trimmed_patch_s_borders_are_drawn_where_its_trim_keeps_them_and_nowhere_else() {
        // The flat square (x from −1 at u = 0 to 0 at u = 1, y = v) trimmed to the strip
        // 0.25 ≤ u ≤ 0.75 across all of v: of its sides y = 0 and y = 1, x from −0.75 to
        // −0.25 is kept; of its side x = −1, nothing.
        let mut library = hinge(40.0);
        let domain = library.patches[0].surface.domain();
        let strip = [(0.25, -0.5), (0.75, -0.5), (0.75, 1.5), (0.25, 1.5)]
            .map(|(u, v)| DVec2::new(u, v))
            .to_vec();
        library.patches[0].trim = Some(Arc::new(Trim::new(vec![strip], domain).unwrap()));
        let library = Arc::new(library);
        let camera = looking(
            Vec3::new(-0.5, -3.0, 4.0),
            Vec3::new(-0.5, 0.5, 0.0),
            Vec3::Z,
        );
        let view_projection = camera.view_projection(1.0);
        let mut tessellator = Tessellator::new(Arc::clone(&library));
        let (mesh, _) = tessellator.mesh(Density::PerSpan { u: 8, v: 8 }, view_projection, 64, 64);
        let pieces = outlined(mesh, &library, &camera, 60.0);
        let on_flat: Vec<&Piece> = pieces.iter().filter(|p| p.patches == [0, 0]).collect();
        for side in [0.0, 1.0] {
            let along: Vec<(f64, f64)> = on_flat
                .iter()
                .filter(|p| p.ends.iter().all(|e| (e.y - side).abs() < 1e-9))
                .map(|p| (p.ends[0].x.min(p.ends[1].x), p.ends[0].x.max(p.ends[1].x)))
                .collect();
            let length: f64 = along.iter().map(|(a, b)| b - a).sum();
            assert!((length - 0.5).abs() < 1e-9, "y = {side}: {along:?}");
            assert!(
                along
                    .iter()
                    .all(|&(a, b)| a >= -0.75 - 1e-9 && b <= -0.25 + 1e-9),
                "y = {side}: {along:?}"
            );
            assert!(on_flat.iter().all(|p| p.kind == LineKind::Border && p.open));
        }
        assert!(
            !on_flat.iter().any(|p| p.ends.iter().all(|e| e.x == -1.0)),
            "the side the trim cuts away is drawn"
        );
    }

    #[test]
    fn a_crease_fades_in_over_its_band_and_open_borders_stay() {
        // The normals of the two squares turn by the hinge's angle.
        let angle = 40.0f32;
        let library = Arc::new(hinge(f64::from(angle)));
        let camera = looking(Vec3::new(0.0, -4.0, 5.0), Vec3::new(0.0, 0.5, 0.0), Vec3::Z);
        let view_projection = camera.view_projection(1.0);
        let mut tessellator = Tessellator::new(Arc::clone(&library));
        let (mesh, _) = tessellator.mesh(Density::PerSpan { u: 3, v: 3 }, view_projection, 64, 64);
        let mut last = None;
        for step in 0..=40 {
            let crease = 25.0 + step as f32 * 0.75;
            let pieces = outlined(mesh, &library, &camera, crease);
            let creases: Vec<f32> = pieces
                .iter()
                .filter(|p| p.kind == LineKind::Crease)
                .map(|p| p.opacity)
                .collect();
            let expected = crease_opacity(angle, crease);
            // Present with the band's opacity, or absent where that is 0.
            assert!(
                creases.iter().all(|&o| (o - expected).abs() < 1e-3),
                "crease {crease}: {creases:?} against {expected}"
            );
            assert_eq!(creases.is_empty(), expected == 0.0, "crease {crease}");
            // The opacity steps by a fraction of the band as the threshold moves: no jump.
            if let (Some(previous), Some(&now)) = (last, creases.first()) {
                let previous: f32 = previous;
                assert!((now - previous).abs() <= 0.75 / CREASE_BAND_DEGREES + 1e-3);
            }
            last = creases.first().copied().or(Some(0.0));
            // The six outer sides of the two squares are borders whatever the threshold.
            let borders = pieces.iter().filter(|p| p.kind == LineKind::Border).count();
            assert!(borders >= 6 * 3, "{borders}");
        }
        assert_eq!(crease_opacity(angle, angle), 0.5);
        assert_eq!(
            crease_opacity(angle, angle + 0.5 * CREASE_BAND_DEGREES),
            0.0
        );
        assert_eq!(
            crease_opacity(angle, angle - 0.5 * CREASE_BAND_DEGREES),
            1.0
        );
    }

    #[test]
    fn a_seam_between_two_materials_is_a_material_border_where_a_side_draws_them() {
        // Two squares side by side in one plane: a smooth seam, no crease.
        let library = Arc::new(hinge(0.0));
        let camera = looking(Vec3::new(0.0, 0.5, 5.0), Vec3::new(0.0, 0.5, 0.0), Vec3::Y);
        let view_projection = camera.view_projection(1.0);
        let mut tessellator = Tessellator::new(Arc::clone(&library));
        let (mesh, _) = tessellator.mesh(Density::PerSpan { u: 3, v: 3 }, view_projection, 64, 64);
        let outlines = outlines(60.0);
        let plain = outlines.style();
        let drawing = LineStyle {
            kinds: crate::render::LineKinds::of(&[LineKind::MaterialBorder]),
            ..plain
        };
        // On the seam x = 0: the pieces of a kind there.
        let on_seam = |styles: &[LineStyle], materials: &[u32], kind: LineKind| {
            borders_and_creases(
                mesh,
                &library,
                &camera,
                view_projection,
                (64, 64),
                (&outlines, styles, materials),
            )
            .into_iter()
            .filter(|p| p.kind == kind && p.ends.iter().all(|e| e.x.abs() < 1e-9))
            .count()
        };
        let material = LineKind::MaterialBorder;
        // Drawn when the materials differ and either side draws material borders.
        assert!(on_seam(&[drawing, drawing], &[0, 1], material) >= 3);
        assert!(on_seam(&[plain, drawing], &[0, 1], material) >= 3);
        // Not when they are one material, or when neither side draws them.
        assert_eq!(on_seam(&[drawing, drawing], &[1, 1], material), 0);
        assert_eq!(on_seam(&[drawing, drawing], &[], material), 0);
        assert_eq!(on_seam(&[plain, plain], &[0, 1], material), 0);
        // Without them, the smooth seam draws nothing.
        assert_eq!(on_seam(&[plain, plain], &[0, 1], LineKind::Border), 0);
    }
}
