//! Where a time code falls among an attribute's time samples, for USD's linear interpolation:
//! between the two samples around it, holding the first before them and the last after them.

/// The samples around `time` among the sorted, distinct `times`, and how far along from the
/// first to the second it is: `(i, j, s)`, the value at `time` being `(1 − s)·vᵢ + s·vⱼ` with
/// `s = (time − tᵢ)/(tⱼ − tᵢ)`. Before the first sample (or for a NaN time) it is `(0, 0, 0)`,
/// after the last `(n − 1, n − 1, 0)`: the end samples are held. `times` must not be empty.
#[must_use]
pub(super) fn bracket(times: &[f64], time: f64) -> (usize, usize, f64) {
    let last = times.len().saturating_sub(1);
    if time.is_nan() || time <= times[0] {
        return (0, 0, 0.0);
    }
    if time >= times[last] {
        return (last, last, 0.0);
    }
    let j = times.partition_point(|&t| t <= time);
    let i = j - 1;
    (i, j, (time - times[i]) / (times[j] - times[i]))
}

/// USD's linear interpolation of numbers: `(1 − s)·a + s·b`.
#[must_use]
pub(super) fn lerp(a: f64, b: f64, s: f64) -> f64 {
    (1.0 - s) * a + s * b
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_time_between_samples_is_bracketed_by_them() {
        let times = [1.0, 12.0, 24.0];
        let (i, j, s) = bracket(&times, 6.5);
        assert_eq!((i, j), (0, 1));
        assert!((s - 0.5).abs() < 1e-15);
        let (i, j, s) = bracket(&times, 18.0);
        assert_eq!((i, j), (1, 2));
        assert!((s - 0.5).abs() < 1e-15);
    }

    #[test]
    fn a_time_on_a_sample_is_that_sample() {
        let times = [1.0, 12.0, 24.0];
        let (i, _, s) = bracket(&times, 12.0);
        assert_eq!((i, s), (1, 0.0));
    }

    #[test]
    fn times_outside_the_samples_and_nan_hold_the_ends() {
        let times = [1.0, 12.0, 24.0];
        assert_eq!(bracket(&times, -100.0), (0, 0, 0.0));
        assert_eq!(bracket(&times, f64::NAN), (0, 0, 0.0));
        assert_eq!(bracket(&times, 1e300), (2, 2, 0.0));
        assert_eq!(bracket(&[5.0], 7.0), (0, 0, 0.0));
    }

    #[test]
    fn lerp_is_exact_at_its_ends() {
        assert_eq!(lerp(0.1, 0.7, 0.0), 0.1);
        assert_eq!(lerp(0.1, 0.7, 1.0), 0.7);
        assert!((lerp(2.0, 4.0, 0.25) - 2.5).abs() < 1e-15);
    }
}
