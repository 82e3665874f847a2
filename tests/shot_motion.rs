//! Smooth motion: in `shots/sphere_ops.ron` the highlight matte's centroid and area change by a
//! bounded amount from one frame to the next — no pops — while a key that steps on purpose is
//! caught by the same measure.

use std::sync::Arc;

use glam::Vec2;
use glint::render::{Antialias, FrameMode, Renderer};
use glint::shot::{load_shot, Aov, Shot};

const SIZE: u32 = 96;

/// The matte's area (in pixels) and centroid at every frame of the shot.
fn matte_track(shot: &mut Shot) -> Vec<(f32, Vec2)> {
    shot.aovs = vec![Aov::Matte];
    let mut settings = shot.settings_with(None, Some((SIZE, SIZE)));
    settings.frames = FrameMode::Exact;
    settings.antialias = Antialias::None;
    let mut renderer = Renderer::new(Arc::clone(&shot.library));
    (shot.frames.0..=shot.frames.1)
        .map(|frame| {
            let state = shot.at(frame as f64);
            let scene = state.scene(shot).unwrap();
            let image = renderer.render(&scene, &settings).unwrap();
            let matte = image.aovs.matte.unwrap();
            let mut area = 0.0;
            let mut sum = Vec2::ZERO;
            for (i, &m) in matte.iter().enumerate() {
                let p = Vec2::new((i as u32 % SIZE) as f32, (i as u32 / SIZE) as f32);
                area += m;
                sum += m * p;
            }
            (area, sum / area.max(1e-6))
        })
        .collect()
}

/// The largest frame-to-frame centroid move (pixels) and relative area change.
fn largest_steps(track: &[(f32, Vec2)]) -> (f32, f32) {
    track.windows(2).fold((0.0f32, 0.0f32), |(mv, da), w| {
        let ((a0, c0), (a1, c1)) = (w[0], w[1]);
        (
            mv.max(c0.distance(c1)),
            da.max((a1 - a0).abs() / a0.max(a1)),
        )
    })
}

/// A pop: the centroid jumps more than 3 pixels (a twentieth of the sphere's 80-pixel
/// diameter here) or the area changes by more than 20% between two frames. The fastest keyed
/// motion in the shot — translate α from 0 to 0.35 over 11 frames, the centre moving by
/// asin(α) — moves about 1.4 pixels a frame.
const MAX_MOVE: f32 = 3.0;
const MAX_AREA_CHANGE: f32 = 0.2;

#[test]
fn sphere_ops_moves_without_pops_and_a_stepped_key_is_a_pop() {
    let path = &crate::common::repo_file("shots/sphere_ops.ron");
    let mut shot = load_shot(path).unwrap();
    let track = matte_track(&mut shot);
    assert!(
        track.iter().all(|&(area, _)| area > 20.0),
        "the highlight vanished"
    );
    let (moved, area) = largest_steps(&track);
    assert!(moved <= MAX_MOVE, "centroid jumps {moved} px");
    assert!(area <= MAX_AREA_CHANGE, "area changes by {area}");

    // The same shot with translate α stepping from 0 to 0.35 within a hundredth of a frame.
    let text = std::fs::read_to_string(path)
        .unwrap()
        .replace("(1, 0.0), (12, 0.35), (24, 0.0)", "(6, 0.0), (6.01, 0.35)")
        .replace(
            "../patches/",
            concat!(env!("CARGO_MANIFEST_DIR"), "/../patches/"),
        );
    let dir = tempfile::tempdir().unwrap();
    let stepped_path = dir.path().join("stepped.ron");
    std::fs::write(&stepped_path, text).unwrap();
    let mut stepped = load_shot(&stepped_path).unwrap();
    let (moved, _) = largest_steps(&matte_track(&mut stepped));
    assert!(
        moved > MAX_MOVE,
        "a stepped key moved the centroid only {moved} px"
    );
}
