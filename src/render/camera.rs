//! Cameras: where the eye is, where it looks, and how it projects.

use glam::{DVec2, DVec3, Mat4, Vec3};
use serde::Deserialize;

use super::RenderError;
use crate::geom::MAX_COORDINATE;
use crate::highlight::View;

/// How a camera projects.
#[derive(Clone, Copy, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Projection {
    /// A pinhole camera with a vertical field of view in degrees, in [0.001, 179.9] ([`Camera::validate`]).
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

/// The nearest a near clipping plane may be: nearer, the depth range of f32 runs out.
pub const MIN_NEAR: f32 = 1e-6;
/// The farthest a far clipping plane may be.
pub const MAX_FAR: f32 = 1e9;
/// The narrowest vertical field of view, in degrees.
pub const MIN_FOV_DEGREES: f32 = 0.001;
/// The widest vertical field of view, in degrees (at 180° the image would be infinitely wide).
pub const MAX_FOV_DEGREES: f32 = 179.9;
/// The tallest orthographic view: twice the largest coordinate a model may have.
pub const MAX_HEIGHT: f32 = 2e6;

impl Camera {
    /// Checks that the camera defines a view: eye, target and up finite and within
    /// ±[`MAX_COORDINATE`], eye ≠ target, `up` not along the line of sight,
    /// `MIN_NEAR ≤ near < far ≤ MAX_FAR`, a field of view in
    /// `[MIN_FOV_DEGREES, MAX_FOV_DEGREES]` or a height in `(0, MAX_HEIGHT]`: ranges that keep
    /// the f32 projection finite.
    pub fn validate(&self) -> Result<(), RenderError> {
        let bad = |what: String| Err(RenderError::Camera(what));
        let placed = |v: Vec3| v.is_finite() && v.abs().max_element() <= MAX_COORDINATE as f32;
        if !(placed(self.eye) && placed(self.target) && placed(self.up)) {
            return bad(format!(
                "eye, target and up must be finite, each coordinate within ±{MAX_COORDINATE:e}"
            ));
        }
        let forward = self.target - self.eye;
        if forward.length_squared() == 0.0 {
            return bad("eye and target are the same point".into());
        }
        if forward.normalize().cross(self.up).length_squared() < 1e-10 {
            return bad("up is parallel to the line of sight; choose an up across it".into());
        }
        if !(self.near >= MIN_NEAR && self.far > self.near && self.far <= MAX_FAR) {
            return bad(format!(
                "near and far must satisfy {MIN_NEAR:e} ≤ near < far ≤ {MAX_FAR:e}, got near {} and far {}",
                self.near, self.far
            ));
        }
        match self.projection {
            Projection::Perspective { fov_y_degrees }
                if !(MIN_FOV_DEGREES..=MAX_FOV_DEGREES).contains(&fov_y_degrees) =>
            {
                bad(format!(
                    "fov_y_degrees must be in [{MIN_FOV_DEGREES}, {MAX_FOV_DEGREES}], got {fov_y_degrees}"
                ))
            }
            Projection::Orthographic { height } if !(height > 0.0 && height <= MAX_HEIGHT) => {
                bad(format!(
                    "orthographic height must be in (0, {MAX_HEIGHT:e}], got {height}"
                ))
            }
            Projection::Perspective { .. } | Projection::Orthographic { .. } => Ok(()),
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

/// A camera at `eye` looking at `target`, `up` up, through a 40° perspective: the unit tests'.
#[cfg(test)]
#[must_use]
pub(crate) fn looking(eye: Vec3, target: Vec3, up: Vec3) -> Camera {
    Camera {
        eye,
        target,
        up,
        projection: Projection::Perspective {
            fov_y_degrees: 40.0,
        },
        near: 0.1,
        far: 100.0,
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
