//! Numerical building blocks the highlight model and the tone share: vectors side by side in
//! lanes, guarded normalization, exponents raised by multiplication where they are integers,
//! the box coverage of a straight edge, a quadratic over a pixel's box, and the distance to a
//! segment.

mod box_coverage;
mod box_quadratic;
mod exponent;
mod lane_count;
mod lanes;
mod normalize;
mod segment;

pub use box_coverage::box_coverage;
pub use box_quadratic::{BoxQuadratic, LevelCrossing};
pub(crate) use exponent::int_pow;
pub use exponent::Exponent;
pub use lane_count::LANES;
pub use lanes::Lanes;
pub(crate) use normalize::{normalize_lanes, normalize_or};
pub use segment::{distance_to_segment, distance_to_segment_f32};
