//! The RON patch-library reader on any text, and every patch it accepts evaluated at its
//! domain's corners and centre: no panic, finite points and unit normals.
#![no_main]

use glint::formats::parse_patch_ron;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    let Ok(library) = parse_patch_ron(text, "fuzz.ron") else {
        return;
    };
    for patch in &library.patches {
        let d = patch.surface.domain();
        for (s, t) in [(0.0, 0.0), (1.0, 1.0), (0.5, 0.5), (0.0, 1.0)] {
            let (u, v) = d.lerp(s, t);
            let frame = patch.surface.frame(u, v);
            assert!(frame.point.is_finite() && (frame.normal.length() - 1.0).abs() < 1e-6);
        }
    }
});
