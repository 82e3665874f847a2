//! The coverage of a pixel's box by the positive side of a function linear across it.

/// The fraction of a pixel's box where the signed value, linear across it, is positive:
/// `s(x, y) = s + g_x x + g_y y` over `(x, y) ∈ [−½, ½]²`, with `g_x`, `g_y` its changes from one
/// pixel to the next (their signs do not matter).
///
/// `g_x x + g_y y` for a point uniform in the box is the sum of two uniform variables of widths
/// `a = max(|g_x|, |g_y|)` and `b = min(…)`; its density is a trapezoid on `±(a + b)/2` with a
/// flat top of `1/a` on `±(a − b)/2`, and the coverage is its distribution function at `s`:
///
/// - `(s + (a + b)/2)² / (2ab)` on `[−(a + b)/2, −(a − b)/2]`,
/// - `½ + s/a` on `[−(a − b)/2, (a − b)/2]`,
/// - `1 − ((a + b)/2 − s)² / (2ab)` on `[(a − b)/2, (a + b)/2]`,
///
/// 0 below and 1 above: the exact box-filtered coverage of a straight edge, where a smoothstep
/// over the footprint `a + b` (the highlight's feathered edge) is off by up to a tenth of a pixel.
/// With `a = 0` the hard edge: 1 where `s > 0`.
#[inline]
#[must_use]
pub fn box_coverage(s: f32, gx: f32, gy: f32) -> f32 {
    let (gx, gy) = (gx.abs(), gy.abs());
    let (a, b) = (gx.max(gy), gx.min(gy));
    if a.is_nan() || a <= 0.0 {
        return if s > 0.0 { 1.0 } else { 0.0 };
    }
    let (outer, inner) = (0.5 * (a + b), 0.5 * (a - b));
    let t = s.abs();
    let upper = if t >= outer {
        1.0
    } else if t <= inner {
        0.5 + t / a
    } else {
        let d = outer - t;
        1.0 - d * d / (2.0 * a * b)
    };
    // Symmetric about s = 0: the coverage at −s is one minus that at s.
    let c = if s >= 0.0 { upper } else { 1.0 - upper };
    c.clamp(0.0, 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The box coverage counted on an `n × n` grid of points, in f64.
    fn counted(s: f32, gx: f32, gy: f32, n: u32) -> f64 {
        let inside = (0..n * n)
            .filter(|i| {
                let x = (f64::from(i % n) + 0.5) / f64::from(n) - 0.5;
                let y = (f64::from(i / n) + 0.5) / f64::from(n) - 0.5;
                f64::from(s) + f64::from(gx) * x + f64::from(gy) * y > 0.0
            })
            .count();
        inside as f64 / f64::from(n * n)
    }

    #[test]
    fn box_coverage_is_the_area_of_the_box_on_the_positive_side() {
        // Against counting on a 1000 × 1000 grid (error below 2e-3 for a straight edge):
        // axis-aligned, diagonal and skew edges, across the whole ramp and beyond it.
        let mut worst = 0.0f64;
        for (gx, gy) in [
            (1.0f32, 0.0f32),
            (0.0, -2.0),
            (1.0, 1.0),
            (-0.3, 0.7),
            (2.5, -0.4),
            (1e-4, 1.0),
        ] {
            for k in -12..=12 {
                let s = k as f32 / 12.0 * 0.6 * (gx.abs() + gy.abs());
                let exact = f64::from(box_coverage(s, gx, gy));
                let count = counted(s, gx, gy, 1000);
                worst = worst.max((exact - count).abs());
                assert!(
                    (exact - count).abs() < 2e-3,
                    "s {s}, g ({gx}, {gy}): {exact} vs {count}"
                );
            }
        }
        assert!(worst > 0.0, "the grid and the formula differ somewhere");
        // The hard edge, and symmetry about the edge.
        assert_eq!(box_coverage(0.1, 0.0, 0.0), 1.0);
        assert_eq!(box_coverage(-0.1, 0.0, -0.0), 0.0);
        assert_eq!(box_coverage(0.0, 1.0, 0.5), 0.5);
    }
}
