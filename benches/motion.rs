//! What a moving instance costs a frame: two teapots at 1280 × 720 with the `final` preset,
//! outlines on, a fixed camera and light, where one teapot drives and turns (translation and
//! rotation keyed), against the same shot where neither moves; side by side in turns
//! (`support/frames.rs`), each variant stepping through the shot's frames, one per render.
//!
//! In both variants the designed highlight on every patch slides (a keyed translation of its
//! stack), so that a still frame is a real frame: were nothing to change, the renderer would
//! hand back the previous frame's surfaces and lines and draw nothing new, and the ratio would
//! compare a frame with no frame. With the highlight moving, the still variant shades every
//! frame again on the surfaces it keeps (mesh, visibility buffer, G-buffer and lines), which is
//! what a frame of a shot where nothing moves costs; the moving variant must also tessellate
//! the moved teapot's patches, rasterize, fill the G-buffer and find its lines again.
//!
//! Run with `cargo bench --bench motion`; it prints each variant's frame time by stage, the
//! grids and intersection pairs the moving frames evaluated and kept, then the ratio
//! moving / still.

// Variant::render is for benchmarks that render one scene again and again.
#[allow(dead_code)]
#[path = "support/frames.rs"]
mod frames;

use std::cell::Cell;
use std::path::Path;
use std::sync::Arc;

use frames::Variant;
use glint::render::Renderer;
use glint::shot::{load_shot_text, Shot};

/// Rounds of frames measured.
const ROUNDS: usize = 12;

/// Frames of the shot.
const FRAMES: i64 = 48;

/// The shot, with the driving teapot's transform `driving`.
fn shot_text(driving: &str) -> String {
    format!(
        r#"Shot(
    resolution: (1280, 720),
    frames: (1, {FRAMES}),
    fps: 24,
    output: "motion.####.png",
    includes: ["looks/studio.ron"],
    instances: [
        (name: "still", file: "../patches/teapot.bpt", material: "porcelain",
         transform: (translate: (-2.4, 0, 0))),
        (name: "driving", file: "../patches/teapot.bpt", material: "clay",
         transform: {driving}),
    ],
    camera: (eye: (0, -14, 6), target: (0, 0, 1.2), projection: Perspective(fov_y_degrees: 34.0)),
    light: Directional(towards: (-0.35, -0.55, 0.75)),
    highlights: [
        (patches: "*", expr: Layer((
            stack: [Translate(alpha: [(1, -0.2), ({FRAMES}, 0.2)], beta: 0.0)],
            epsilon: 0.04,
            colour: (1, 1, 1),
        ))),
    ],
    render: (
        preset: Final,
        outlines: (width: 2.0, colour: (0.05, 0.04, 0.1), crease_degrees: 70.0),
    ),
)"#
    )
}

fn load(driving: &str) -> Shot {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("shots/motion_bench.ron");
    load_shot_text(&path, shot_text(driving)).unwrap()
}

fn main() {
    let moving = load(&format!(
        "(translate: [(1, (2.4, -0.5, 0)), ({FRAMES}, (2.4, 1.5, 0))], \
         degrees: [(1, 0), ({FRAMES}, 90)])"
    ));
    let still = load("(translate: (2.4, -0.5, 0))");
    // The frame each variant renders next: they step through the shot alike.
    let variant = |label: &'static str, shot: &'static Shot| {
        let mut renderer = Renderer::new(Arc::clone(&shot.library));
        let settings = shot.settings_with(None, None);
        let next = Cell::new(0i64);
        Variant::new(label, move || {
            let frame = 1 + next.get() % FRAMES;
            next.set(next.get() + 1);
            let state = shot.at(frame as f64);
            let scene = state.scene(shot).unwrap();
            Some(renderer.render(&scene, &settings).unwrap().stats)
        })
    };
    let (moving, still): (&'static Shot, &'static Shot) =
        (Box::leak(Box::new(moving)), Box::leak(Box::new(still)));
    let mut variants = [variant("moving", moving), variant("still", still)];
    let measured = frames::measure(&mut variants, ROUNDS);
    measured.print_frames(
        "two teapots, 1280 × 720, final, outlines: one drives and turns, or neither moves",
    );
    // What one moving frame made again and kept.
    let mut renderer = Renderer::new(Arc::clone(&moving.library));
    let settings = moving.settings_with(None, None);
    for frame in [1, 2] {
        let state = moving.at(frame as f64);
        let scene = state.scene(moving).unwrap();
        let s = renderer.render(&scene, &settings).unwrap().stats;
        println!(
            "moving frame {frame}: {} grids evaluated, {} kept; intersections: {} patch pairs \
             kept, {} tested",
            s.grids_evaluated, s.grids_kept, s.intersection_pairs_kept, s.intersection_pairs_tested
        );
    }
    measured.print_ratios("moving / still", &[("moving", "still")]);
}
