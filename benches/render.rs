//! The teapot at 1280×720 with a 5-op highlight stack on every patch, outlines on and exact
//! frames, against variants measured side by side in the same run, frame by frame in turn:
//! highlights off, lines off, hidden lines on (behind two surfaces, dashed), interpolated frames,
//! one thread, and two effect-free shots against a flat-colour raster of the same mesh. Run with `cargo bench --bench render`; it prints each
//! variant's frame time by stage, then the ratios.
//!
//! Frames, not edits. Every variant but `edit_full` turns the camera by a degree between
//! frames, as a shot does, so that every frame finds its surfaces (rasterized, its G-buffer
//! filled) and lines again: each ratio compares what frames of a shot cost. The flat raster
//! turns with them. `edit_full` repeats one view, as an animator's edit of a highlight does:
//! the renderer keeps the surfaces and lines and runs only the stages the edit touches, so it is
//! compared with the frame (`edit_full / moving`), never with the raster.
//!
//! The effect-free comparison. The effect-free shot has cel tone only — no highlight, no
//! outline, no AOV — and is rendered with interpolated frames, the preview setting: an exact
//! frame per pixel is an accuracy choice a flat raster does not make, and with exact frames the
//! shot would (rightly) evaluate them. Its plan then shades straight from the visibility buffer:
//! the ramp's colour once per triangle that lies in one band, and on the others, per covered
//! pixel, the vertex normal interpolated there, `N·L` and the ramp. The flat raster
//! is the least any renderer of that mesh does per frame, written the way the renderer's own
//! stages are: the same cached mesh, its vertices transformed to clip space, rasterized at the
//! same size in the same thread pool by a rasterizer that keeps its memory between frames, and
//! one flat colour per covered pixel written in parallel into a new image. What the ratio
//! leaves to the effect-free shot is the tone itself and the renderer's bookkeeping.
//!
//! The second effect-free shot, `flat_colours`, gives every patch a ramp of one colour (the
//! flat fill of ink and paint) — the flat raster's own picture, made by the renderer. No tone
//! depends on `N·L` there, so what its ratio leaves is the renderer's bookkeeping alone.

#[path = "support/frames.rs"]
mod frames;
#[path = "support/teapot.rs"]
mod teapot;

use frames::Variant;
use teapot::{camera, HEIGHT, WIDTH};

use std::hint::black_box;
use std::sync::Arc;

use glam::{Vec3, Vec4};
use glint::formats::load_patches;
use glint::geom::PatchLibrary;
use glint::highlight::{Expr, Layer, Light};
use glint::render::raster::{RasterOptions, Rasterizer, Viewport, VisibilityBuffer};
use glint::render::tessellate::{Density, Tessellator};
use glint::render::{
    Aovs, Dash, FrameMode, HiddenLines, LineStyle, Outlines, PatchLook, Scene, Settings, Tone,
};
use glint::toon::CelRamp;
use rayon::prelude::*;

const DENSITY: Density = Density::PerSpan { u: 12, v: 12 };

fn scene<'a>(
    library: &'a PatchLibrary,
    tone: &CelRamp,
    highlights: bool,
    outlines: bool,
) -> Scene<'a> {
    let stack = teapot::five_op_stack();
    let expr = Expr::Layer(Layer::new(stack, 0.08, [1.0, 1.0, 1.0]))
        .prepare()
        .unwrap();
    Scene {
        library,
        looks: (0..library.patches.len())
            .map(|_| PatchLook {
                designed_light: None,
                lines: None,
                tone: Tone::Cel(tone.clone()),
                highlight: highlights.then(|| expr.clone()),
            })
            .collect(),
        camera: camera(),
        light: Light::Directional {
            towards: Vec3::new(0.3, -0.6, 0.75).normalize(),
        },
        outlines: outlines.then_some(Outlines {
            width: 2.0,
            colour: Vec3::ZERO,
            crease_degrees: 60.0,
            patch_borders: false,
        }),
        aovs: Aovs::default(),
        materials: Vec::new(),
    }
}

/// A variant whose frames alternate between two views: no frame finds the previous one's
/// surfaces.
fn moving<'a>(
    name: &'static str,
    library: &Arc<PatchLibrary>,
    view: &'a Scene<'a>,
    turned: &'a Scene<'a>,
    settings: &'a Settings,
) -> Variant<'a> {
    let mut renderer = glint::render::Renderer::new(Arc::clone(library));
    let mut turn = 0usize;
    Variant::new(name, move || {
        turn += 1;
        let scene = if turn % 2 == 0 { view } else { turned };
        Some(renderer.render(scene, settings).unwrap().stats)
    })
}

/// `scene` with the camera turned about the vertical axis by a degree.
fn turned<'a>(scene: &Scene<'a>) -> Scene<'a> {
    let mut camera = scene.camera;
    camera.eye = glam::Quat::from_rotation_z(1f32.to_radians()) * camera.eye;
    Scene {
        camera,
        ..scene.clone()
    }
}

/// Rounds of frames measured.
const ROUNDS: usize = 100;

