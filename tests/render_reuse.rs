//! A frame that changes only materials, highlights, the light or outline settings reuses the
//! previous frame's mesh, visibility buffer and G-buffer (and its lines, unless their styles
//! changed), runs only the stages the change touches, and gives the bytes of a fresh
//! renderer's frame; a change of camera or settings runs every stage.

use std::sync::Arc;

use glam::Vec3;
use glint::formats::image_encoding::colour_rgba8;
use glint::geom::PatchLibrary;
use glint::highlight::{Expr, Layer, Light, Op};
use glint::job::{Overrides, RenderJob};
use glint::render::tessellate::Density;
use glint::render::{
    Antialias, Aovs, Camera, FrameMode, Outlines, PatchLook, Projection, RenderedFrame, Renderer,
    Scene, Settings, Stage, Tone,
};
use glint::shot::Preset;
use glint::toon::CelRamp;

use crate::common::{repo_file, teapot};

/// The stages whose results depend on the surfaces alone.
const SURFACE_STAGES: [Stage; 3] = [Stage::Tessellate, Stage::Rasterize, Stage::GBuffer];

fn camera(azimuth_degrees: f32) -> Camera {
    let a = azimuth_degrees.to_radians();
    let target = Vec3::new(0.0, 0.0, 1.5);
    Camera {
        eye: target + Vec3::new(8.0 * a.cos(), 8.0 * a.sin(), 4.0),
        target,
        up: Vec3::Z,
        projection: Projection::Perspective {
            fov_y_degrees: 35.0,
        },
        near: 0.1,
        far: 50.0,
    }
}

/// A highlight of width `epsilon`, moved along du by `alpha`.
fn highlight(alpha: f32, epsilon: f32) -> Expr {
    Expr::Layer(Layer::new(
        vec![
            Op::Translate { alpha, beta: 0.0 },
            Op::Scale {
                delta: 0.5,
                axis: Default::default(),
            },
        ],
        epsilon,
        [1.0, 0.9, 0.8],
    ))
}

/// The teapot under a two-tone ramp, with `expr` on every patch (if any) and outlines.
fn scene<'a>(
    library: &'a PatchLibrary,
    camera: Camera,
    expr: Option<&Expr>,
    light: Vec3,
    aovs: Aovs,
) -> Scene<'a> {
    let prepared = expr.map(|e| e.prepare().unwrap());
    Scene {
        library,
        looks: (0..library.patches.len())
            .map(|_| PatchLook {
                designed_light: None,
                lines: None,
                tone: Tone::Cel(CelRamp::two_tone(Vec3::splat(0.2), Vec3::splat(0.7), 0.0)),
                highlight: prepared.clone(),
            })
            .collect(),
        camera,
        light: Light::Directional {
            towards: light.normalize(),
        },
        outlines: Some(Outlines {
            width: 2.0,
            colour: Vec3::ZERO,
            crease_degrees: 60.0,
            patch_borders: true,
        }),
        aovs,
        materials: Vec::new(),
    }
}

fn preview(width: u32, height: u32) -> Settings {
    Settings {
        density: Density::ScreenTolerance { pixels: 1.0 },
        ..Settings::preview(width, height)
    }
}

/// The colour as written, and every AOV.
fn same_output(a: &RenderedFrame, b: &RenderedFrame) -> bool {
    colour_rgba8(&a.colour) == colour_rgba8(&b.colour) && a.colour == b.colour && a.aovs == b.aovs
}

