//! The view both frame benchmarks render the teapot from, at 1280×720.

use glam::Vec3;
use glint::render::{Camera, Projection};

pub const WIDTH: u32 = 1280;
pub const HEIGHT: u32 = 720;

/// The teapot from the front right, above, filling most of the frame.
pub fn camera() -> Camera {
    Camera {
        eye: Vec3::new(5.5, -7.0, 4.5),
        target: Vec3::new(0.0, 0.0, 1.4),
        up: Vec3::Z,
        projection: Projection::Perspective {
            fov_y_degrees: 30.0,
        },
        near: 0.1,
        far: 100.0,
    }
}
