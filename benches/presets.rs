//! What `final` costs against `preview`, side by side in one run: the teapot at 1280×720 (a
//! 5-op highlight stack on every patch, outlines on, and `final` without them) under a camera that orbits half a degree
//! a frame, and the analytic sphere at 1024×1024 cycling through the hard views of the
//! accuracy ladder, each with `preview`, `final` and refined frames with analytic edges (one
//! sample a pixel). Every frame is a new view (the sphere's eye turns by a hundredth of a degree
//! from one frame to the next), so the surfaces are built afresh as in a moving shot. Run with `cargo bench --bench presets`; it prints each variant's frame time by stage,
//! then the ratios.

// Shared with the other frame benchmarks; this one builds its variants itself.
#[allow(dead_code)]
#[path = "support/frames.rs"]
mod frames;
#[path = "support/teapot.rs"]
mod teapot;

use std::sync::Arc;

use frames::Variant;
use glam::{Mat3, Vec3};
use glint::accuracy::case::Case;
use glint::accuracy::AnalyticSphere;
use glint::formats::load_patches;
use glint::geom::PatchLibrary;
use glint::highlight::{Expr, Layer, Light, PreparedExpr};
use glint::render::tessellate::Density;
use glint::render::{
    Antialias, Aovs, FrameMode, Outlines, PatchLook, Renderer, Scene, Settings, Tone,
};
use glint::toon::CelRamp;

/// Rounds of frames measured.
const ROUNDS: usize = 12;

/// The teapot's highlight: the stack the render benchmark uses.
fn teapot_highlight() -> PreparedExpr {
    Expr::Layer(Layer::new(teapot::five_op_stack(), 0.08, [1.0, 1.0, 1.0]))
        .prepare()
        .unwrap()
}

fn teapot_scene<'a>(library: &'a PatchLibrary, highlight: &PreparedExpr, lines: bool) -> Scene<'a> {
    let tone = CelRamp::two_tone(Vec3::new(0.2, 0.25, 0.5), Vec3::new(0.4, 0.55, 0.9), 0.1);
    Scene {
        library,
        looks: (0..library.patches.len())
            .map(|_| PatchLook {
                designed_light: None,
                lines: None,
                tone: Tone::Cel(tone.clone()),
                highlight: Some(highlight.clone()),
            })
            .collect(),
        camera: teapot::camera(),
        light: Light::Directional {
            towards: Vec3::new(0.3, -0.6, 0.75).normalize(),
        },
        outlines: lines.then_some(Outlines {
            width: 2.0,
            colour: Vec3::ZERO,
            crease_degrees: 60.0,
            patch_borders: false,
        }),
        aovs: Aovs::default(),
        materials: Vec::new(),
    }
}

/// Refined frames with analytic edges at one sample a pixel, 0.5 px tessellation.
fn refined_analytic(width: u32, height: u32) -> Settings {
    Settings {
        density: Density::ScreenTolerance { pixels: 0.5 },
        frames: FrameMode::Refined,
        antialias: Antialias::Analytic,
        ..Settings::preview(width, height)
    }
}

/// The teapot rendered with `settings`, the camera turning half a degree about the vertical
/// axis each frame.
fn teapot_variant<'a>(
    name: &'static str,
    library: &'a Arc<PatchLibrary>,
    highlight: &'a PreparedExpr,
    settings: Settings,
    lines: bool,
) -> Variant<'a> {
    let mut renderer = Renderer::new(Arc::clone(library));
    let mut scene = teapot_scene(library, highlight, lines);
    let start = teapot::camera();
    let mut frame = 0u32;
    Variant::new(name, move || {
        let turn = Mat3::from_rotation_z((0.5 * frame as f32).to_radians());
        scene.camera.eye = turn * start.eye;
        frame += 1;
        Some(renderer.render(&scene, &settings).unwrap().stats)
    })
}

/// The sphere rendered with `settings`, one hard view of the ladder after another.
fn sphere_variant<'a>(
    name: &'static str,
    library: &'a Arc<PatchLibrary>,
    views: &'a [(AnalyticSphere, PreparedExpr)],
    settings: Settings,
) -> Variant<'a> {
    let mut renderer = Renderer::new(Arc::clone(library));
    let mut frame = 0usize;
    Variant::new(name, move || {
        let (sphere, highlight) = &views[frame % views.len()];
        let mut scene = sphere.scene(library, highlight, Aovs::default());
        // Views that share a pose would share surfaces: a hundredth of a degree apart, each
        // frame builds its own, as in a moving shot.
        let turn = Mat3::from_rotation_z((0.01 * (frame % 2 + 1) as f32).to_radians());
        scene.camera.eye = turn * scene.camera.eye;
        frame += 1;
        Some(renderer.render(&scene, &settings).unwrap().stats)
    })
}

fn main() {
    let teapot = Arc::new(load_patches(std::path::Path::new("patches/teapot.bpt")).unwrap());
    let highlight = teapot_highlight();
    let (w, h) = (teapot::WIDTH, teapot::HEIGHT);
    let mut variants = [
        teapot_variant(
            "preview",
            &teapot,
            &highlight,
            Settings::preview(w, h),
            true,
        ),
        teapot_variant(
            "final",
            &teapot,
            &highlight,
            Settings::final_quality(w, h),
            true,
        ),
        teapot_variant(
            "refined_analytic",
            &teapot,
            &highlight,
            refined_analytic(w, h),
            true,
        ),
        teapot_variant(
            "final_no_lines",
            &teapot,
            &highlight,
            Settings::final_quality(w, h),
            false,
        ),
    ];
    let measured = frames::measure(&mut variants, ROUNDS);
    measured.print_frames("teapot, 1280×720, orbiting: frame time by stage");
    let pairs = [
        ("final", "preview"),
        ("refined_analytic", "preview"),
        ("final", "refined_analytic"),
    ];
    let mut teapot_pairs = pairs.to_vec();
    teapot_pairs.push(("final", "final_no_lines"));
    measured.print_ratios("teapot frame-time ratios", &teapot_pairs);

    let sphere = AnalyticSphere::library();
    let views: Vec<(AnalyticSphere, PreparedExpr)> = Case::hard()
        .into_iter()
        .map(|case| (case.pose.sphere(), case.stack.expression()))
        .collect();
    let size = 1024;
    let mut variants = [
        sphere_variant("preview", &sphere, &views, Settings::preview(size, size)),
        sphere_variant(
            "final",
            &sphere,
            &views,
            Settings::final_quality(size, size),
        ),
        sphere_variant(
            "refined_analytic",
            &sphere,
            &views,
            refined_analytic(size, size),
        ),
    ];
    let measured = frames::measure(&mut variants, ROUNDS * views.len());
    measured.print_frames("sphere, 1024×1024, the hard views in turn: frame time by stage");
    measured.print_ratios("sphere frame-time ratios", &pairs);
}
