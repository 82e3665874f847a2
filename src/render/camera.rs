//! Cameras: where the eye is, where it looks, and how it projects.

use glam::{DVec2, DVec3, Mat4, Vec3};
use serde::Deserialize;

use super::RenderError;
use crate::highlight::View;

/// How a camera projects.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Projection {
    /// A pinhole camera with a vertical field of view in degrees, in (0, 180).
    Perspective { fov_y_degrees: f32 },
    /// A parallel projection showing `height` world units vertically.
    Orthographic { height: f32 },
}

/// A camera at `eye` looking at `target`, with `up` fixing the roll. Right-handed: the view looks
/// down −z of its own space, x to the right, y up.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Camera {
    pub eye: Vec3,
    pub target: Vec3,
    pub up: Vec3,
    pub projection: Projection,
    /// Distance to the near clipping plane (> 0).
    pub near: f32,
    /// Distance to the far clipping plane (> near).
    pub far: f32,
}

impl Camera {
    /// Checks that the camera defines a view: finite values, eye ≠ target, `up` not along the
    /// line of sight, `0 < near < far`, a field of view in (0°, 180°) or a positive height.
    pub fn validate(&self) -> Result<(), RenderError> {
        let bad = |what: String| Err(RenderError::Camera(what));
        if !(self.eye.is_finite() && self.target.is_finite() && self.up.is_finite()) {
            return bad("eye, target and up must be finite".into());
        }
        let forward = self.target - self.eye;
        if forward.length_squared() == 0.0 {
            return bad("eye and target are the same point".into());
        }
        if forward.normalize().cross(self.up).length_squared() < 1e-10 {
            return bad("up is parallel to the line of sight; choose an up across it".into());
        }
        if !(self.near > 0.0 && self.far > self.near && self.far.is_finite()) {
            return bad(format!(
                "near and far must satisfy 0 < near < far, got near {} and far {}",
                self.near, self.far
            ));
        }
        match self.projection {
            Projection::Perspective { fov_y_degrees }
                if !(fov_y_degrees > 0.0 && fov_y_degrees < 180.0) =>
            {
                bad(format!(
                    "fov_y_degrees must be in (0, 180), got {fov_y_degrees}"
                ))
            }
            Projection::Orthographic { height } if !(height > 0.0 && height.is_finite()) => bad(
                format!("orthographic height must be greater than 0, got {height}"),
            ),
            _ => Ok(()),
        }
    }

    /// The world-to-view matrix (`look_at_rh`).
    pub fn view_matrix(&self) -> Mat4 {
        Mat4::look_at_rh(self.eye, self.target, self.up)
    }

    /// The view-to-clip matrix for an image of the given aspect (width / height); depth maps to
    /// [0, 1] from near to far.
    pub fn projection_matrix(&self, aspect: f32) -> Mat4 {
        match self.projection {
            Projection::Perspective { fov_y_degrees } => {
                Mat4::perspective_rh(fov_y_degrees.to_radians(), aspect, self.near, self.far)
            }
            Projection::Orthographic { height } => {
                let (h, w) = (0.5 * height, 0.5 * height * aspect);
                Mat4::orthographic_rh(-w, w, -h, h, self.near, self.far)
            }
        }
    }

    /// World to clip space.
    pub fn view_projection(&self, aspect: f32) -> Mat4 {
        self.projection_matrix(aspect) * self.view_matrix()
    }

    /// The unit direction the camera looks along.
    pub fn forward(&self) -> Vec3 {
        (self.target - self.eye).normalize()
    }

    /// A vector from `point` toward the eye, of any length: `eye − point` under perspective,
    /// `eye − target` (the reverse line of sight) under orthographic projection. Enough to tell
    /// which side of a surface the eye is on, without a square root.
    #[inline]
    #[must_use]
    pub fn eye_direction(&self, point: Vec3) -> Vec3 {
        match self.projection {
            Projection::Perspective { .. } => self.eye - point,
            Projection::Orthographic { .. } => self.eye - self.target,
        }
    }

