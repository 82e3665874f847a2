//! The initial highlight vector (Blinn's half vector) and the paper's inverse, the virtual light.

use glam::Vec3;

use crate::math::normalize_or;

/// A light, seen from a surface point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Light {
    /// A light at infinity; `towards` is the unit direction from the scene to the light.
    Directional {
        /// Unit direction toward the light.
        towards: Vec3,
    },
    /// A light at `position`.
    Point {
        /// World position of the light.
        position: Vec3,
    },
}

/// The viewer, seen from a surface point: the one definition of the view vector V and of its
/// fallback, which the renderer's camera hands out ([`Camera::view`]).
///
/// [`Camera::view`]: crate::render::Camera::view
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum View {
    /// Orthographic camera: V is `towards` everywhere.
    Orthographic {
        /// Unit direction toward the eye: the reverse line of sight.
        towards: Vec3,
    },
    /// Perspective camera with its eye at `eye`: V is per point.
    Perspective {
        /// World position of the eye.
        eye: Vec3,
        /// Unit reverse line of sight, V where the eye sits on the point and `eye − p` has no
        /// direction: the direction the point is seen along from any nearby place.
        towards: Vec3,
    },
}

impl Light {
    /// The unit vector L from `point` toward the light; N when a point light sits on the point.
    #[must_use]
    pub fn direction(&self, point: Vec3, n: Vec3) -> Vec3 {
        match *self {
            Light::Directional { towards } => towards,
            Light::Point { position } => normalize_or(position - point, n),
        }
    }
}

impl View {
    /// The unit vector V from `point` toward the eye: `towards` under orthographic projection;
    /// `normalize(eye − point)` under perspective, or `towards` when the eye sits on the point.
    #[inline]
    #[must_use]
    pub fn direction(&self, point: Vec3) -> Vec3 {
        match *self {
            View::Orthographic { towards } => towards,
            View::Perspective { eye, towards } => normalize_or(eye - point, towards),
        }
    }
}

/// Blinn's half vector `H = (L + V) / ‖L + V‖` for unit L and V, the paper's original
/// highlight vector.
///
/// When `L = −V` (light straight behind the surface point as seen from the eye) `L + V` vanishes
/// and no half vector exists; `n` is returned, which puts the highlight centre on the point. It
/// is finite, and such a configuration only occurs at grazing points that face neither.
#[inline]
#[must_use]
pub fn half_vector(l: Vec3, v: Vec3, n: Vec3) -> Vec3 {
    normalize_or(l + v, n)
}

/// The half vector for a light and a view at a surface point with normal `n`.
#[must_use]
pub fn blinn_half_vector(light: &Light, view: &View, point: Vec3, n: Vec3) -> Vec3 {
    half_vector(light.direction(point, n), view.direction(point), n)
}

/// The virtual light of a highlight vector (paper: "once H is specified, it follows that
/// `L = 2(H, V)H − V`"): the mirror image of V about H, a unit vector for unit H and V.
#[inline]
#[must_use]
pub fn virtual_light(h: Vec3, v: Vec3) -> Vec3 {
    2.0 * h.dot(v) * h - v
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_vector_bisects() {
        let l = Vec3::new(1.0, 0.0, 1.0).normalize();
        let h = half_vector(l, Vec3::Z, Vec3::Y);
        let want = Vec3::new(
            (22.5_f32).to_radians().sin(),
            0.0,
            (22.5_f32).to_radians().cos(),
        );
        assert!((h - want).length() < 1e-6);
    }

    #[test]
    fn opposite_light_and_view_fall_back_to_normal() {
        let n = Vec3::new(0.0, 1.0, 0.0);
        assert_eq!(half_vector(Vec3::X, -Vec3::X, n), n);
    }

    #[test]
    fn virtual_light_inverts_half_vector() {
        let l = Vec3::new(0.3, 0.5, 0.8).normalize();
        let v = Vec3::new(-0.2, 0.1, 0.97).normalize();
        let back = virtual_light(half_vector(l, v, Vec3::Z), v);
        assert!((back - l).length() < 1e-6);
    }

    #[test]
    fn point_light_and_perspective_vary_per_point() {
        let light = Light::Point {
            position: Vec3::new(0.0, 0.0, 10.0),
        };
        let view = View::Perspective {
            eye: Vec3::new(10.0, 0.0, 0.0),
            towards: Vec3::X,
        };
        let h = blinn_half_vector(&light, &view, Vec3::ZERO, Vec3::Y);
        assert!((h - Vec3::new(1.0, 0.0, 1.0).normalize()).length() < 1e-6);
        let elsewhere = blinn_half_vector(&light, &view, Vec3::new(0.0, 0.0, 5.0), Vec3::Y);
        assert!((h - elsewhere).length() > 0.1);
        // A point light on the point itself: L falls back to N.
        assert_eq!(light.direction(Vec3::new(0.0, 0.0, 10.0), Vec3::Y), Vec3::Y);
        let ortho = View::Orthographic { towards: Vec3::Z };
        assert_eq!(ortho.direction(Vec3::ONE), Vec3::Z);
        // The eye on the point: V falls back to the reverse line of sight, not to N.
        assert_eq!(view.direction(Vec3::new(10.0, 0.0, 0.0)), Vec3::X);
    }
}
