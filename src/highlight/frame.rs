//! The f32 tangent frame the highlight operations work in, and the guarded normalization every
//! operation ends with.

use glam::Vec3;

use crate::geom::Frame;

/// An orthonormal, right-handed frame `(du, dv, N)` at a surface point, in f32 (DESIGN §4, §8).
///
/// The operations express a highlight vector in this frame's coordinates
/// `(t_u, t_v, h_n) = ((H, du), (H, dv), (H, N))`, act there, and map back.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TangentFrame {
    /// Unit tangent along increasing u.
    pub du: Vec3,
    /// Unit tangent `N × du`.
    pub dv: Vec3,
    /// Unit normal N.
    pub n: Vec3,
}

impl TangentFrame {
    /// The frame with the given axes; they are expected to be orthonormal with `du × dv = n`.
    #[must_use]
    pub const fn new(du: Vec3, dv: Vec3, n: Vec3) -> Self {
        Self { du, dv, n }
    }

    /// Coordinates of `h` in this frame: `((h, du), (h, dv), (h, N))`.
    #[inline]
    #[must_use]
    pub fn to_local(&self, h: Vec3) -> Vec3 {
        Vec3::new(h.dot(self.du), h.dot(self.dv), h.dot(self.n))
    }

    /// The world vector with frame coordinates `l`: `l.x du + l.y dv + l.z N`.
    #[inline]
    #[must_use]
    pub fn to_world(&self, l: Vec3) -> Vec3 {
        l.x * self.du + l.y * self.dv + l.z * self.n
    }
}

impl From<&Frame> for TangentFrame {
    fn from(f: &Frame) -> Self {
        Self {
            du: f.du.as_vec3(),
            dv: f.dv.as_vec3(),
            n: f.normal.as_vec3(),
        }
    }
}

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
/// a time, which vectorize; every other one becomes `exact(k)`.
///
/// # Panics
/// If the arrays differ in length.
#[inline]
pub(crate) fn normalize_lanes(
    x: &mut [f32],
    y: &mut [f32],
    z: &mut [f32],
    exact: impl Fn(usize) -> Vec3,
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
        for k in 0..x.len() {
            let len2 = x[k] * x[k] + y[k] * y[k] + z[k] * z[k];
            scale[k] = if len2 > MIN_LENGTH_SQUARED && len2 < f32::INFINITY {
                len2.sqrt().recip()
            } else {
                0.0
            };
        }
        for k in 0..x.len() {
            if scale[k] > 0.0 {
                x[k] *= scale[k];
                y[k] *= scale[k];
                z[k] *= scale[k];
            }
        }
        for k in 0..x.len() {
            if scale[k] <= 0.0 {
                (x[k], y[k], z[k]) = exact(start + k).into();
            }
        }
    }
}

/// Lanes [`normalize_lanes`] works on at once.
const LANES: usize = 64;

#[cfg(test)]
mod tests {
    use super::*;
    use glam::DVec3;

    #[test]
    fn from_geom_frame_and_round_trip() {
        let s = 0.5_f64.sqrt();
        let f = Frame {
            point: DVec3::ZERO,
            normal: DVec3::Z,
            du: DVec3::new(s, s, 0.0),
            dv: DVec3::new(-s, s, 0.0),
            degenerate: false,
        };
        let t = TangentFrame::from(&f);
        assert!((t.du.cross(t.dv) - t.n).length() < 1e-6);
        let h = Vec3::new(0.3, -0.2, 0.9);
        let l = t.to_local(h);
        assert!((l.x - (0.3 * s as f32 - 0.2 * s as f32)).abs() < 1e-6);
        assert!((t.to_world(l) - h).length() < 1e-6);
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
