//! The inside test of a highlight and soft coverage from its signed value.

use glam::Vec3;

/// The signed inside value `s = ε − ‖N − H‖² / 2` (docs/highlights.md).
///
/// For unit vectors `‖N − H‖² / 2 = 1 − (N, H)`, so `s > 0` is Eq. 3 of Anjyo & Hiramitsu 2003,
/// `(N, H) > 1 − ε`. Written as a squared distance it keeps its precision in f32 for the tiny ε of
/// a pin-point glint, where `1 − (N, H)` rounds to a multiple of 2⁻²⁴ and loses it all.
#[inline]
#[must_use]
pub fn signed_inside(n: Vec3, h: Vec3, epsilon: f32) -> f32 {
    epsilon - 0.5 * (n - h).length_squared()
}

/// Whether a point with normal `n` lies in the highlight of `h`: `‖N − H‖² / 2 < ε`.
#[inline]
#[must_use]
pub fn inside(n: Vec3, h: Vec3, epsilon: f32) -> bool {
    signed_inside(n, h, epsilon) > 0.0
}

/// Coverage in `[0, 1]` from a signed inside value `s` and an edge width `w` (in units of `s`).
///
/// `w ≤ 0` is the hard edge of Anjyo & Hiramitsu 2003: 1 where `s > 0`, else 0. `w > 0` is a smoothstep over the
/// band `[−w/2, w/2]` centred on the hard edge, so coverage is ½ exactly on it: the renderer passes
/// a pixel's footprint of `s` for analytic anti-aliasing, and a layer's feather widens the band.
#[inline]
#[must_use]
pub fn coverage_from_signed(s: f32, width: f32) -> f32 {
    if width > 0.0 {
        let x = (s / width + 0.5).clamp(0.0, 1.0);
        x * x * (3.0 - 2.0 * x)
    } else if s > 0.0 {
        1.0
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn signed_value_matches_one_minus_cosine() {
        let n = Vec3::Z;
        let h = Vec3::new(0.6, 0.0, 0.8);
        assert!((signed_inside(n, h, 0.25) - (0.25 - (1.0 - 0.8))).abs() < 1e-6);
        assert!(inside(n, h, 0.25));
        assert!(!inside(n, h, 0.15));
    }

    #[test]
    fn tiny_epsilon_keeps_precision_where_one_minus_dot_does_not() {
        // A normal 1.5e-4 rad from H: 1 − cos ≈ 1.125e-8, well inside ε = 2e-8 and outside 5e-9.
        let a = 1.5e-4_f32;
        let h = Vec3::new(a.sin(), 0.0, a.cos());
        assert!(inside(Vec3::Z, h, 2e-8));
        assert!(!inside(Vec3::Z, h, 5e-9));
        // The naive form sees cos a == 1 in f32 and calls both "outside".
        assert_eq!(1.0 - Vec3::Z.dot(h), 0.0);
    }

    #[test]
    fn coverage_hard_and_smooth() {
        assert_eq!(coverage_from_signed(1e-9, 0.0), 1.0);
        assert_eq!(coverage_from_signed(0.0, 0.0), 0.0);
        assert_eq!(coverage_from_signed(-1e-9, 0.0), 0.0);
        assert_eq!(coverage_from_signed(0.0, 0.1), 0.5);
        assert_eq!(coverage_from_signed(0.05, 0.1), 1.0);
        assert_eq!(coverage_from_signed(-0.05, 0.1), 0.0);
        let a = coverage_from_signed(0.01, 0.1);
        let b = coverage_from_signed(0.02, 0.1);
        assert!(0.5 < a && a < b && b < 1.0);
        // Symmetric about the edge.
        assert!((coverage_from_signed(-0.01, 0.1) - (1.0 - a)).abs() < 1e-6);
    }

    #[test]
    fn the_edge_itself_is_outside() {
        // ‖N − H‖² / 2 = 1/2 exactly, so s = 0 at ε = 1/2: the strict inequality of Anjyo &
        // Hiramitsu 2003.
        assert_eq!(signed_inside(Vec3::Z, Vec3::ZERO, 0.5), 0.0);
        assert!(!inside(Vec3::Z, Vec3::ZERO, 0.5));
    }
}
