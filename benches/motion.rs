//! What a moving instance costs a frame: two teapots at 1280 × 720 with the `final` preset,
//! outlines on, a fixed camera and light, where one teapot drives and turns (translation and
//! rotation keyed), against a frame of the same picture where nothing moved since the frame
//! before; side by side in turns (`support/frames.rs`).
//!
//! A turn renders two frames and times the second, and both variants' timed frames are the
//! same picture, frame `f` of the moving shot, stepping through `f = 2 ..= 48`:
//! - moving: frame `f − 1`, then frame `f` (the driving teapot moved between them);
//! - still: frame `f`'s poses with frame `f − 1`'s highlights, then frame `f` (the model stayed,
//!   only the highlights' parameter changed).
//!
//! So the ratio compares like with like: were the still variant a shot where neither teapot
//! moves, its driving teapot would sit at one place (the nearest the camera, so the largest)
//! in every frame, and the stages that scale with what is on screen (edge widths,
//! supersampling) would cost it more than the moving variant's average frame, flattering the
//! ratio. The first frame of the still pair keeps frame `f`'s model (`FrameState::library`)
//! and takes the rest of frame `f − 1`'s state; of that state only the highlights differ here
//! (the shot has no pinned layers and no `Along` layer frames, the two parts of a frame's state
//! that also follow the model, and its camera, light and materials do not move).
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
//! grids, triangles, texels, intersection pairs and silhouettes the first moving frames made
//! again and kept, then the ratio moving / still, and what making each moving frame's SVG
//! (`glint render --svg`) costs beside the frame.

// Variant::render is for benchmarks that render one scene again and again.
#[allow(dead_code)]
#[path = "support/frames.rs"]
mod frames;

use std::cell::Cell;
use std::path::Path;
use std::sync::Arc;

use frames::Variant;
use glint::formats::svg::svg_document;
use glint::render::Renderer;
use glint::shot::{load_shot_text, Shot};

/// Rounds of frames measured.
const ROUNDS: usize = FRAMES as usize - 1;

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
    let shot = load(&format!(
        "(translate: [(1, (2.4, -0.5, 0)), ({FRAMES}, (2.4, 1.5, 0))], \
         degrees: [(1, 0), ({FRAMES}, 90)])"
    ));
    let shot: &'static Shot = Box::leak(Box::new(shot));
    // Each variant's calls alternate: the untimed first frame of a turn, then the timed frame
    // `f`, which steps through 2 ..= FRAMES.
    let variant = |label: &'static str, moved: bool| {
        let mut renderer = Renderer::new(Arc::clone(&shot.library));
        let settings = shot.settings_with(None, None);
        let calls = Cell::new(0i64);
        Variant::new(label, move || {
            let call = calls.get();
            calls.set(call + 1);
            let frame = 2 + (call / 2) % (FRAMES - 1);
            let state = shot.at(frame as f64);
            let state = match (call % 2 == 0, moved) {
                (false, _) => state,
                (true, true) => shot.at((frame - 1) as f64),
                (true, false) => {
                    let mut before = shot.at((frame - 1) as f64);
                    before.library = Arc::clone(&state.library);
                    before
                }
            };
            let scene = state.scene(shot).unwrap();
            Some(renderer.render(&scene, &settings).unwrap().stats)
        })
    };
    let mut variants = [variant("moving", true), variant("still", false)];
    let measured = frames::measure(&mut variants, ROUNDS);
    measured.print_frames(
        "two teapots, 1280 × 720, final, outlines: one drove and turned since the frame before, \
         or neither moved",
    );
    // What one moving frame made again and kept.
    let mut renderer = Renderer::new(Arc::clone(&shot.library));
    let settings = shot.settings_with(None, None);
    for frame in [1, 2, 3] {
        let state = shot.at(frame as f64);
        let scene = state.scene(shot).unwrap();
        let s = renderer.render(&scene, &settings).unwrap().stats;
        println!(
            "moving frame {frame}: {} grids evaluated, {} kept; {} of {} triangles rasterized; \
             {} G-buffer texels kept; intersections: {} patch pairs kept, {} tested; \
             silhouettes of {} patches kept",
            s.grids_evaluated,
            s.grids_kept,
            s.triangles_rasterized,
            s.triangles,
            s.texels_kept,
            s.intersection_pairs_kept,
            s.intersection_pairs_tested,
            s.silhouettes_kept
        );
    }
    measured.print_ratios("moving / still", &[("moving", "still")]);
    // What writing a moving frame's lines as SVG costs beside the frame: the document made
    // from the frame's strokes (`--svg`), frame by frame through the shot.
    let mut renderer = Renderer::new(Arc::clone(&shot.library));
    let mut ratios = Vec::new();
    for frame in 1..=FRAMES {
        let state = shot.at(frame as f64);
        let scene = state.scene(shot).unwrap();
        let start = std::time::Instant::now();
        let image = renderer.render(&scene, &settings).unwrap();
        let frame_seconds = start.elapsed().as_secs_f64();
        let start = std::time::Instant::now();
        let svg = svg_document(image.lines.as_deref().unwrap(), &[]);
        let svg_seconds = start.elapsed().as_secs_f64();
        std::hint::black_box(svg);
        if frame > 1 {
            ratios.push(svg_seconds / frame_seconds);
        }
    }
    ratios.sort_by(f64::total_cmp);
    let at = |q: f64| ratios[((ratios.len() - 1) as f64 * q).round() as usize];
    println!(
        "svg / moving frame (per frame, median and quartiles)   {:.4}   [{:.4}, {:.4}]",
        at(0.5),
        at(0.25),
        at(0.75)
    );
}
