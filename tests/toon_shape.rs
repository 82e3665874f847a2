//! Shape detail against exact shapes: the abstracted normals of an exact sphere, ellipsoid and
//! cylinder are the shapes' own NURBS normals; a smoothed net loses a bump; the blend.

use std::sync::Arc;

use glam::{DMat3, DVec3, Vec2, Vec3};
use glint::geom::{shapes, GridEvaluator, NamedPatch, NurbsSurface, PatchLibrary};
use glint::toon::{AbstractShape, Abstraction, HighlightFrame, ShapeDetail, XToonError};

fn library(surface: NurbsSurface) -> PatchLibrary {
    PatchLibrary {
        patches: vec![NamedPatch {
            name: "shape".into(),
            trim: None,
            surface,
        }],
        groups: Vec::new(),
    }
}

/// Points and exact unit normals of patch 0 of `library` on a grid, as f32.
fn samples(library: &PatchLibrary, n: usize) -> Vec<(Vec3, Vec3, Vec2)> {
    let surface = &library.patches[0].surface;
    let grid = GridEvaluator::uniform(surface, n, n);
    (0..n)
        .flat_map(|i| {
            let u = grid.us()[i];
            grid.row_frames(i)
                .zip(grid.vs())
                .map(move |(f, &v)| {
                    (
                        f.point.as_vec3(),
                        f.normal.as_vec3(),
                        Vec2::new(u as f32, v as f32),
                    )
                })
                .collect::<Vec<_>>()
        })
        .collect()
}

/// The largest angle-like error `‖n_a − n‖` over the samples, for the normal blended with
/// weight `w`.
fn worst(shape: &Arc<AbstractShape>, w: f32, library: &PatchLibrary) -> f32 {
    let detail = ShapeDetail {
        abstraction: shape.abstraction(),
        weight: w,
        highlight_frame: HighlightFrame::Abstracted,
    };
    let prepared = detail.prepare(shape).unwrap().unwrap();
    samples(library, 33)
        .iter()
        .map(|&(p, n, uv)| (prepared.shading_normal(n, p, 0, uv) - n).length())
        .fold(0.0, f32::max)
}

#[test]
fn sphere_abstraction_of_an_exact_sphere_leaves_normals_unchanged() {
    let library = library(shapes::sphere(DVec3::new(1.0, -2.0, 0.5), 2.0).unwrap());
    let shape = Abstraction::Sphere.build(&library).unwrap();
    for w in [0.3, 1.0] {
        let e = worst(&shape, w, &library);
        assert!(e < 1e-6, "w = {w}: {e}");
    }
}

#[test]
fn ellipsoid_abstraction_of_an_exact_ellipsoid_gives_its_normals() {
    // A unit NURBS sphere scaled to semi-axes 3, 1.5, 0.8, turned and moved: an exact
    // ellipsoid, whose normals are the surface's own.
    let turn = DMat3::from_rotation_z(0.5) * DMat3::from_rotation_x(0.3);
    let scale = DVec3::new(3.0, 1.5, 0.8);
    let offset = DVec3::new(0.5, 1.0, -1.0);
    let ellipsoid = shapes::sphere(DVec3::ZERO, 1.0)
        .unwrap()
        .map_points(|p| offset + turn * (p * scale));
    let library = library(ellipsoid);
    let shape = Abstraction::Ellipsoid.build(&library).unwrap();
    let e = worst(&shape, 1.0, &library);
    assert!(e < 2e-6, "{e}");
    // The sphere abstraction of the same model is another shape.
    let sphere = Abstraction::Sphere.build(&library).unwrap();
    assert!(worst(&sphere, 1.0, &library) > 0.3);
}

#[test]
fn ellipsoid_normals_are_the_gradient_not_the_radial_direction() {
    // On an ellipse x²/a² + y²/b² = 1 the normal is ∝ (x/a², y/b²), not (x/a, y/b) or (x, y).
    let library = library(
        shapes::sphere(DVec3::ZERO, 1.0)
            .unwrap()
            .map_points(|p| p * DVec3::new(4.0, 1.0, 1.0)),
    );
    let shape = Abstraction::Ellipsoid.build(&library).unwrap();
    let (x, y) = (4.0 * 0.6_f32, 0.8_f32);
    let n = shape.normal(Vec3::new(x, y, 0.0), 0, Vec2::ZERO).unwrap();
    let gradient = Vec3::new(x / 16.0, y, 0.0).normalize();
    assert!((n - gradient).length() < 1e-6, "{n}");
}

#[test]
fn cylinder_abstraction_of_an_exact_cylinder_gives_its_normals() {
    // Radius 1, height 6: the principal axis is the cylinder's axis.
    let library = library(shapes::cylinder(1.0, 6.0).unwrap());
    let shape = Abstraction::Cylinder.build(&library).unwrap();
    let e = worst(&shape, 1.0, &library);
    assert!(e < 1e-6, "{e}");
}

