//! The Utah teapot (32 bicubic Bezier patches): finite orthonormal frames everywhere, the limit
//! normal at its collapsed edges, and agreement between neighbouring patches.

use glam::DVec3;
use glint::geom::{GridEvaluator, NurbsSurface};

use crate::common::teapot;

/// The parameters of an edge of [0,1]²: 0 = (t, 0), 1 = (1, t), 2 = (t, 1), 3 = (0, t).
fn edge_uv(edge: usize, t: f64) -> (f64, f64) {
    match edge {
        0 => (t, 0.0),
        1 => (1.0, t),
        2 => (t, 1.0),
        _ => (0.0, t),
    }
}

fn edge_points(s: &NurbsSurface, edge: usize, n: usize) -> Vec<DVec3> {
    (0..=n)
        .map(|k| {
            let (u, v) = edge_uv(edge, k as f64 / n as f64);
            s.point(u, v)
        })
        .collect()
}

#[test]
fn every_patch_has_finite_orthonormal_frames_on_a_33_by_33_grid() {
    let lib = teapot();
    assert_eq!(lib.patches.len(), 32);
    for patch in &lib.patches {
        let grid = GridEvaluator::uniform(&patch.surface, 33, 33);
        for i in 0..33 {
            for (j, f) in grid.row_frames(i).enumerate() {
                let what = format!("patch {} at ({i}, {j}): {f:?}", patch.name);
                assert!(f.point.is_finite() && f.normal.is_finite(), "{what}");
                assert!(f.du.is_finite() && f.dv.is_finite(), "{what}");
                for axis in [f.normal, f.du, f.dv] {
                    assert!((axis.length() - 1.0).abs() < 1e-12, "{what}");
                }
                assert!(f.normal.dot(f.du).abs() < 1e-12, "{what}");
                assert!((f.du.cross(f.dv) - f.normal).length() < 1e-12, "{what}");
                // The grid's shared contractions give exactly the direct evaluation.
                assert_eq!(f, patch.surface.frame(grid.us()[i], grid.vs()[j]), "{what}");
                assert_eq!(f, grid.frame(i, j), "{what}");
            }
        }
    }
}

#[test]
fn collapsed_edges_at_lid_apex_and_bottom_centre_take_the_vertical_limit_normal() {
    let lib = teapot();
    let mut collapsed = 0;
    for patch in &lib.patches {
        let s = &patch.surface;
        for edge in 0..4 {
            let points = edge_points(s, edge, 8);
            if points.iter().any(|p| (*p - points[0]).length() > 1e-12) {
                continue;
            }
            collapsed += 1;
            let apex = points[0];
            assert!(apex.x.abs() < 1e-12 && apex.y.abs() < 1e-12, "{apex}");
            // The lid's apex faces up, the bottom centre down.
            let expected = if apex.z > 1.0 { DVec3::Z } else { -DVec3::Z };
            for k in 0..=8 {
                let t = k as f64 / 8.0;
                let (u, v) = edge_uv(edge, t);
                let f = s.frame(u, v);
                assert!(f.degenerate, "patch {} edge {edge}", patch.name);
                assert!((f.normal - expected).length() < 1e-12, "{f:?}");
                // Just inside, along the edge's inward direction.
                let (ui, vi) = match edge {
                    0 => (u, 1e-7),
                    1 => (1.0 - 1e-7, v),
                    2 => (u, 1.0 - 1e-7),
                    _ => (1e-7, v),
                };
                let inside = s.frame(ui, vi);
                assert!((inside.normal - f.normal).length() < 1e-5, "{inside:?}");
            }
        }
    }
    // Four lid patches meet at the apex, four bottom patches at the centre.
    assert_eq!(collapsed, 8);
}

/// Whether the Bezier net is G1 across the given edge of `a` where it meets `b`: at each edge
/// control point, the neighbouring inner control points of both patches are collinear with it.
fn net_is_smooth_across(a: &NurbsSurface, b: &NurbsSurface, edge_a: usize, edge_b: usize) -> bool {
    let n = 3;
    let row = |s: &NurbsSurface, edge: usize, depth: usize| -> Vec<DVec3> {
        (0..=n)
            .map(|k| {
                let (i, j) = match edge {
                    0 => (k, depth),
                    1 => (n - depth, k),
                    2 => (k, n - depth),
                    _ => (depth, k),
                };
                s.control_point(i, j).0
            })
            .collect()
    };
    let (edge, inner_a) = (row(a, edge_a, 0), row(a, edge_a, 1));
    let mut inner_b = row(b, edge_b, 1);
    if (row(b, edge_b, 0)[0] - edge[0]).length() > 1e-9 {
        inner_b.reverse();
    }
    (0..=n).all(|k| {
        let (da, db) = (inner_a[k] - edge[k], inner_b[k] - edge[k]);
        da.length() < 1e-12
            || db.length() < 1e-12
            || da.cross(db).length() < 1e-9 * da.length() * db.length()
    })
}

#[test]
fn neighbouring_patches_agree_on_position_and_on_normal_where_smooth() {
    let lib = teapot();
    let samples = 16;
    let (mut shared, mut smooth) = (0, 0);
    for (ia, a) in lib.patches.iter().enumerate() {
        for b in &lib.patches[ia + 1..] {
            for edge_a in 0..4 {
                let pa = edge_points(&a.surface, edge_a, samples);
                if pa.iter().all(|p| (*p - pa[0]).length() < 1e-12) {
                    continue; // a collapsed edge is a point, not an edge
                }
                for edge_b in 0..4 {
                    let pb = edge_points(&b.surface, edge_b, samples);
                    let forward = pa.iter().zip(&pb).all(|(p, q)| (*p - *q).length() < 1e-12);
                    let backward = pa
                        .iter()
                        .zip(pb.iter().rev())
                        .all(|(p, q)| (*p - *q).length() < 1e-12);
                    if !(forward || backward) {
                        continue;
                    }
                    shared += 1;
                    if !net_is_smooth_across(&a.surface, &b.surface, edge_a, edge_b) {
                        continue;
                    }
                    smooth += 1;
                    for k in 0..=samples {
                        let t = k as f64 / samples as f64;
                        let (ua, va) = edge_uv(edge_a, t);
                        let (ub, vb) = edge_uv(edge_b, if forward { t } else { 1.0 - t });
                        let (fa, fb) = (a.surface.frame(ua, va), b.surface.frame(ub, vb));
                        assert!(
                            (fa.normal - fb.normal).length() < 1e-6,
                            "patches {} and {} at t = {t}: {:?} vs {:?}",
                            a.name,
                            b.name,
                            fa.normal,
                            fb.normal
                        );
                    }
                }
            }
        }
    }
    assert!(shared >= 40, "only {shared} shared edges found");
    assert!(smooth >= 30, "only {smooth} smooth shared edges found");
}
