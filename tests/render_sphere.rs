//! The renderer against the analytic sphere: the highlight matte of an orthographic and a
//! perspective render of the exact NURBS sphere, compared per pixel with the region found by
//! ray-casting the analytic sphere and running the same operations on its analytic frame.

use glam::{DVec3, Vec2, Vec3};
use glint::geom::{shapes, NamedPatch, PatchLibrary};
use glint::highlight::{
    half_vector, Expr, Layer, Light, Op, PreparedExpr, SquareStyle, TangentFrame,
};
use glint::render::tessellate::Density;
use glint::render::{
    Antialias, Aovs, Camera, FrameMode, PatchLook, Projection, Renderer, Scene, Settings, Tone,
};
use glint::toon::CelRamp;

const SIZE: u32 = 512;

fn sphere() -> PatchLibrary {
    PatchLibrary {
        patches: vec![NamedPatch {
            name: "sphere".into(),
            surface: shapes::sphere(DVec3::ZERO, 1.0).unwrap(),
        }],
    }
}

fn light() -> Vec3 {
    Vec3::new(0.35, -1.0, 0.45).normalize()
}

fn camera(projection: Projection) -> Camera {
    Camera {
        eye: Vec3::new(0.0, -5.0, 0.0),
        target: Vec3::ZERO,
        up: Vec3::Z,
        projection,
        near: 0.5,
        far: 20.0,
    }
}

fn expression(stack: Vec<Op>) -> PreparedExpr {
    Expr::Layer(Layer::new(stack, 0.04, [1.0, 1.0, 1.0]))
        .prepare()
        .unwrap()
}

/// The renderer's highlight matte (coverage > 1/2 per pixel).
fn rendered(expr: &PreparedExpr, camera: Camera) -> Vec<bool> {
    let settings = Settings {
        density: Density::PerSpan { u: 16, v: 16 },
        frames: FrameMode::Exact,
        ..Settings::preview(SIZE, SIZE)
    };
    rendered_matte(expr, camera, &settings)
        .iter()
        .map(|&c| c > 0.5)
        .collect()
}

/// The renderer's highlight matte with `settings`.
fn rendered_matte(expr: &PreparedExpr, camera: Camera, settings: &Settings) -> Vec<f32> {
    let library = sphere();
    let scene = Scene {
        library: &library,
        looks: vec![PatchLook {
            tone: Tone::Cel(CelRamp::two_tone(Vec3::splat(0.2), Vec3::splat(0.6), 0.0)),
            highlight: Some(expr.clone()),
        }],
        camera,
        light: Light::Directional { towards: light() },
        outlines: None,
        aovs: Aovs {
            matte: true,
            ..Aovs::default()
        },
    };
    let frame = Renderer::new(&library).render(&scene, settings).unwrap();
    frame.aovs.matte.unwrap()
}

/// The same region by ray-casting the unit sphere through each pixel centre: the analytic frame
/// (east, north, outward) and the same operations.
fn analytic(expr: &PreparedExpr, camera: Camera) -> Vec<bool> {
    analytic_coverage(expr, camera, SIZE, 1)
        .iter()
        .map(|&c| c > 0.5)
        .collect()
}

