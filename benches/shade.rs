//! What designed shade costs a frame: the teapot at 1280×720 with the `final` preset, the 5-op
//! highlight stack of `benches/render.rs` on every patch and outlines on, with a 3-operation
//! shade stack (translate, scale along u, square) on every patch against the same scene
//! without it; side by side in turns (`support/frames.rs`).
//!
//! The camera turns about the vertical axis by a quarter degree at every frame of either
//! variant, both from the same start, so that no frame finds the previous one's surfaces and
//! every stage runs: tessellation, rasterization, G-buffer, edge widths, shading, lines and the
//! adaptive supersampling. Both variants' n-th frames show the same view.
//!
//! The cel ramp's band edge sits at `N·L = 0.3`, above 0, where the shade stack moves it (an
//! edge at 0 cannot move: every operation keeps the sign of `N·L`).
//!
//! Run with `cargo bench --bench shade`; it prints each variant's frame time by stage, then the
//! ratio shade / no shade with its quartiles.

// Variant::render is for benchmarks that render one scene again and again.
#[allow(dead_code)]
#[path = "support/frames.rs"]
mod frames;
#[path = "support/teapot.rs"]
mod teapot;

use std::sync::Arc;

use frames::Variant;
use glam::{Quat, Vec3};
use glint::formats::load_patches;
use glint::geom::PatchLibrary;
use glint::highlight::{Axis, DesignedLight, Expr, Layer, Light, Op, ShadeStack, SquareStyle};
use glint::render::{Aovs, Outlines, PatchLook, Renderer, Scene, Settings, Tone};
use glint::toon::CelRamp;
use teapot::{camera, HEIGHT, WIDTH};

/// Rounds of frames measured.
const ROUNDS: usize = 20;

/// How far the camera turns between one frame and the next, in degrees.
const TURN_DEGREES: f32 = 0.25;

/// The shade stack on every patch: translate, scale along u, square.
fn shade_stack() -> ShadeStack {
    ShadeStack {
        stack: vec![
            Op::Translate {
                alpha: 0.25,
                beta: 0.1,
            },
            Op::Scale {
                delta: 0.5,
                axis: Axis::U,
            },
            Op::Square {
                sigma: 0.3,
                n: 2.0,
                style: SquareStyle::Tangent,
            },
        ],
        mask: None,
    }
}

/// The teapot with highlights and outlines as in `benches/render.rs`, and `shade` on every
/// patch's tone.
fn scene<'a>(library: &'a PatchLibrary, shade: Option<&DesignedLight>) -> Scene<'a> {
    let tone = CelRamp::two_tone(Vec3::new(0.2, 0.25, 0.5), Vec3::new(0.4, 0.55, 0.9), 0.3);
    let expr = Expr::Layer(Layer::new(teapot::five_op_stack(), 0.08, [1.0, 1.0, 1.0]))
        .prepare()
        .unwrap();
    Scene {
        library,
        looks: (0..library.patches.len())
            .map(|_| PatchLook {
                designed_light: shade.cloned(),
                lines: None,
                tone: Tone::Cel(tone.clone()),
                highlight: Some(expr.clone()),
            })
            .collect(),
        camera: camera(),
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

/// A variant rendering `scene` with the camera turned by [`TURN_DEGREES`] more at each frame.
fn turning<'a>(
    name: &'static str,
    library: &Arc<PatchLibrary>,
    scene: &'a Scene<'a>,
    settings: &'a Settings,
) -> Variant<'a> {
    let mut renderer = Renderer::new(Arc::clone(library));
    let mut frame = 0u32;
    Variant::new(name, move || {
        frame += 1;
        let mut camera = scene.camera;
        let turn = Quat::from_rotation_z((frame as f32 * TURN_DEGREES).to_radians());
        camera.eye = turn * camera.eye;
        let turned = Scene {
            camera,
            ..scene.clone()
        };
        Some(renderer.render(&turned, settings).unwrap().stats)
    })
}

fn main() {
    let library = Arc::new(load_patches(std::path::Path::new("patches/teapot.bpt")).unwrap());
    let designed = DesignedLight::new(vec![shade_stack().prepare().unwrap()]);
    let shaded = scene(&library, Some(&designed));
    let plain = scene(&library, None);
    let settings = Settings::final_quality(WIDTH, HEIGHT);
    let mut variants = [
        turning("shade", &library, &shaded, &settings),
        turning("no_shade", &library, &plain, &settings),
    ];
    let measured = frames::measure(&mut variants, ROUNDS);
    measured.print_frames(
        "teapot, 1280×720, final, highlights and outlines, the camera turning: frame time by \
         stage with a 3-op shade stack on every patch, and without",
    );
    measured.print_ratios("frame-time ratio", &[("shade", "no_shade")]);
}