    /// The ray through the image position `(x, y)` of a `width × height` image, in pixel
    /// units with pixel `(i, j)`'s centre at `(i + 0.5, j + 0.5)`: the points the inverse
    /// view-projection maps to the near and far planes there, as origin and direction (the
    /// refined frames' rays, [`NurbsSurface::try_refine_on_ray`]).
    ///
    /// [`NurbsSurface::try_refine_on_ray`]: crate::geom::NurbsSurface::try_refine_on_ray
    #[must_use]
    pub fn ray_through(&self, (x, y): (f64, f64), (width, height): (u32, u32)) -> (DVec3, DVec3) {
        let inverse = self
            .view_projection(width as f32 / height as f32)
            .as_dmat4()
            .inverse();
        let ndc = DVec2::new(
            2.0 * x / f64::from(width) - 1.0,
            1.0 - 2.0 * y / f64::from(height),
        );
        let near = inverse.project_point3(ndc.extend(0.0));
        let far = inverse.project_point3(ndc.extend(1.0));
        (near, far - near)
    }

    /// The viewer as the highlight model sees it: V and its fallback, defined once in
    /// [`View::direction`].
    #[must_use]
    pub fn view(&self) -> View {
        let towards = -self.forward();
        match self.projection {
            Projection::Perspective { .. } => View::Perspective {
                eye: self.eye,
                towards,
            },
            Projection::Orthographic { .. } => View::Orthographic { towards },
        }
    }

    /// The unit vector V from `point` toward the eye: [`View::direction`] of [`Camera::view`],
    /// per point under perspective, the reverse line of sight under orthographic projection
    /// and where the eye sits on the point.
    #[must_use]
    pub fn toward_eye(&self, point: Vec3) -> Vec3 {
        self.view().direction(point)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera(projection: Projection) -> Camera {
        Camera {
            eye: Vec3::new(0.0, -5.0, 0.0),
            target: Vec3::ZERO,
            up: Vec3::Z,
            projection,
            near: 0.1,
            far: 100.0,
        }
    }

    #[test]
    fn target_projects_to_the_image_centre_and_up_to_the_top() {
        for projection in [
            Projection::Perspective {
                fov_y_degrees: 40.0,
            },
            Projection::Orthographic { height: 4.0 },
        ] {
            let m = camera(projection).view_projection(1.5);
            let centre = m.project_point3(Vec3::ZERO);
            assert!(centre.x.abs() < 1e-6 && centre.y.abs() < 1e-6);
            assert!((0.0..1.0).contains(&centre.z));
            let above = m.project_point3(Vec3::new(0.0, 0.0, 1.0));
            assert!(above.y > 0.1 && above.x.abs() < 1e-6);
            let right = m.project_point3(Vec3::new(1.0, 0.0, 0.0));
            assert!(right.x > 0.1);
        }
    }

    #[test]
    fn view_vectors_point_to_the_eye() {
        let p = Vec3::new(1.0, 0.0, 0.5);
        let persp = camera(Projection::Perspective {
            fov_y_degrees: 40.0,
        });
        assert!((persp.toward_eye(p) - (persp.eye - p).normalize()).length() < 1e-6);
        let ortho = camera(Projection::Orthographic { height: 4.0 });
        assert!((ortho.toward_eye(p) - Vec3::NEG_Y).length() < 1e-6);
        // The eye on the point: the reverse line of sight, as under orthographic projection.
        assert_eq!(persp.toward_eye(persp.eye), -persp.forward());
        // The unnormalized direction points the same way.
        for c in [persp, ortho] {
            let d = c.eye_direction(p);
            assert!((d.normalize() - c.toward_eye(p)).length() < 1e-6, "{d}");
        }
    }

    #[test]
    fn invalid_cameras_are_refused_with_a_reason() {
        let mut c = camera(Projection::Perspective {
            fov_y_degrees: 40.0,
        });
        c.up = Vec3::Y;
        assert!(c
            .validate()
            .unwrap_err()
            .to_string()
            .contains("up is parallel"));
        let mut c = camera(Projection::Perspective {
            fov_y_degrees: 180.0,
        });
        assert!(c.validate().is_err());
        c.projection = Projection::Orthographic { height: 2.0 };
        c.near = 0.0;
        assert!(c.validate().unwrap_err().to_string().contains("near"));
    }
}
