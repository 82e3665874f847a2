//! The toon-texture reader on any bytes: no panic, and every texel of what it accepts finite.
#![no_main]

use glint::formats::toon_texture_from_png;
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let Ok(texture) = toon_texture_from_png(bytes, "fuzz.png") else {
        return;
    };
    for y in 0..texture.height() {
        for x in 0..texture.width() {
            assert!(texture.texel(x, y).is_finite());
        }
    }
});
