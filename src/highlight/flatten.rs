//! Flattening a cubic Bézier segment of a drawn outline into a polyline within a tolerance.

use glam::DVec2;

/// The flattening tolerance of a drawn outline relative to its size: a Bézier segment's
/// polyline lies within `FLATNESS × d` of the curve, `d` the diagonal of the bounding box of
/// every point and control point the outline is written with. Relative, so that a pin-point
/// glint is flattened as finely, for its size, as a large highlight.
pub const FLATNESS: f64 = 1e-4;

/// How many straight pieces approximate the cubic `p0 p1 p2 p3` within `tolerance`.
///
/// The second derivative of the cubic is the linear blend of `6 (p0 − 2p1 + p2)` and
/// `6 (p1 − 2p2 + p3)`, so `|B''| ≤ 6M` with M the larger of the two second differences. A chord
/// over a parameter interval h lies within `h² max|B''| / 8` of the curve, so n uniform pieces
/// are within `0.75 M / n²`: `n = ⌈√(0.75 M / tolerance)⌉`, at least 1.
#[must_use]
pub fn pieces(p: [DVec2; 4], tolerance: f64) -> usize {
    let m = (p[0] - 2.0 * p[1] + p[2])
        .length()
        .max((p[1] - 2.0 * p[2] + p[3]).length());
    if tolerance.is_nan() || tolerance <= 0.0 || !m.is_finite() {
        return 1;
    }
    // Capped so that hostile input cannot ask for an unbounded count; the outline's own limit
    // on flattened points refuses what is still too many.
    let n = (0.75 * m / tolerance).sqrt().ceil();
    if n >= 1e6 {
        1_000_000
    } else {
        (n as usize).max(1)
    }
}

/// The point of the cubic `p0 p1 p2 p3` at parameter `t`:
/// `(1−t)³ p0 + 3(1−t)²t p1 + 3(1−t)t² p2 + t³ p3`.
#[must_use]
pub fn cubic_at(p: [DVec2; 4], t: f64) -> DVec2 {
    let s = 1.0 - t;
    p[0] * (s * s * s) + p[1] * (3.0 * s * s * t) + p[2] * (3.0 * s * t * t) + p[3] * (t * t * t)
}

/// The points after `p0` of the cubic's polyline of `n` uniform pieces: `B(k/n)` for
/// k = 1..=n, the last exactly `p3`.
#[must_use]
pub fn flatten_cubic(p: [DVec2; 4], n: usize) -> Vec<DVec2> {
    let n = n.max(1);
    (1..=n)
        .map(|k| {
            if k == n {
                p[3]
            } else {
                cubic_at(p, k as f64 / n as f64)
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_straight_cubic_is_one_piece_and_a_curved_one_meets_the_tolerance() {
        let line = [
            DVec2::ZERO,
            DVec2::new(1.0, 0.0),
            DVec2::new(2.0, 0.0),
            DVec2::new(3.0, 0.0),
        ];
        assert_eq!(pieces(line, 1e-3), 1);
        // A quarter-circle-like arc of radius 1: the chord error of the pieces, measured at the
        // midpoint of each piece against the curve there, stays within the tolerance.
        let k = 0.552_284_75;
        let arc = [
            DVec2::new(1.0, 0.0),
            DVec2::new(1.0, k),
            DVec2::new(k, 1.0),
            DVec2::new(0.0, 1.0),
        ];
        let tol = 1e-4;
        let n = pieces(arc, tol);
        assert!(n > 10 && n < 200, "{n}");
        let points = flatten_cubic(arc, n);
        assert_eq!(*points.last().unwrap(), arc[3]);
        let mut previous = arc[0];
        for (i, p) in points.iter().enumerate() {
            let mid_t = (i as f64 + 0.5) / n as f64;
            let chord_mid = (previous + *p) * 0.5;
            assert!((cubic_at(arc, mid_t) - chord_mid).length() <= tol, "{i}");
            previous = *p;
        }
    }
}
