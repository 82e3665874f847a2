//! Geometry in f64: knot vectors and B-spline bases, rational surfaces with derivatives, frames,
//! grid evaluation, exact shapes, and trims in the (u, v) plane.

mod edges;
mod error;
mod fixed_degree;
mod frame;
mod grid;
pub mod knots;
mod library;
mod on_ray;
pub mod shapes;
mod surface;
mod trim;
mod trim_curve;

pub use edges::Edge;
pub use error::GeomError;
pub use frame::Frame;
pub use grid::GridEvaluator;
pub use knots::{KnotVector, MAX_DEGREE};
pub use library::{NamedPatch, PatchGroup, PatchLibrary, PatchNotFound};
pub use on_ray::{RaySearch, ALL_EVALUATIONS, REFINE_STEPS};
pub use surface::{Domain, NurbsSurface, SurfaceDerivs, MAX_COORDINATE, MAX_WEIGHT, MIN_WEIGHT};
pub use trim::{Region, Trim, TrimError, MAX_TRIM_SEGMENTS, MOST_CELLS_SEARCHED};
pub use trim_curve::TrimCurve;
