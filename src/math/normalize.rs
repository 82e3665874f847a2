//! Normalization guarded against zero, overflow and NaN: one vector, or many side by side.

use glam::Vec3;

use super::lane_count::LANES;

/// Below this squared length a vector counts as zero and is not normalized.
const MIN_LENGTH_SQUARED: f32 = 1e-12;

/// `v / ‖v‖`, or `fallback` when `v` is (nearly) zero or not finite.
///
/// A vector too long to square in f32 (possible with a huge translation) is first scaled by its
/// largest component, so it still normalizes.
#[inline]
#[must_use]
pub(crate) fn normalize_or(v: Vec3, fallback: Vec3) -> Vec3 {
    let len2 = v.length_squared();
    if len2 > MIN_LENGTH_SQUARED && len2.is_finite() {
        v * len2.sqrt().recip()
    } else if len2.is_infinite() && v.is_finite() {
        let w = v / v.abs().max_element();
        w / w.length()
    } else {
        fallback
    }
}

/// Normalizes the vectors `(x[k], y[k], z[k])` in place, side by side: each one whose squared
/// length is finite and above the zero threshold becomes `v · (1/√(v·v))` — the same value
/// [`normalize_or`] and glam's `try_normalize` give it — in loops over one coordinate array at
/// a time, which vectorize; every other one `v` becomes `exact(k, v)`.
///
/// # Panics
/// If the arrays differ in length.
#[inline]
pub(crate) fn normalize_lanes(
    x: &mut [f32],
    y: &mut [f32],
    z: &mut [f32],
    exact: impl Fn(usize, Vec3) -> Vec3,
) {
    let n = x.len();
    assert!(y.len() == n && z.len() == n, "lane lengths differ");
    // The scale of each lane, 0 where `exact` takes over.
    let mut scale = [0.0f32; LANES];
    for (start, ((x, y), z)) in (0..n).step_by(LANES).zip(
        x.chunks_mut(LANES)
            .zip(y.chunks_mut(LANES))
            .zip(z.chunks_mut(LANES)),
    ) {
        let scale = &mut scale[..x.len()];
        let (y, z) = (&mut y[..x.len()], &mut z[..x.len()]);
        let mut all_scaled = true;
        for k in 0..x.len() {
            let len2 = x[k] * x[k] + y[k] * y[k] + z[k] * z[k];
            let normal = len2 > MIN_LENGTH_SQUARED && len2 < f32::INFINITY;
            scale[k] = if normal { len2.sqrt().recip() } else { 0.0 };
            all_scaled &= normal;
        }
        // Every lane is stored, scaled or as it was: a store only where a condition holds
        // would be done lane by lane, with a branch each.
        for k in 0..x.len() {
            let s = if scale[k] > 0.0 { scale[k] } else { 1.0 };
            x[k] *= s;
            y[k] *= s;
            z[k] *= s;
        }
        if all_scaled {
            continue;
        }
        for k in 0..x.len() {
            if scale[k] <= 0.0 {
                (x[k], y[k], z[k]) = exact(start + k, Vec3::new(x[k], y[k], z[k])).into();
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lanes_normalize_as_one_by_one_and_hand_the_rest_over_as_given() {
        // More than one block of lanes; among them zero, tiny, huge, infinite and NaN vectors.
        let vectors: Vec<Vec3> = (0..LANES + 9)
            .map(|k| match k % 13 {
                3 => Vec3::ZERO,
                5 => Vec3::splat(1e-7),
                7 => Vec3::new(3e19, 0.0, 1.0),
                9 => Vec3::new(f32::INFINITY, 0.0, 0.0),
                11 => Vec3::new(0.0, f32::NAN, 1.0),
                _ => Vec3::new((k as f32).sin(), 0.3 * k as f32, -2.0),
            })
            .collect();
        let lane = |i: usize| vectors.iter().map(|v| v[i]).collect::<Vec<f32>>();
        let (mut x, mut y, mut z) = (lane(0), lane(1), lane(2));
        let handed = std::cell::RefCell::new(Vec::new());
        normalize_lanes(&mut x, &mut y, &mut z, |k, v| {
            handed.borrow_mut().push(k);
            assert_eq!(
                v.to_array().map(f32::to_bits),
                vectors[k].to_array().map(f32::to_bits)
            );
            Vec3::new(-1.0, -2.0, -3.0)
        });
        let mut want_handed = Vec::new();
        for (k, v) in vectors.iter().enumerate() {
            let got = Vec3::new(x[k], y[k], z[k]);
            let len2 = v.length_squared();
            if len2 > MIN_LENGTH_SQUARED && len2.is_finite() {
                assert_eq!(got, v.try_normalize().unwrap(), "lane {k}");
            } else {
                want_handed.push(k);
                assert_eq!(got, Vec3::new(-1.0, -2.0, -3.0), "lane {k}");
            }
        }
        assert_eq!(*handed.borrow(), want_handed);
        // Both blocks had lanes to hand over.
        assert!(want_handed.first() < Some(&LANES) && want_handed.last() > Some(&LANES));
    }

    #[test]
    fn normalize_guards_zero_and_overflow() {
        let fb = Vec3::X;
        assert_eq!(normalize_or(Vec3::ZERO, fb), fb);
        assert_eq!(normalize_or(Vec3::splat(1e-8), fb), fb);
        assert_eq!(normalize_or(Vec3::new(f32::NAN, 0.0, 0.0), fb), fb);
        let big = normalize_or(Vec3::new(3e30, 4e30, 0.0), fb);
        assert!((big - Vec3::new(0.6, 0.8, 0.0)).length() < 1e-6);
        assert!((normalize_or(Vec3::new(0.0, 2.0, 0.0), fb) - Vec3::Y).length() < 1e-7);
    }
}
