//! Tracks over random key sets and fractional frames: exact at keys, linear between them (the
//! mean halfway), held outside.

use glint::anim::{Key, Track};
use proptest::prelude::*;

/// Keys at strictly increasing frames, as a shot could write them.
fn keys() -> impl Strategy<Value = Vec<Key<f32>>> {
    prop::collection::vec((0.01f64..50.0, -1e3f32..1e3), 1..12).prop_flat_map(|steps| {
        let start = -20.0;
        let mut frame = start;
        let keys: Vec<Key<f32>> = steps
            .into_iter()
            .map(|(gap, value)| {
                frame += gap;
                Key { frame, value }
            })
            .collect();
        Just(keys)
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn exact_at_keys_linear_between_and_held_outside(keys in keys(), s in 0.0f64..1.0, before in 0.0f64..1e4) {
        let track = Track::Keys(keys.clone());
        for key in &keys {
            prop_assert_eq!(track.at(key.frame), key.value);
        }
        for pair in keys.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            let mid = track.at(0.5 * (a.frame + b.frame));
            let mean = 0.5 * (a.value + b.value);
            prop_assert!((mid - mean).abs() <= 1e-4 * (1.0 + mean.abs()), "{} vs {}", mid, mean);
            let frame = a.frame + s * (b.frame - a.frame);
            let expected = f64::from(a.value) + s * f64::from(b.value - a.value);
            let got = f64::from(track.at(frame));
            prop_assert!((got - expected).abs() <= 1e-3 * (1.0 + expected.abs()), "{} vs {}", got, expected);
            prop_assert!(got >= f64::from(a.value.min(b.value)) - 1e-3 && got <= f64::from(a.value.max(b.value)) + 1e-3);
        }
        let (first, last) = (keys[0], keys[keys.len() - 1]);
        prop_assert_eq!(track.at(first.frame - before - 1e-9), first.value);
        prop_assert_eq!(track.at(last.frame + before + 1e-9), last.value);
    }
}