#[test]
fn smoothing_flattens_a_bump() {
    // A bicubic B-spline sheet, 7 × 7 control points on z = 0 with the centre one raised.
    let points: Vec<Vec<DVec3>> = (0..7)
        .map(|i| {
            (0..7)
                .map(|j| {
                    let z = if (i, j) == (3, 3) { 1.5 } else { 0.0 };
                    DVec3::new(i as f64, j as f64, z)
                })
                .collect()
        })
        .collect();
    let knots = vec![0.0, 0.0, 0.0, 0.0, 0.25, 0.5, 0.75, 1.0, 1.0, 1.0, 1.0];
    let sheet = NurbsSurface::new(3, 3, knots.clone(), knots, &points, None).unwrap();
    let library = library(sheet);
    // How far the bump's normals lean from +z, at its flank.
    let lean = |normal: Vec3| 1.0 - normal.normalize().z.abs();
    let surface = &library.patches[0].surface;
    let flank = (0.4, 0.5);
    let original = lean(surface.frame(flank.0, flank.1).normal.as_vec3());
    let uv = Vec2::new(flank.0 as f32, flank.1 as f32);
    let mut previous = original;
    for iterations in [1, 4, 16] {
        let shape = Abstraction::Smoothed { iterations }
            .build(&library)
            .unwrap();
        let n = shape.normal(Vec3::ZERO, 0, uv).unwrap();
        let l = lean(n);
        assert!(
            l < previous,
            "{iterations} iterations: {l} after {previous}"
        );
        previous = l;
    }
    assert!(previous < 0.25 * original, "{previous} vs {original}");
}

#[test]
fn smoothing_keeps_a_sphere_round_across_its_seam_and_poles() {
    // The sphere's patch closes on itself at u = 0 and 1 (its seam) and collapses to a point at
    // v = 0 and 1 (its poles), and its rational parametrisation is not uniform in angle: a
    // smoothing that follows the net or the parameters bends the normals at all three.
    let centre = DVec3::new(0.5, -1.0, 2.0);
    let library = library(shapes::sphere(centre, 1.5).unwrap());
    for iterations in [1, 3, 30] {
        let shape = Abstraction::Smoothed { iterations }
            .build(&library)
            .unwrap();
        let at = |u: f32, v: f32| shape.normal(Vec3::ZERO, 0, Vec2::new(u, v)).unwrap();
        // Round: within 2.6° (cos > 0.999) of the sphere's own normal everywhere, including
        // between the grid's samples.
        for (p, n, uv) in samples(&library, 53) {
            let a = shape.normal(p, 0, uv).unwrap().normalize();
            assert!(
                a.dot(n) > 0.999,
                "{iterations} iterations, at {uv}: {a} vs {n}"
            );
        }
        for k in 0..=40 {
            let t = k as f32 / 40.0;
            // Across the seam: the same normal from either side.
            let (start, end) = (at(0.0, t), at(1.0, t));
            assert!(
                (start - end).length() < 1e-5,
                "{iterations} iterations, seam at v = {t}: {start} vs {end}"
            );
            // At the poles: one normal, whichever meridian it is reached along, and it is the
            // normal a step away from the pole tends to.
            for (pole, axis) in [(0.0, -Vec3::Z), (1.0, Vec3::Z)] {
                let n = at(t, pole).normalize();
                assert!(
                    n.dot(axis) > 0.99999,
                    "{iterations} iterations: {n} at ({t}, {pole})"
                );
                let near = at(t, (pole - 0.01f32).abs()).normalize();
                assert!(
                    near.dot(axis) > 0.995,
                    "{iterations} iterations: {near} near the pole"
                );
            }
        }
    }
}

#[test]
fn zero_weight_prepares_to_nothing_and_mismatched_shapes_are_errors() {
    let library = library(shapes::sphere(DVec3::ZERO, 1.0).unwrap());
    let sphere = Abstraction::Sphere.build(&library).unwrap();
    let detail = |abstraction, weight| ShapeDetail {
        abstraction,
        weight,
        highlight_frame: HighlightFrame::True,
    };
    assert_eq!(detail(Abstraction::Sphere, 0.0).prepare(&sphere), Ok(None));
    assert!(matches!(
        detail(Abstraction::Cylinder, 0.5).prepare(&sphere),
        Err(XToonError::ShapeMismatch { .. })
    ));
    let e = detail(Abstraction::Sphere, 1.5)
        .prepare(&sphere)
        .unwrap_err();
    assert!(
        e.to_string()
            .starts_with("shape weight (w) is 1.5, outside the allowed range [0, 1]"),
        "{e}"
    );
    let e = Abstraction::Smoothed { iterations: 0 }
        .build(&library)
        .unwrap_err();
    assert!(e.to_string().contains("iterations is 0"), "{e}");
    assert!(Abstraction::Ellipsoid
        .build(&PatchLibrary::default())
        .is_err());
}
