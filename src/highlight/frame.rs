//! The f32 tangent frame the highlight operations work in.

use glam::Vec3;

use crate::geom::Frame;

/// An orthonormal, right-handed frame `(du, dv, N)` at a surface point, in f32.
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
}
