//! The shot loader on any text, as if it were `shots/fuzz.ron` (so that it can name the shipped
//! models and textures), and a tiny render of what loads: no panic, no pixel that is not finite.
#![no_main]

use std::path::Path;

use glint::job::{Overrides, RenderJob};
use glint::shot::{load_shot_text, Preset};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shots/fuzz.ron");
    let Ok(shot) = load_shot_text(&path, text.to_string()) else {
        return;
    };
    let first = shot.frames.0;
    let overrides = Overrides {
        frames: Some(vec![first]),
        size: Some((8, 8)),
        preset: Some(Preset::Preview),
        threads: Some(1),
        max_memory: Some(1 << 30),
        ..Overrides::default()
    };
    let Ok(mut job) = RenderJob::new(shot, &overrides) else {
        return;
    };
    if let Ok(frame) = job.render_frame(first as f64) {
        assert!(frame.colour.iter().all(|c| c.is_finite()));
    }
});
