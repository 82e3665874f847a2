//! The frame-list parser (`--frames`) on any text: no panic, and never more frames than the
//! ceiling.
#![no_main]

use glint::job::parse_frames;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    if let Ok(frames) = parse_frames(text) {
        assert!(frames.len() <= 1_000_000);
    }
});