#[test]
fn a_highlight_change_reuses_the_surfaces_and_gives_a_fresh_renderers_bytes() {
    let library = teapot();
    let all_aovs = Aovs {
        matte: true,
        patch_id: true,
        depth: true,
        normal: true,
        uv: true,
        n_dot_h: true,
        n_dot_l: true,
        outline: true,
    };
    let settings = [
        preview(96, 64),
        Settings {
            frames: FrameMode::Exact,
            antialias: Antialias::Analytic,
            ..preview(96, 64)
        },
        Settings {
            frames: FrameMode::Refined,
            ..Settings::final_quality(48, 32)
        },
    ];
    let light = Vec3::new(0.4, -0.5, 0.8);
    for settings in settings {
        for aovs in [Aovs::default(), all_aovs] {
            let what = format!("{settings:?} {aovs:?}");
            let a = scene(
                &library,
                camera(30.0),
                Some(&highlight(0.0, 0.05)),
                light,
                aovs,
            );
            let b = scene(
                &library,
                camera(30.0),
                Some(&highlight(0.2, 0.08)),
                light,
                aovs,
            );
            let mut renderer = Renderer::new(Arc::clone(&library));
            let first = renderer.render(&a, &settings).unwrap();
            let reused = renderer.render(&b, &settings).unwrap();
            let fresh = Renderer::new(Arc::clone(&library))
                .render(&b, &settings)
                .unwrap();
            for stage in SURFACE_STAGES {
                assert!(
                    first.stats.ran(stage) && !first.stats.reused(stage),
                    "{what}"
                );
                assert!(reused.stats.reused(stage), "{stage} {what}");
                assert!(!reused.stats.ran(stage), "{stage} {what}");
                assert_eq!(reused.stats[stage].pixels, 0, "{stage} {what}");
            }
            // The lines, whose styles did not change, are the previous frame's.
            assert!(reused.stats.ran(Stage::Shade) && reused.stats.reused(Stage::Outline));
            let analytic = matches!(
                settings.antialias,
                Antialias::Analytic | Antialias::Adaptive(_)
            );
            assert_eq!(reused.stats.ran(Stage::EdgeWidths), analytic, "{what}");
            // Which pixels need more samples depends on the shaded colour: chosen afresh.
            assert_eq!(
                reused.stats.ran(Stage::Supersample),
                matches!(settings.antialias, Antialias::Adaptive(_)),
                "{what}"
            );
            assert_eq!(reused.stats.triangles, fresh.stats.triangles, "{what}");
            assert_eq!(
                reused.stats.highlight_pixels, fresh.stats.highlight_pixels,
                "{what}"
            );
            assert!(
                !same_output(&first, &fresh),
                "the change shows in the frame: {what}"
            );
            assert!(same_output(&reused, &fresh), "{what}");
        }
    }
}

#[test]
fn a_camera_or_settings_change_runs_every_stage() {
    let library = teapot();
    let light = Vec3::new(0.4, -0.5, 0.8);
    let expr = highlight(0.0, 0.05);
    let mut renderer = Renderer::new(Arc::clone(&library));
    let here = scene(&library, camera(30.0), Some(&expr), light, Aovs::default());
    let moved = scene(&library, camera(31.0), Some(&expr), light, Aovs::default());
    renderer.render(&here, &preview(96, 64)).unwrap();
    let after_move = renderer.render(&moved, &preview(96, 64)).unwrap();
    let fresh = Renderer::new(Arc::clone(&library))
        .render(&moved, &preview(96, 64))
        .unwrap();
    assert!(same_output(&after_move, &fresh));
    let resized = renderer.render(&moved, &preview(96, 66)).unwrap();
    let exact = Settings {
        frames: FrameMode::Exact,
        ..preview(96, 66)
    };
    let other_frames = renderer.render(&moved, &exact).unwrap();
    for (what, frame) in [
        ("camera", &after_move),
        ("size", &resized),
        ("frame mode", &other_frames),
    ] {
        for stage in [Stage::Rasterize, Stage::GBuffer] {
            assert!(frame.stats.ran(stage), "{what}: {stage}");
            assert!(!frame.stats.reused(stage), "{what}: {stage}");
            assert!(frame.stats[stage].pixels > 0, "{what}: {stage}");
        }
        assert!(frame.stats.ran(Stage::Tessellate), "{what}");
    }
    // The same again reuses; a thread count of its own changes nothing.
    let again = renderer
        .render(
            &moved,
            &Settings {
                threads: 1,
                ..exact
            },
        )
        .unwrap();
    assert!(again.stats.reused(Stage::GBuffer));
    assert!(same_output(&again, &other_frames));
}

#[test]
fn a_light_change_on_the_tone_alone_reuses_the_visibility_buffer() {
    let library = teapot();
    let mut renderer = Renderer::new(Arc::clone(&library));
    let mut tone_only = scene(
        &library,
        camera(120.0),
        None,
        Vec3::new(0.4, -0.5, 0.8),
        Aovs::default(),
    );
    tone_only.outlines = None;
    let mut relit = tone_only.clone();
    relit.light = Light::Directional {
        towards: Vec3::new(-0.6, 0.2, 0.7).normalize(),
    };
    let settings = preview(96, 64);
    let first = renderer.render(&tone_only, &settings).unwrap();
    let second = renderer.render(&relit, &settings).unwrap();
    let fresh = Renderer::new(Arc::clone(&library))
        .render(&relit, &settings)
        .unwrap();
    assert!(!first.stats.ran(Stage::GBuffer) && !first.stats.reused(Stage::GBuffer));
    assert!(second.stats.reused(Stage::Tessellate) && second.stats.reused(Stage::Rasterize));
    assert!(
        !second.stats.reused(Stage::GBuffer),
        "the plan uses no G-buffer"
    );
    assert_eq!(
        second.stats[Stage::Shade].pixels,
        fresh.stats[Stage::Shade].pixels
    );
    assert!(!same_output(&first, &fresh), "the light shows in the frame");
    assert!(same_output(&second, &fresh));

    // Lines switched on are found on the mesh and tested against the kept depth: the
    // surfaces serve, still without a G-buffer, and the lines show.
    let mut outlined = relit.clone();
    outlined.outlines = scene(&library, camera(120.0), None, Vec3::Z, Aovs::default()).outlines;
    assert!(outlined.outlines.is_some());
    let third = renderer.render(&outlined, &settings).unwrap();
    assert!(third.stats.reused(Stage::Rasterize) && third.stats.ran(Stage::Outline));
    assert!(!third.stats.ran(Stage::GBuffer) && !third.stats.reused(Stage::GBuffer));
    assert!(third.stats[Stage::Outline].pixels > 0);
    assert!(!same_output(&third, &fresh), "the lines show in the frame");
    let fresh_outlined = Renderer::new(Arc::clone(&library))
        .render(&outlined, &settings)
        .unwrap();
    assert!(same_output(&third, &fresh_outlined));
}

