//! One surface point as an exact frame shades it: its position, its frame turned toward the
//! viewer, and the initial highlight vector there.

use glam::Vec3;

use super::camera::Camera;
use super::facing::facing_patch_frame;
use crate::geom::NurbsSurface;
use crate::highlight::{blinn_half_vector, half_vector, Light, TangentFrame};

/// A point of a patch seen by a camera under a light, with the values an exact frame
/// ([`FrameMode::Exact`](super::FrameMode::Exact)) shades it with: the same facing frame and
/// the same half vector, so that what is solved here holds in the rendered image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    /// World position.
    pub position: Vec3,
    /// The patch frame at the point, turned toward the viewer.
    pub frame: TangentFrame,
    /// Blinn's half vector `H = normalize(L + V)` there, in world coordinates.
    pub half_vector: Vec3,
}

impl SurfacePoint {
    /// The point at `(u, v)` of `surface` (clamped to its domain), for `camera` and `light`.
    #[must_use]
    pub fn new(surface: &NurbsSurface, (u, v): (f64, f64), camera: &Camera, light: &Light) -> Self {
        let domain = surface.domain();
        let u = u.clamp(domain.u.0, domain.u.1);
        let v = v.clamp(domain.v.0, domain.v.1);
        let f = surface.frame(u, v);
        let position = f.point.as_vec3();
        let frame = facing_patch_frame(&f, camera.eye_direction(position));
        let half_vector = blinn_half_vector(light, &camera.view(), position, frame.n);
        Self {
            position,
            frame,
            half_vector,
        }
    }

    /// The same point with its half vector taken from the unit light direction `l` in place
    /// of the light's own: `H = normalize(l + V)`, V toward `camera`'s eye.
    #[must_use]
    pub fn lit_from(self, l: Vec3, camera: &Camera) -> Self {
        Self {
            half_vector: half_vector(l, camera.view().direction(self.position)),
            ..self
        }
    }

    /// The half vector in frame coordinates `((H, du), (H, dv), (H, N))`, as the highlight
    /// operations see it.
    #[must_use]
    pub fn local_half_vector(&self) -> Vec3 {
        self.frame.to_local(self.half_vector)
    }
}
