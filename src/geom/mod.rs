//! Geometry in f64: knot vectors and B-spline bases, rational surfaces with derivatives, frames,
//! grid evaluation and exact shapes.

mod frame;

pub use frame::Frame;
