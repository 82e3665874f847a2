//! The USD text-layer reader on any text: no panic, and every patch it accepts evaluates to
//! finite points.
#![no_main]

use glint::formats::parse_usda;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    let Ok(library) = parse_usda(text, "fuzz.usda") else {
        return;
    };
    for patch in &library.patches {
        let d = patch.surface.domain();
        let (u, v) = d.lerp(0.5, 0.5);
        assert!(patch.surface.point(u, v).is_finite());
    }
});
