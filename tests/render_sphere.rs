//! The renderer against the analytic sphere: the highlight matte of an orthographic and a
//! perspective render of the exact NURBS sphere, compared per pixel with the region found by
//! ray-casting the analytic sphere and evaluating the same highlight description in closed form
//! on its analytic frame (`glint::accuracy::AnalyticSphere` with `ClosedForm`, shared with
//! `glint bench accuracy`), which shares no code with the renderer's highlight evaluation.

use std::sync::Arc;

use glam::DVec3;
use glint::accuracy::sphere_point::sphere_parameters;
use glint::accuracy::sweep::Stack;
use glint::accuracy::{metrics, AnalyticSphere, ClosedForm};
use glint::highlight::{Axis, Expr, Layer, Mask, Op, PreparedExpr, SquareStyle};
use glint::render::tessellate::Density;
use glint::render::{Antialias, Aovs, FrameMode, Projection, Renderer, Settings};

const SIZE: u32 = 512;

fn expression(stack: Vec<Op>) -> Expr {
    Expr::Layer(Layer::new(stack, 0.04, [1.0, 1.0, 1.0]))
}

/// The highlight as the renderer takes it.
fn prepared(expr: &Expr) -> PreparedExpr {
    expr.prepare().unwrap()
}

/// The highlight as the reference evaluates it, in closed form.
fn closed(expr: &Expr) -> ClosedForm {
    ClosedForm::try_new(expr).unwrap()
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

/// Asserts that the renderer's matte of `render` matches the closed-form region of `truth`
/// (pixel centres) with at least `minimum` IoU, in an orthographic and a perspective view.
fn assert_matches_closed_form(render: &PreparedExpr, truth: &ClosedForm, minimum: f64) {
    for projection in [
        Projection::Orthographic { height: 2.4 },
        Projection::Perspective {
            fov_y_degrees: 30.0,
        },
    ] {
        let sphere = AnalyticSphere::new(projection);
        let analytic = sphere.coverage(truth, SIZE, 1);
        let score = iou(&rendered(render, &sphere), &analytic);
        assert!(
            score >= minimum,
            "{:?}, {projection:?}: IoU {score}",
            truth.expr()
        );
    }
}

/// [`assert_matches_closed_form`] of one description.
fn assert_matches_analytic(expr: &Expr, minimum: f64) {
    assert_matches_closed_form(&prepared(expr), &closed(expr), minimum);
}

#[test]
fn identity_highlight_matches_the_analytic_region_orthographic_and_perspective() {
    assert_matches_analytic(&expression(vec![]), 0.995);
}

#[test]
fn operated_highlights_match_the_same_operations_on_the_analytic_frame() {
    // The accuracy ladder's stacks: translation + scaling, split, squaring and the crescent,
    // ε = 0.04; the renderer reads the keyed translation from its track, the reference from
    // the keys by hand.
    for stack in [
        Stack::TranslateScale,
        Stack::Split,
        Stack::Square,
        Stack::Crescent,
        Stack::Keyed { frame: 6.25 },
    ] {
        assert_matches_closed_form(&stack.expression(), &stack.reference_expression(), 0.99);
    }
}

#[test]
fn every_operation_renders_its_closed_form_region() {
    // Each operation at intermediate strength and a stack of several, ε = 0.04.
    let scale = |delta: f32, axis: Axis| Op::Scale { delta, axis };
    let square = |sigma: f32, n: f32, style: SquareStyle| Op::Square { sigma, n, style };
    for stack in [
        vec![Op::Rotate { degrees: 30.0 }, scale(0.6, Axis::U)],
        vec![scale(0.5, Axis::V)],
        vec![scale(0.7, Axis::Angle(-40.0))],
        vec![Op::Split {
            gamma_u: 0.0,
            gamma_v: 0.08,
        }],
        vec![Op::Split {
            gamma_u: 0.07,
            gamma_v: 0.07,
        }],
        vec![square(0.5, 1.5, SquareStyle::Tangent)],
        vec![square(1.0, 1.0, SquareStyle::PerAxis)],
        vec![
            Op::Translate {
                alpha: 0.05,
                beta: 0.1,
            },
            Op::Rotate { degrees: -25.0 },
            scale(0.5, Axis::U),
            Op::Split {
                gamma_u: 0.04,
                gamma_v: 0.0,
            },
            square(0.2, 2.0, SquareStyle::Tangent),
        ],
    ] {
        assert_matches_analytic(&expression(stack), 0.985);
    }
}

#[test]
fn feather_mask_and_booleans_render_their_closed_form_regions() {
    // The feather's half level is the hard edge; the mask keeps the side of the highlight's
    // centre of smaller u on the NURBS sphere, found from the closed form's (u, v) of the
    // sphere at the point where H = N in the orthographic view.
    let light = glam::DVec3::new(0.35, -1.0, 0.45).normalize();
    let centre = sphere_parameters((light + glam::DVec3::NEG_Y).normalize());
    let layer = |stack: Vec<Op>, epsilon: f32| Layer::new(stack, epsilon, [1.0, 1.0, 1.0]);
    let feathered = Expr::Layer(Layer {
        feather: Some(0.02),
        ..layer(vec![], 0.05)
    });
    let masked = Expr::Layer(Layer {
        mask: Some(Mask {
            u: (0.0, centre.x as f32),
            v: (0.0, 1.0),
            feather: 0.0,
        }),
        ..layer(vec![], 0.06)
    });
    let moved = |alpha: f32, beta: f32| {
        Box::new(Expr::Layer(layer(
            vec![Op::Translate { alpha, beta }],
            0.04,
        )))
    };
    let union = Expr::Union(moved(-0.15, 0.0), moved(0.15, 0.05));
    let intersect = Expr::Intersect(moved(-0.08, 0.0), moved(0.08, 0.05));
    for expr in [feathered, masked, union, intersect] {
        assert_matches_analytic(&expr, 0.985);
    }
}

#[test]
fn anti_aliasing_brings_the_matte_closer_to_the_true_pixel_coverage() {
    let size = 96;
    let sphere = AnalyticSphere::new(Projection::Orthographic { height: 2.4 });
    let description = expression(vec![Op::Scale {
        delta: 0.5,
        axis: Default::default(),
    }]);
    let expr = prepared(&description);
    let truth = sphere.coverage(&closed(&description), size, 8);
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

/// The highlight region in closed form, in f64, for the view of `AnalyticSphere` (the unit
/// sphere, the eye at (0, −5, 0) looking along +y with z up, the light toward
/// (0.35, −1, 0.45)): per pixel centre of a `size × size` image, `Some(inside)`, or `None` off
/// the sphere or within `1e-4` of the edge `1 − N·H' = ε`. H is the normalized `L + V`, and
/// `H' = normalize(H + α east + β north)` with east `(−N.y, N.x, 0)/|…|` and north `N × east`.
fn closed_form(
    projection: Projection,
    size: u32,
    (alpha, beta): (f64, f64),
    epsilon: f64,
) -> Vec<Option<bool>> {
    let light = DVec3::new(0.35, -1.0, 0.45).normalize();
    let eye = DVec3::new(0.0, -5.0, 0.0);
    (0..size * size)
        .map(|i| {
            let s = f64::from(size);
            let x = 2.0 * (f64::from(i % size) + 0.5) / s - 1.0;
            let y = 1.0 - 2.0 * (f64::from(i / size) + 0.5) / s;
            let (origin, direction) = match projection {
                Projection::Orthographic { height } => {
                    let half = f64::from(height) / 2.0;
                    (eye + DVec3::new(x * half, 0.0, y * half), DVec3::Y)
                }
                Projection::Perspective { fov_y_degrees } => {
                    let t = (f64::from(fov_y_degrees).to_radians() / 2.0).tan();
                    (eye, DVec3::new(x * t, 1.0, y * t).normalize())
                }
            };
            let b = origin.dot(direction);
            let disc = b * b - (origin.length_squared() - 1.0);
            if disc < 0.0 {
                return None;
            }
            let n = origin + (-b - disc.sqrt()) * direction;
            let v = -direction;
            let h = (light + v).normalize();
            let east = DVec3::new(-n.y, n.x, 0.0).normalize();
            let north = n.cross(east);
            let moved = (h + alpha * east + beta * north).normalize();
            let margin = epsilon - (1.0 - n.dot(moved));
            (margin.abs() > 1e-4).then_some(margin > 0.0)
        })
        .collect()
}

#[test]
fn the_reference_and_the_render_match_the_closed_form_cap() {
    let epsilon = 0.04_f32;
    for (alpha, beta) in [(0.0_f32, 0.0_f32), (0.15, -0.1)] {
        let stack = if alpha == 0.0 && beta == 0.0 {
            vec![]
        } else {
            vec![Op::Translate { alpha, beta }]
        };
        let description = expression(stack);
        let expr = prepared(&description);
        for projection in [
            Projection::Orthographic { height: 2.4 },
            Projection::Perspective {
                fov_y_degrees: 30.0,
            },
        ] {
            let truth = closed_form(
                projection,
                SIZE,
                (f64::from(alpha), f64::from(beta)),
                f64::from(epsilon),
            );
            let inside = truth.iter().filter(|t| **t == Some(true)).count();
            assert!(inside > 500, "{projection:?}: {inside} pixels");
            let sphere = AnalyticSphere::new(projection);
            let reference = sphere.coverage(&closed(&description), SIZE, 1);
            let wrong = truth
                .iter()
                .zip(&reference)
                .filter(|(t, r)| t.is_some_and(|t| t != (**r > 0.5)))
                .count();
            assert_eq!(wrong, 0, "reference, ({alpha}, {beta}), {projection:?}");
            let truth: Vec<f32> = truth
                .iter()
                .map(|t| f32::from(u8::from(*t == Some(true))))
                .collect();
            let score = metrics::iou(&rendered(&expr, &sphere), &truth).unwrap();
            assert!(
                score >= 0.99,
                "render, ({alpha}, {beta}), {projection:?}: IoU {score}"
            );
        }
    }
}
