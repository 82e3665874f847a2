//! Designed shade runs nothing a shot without it does not: an identity shade stack renders the
//! stages and the picture of the same shot without one, and only a designed light makes a
//! tone-only frame over interpolated frames build the G-buffer (the visibility buffer holds no
//! surface frame or (u, v) for the stack to read).

use std::sync::Arc;

use glint::formats::image_encoding::colour_rgba8;
use glint::render::{RenderedFrame, Renderer, Settings, Stage, Surfaces};
use glint::shot::{load_shot_text, Shot};

use crate::common::root;

/// The teapot with a two-colour ramp (band edge at 0.3), a highlight, outlines and the
/// `preset`, with `shade` as its shade list (`None`: no `shade` field at all), and a light
/// that moves over the three frames.
fn shot_text(preset: &str, highlights: bool, outlines: bool, shade: Option<&str>) -> String {
    let highlights = if highlights {
        r#"(patches: "teapot/*", expr: Layer((
            stack: [Translate(alpha: 0.1, beta: 0.05), Scale(delta: 0.5, axis: U)],
            epsilon: 0.06,
            colour: (1.0, 0.97, 0.9),
        ))),"#
    } else {
        ""
    };
    let outlines = if outlines {
        "outlines: (width: 2.0, colour: (0.05, 0.05, 0.12)),"
    } else {
        ""
    };
    let shade = shade.map_or(String::new(), |list| format!("shade: [{list}],"));
    format!(
        r#"Shot(
    resolution: (320, 180),
    frames: (1, 3),
    fps: 24,
    output: "out/plan.####.png",
    instances: [(name: "teapot", file: "../patches/teapot.bpt", material: "glaze")],
    materials: {{
        "glaze": Cel(base: (0.12, 0.16, 0.34), bands: [(0.3, (0.40, 0.55, 0.90))]),
    }},
    camera: (eye: (5.5, -7.0, 4.5), target: (0.0, 0.0, 1.4),
             projection: Perspective(fov_y_degrees: 32.0)),
    light: Directional(towards: [(1, (-0.7, -0.3, 0.65)), (3, (0.3, -0.7, 0.65))]),
    highlights: [{highlights}],
    {shade}
    render: (preset: {preset}, {outlines}),
)"#
    )
}

fn load(text: String) -> Shot {
    let path = root().join("shots/shade_plan.ron");
    load_shot_text(&path, text).unwrap()
}

/// Frame `frame` of `shot` rendered with its own settings by a fresh renderer.
fn render(shot: &Shot, frame: f64) -> RenderedFrame {
    let state = shot.at(frame);
    let scene = state.scene(shot).unwrap();
    Renderer::new(Arc::clone(&shot.library))
        .render(&scene, &shot.settings_with(None, None))
        .unwrap()
}

/// The identity shade stack on every patch: `L' = normalize(L + 0 du + 0 dv) = L`.
const IDENTITY: &str = r#"(patches: "teapot/*", stack: [Translate(alpha: 0.0, beta: 0.0)])"#;

#[test]
fn an_identity_shade_stack_renders_the_stages_and_bytes_of_no_shade() {
    let without = load(shot_text("Final", true, true, None));
    let with = load(shot_text("Final", true, true, Some(IDENTITY)));
    for frame in [1.0, 2.0] {
        let (a, b) = (render(&without, frame), render(&with, frame));
        assert_eq!(a.stats.plan, b.stats.plan, "frame {frame}: the same plan");
        for stage in Stage::ALL {
            assert_eq!(
                a.stats[stage].pixels, b.stats[stage].pixels,
                "frame {frame}: {stage} processed as many pixels"
            );
        }
        assert_eq!(
            a.stats.exact_frames, b.stats.exact_frames,
            "frame {frame}: as many exact frames"
        );
        assert!(
            a.colour.iter().any(|c| c.w > 0.0),
            "frame {frame}: a teapot"
        );
        // The written bytes are the same. The linear colours may not be to the bit: the
        // identity stack normalizes L's frame coordinates once more, which can move `N·L'` by
        // an ulp, and a pixel the band edge crosses takes its colour from `N·L'` continuously.
        let largest = a
            .colour
            .iter()
            .zip(&b.colour)
            .map(|(x, y)| (*x - *y).abs().max_element())
            .fold(0.0_f32, f32::max);
        assert!(largest < 1e-5, "frame {frame}: colours differ by {largest}");
        let (bytes_a, bytes_b) = (colour_rgba8(&a.colour), colour_rgba8(&b.colour));
        let bytes_differing = bytes_a.iter().zip(&bytes_b).filter(|(x, y)| x != y).count();
        assert_eq!(bytes_differing, 0, "frame {frame}: the same bytes");
    }
}

#[test]
fn only_designed_light_makes_a_tone_only_interpolated_frame_build_the_g_buffer() {
    // Preview: interpolated frames, no anti-aliasing; no highlight, no outline, no AOV.
    let without = load(shot_text("Preview", false, false, None));
    let with = load(shot_text("Preview", false, false, Some(IDENTITY)));
    let settings = without.settings_with(None, None);
    assert_eq!(settings, Settings::preview(320, 180));
    assert_eq!(with.settings_with(None, None), settings);
    let (a, b) = (render(&without, 1.0), render(&with, 1.0));
    assert_eq!(a.stats.plan.surfaces, Surfaces::Visibility);
    assert!(!a.stats.plan.runs(Stage::GBuffer));
    assert_eq!(a.stats[Stage::GBuffer].pixels, 0, "no G-buffer filled");
    assert_eq!(b.stats.plan.surfaces, Surfaces::Texels);
    assert!(b.stats.plan.runs(Stage::GBuffer));
    assert!(b.stats[Stage::GBuffer].pixels > 0, "the G-buffer filled");
    // Nothing else is added: the same stages but the G-buffer.
    for stage in Stage::ALL {
        if stage != Stage::GBuffer {
            assert_eq!(
                a.stats.plan.runs(stage),
                b.stats.plan.runs(stage),
                "{stage}"
            );
        }
    }
}
