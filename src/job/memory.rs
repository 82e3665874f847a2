//! How much memory rendering a frame takes, estimated before rendering: what a farm task should
//! request.

use crate::render::{FrameMode, Settings};

/// Bytes held per sample while a frame renders (its G-buffer entry, visibility and shading, the
/// resolved colour and the images written, shared out): with interpolated frames, measured as
/// 80 B a pixel at `preview`; with exact or refined frames, which keep each sample's frame,
/// 1.25 KB a pixel at `final` (3 × 3 samples) — the teapot turntable at 1920×1080 (README, farm
/// section).
fn bytes_per_sample(frames: FrameMode) -> u64 {
    match frames {
        FrameMode::Interpolated => 90,
        FrameMode::Exact | FrameMode::Refined => 150,
    }
}

/// What the process holds before the first frame: code, the model, its mesh.
const BASE_BYTES: u64 = 64 << 20;

/// The peak memory of rendering one frame with `settings`:
/// `64 MiB + pixels × samples × (90 B interpolated, 150 B exact or refined)`, an upper estimate
/// from measured peaks (the README's farm table); the model's mesh beyond the base is not
/// counted.
#[must_use]
pub fn estimate_peak_bytes(settings: &Settings) -> u64 {
    let pixels = u64::from(settings.width) * u64::from(settings.height);
    let samples = u64::from(settings.samples_per_side()).pow(2);
    BASE_BYTES + pixels * samples * bytes_per_sample(settings.frames)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_estimate_covers_the_measured_peaks() {
        // Peaks measured with /usr/bin/time on the teapot turntable (README, farm section).
        for (settings, measured) in [
            (Settings::final_quality(1920, 1080), 2_600_000_000u64),
            (Settings::final_quality(640, 360), 325_000_000),
            (Settings::preview(1920, 1080), 170_000_000),
            (Settings::preview(3840, 2160), 575_000_000),
        ] {
            let estimate = estimate_peak_bytes(&settings);
            assert!(
                estimate >= measured,
                "{settings:?}: {estimate} < {measured}"
            );
            assert!(
                estimate < measured * 2,
                "{settings:?}: {estimate} is far above {measured}"
            );
        }
    }
}