/// The fraction of `k × k` sub-pixel samples per pixel inside the analytic highlight, on a
/// `size × size` image.
fn analytic_coverage(expr: &PreparedExpr, camera: Camera, size: u32, k: u32) -> Vec<f32> {
    let inverse = camera.view_projection(1.0).inverse();
    let inside = |x: f32, y: f32| -> bool {
        let ndc = Vec2::new(2.0 * x / size as f32 - 1.0, 1.0 - 2.0 * y / size as f32);
        let near = inverse.project_point3(ndc.extend(0.0)).as_dvec3();
        let far = inverse.project_point3(ndc.extend(1.0)).as_dvec3();
        let d = (far - near).normalize();
        // |near + t d| = 1
        let b = near.dot(d);
        let disc = b * b - (near.length_squared() - 1.0);
        if disc < 0.0 {
            return false;
        }
        let p = near + (-b - disc.sqrt()) * d;
        let n = p.normalize();
        let east = DVec3::new(-n.y, n.x, 0.0).normalize();
        let north = n.cross(east);
        let frame = TangentFrame::new(east.as_vec3(), north.as_vec3(), n.as_vec3());
        let v = camera.toward_eye(p.as_vec3());
        let h = half_vector(light(), v, n.as_vec3());
        // The uv only matters for masks, which these layers do not have.
        expr.eval(&frame, Vec2::ZERO, h, 0.0).coverage > 0.5
    };
    (0..size * size)
        .map(|i| {
            let (px, py) = ((i % size) as f32, (i / size) as f32);
            let hits = (0..k * k)
                .filter(|s| {
                    let (sx, sy) = ((s % k) as f32 + 0.5, (s / k) as f32 + 0.5);
                    inside(px + sx / k as f32, py + sy / k as f32)
                })
                .count();
            hits as f32 / (k * k) as f32
        })
        .collect()
}

fn iou(a: &[bool], b: &[bool]) -> f64 {
    let both = a.iter().zip(b).filter(|(x, y)| **x && **y).count();
    let either = a.iter().zip(b).filter(|(x, y)| **x || **y).count();
    assert!(
        either > 500,
        "the highlight should cover a visible area, got {either} pixels"
    );
    both as f64 / either as f64
}

/// Asserts that the renderer's matte matches the analytic one with at least `minimum` IoU, in
/// an orthographic and a perspective view.
fn assert_matches_analytic(expr: &PreparedExpr, minimum: f64) {
    for projection in [
        Projection::Orthographic { height: 2.4 },
        Projection::Perspective {
            fov_y_degrees: 30.0,
        },
    ] {
        let camera = camera(projection);
        let score = iou(&rendered(expr, camera), &analytic(expr, camera));
        assert!(score >= minimum, "{expr:?}, {projection:?}: IoU {score}");
    }
}

#[test]
fn identity_highlight_matches_the_analytic_region_orthographic_and_perspective() {
    assert_matches_analytic(&expression(vec![]), 0.995);
}

#[test]
fn operated_highlights_match_the_same_operations_on_the_analytic_frame() {
    let stacks = [
        vec![
            Op::Translate {
                alpha: 0.15,
                beta: -0.1,
            },
            Op::Scale {
                delta: 0.6,
                axis: Default::default(),
            },
        ],
        vec![Op::Split {
            gamma_u: 0.08,
            gamma_v: 0.0,
        }],
        vec![Op::Square {
            sigma: 0.2,
            n: 2.0,
            style: SquareStyle::Tangent,
        }],
    ];
    for stack in stacks {
        assert_matches_analytic(&expression(stack), 0.99);
    }
}

#[test]
fn anti_aliasing_brings_the_matte_closer_to_the_true_pixel_coverage() {
    let size = 96;
    let camera = camera(Projection::Orthographic { height: 2.4 });
    let expr = expression(vec![Op::Scale {
        delta: 0.5,
        axis: Default::default(),
    }]);
    let truth = analytic_coverage(&expr, camera, size, 8);
    let error = |antialias: Antialias| -> f32 {
        let settings = Settings {
            density: Density::PerSpan { u: 16, v: 16 },
            frames: FrameMode::Exact,
            antialias,
            ..Settings::preview(size, size)
        };
        let matte = rendered_matte(&expr, camera, &settings);
        matte
            .iter()
            .zip(&truth)
            .map(|(a, b)| (a - b).abs())
            .sum::<f32>()
    };
    let (hard, analytic, supersampled) = (
        error(Antialias::None),
        error(Antialias::Analytic),
        error(Antialias::Supersample(4)),
    );
    assert!(analytic < 0.8 * hard, "analytic {analytic} vs hard {hard}");
    assert!(
        supersampled < 0.6 * hard,
        "4x4 supersampling {supersampled} vs hard {hard}"
    );
}
