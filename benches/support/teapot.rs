//! The view both frame benchmarks render the teapot from, at 1280×720.

use glam::Vec3;
use glint::highlight::{Axis, Op, SquareStyle};
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

/// The 5-op highlight stack the frame benchmarks put on every patch: translate, rotate, scale
/// along u, split and square.
#[allow(dead_code)] // not every benchmark draws highlights
pub fn five_op_stack() -> Vec<Op> {
    vec![
        Op::Translate {
            alpha: 0.1,
            beta: 0.05,
        },
        Op::Rotate { degrees: 20.0 },
        Op::Scale {
            delta: 0.5,
            axis: Axis::U,
        },
        Op::Split {
            gamma_u: 0.05,
            gamma_v: 0.0,
        },
        Op::Square {
            sigma: 0.2,
            n: 2.0,
            style: SquareStyle::Tangent,
        },
    ]
}