/// Every shot, at two frames in a row with one job, against the second frame with a fresh
/// job: the same bytes. Shots whose camera holds still between those frames reuse surfaces
/// (the highlights, tones and lights of sphere_ops, crescent, the light orbit and X-Toon
/// shots move), and the others do not.
#[test]
fn consecutive_frames_of_every_shot_give_a_fresh_jobs_bytes() {
    let mut reusing = Vec::new();
    let mut shots: Vec<_> = std::fs::read_dir(repo_file("shots"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    shots.sort();
    for shot in &shots {
        for preset in [Preset::Preview, Preset::Final] {
            let overrides = Overrides {
                size: Some((48, 32)),
                preset: Some(preset),
                ..Overrides::default()
            };
            let mut job = RenderJob::load(shot, &overrides).unwrap();
            let (first, _) = job.shot().frames;
            job.render_frame(first as f64 + 1.0).unwrap();
            let second = job.render_frame(first as f64 + 2.0).unwrap();
            let fresh = RenderJob::load(shot, &overrides)
                .unwrap()
                .render_frame(first as f64 + 2.0)
                .unwrap();
            let name = shot.file_stem().unwrap().to_string_lossy().into_owned();
            assert!(same_output(&second, &fresh), "{name} {preset:?}");
            let (one, two) = (job.state(first as f64 + 1.0), job.state(first as f64 + 2.0));
            // The surfaces are kept while the camera holds and the model does not move.
            let surfaces_held = one.camera == two.camera && one.library == two.library;
            assert_eq!(
                second.stats.reused(Stage::Rasterize),
                surfaces_held,
                "{name} {preset:?}"
            );
            if surfaces_held {
                reusing.push(name);
            }
        }
    }
    for name in [
        "sphere_ops",
        "crescent",
        "teapot_light_orbit",
        "xtoon_plastic",
    ] {
        assert!(reusing.iter().any(|n| n == name), "{name}: {reusing:?}");
    }
}

/// Lines depend on the surfaces, the outlines and the patches' line styles alone: a frame that
/// changes only a highlight keeps the previous frame's lines, and one that restyles a patch's
/// lines draws them again over the kept surfaces — each giving a fresh renderer's bytes.
#[test]
fn lines_are_drawn_again_only_when_their_styles_change() {
    let library = teapot();
    let mut renderer = Renderer::new(Arc::clone(&library));
    let lit = Vec3::new(0.4, -0.5, 0.8);
    let first_scene = scene(
        &library,
        camera(60.0),
        Some(&highlight(0.0, 0.1)),
        lit,
        Aovs {
            outline: true,
            ..Aovs::default()
        },
    );
    let settings = preview(96, 64);
    let first = renderer.render(&first_scene, &settings).unwrap();
    assert!(first.stats.ran(Stage::Outline));

    let mut moved = scene(
        &library,
        camera(60.0),
        Some(&highlight(0.3, 0.1)),
        lit,
        first_scene.aovs,
    );
    let second = renderer.render(&moved, &settings).unwrap();
    assert!(second.stats.reused(Stage::Outline) && !second.stats.ran(Stage::Outline));
    assert!(second.stats.ran(Stage::Shade));
    let fresh = Renderer::new(Arc::clone(&library))
        .render(&moved, &settings)
        .unwrap();
    assert!(same_output(&second, &fresh));

    // One patch's lines in red: drawn again, the surfaces still kept.
    let outlines = moved.outlines.unwrap();
    moved.looks[3].lines = Some(glint::render::LineStyle {
        colour: Vec3::X,
        ..outlines.style()
    });
    let third = renderer.render(&moved, &settings).unwrap();
    assert!(third.stats.ran(Stage::Outline) && third.stats.reused(Stage::Rasterize));
    let fresh = Renderer::new(Arc::clone(&library))
        .render(&moved, &settings)
        .unwrap();
    assert!(same_output(&third, &fresh));
    assert!(
        third.aovs.outline != second.aovs.outline,
        "the restyled patch's lines show"
    );
}
