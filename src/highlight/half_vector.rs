//! The initial highlight vector (Blinn's half vector) and its inverse from Anjyo & Hiramitsu
//! 2003, the virtual light.

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

/// Blinn's half vector `H = (L + V) / ‖L + V‖` for unit L and V, the original highlight vector
/// of Anjyo & Hiramitsu 2003.
///
/// When `L = −V` (the light straight behind the point as seen from the eye) `L + V` vanishes
/// and no half vector exists. As L approaches −V from any side, H turns perpendicular to V, which
/// puts the highlight on the silhouette; the fallback keeps it there: a fixed unit vector
/// perpendicular to V (`V.any_orthonormal_vector()`). A light passing behind the model so never
/// lights the whole model for a frame, as taking H = N there would.
#[inline]
#[must_use]
pub fn half_vector(l: Vec3, v: Vec3) -> Vec3 {
    normalize_or(l + v, v.any_orthonormal_vector())
}

/// The half vector for a light and a view at a surface point with normal `n`.
#[must_use]
pub fn blinn_half_vector(light: &Light, view: &View, point: Vec3, n: Vec3) -> Vec3 {
    half_vector(light.direction(point, n), view.direction(point))
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
        let h = half_vector(l, Vec3::Z);
        let want = Vec3::new(
            (22.5_f32).to_radians().sin(),
            0.0,
            (22.5_f32).to_radians().cos(),
        );
        assert!((h - want).length() < 1e-6);
    }

    #[test]
    fn opposite_light_and_view_put_the_highlight_on_the_silhouette_as_nearby_lights_do() {
        let v = Vec3::new(0.2, -0.3, 0.93).normalize();
        let h = half_vector(-v, v);
        assert!(
            (h.length() - 1.0).abs() < 1e-6 && h.dot(v).abs() < 1e-6,
            "{h}"
        );
        // Lights a thousandth of a radian away from −V give an H perpendicular to V too.
        let aside = (-v + 1e-3 * v.any_orthonormal_vector().cross(v)).normalize();
        assert!(half_vector(aside, v).dot(v).abs() < 2e-3);
    }

    #[test]
    fn virtual_light_inverts_half_vector() {
        let l = Vec3::new(0.3, 0.5, 0.8).normalize();
        let v = Vec3::new(-0.2, 0.1, 0.97).normalize();
        let back = virtual_light(half_vector(l, v), v);
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
