//! The renderer against the analytic sphere: the highlight matte of an orthographic and a
//! perspective render of the exact NURBS sphere, compared per pixel with the region found by
//! ray-casting the analytic sphere and running the same operations on its analytic frame
//! (`glint::accuracy::AnalyticSphere`, shared with `glint bench accuracy`).

use std::sync::Arc;

use glint::accuracy::sweep::Stack;
use glint::accuracy::{metrics, AnalyticSphere};
use glint::highlight::{Expr, Layer, Op, PreparedExpr};
use glint::render::tessellate::Density;
use glint::render::{Antialias, Aovs, FrameMode, Projection, Renderer, Settings};

const SIZE: u32 = 512;

fn expression(stack: Vec<Op>) -> PreparedExpr {
    Expr::Layer(Layer::new(stack, 0.04, [1.0, 1.0, 1.0]))
        .prepare()
        .unwrap()
}

/// The renderer's highlight matte with `settings`.
fn rendered_matte(expr: &PreparedExpr, sphere: &AnalyticSphere, settings: &Settings) -> Vec<f32> {
    let library = AnalyticSphere::library();
    let aovs = Aovs {
        matte: true,
        ..Aovs::default()
    };
    let scene = sphere.scene(&library, expr, aovs);
    let frame = Renderer::new(Arc::clone(&library))
        .render(&scene, settings)
        .unwrap();
    frame.aovs.matte.unwrap()
}

/// 1 where coverage > 1/2, else 0.
fn hard(coverage: &[f32]) -> Vec<f32> {
    coverage
        .iter()
        .map(|&c| if c > 0.5 { 1.0 } else { 0.0 })
        .collect()
}

/// The renderer's hard highlight matte (coverage > 1/2 per pixel).
fn rendered(expr: &PreparedExpr, sphere: &AnalyticSphere) -> Vec<f32> {
    let settings = Settings {
        density: Density::PerSpan { u: 16, v: 16 },
        frames: FrameMode::Exact,
        ..Settings::preview(SIZE, SIZE)
    };
    hard(&rendered_matte(expr, sphere, &settings))
}

fn iou(a: &[f32], b: &[f32]) -> f64 {
    let either = a
        .iter()
        .zip(b)
        .filter(|(x, y)| **x > 0.0 || **y > 0.0)
        .count();
    assert!(
        either > 500,
        "the highlight should cover a visible area, got {either} pixels"
    );
    metrics::iou(a, b).unwrap()
}

/// Asserts that the renderer's matte matches the analytic one (pixel centres) with at least
/// `minimum` IoU, in an orthographic and a perspective view.
fn assert_matches_analytic(expr: &PreparedExpr, minimum: f64) {
    for projection in [
        Projection::Orthographic { height: 2.4 },
        Projection::Perspective {
            fov_y_degrees: 30.0,
        },
    ] {
        let sphere = AnalyticSphere::new(projection);
        let analytic = sphere.coverage(expr, SIZE, 1);
        let score = iou(&rendered(expr, &sphere), &analytic);
        assert!(score >= minimum, "{expr:?}, {projection:?}: IoU {score}");
    }
}

#[test]
fn identity_highlight_matches_the_analytic_region_orthographic_and_perspective() {
    assert_matches_analytic(&expression(vec![]), 0.995);
}

#[test]
fn operated_highlights_match_the_same_operations_on_the_analytic_frame() {
    // The accuracy ladder's stacks: translation + scaling, split and squaring, ε = 0.04.
    for stack in [Stack::TranslateScale, Stack::Split, Stack::Square] {
        assert_matches_analytic(&stack.expression(), 0.99);
    }
}

#[test]
fn anti_aliasing_brings_the_matte_closer_to_the_true_pixel_coverage() {
    let size = 96;
    let sphere = AnalyticSphere::new(Projection::Orthographic { height: 2.4 });
    let expr = expression(vec![Op::Scale {
        delta: 0.5,
        axis: Default::default(),
    }]);
    let truth = sphere.coverage(&expr, size, 8);
    let error = |antialias: Antialias| -> f32 {
        let settings = Settings {
            density: Density::PerSpan { u: 16, v: 16 },
            frames: FrameMode::Exact,
            antialias,
            ..Settings::preview(size, size)
        };
        let matte = rendered_matte(&expr, &sphere, &settings);
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
