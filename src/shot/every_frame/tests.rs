//! Tests of the checks at every frame, on shots loaded from text.

use std::path::Path;

use super::*;
use crate::shot::load_shot_text;

/// A shot of frames 1–`frames` whose one highlight has `ops` rotations, each keyed at two
/// frames of its own, and whose material has a keyed colour.
fn shot_text(frames: i64, ops: usize) -> String {
    let stack: Vec<String> = (0..ops)
        .map(|i| format!("Rotate(degrees: [({i}, 0.0), ({}, 1.0)])", i + 1))
        .collect();
    format!(
        r#"Shot(
    resolution: (16, 16), frames: (1, {frames}), fps: 24, output: "out/x.####.png",
    instances: [(name: "ball", file: "../../patches/sphere.ron", material: "m")],
    materials: {{"m": Cel(base: [(1, (0.1, 0.1, 0.1)), (50, (0.2, 0.2, 0.2))], bands: [])}},
    camera: (eye: (0.0, -6.0, 0.0), target: (0.0, 0.0, 0.0), projection: Orthographic(height: 2.4)),
    light: Directional(towards: (0.35, -1.0, 0.45)),
    highlights: [(patches: "ball/*", expr: Layer((stack: [{}], epsilon: 0.05, colour: (1.0, 1.0, 1.0))))],
)"#,
        stack.join(", ")
    )
}

fn checks(frames: i64, ops: usize) -> usize {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/shot/every_frame.test.ron");
    let text = shot_text(frames, ops);
    let shot = load_shot_text(&path, text.clone()).unwrap();
    let sources = [Source::new(&path, text)];
    let written = [Written {
        source: 0,
        index: 0,
    }];
    check_every_frame_counted(&shot, &sources, &[0], &written, &[]).unwrap()
}

#[test]
fn the_checks_grow_with_what_is_written_not_with_frames_times_operations() {
    for (frames, ops) in [(100, 10), (1000, 100), (10_000, 1000)] {
        let written = frames as usize + 3 * ops + 2;
        let made = checks(frames, ops);
        // The camera and light once a frame, each op at its keys and the first frame, the
        // material at its keys: a few checks for each thing written. Checking every op at
        // every frame would make frames × ops.
        assert!(
            made <= 2 * written,
            "{frames} frames, {ops} ops: {made} checks for {written} things written"
        );
        assert!(
            made >= frames as usize + 2 * ops,
            "{made} checks: some were skipped"
        );
    }
}

#[test]
fn a_key_beyond_the_frame_range_is_checked_too() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/shot/every_frame.test.ron");
    // Frames 1–10 hold the first key's value; the negative split is keyed at frame 40.
    let text = shot_text(10, 1).replace(
        "Rotate(degrees: [(0, 0.0), (1, 1.0)])",
        "Split(gamma_u: [(20, 0.0), (40, -0.5)], gamma_v: 0.0)",
    );
    let e = load_shot_text(&path, text).unwrap_err().to_string();
    assert!(
        e.contains("at frame 40") && e.contains("layers[0]: stack[0]"),
        "{e}"
    );
}
