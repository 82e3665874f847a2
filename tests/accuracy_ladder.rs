//! A reduced accuracy sweep (`glint::accuracy::sweep`) on small images: the facts the ladder
//! rests on, measured against the analytic sphere. No timings are checked.

use glint::accuracy::sweep::{Measurement, Rung, Stack, Sweep};
use glint::render::tessellate::Density;
use glint::render::{Antialias, FrameMode};

const SIZE: u32 = 128;

fn span(n: u32) -> Density {
    Density::PerSpan { u: n, v: n }
}

fn measure(stacks: &[Stack], rungs: Vec<Rung>) -> Vec<Measurement> {
    let sweep = Sweep {
        sizes: vec![SIZE],
        stacks: stacks.to_vec(),
        rungs,
        repeats: 1,
        threads: 0,
    };
    sweep.run(|_| {}).unwrap()
}

fn rung(density: Density, frames: FrameMode, antialias: Antialias) -> Rung {
    Rung {
        density,
        frames,
        antialias,
    }
}

#[test]
fn exact_frames_beat_interpolated_frames_at_equal_tessellation() {
    for n in [2, 4] {
        let m = measure(
            &[Stack::Identity, Stack::TranslateScale],
            vec![
                rung(span(n), FrameMode::Interpolated, Antialias::None),
                rung(span(n), FrameMode::Exact, Antialias::None),
            ],
        );
        for pair in m.chunks(2) {
            let (interpolated, exact) = (&pair[0].errors, &pair[1].errors);
            assert!(
                exact.one_minus_iou < interpolated.one_minus_iou
                    && exact.mean_normal_degrees < interpolated.mean_normal_degrees,
                "{n} segments, {:?}: exact {exact:?} vs interpolated {interpolated:?}",
                pair[0].stack
            );
        }
    }
}

#[test]
fn finer_tessellation_never_raises_the_error_beyond_noise() {
    let densities = [2, 4, 8, 16, 32];
    for frames in [FrameMode::Interpolated, FrameMode::Exact] {
        let m = measure(
            &[Stack::Identity, Stack::Crescent],
            densities
                .iter()
                .map(|&n| rung(span(n), frames, Antialias::None))
                .collect(),
        );
        for per_stack in m.chunks(densities.len()) {
            let errors: Vec<f64> = per_stack.iter().map(|m| m.errors.one_minus_iou).collect();
            // Noise: where hard edges happen to fall on pixel centres, a tenth of the error.
            for w in errors.windows(2) {
                assert!(w[1] <= 1.1 * w[0] + 1e-3, "{frames:?}: {errors:?}");
            }
            assert!(
                errors[errors.len() - 1] < 0.8 * errors[0],
                "{frames:?}: {errors:?}"
            );
        }
    }
}

#[test]
fn anti_aliasing_lowers_the_boundary_error() {
    let m = measure(
        &[Stack::Identity, Stack::Crescent],
        [
            Antialias::None,
            Antialias::Analytic,
            Antialias::Supersample(2),
            Antialias::Supersample(4),
        ]
        .into_iter()
        .map(|aa| rung(span(16), FrameMode::Exact, aa))
        .collect(),
    );
    for per_stack in m.chunks(4) {
        let b: Vec<f64> = per_stack.iter().map(|m| m.errors.boundary_pixels).collect();
        let stack = per_stack[0].stack;
        assert!(b[1] < 0.8 * b[0], "{stack:?} analytic vs none: {b:?}");
        assert!(b[2] < 0.8 * b[0], "{stack:?} 2x2 vs none: {b:?}");
        assert!(b[3] < b[2], "{stack:?} 4x4 vs 2x2: {b:?}");
    }
}
