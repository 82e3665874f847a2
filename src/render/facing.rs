//! Shading frames turned toward the viewer: surfaces are two-sided, so the frame a pixel shades
//! with has its normal on the eye's side.

use glam::{DVec3, Vec3};

use crate::geom::Frame;
use crate::highlight::TangentFrame;

/// An orthonormal frame from a normal and a direction along u, turned toward the viewer:
/// `N = normalize(n)`, flipped when `N·V < 0` (the back of a two-sided surface);
/// `du = normalize(a − (a·N) N)`; `dv = N × du`. `toward_eye` is V at any length (only its
/// direction counts). Degenerate input falls back to any frame around the viewer direction,
/// never NaN.
#[inline]
pub fn facing_frame(n: Vec3, along_u: Vec3, toward_eye: Vec3) -> TangentFrame {
    let Some((normal, inverse_squared)) = facing(n, toward_eye) else {
        let normal = unfacing_fallback(toward_eye);
        let du = normal.any_orthonormal_vector();
        return TangentFrame::new(du, normal.cross(du), normal);
    };
    // The projection uses `1/|n|²` and the normal `1/|n|`, so the two normalizations do not
    // wait for each other: `du ∝ a − (a·n) n / |n|²`.
    let du = (along_u - (along_u.dot(n) * inverse_squared) * n)
        .try_normalize()
        .unwrap_or_else(|| normal.any_orthonormal_vector());
    TangentFrame::new(du, normal.cross(du), normal)
}

/// An evaluated patch frame — orthonormal and right-handed, in f64 — in f32 and turned toward
/// the viewer: `(du, s dv, s N)` with `s = −1` where `N·V < 0`. This is [`facing_frame`] of it
/// without normalizing again; a frame whose axes are not unit to within 10⁻⁵ after rounding
/// goes through [`facing_frame`].
#[inline]
pub(super) fn facing_patch_frame(f: &Frame, toward_eye: Vec3) -> TangentFrame {
    let (n, du, dv) = (f.normal.as_vec3(), f.du.as_vec3(), f.dv.as_vec3());
    let unit = |v: Vec3| (v.length_squared() - 1.0).abs() < 1e-5;
    if !(unit(n) && unit(du) && unit(dv)) {
        return facing_frame(n, du, toward_eye);
    }
    let s = if faces_away(n, toward_eye) { -1.0 } else { 1.0 };
    TangentFrame::new(du, dv * s, n * s)
}

/// Whether the normal `n` faces away from the viewer, `N·V < 0`: the side [`facing_frame`]
/// and [`facing_patch_frame`] turn.
#[inline]
#[must_use]
pub(super) fn faces_away(n: Vec3, toward_eye: Vec3) -> bool {
    n.dot(toward_eye) < 0.0
}

/// The normal of [`facing_frame`] alone, for shading that needs no tangents.
#[inline]
pub(crate) fn facing_normal(n: Vec3, toward_eye: Vec3) -> Vec3 {
    facing(n, toward_eye).map_or_else(|| unfacing_fallback(toward_eye), |(normal, _)| normal)
}

/// `normalize(n)` turned toward the viewer, and `1/|n|²`; `None` when `n` is zero or not
/// finite.
#[inline]
fn facing(n: Vec3, toward_eye: Vec3) -> Option<(Vec3, f32)> {
    let length_squared = n.length_squared();
    if !(length_squared > f32::MIN_POSITIVE && length_squared.is_finite()) {
        return None;
    }
    let inverse_squared = length_squared.recip();
    let facing = if faces_away(n, toward_eye) { -1.0 } else { 1.0 };
    Some((n * (facing * inverse_squared.sqrt()), inverse_squared))
}

/// The normal where no normal is given: the viewer direction.
#[inline]
fn unfacing_fallback(toward_eye: Vec3) -> Vec3 {
    toward_eye.normalize_or(Vec3::Z)
}

/// A frame to fill scratch buffers with before evaluation overwrites it.
pub(super) const NO_FRAME: Frame = Frame {
    point: DVec3::ZERO,
    normal: DVec3::Z,
    du: DVec3::X,
    dv: DVec3::Y,
    degenerate: false,
};

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    #[test]
    fn patch_frames_turn_like_facing_frames_without_normalizing_again() {
        let sphere = crate::geom::shapes::sphere(DVec3::new(0.5, 0.0, -1.0), 2.0).unwrap();
        let params: Vec<(f64, f64)> = (0..200)
            .map(|k| ((k as f64 * 0.618).fract(), (k as f64 * 0.371).fract()))
            .collect();
        let mut frames = vec![NO_FRAME; params.len()];
        sphere.frames(&params, &mut frames);
        let mut flipped = 0;
        for f in &frames {
            for eye in [Vec3::new(0.0, -9.0, 1.0), Vec3::new(3.0, 4.0, -2.0)] {
                let toward_eye = eye - f.point.as_vec3();
                let got = facing_patch_frame(f, toward_eye);
                let want = facing_frame(f.normal.as_vec3(), f.du.as_vec3(), toward_eye);
                for (a, b) in [(got.du, want.du), (got.dv, want.dv), (got.n, want.n)] {
                    assert!((a - b).length() < 1e-6, "{a} vs {b}");
                }
                flipped += usize::from(got.n.dot(f.normal.as_vec3()) < 0.0);
            }
        }
        assert!(flipped > 50, "{flipped}");
        // Not a unit frame: the general construction takes over, and gives no NaN.
        let broken = Frame {
            normal: DVec3::new(f64::NAN, 0.0, 0.0),
            ..NO_FRAME
        };
        let f = facing_patch_frame(&broken, Vec3::Z);
        assert!(f.n.is_finite() && f.du.is_finite() && f.dv.is_finite());
    }

    #[test]
    fn facing_frame_is_orthonormal_and_faces_the_viewer() {
        let f = facing_frame(Vec3::new(0.0, 0.0, -2.0), Vec3::new(1.0, 0.0, 0.3), Vec3::Z);
        assert_eq!(f.n, Vec3::Z);
        assert!((f.du - Vec3::X).length() < 1e-6);
        assert!((f.du.cross(f.dv) - f.n).length() < 1e-6);
        let g = facing_frame(Vec3::ZERO, Vec3::ZERO, Vec3::Y);
        assert!(g.n.is_finite() && g.du.is_finite() && (g.du.dot(g.n)).abs() < 1e-6);
    }
}