fn main() {
    let library = Arc::new(load_patches(std::path::Path::new("patches/teapot.bpt")).unwrap());
    let two_tone = CelRamp::two_tone(Vec3::new(0.2, 0.25, 0.5), Vec3::new(0.4, 0.55, 0.9), 0.1);
    let full = scene(&library, &two_tone, true, true);
    // Every patch's lines also drawn behind up to two surfaces, thinner, in red, dashed.
    let hidden_style = LineStyle {
        hidden: Some(HiddenLines {
            levels: 2,
            width: 1.0,
            colour: Vec3::X,
            dash: Dash::try_new(&[5.0, 3.0]).unwrap(),
        }),
        ..full.outlines.unwrap().style()
    };
    let hidden = Scene {
        looks: full
            .looks
            .iter()
            .map(|look| PatchLook {
                lines: Some(hidden_style),
                ..look.clone()
            })
            .collect(),
        ..full.clone()
    };
    let plain = scene(&library, &two_tone, false, true);
    let unlined = scene(&library, &two_tone, true, false);
    let effect_free = scene(&library, &two_tone, false, false);
    let one_colour = CelRamp {
        base: Vec3::new(0.4, 0.55, 0.9),
        bands: Vec::new(),
    };
    let flat_colours = scene(&library, &one_colour, false, false);
    let settings = |frames, threads| Settings {
        density: DENSITY,
        frames,
        threads,
        ..Settings::preview(WIDTH, HEIGHT)
    };
    let exact = settings(FrameMode::Exact, 0);
    let interpolated = settings(FrameMode::Interpolated, 0);
    let one_thread = settings(FrameMode::Exact, 1);

    // The baseline: the same mesh rasterized and filled with one flat colour, from the two
    // views the moving variants alternate between.
    let mut tessellator = Tessellator::new(Arc::clone(&library));
    let aspect = WIDTH as f32 / HEIGHT as f32;
    let view_projections = [
        full.camera.view_projection(aspect),
        turned(&full).camera.view_projection(aspect),
    ];
    let (mesh, _) = tessellator.mesh(DENSITY, view_projections[0], WIDTH, HEIGHT);
    let (mut rasterizer, mut visibility) = (Rasterizer::new(), VisibilityBuffer::default());
    let mut clip = Vec::new();
    let flat = Vec4::new(0.4, 0.55, 0.9, 1.0);
    let mut turn = 0usize;
    let flat_raster = move || {
        turn += 1;
        let view_projection = view_projections[turn % 2];
        mesh.positions
            .par_iter()
            .map(|p| view_projection * p.extend(1.0))
            .collect_into_vec(&mut clip);
        let viewport = Viewport {
            width: WIDTH,
            height: HEIGHT,
        };
        let options = RasterOptions::default();
        rasterizer.rasterize_into(viewport, &clip, &mesh.triangles, &options, &mut visibility);
        let colour: Vec<Vec4> = visibility
            .triangle
            .par_iter()
            .map(|&t| if t == u32::MAX { Vec4::ZERO } else { flat })
            .collect();
        black_box(colour);
        None
    };

    let turned_scenes = [
        &full,
        &plain,
        &unlined,
        &effect_free,
        &flat_colours,
        &hidden,
    ]
    .map(turned);
    let [full_turned, plain_turned, unlined_turned, effect_free_turned, flat_colours_turned, hidden_turned] =
        &turned_scenes;
    let mut variants = [
        moving("moving", &library, &full, full_turned, &exact),
        moving(
            "moving_no_highlights",
            &library,
            &plain,
            plain_turned,
            &exact,
        ),
        moving(
            "moving_no_lines",
            &library,
            &unlined,
            unlined_turned,
            &exact,
        ),
        moving(
            "moving_hidden_lines",
            &library,
            &hidden,
            hidden_turned,
            &exact,
        ),
        moving(
            "moving_interpolated",
            &library,
            &full,
            full_turned,
            &interpolated,
        ),
        moving(
            "moving_one_thread",
            &library,
            &full,
            full_turned,
            &one_thread,
        ),
        moving(
            "effect_free",
            &library,
            &effect_free,
            effect_free_turned,
            &interpolated,
        ),
        moving(
            "flat_colours",
            &library,
            &flat_colours,
            flat_colours_turned,
            &interpolated,
        ),
        Variant::new("flat_raster", flat_raster),
        Variant::render("edit_full", &library, &full, &exact),
    ];
    let measured = frames::measure(&mut variants, ROUNDS);
    measured.print_frames("teapot, 1280×720: frame time by stage");
    measured.print_ratios(
        "frame-time ratios",
        &[
            ("moving", "flat_raster"),
            ("moving_interpolated", "flat_raster"),
            ("moving", "moving_no_highlights"),
            ("moving", "moving_no_lines"),
            ("moving_hidden_lines", "moving"),
            ("moving", "moving_interpolated"),
            ("moving_one_thread", "moving"),
            ("effect_free", "flat_raster"),
            ("flat_colours", "flat_raster"),
            ("edit_full", "moving"),
        ],
    );
}
