//! What a drawn outline costs a frame: the teapot at 1280×720 under the `final` preset, with
//! outlines and the 5-op highlight stack on every patch, its layer testing H' against a
//! 12-point outline (a six-pointed star), against the same shot with the ε-disc; side by side
//! in turns (`support/frames.rs`).
//!
//! Both variants' frames alternate between two views a degree apart, so that every frame finds
//! its surfaces and lines again and shades every pixel anew, as a frame of a shot does: a view
//! repeated would hand back what the frame before it made. Then a third pair, the outline
//! keyed to morph into a turned star, read halfway between its keys (three polygons a point)
//! against the disc: what a frame between keys pays.
//!
//! Run with `cargo bench --bench outline`; it prints each variant's frame time by stage, then
//! the ratios outline / disc and morph / disc.

// Variant::render is for benchmarks that render one scene again and again.
#[allow(dead_code)]
#[path = "support/frames.rs"]
mod frames;
#[path = "support/teapot.rs"]
mod teapot;

use std::f32::consts::{PI, TAU};
use std::sync::Arc;

use frames::Variant;
use teapot::{camera, HEIGHT, WIDTH};

use glam::Vec3;
use glint::anim::Track;
use glint::formats::load_patches;
use glint::geom::PatchLibrary;
use glint::highlight::{Expr, Layer, Light, Outline, Segment, Shape};
use glint::render::{Aovs, Outlines, PatchLook, Renderer, Scene, Settings, Tone};
use glint::toon::CelRamp;

/// Rounds of frames measured.
const ROUNDS: usize = 24;

/// The ε of the disc: its circle in t' has radius `√(1 − (1 − ε)²)` = 0.39.
const EPSILON: f32 = 0.08;

/// A six-pointed star of 12 corners, tips at 0.44 and notches at 0.3, turned by `turn` radians:
/// about the disc's area.
fn star(turn: f32) -> Vec<[f32; 2]> {
    (0..12)
        .map(|k| {
            let a = turn + TAU * k as f32 / 12.0 + PI / 2.0;
            let r = if k % 2 == 0 { 0.44 } else { 0.3 };
            [r * a.cos(), r * a.sin()]
        })
        .collect()
}

fn outline(points: &[[f32; 2]]) -> Outline {
    Outline {
        segments: points.iter().map(|&p| Segment::Corner(p)).collect(),
    }
}

/// The layer on every patch, with `shape`.
fn scene<'a>(library: &'a PatchLibrary, shape: Shape, turned: bool) -> Scene<'a> {
    let layer = Layer {
        shape,
        ..Layer::new(teapot::five_op_stack(), EPSILON, [1.0, 1.0, 1.0])
    };
    let expr = Expr::Layer(layer).prepare().unwrap();
    let tone = CelRamp::two_tone(Vec3::new(0.2, 0.25, 0.5), Vec3::new(0.4, 0.55, 0.9), 0.1);
    let mut camera = camera();
    if turned {
        camera.eye = glam::Quat::from_rotation_z(1f32.to_radians()) * camera.eye;
    }
    Scene {
        library,
        looks: (0..library.patches.len())
            .map(|_| PatchLook {
                designed_light: None,
                lines: None,
                tone: Tone::Cel(tone.clone()),
                highlight: Some(expr.clone()),
            })
            .collect(),
        camera,
        light: Light::Directional {
            towards: Vec3::new(0.3, -0.6, 0.75).normalize(),
        },
        outlines: Some(Outlines {
            width: 2.0,
            colour: Vec3::ZERO,
            crease_degrees: 60.0,
            patch_borders: false,
        }),
        aovs: Aovs::default(),
        materials: Vec::new(),
    }
}

/// A variant whose frames alternate between the two views of `views`.
fn moving<'a>(
    name: &'static str,
    library: &Arc<PatchLibrary>,
    views: &'a [Scene<'a>; 2],
    settings: &'a Settings,
) -> Variant<'a> {
    let mut renderer = Renderer::new(Arc::clone(library));
    let mut turn = 0usize;
    Variant::new(name, move || {
        turn += 1;
        Some(renderer.render(&views[turn % 2], settings).unwrap().stats)
    })
}

fn main() {
    let library = Arc::new(load_patches(std::path::Path::new("patches/teapot.bpt")).unwrap());
    let settings = Settings::final_quality(WIDTH, HEIGHT);
    let drawn = Shape::Outline(outline(&star(0.0)));
    // The star keyed to turn by a twelfth of a turn from frame 1 to frame 3, read at frame 2.
    let key = |turn: f32| {
        let points: Vec<String> = star(turn)
            .iter()
            .map(|[x, y]| format!("({x}, {y})"))
            .collect();
        format!("[{}]", points.join(", "))
    };
    let keyed: Shape<Track<f32>> = ron::from_str(&format!(
        "OutlineKeys([(1, {}), (3, {})])",
        key(0.0),
        key(TAU / 12.0)
    ))
    .unwrap();
    let morph = keyed.map(|t| t.at(2.0));
    assert!(matches!(morph, Shape::Morph(_)), "{morph:?}");
    let views = |shape: &Shape| [false, true].map(|t| scene(&library, shape.clone(), t));
    let (disc, outline, between) = (views(&Shape::Disc), views(&drawn), views(&morph));
    let mut variants = [
        moving("disc", &library, &disc, &settings),
        moving("outline", &library, &outline, &settings),
        moving("morph", &library, &between, &settings),
    ];
    let measured = frames::measure(&mut variants, ROUNDS);
    measured.print_frames(
        "teapot, 1280×720, final, outlines, 5-op stack on every patch: the ε-disc, a 12-point \
         outline, and that outline halfway through a morph",
    );
    measured.print_ratios(
        "frame-time ratios",
        &[("outline", "disc"), ("morph", "disc"), ("morph", "outline")],
    );
}
