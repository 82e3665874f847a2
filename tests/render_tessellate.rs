//! Tessellation: frames at the vertices, watertight seams between patches, the cache.

use std::collections::HashMap;

use glam::{DVec3, Mat4, Vec3};
use glint::geom::{shapes, NamedPatch, PatchLibrary};
use glint::render::tessellate::{Density, Tessellator};

use crate::common::teapot;

fn view() -> Mat4 {
    Mat4::perspective_rh(0.6, 1.5, 0.1, 100.0)
        * Mat4::look_at_rh(Vec3::new(6.0, -7.0, 5.0), Vec3::new(0.0, 0.0, 1.5), Vec3::Z)
}

#[test]
fn sphere_vertices_lie_on_the_sphere_with_its_frames() {
    let library = PatchLibrary {
        patches: vec![NamedPatch {
            name: "ball".into(),
            trim: None,
            surface: shapes::sphere(DVec3::ZERO, 2.0).unwrap(),
        }],
        groups: Vec::new(),
    };
    let mut t = Tessellator::new(library.clone());
    let (mesh, _) = t.mesh(Density::PerSpan { u: 4, v: 6 }, view(), 640, 480);
    // 4 spans in u, 2 in v: (16 + 1) × (12 + 1) vertices, 16 × 12 × 2 triangles.
    assert_eq!(mesh.positions.len(), 17 * 13);
    assert_eq!(mesh.triangles.len(), 16 * 12 * 2);
    let mut off_the_poles = 0;
    for (k, p) in mesh.positions.iter().enumerate() {
        assert!((p.length() - 2.0).abs() < 1e-6);
        assert!((mesh.normals[k] - *p / 2.0).length() < 1e-6);
        assert!(mesh.tangents_u[k].dot(mesh.normals[k]).abs() < 1e-6);
        // u runs east: du is the unit east direction (−y, x, 0)/|…|, wherever it is defined.
        let east = Vec3::new(-p.y, p.x, 0.0);
        if east.length() > 1e-3 {
            let east = east.normalize();
            assert!(
                (mesh.tangents_u[k] - east).length() < 1e-5,
                "vertex {k} at {p}: du {} vs east {east}",
                mesh.tangents_u[k]
            );
            off_the_poles += 1;
        }
    }
    // Every vertex but the poles' (13 rows of 17, the first and last at a pole).
    assert_eq!(off_the_poles, 17 * 11);
}

/// The unordered pair of exact vertex positions of a triangle edge.
fn edge_key(a: Vec3, b: Vec3) -> [u32; 6] {
    let (a, b) = (
        a.to_array().map(f32::to_bits),
        b.to_array().map(f32::to_bits),
    );
    let (lo, hi) = if a <= b { (a, b) } else { (b, a) };
    [lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]]
}

/// Patch edges (patch, edge) not shared with any other patch, found in f64 on the exact
/// surfaces: 0: v = 0, 1: u = 1, 2: v = 1, 3: u = 0.
fn open_patch_edges(library: &PatchLibrary) -> Vec<(usize, usize)> {
    let points = |p: usize, e: usize| -> Vec<DVec3> {
        (0..=8)
            .map(|k| {
                let t = k as f64 / 8.0;
                let (u, v) = [(t, 0.0), (1.0, t), (t, 1.0), (0.0, t)][e];
                library.patches[p].surface.point(u, v)
            })
            .collect()
    };
    let close = |a: &[DVec3], b: &[DVec3]| a.iter().zip(b).all(|(p, q)| (*p - *q).length() < 1e-9);
    let mut open = Vec::new();
    for p in 0..library.patches.len() {
        for e in 0..4 {
            let a = points(p, e);
            if a.iter().all(|x| (*x - a[0]).length() < 1e-9) {
                continue; // collapsed: its triangles have no area
            }
            let shared = (0..library.patches.len()).filter(|&q| q != p).any(|q| {
                (0..4).any(|f| {
                    let b = points(q, f);
                    let reversed: Vec<DVec3> = b.iter().rev().copied().collect();
                    close(&a, &b) || close(&a, &reversed)
                })
            });
            if !shared {
                open.push((p, e));
            }
        }
    }
    open
}

#[test]
fn teapot_seams_are_closed_edge_for_edge() {
    let library = teapot();
    let mut t = Tessellator::new(library.clone());
    // Adaptive density wants different counts on different patches; shared edges must still be
    // cut alike.
    let density = Density::ScreenTolerance { pixels: 0.25 };
    let segments = t.segments(density, view(), 640, 480);
    let (mesh, _) = t.mesh(density, view(), 640, 480);
    let mut uses: HashMap<[u32; 6], u32> = HashMap::new();
    for tri in &mesh.triangles {
        let p = tri.map(|i| mesh.positions[i as usize]);
        if p[0] == p[1] || p[1] == p[2] || p[2] == p[0] {
            continue; // at a collapsed edge: no area, nothing drawn
        }
        for k in 0..3 {
            *uses.entry(edge_key(p[k], p[(k + 1) % 3])).or_default() += 1;
        }
    }
    assert!(
        uses.values().all(|&n| n <= 2),
        "an edge used by more than two triangles"
    );
    let once = uses.values().filter(|&&n| n == 1).count();
    // Only the model's open boundary may be used once: the segments along each unshared edge.
    let expected: u32 = open_patch_edges(&library)
        .iter()
        .map(|&(p, e)| {
            if e % 2 == 0 {
                segments[p].0
            } else {
                segments[p].1
            }
        })
        .sum();
    assert!(expected > 0);
    assert_eq!(once as u32, expected);
}

#[test]
fn the_mesh_is_cached_while_its_segment_counts_stay() {
    let library = teapot();
    let mut t = Tessellator::new(library.clone());
    let density = Density::ScreenTolerance { pixels: 0.5 };
    assert!(t.mesh(density, view(), 640, 480).1);
    assert!(!t.mesh(density, view(), 640, 480).1);
    let closer = Mat4::perspective_rh(0.6, 1.5, 0.1, 100.0)
        * Mat4::look_at_rh(Vec3::new(1.5, -2.0, 2.5), Vec3::new(0.0, 0.0, 1.5), Vec3::Z);
    let (mesh, rebuilt) = t.mesh(density, closer, 640, 480);
    assert!(rebuilt);
    assert!(mesh
        .normals
        .iter()
        .all(|n| n.is_finite() && (n.length() - 1.0).abs() < 1e-5));
}
