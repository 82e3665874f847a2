//! Numerical building blocks the highlight model and the tone share: vectors side by side in
//! lanes, guarded normalization, exponents raised by multiplication where they are integers, and
//! the box coverage of a straight edge.

mod box_coverage;
mod exponent;
mod lanes;
mod normalize;

pub use box_coverage::box_coverage;
pub(crate) use exponent::int_pow;
pub use exponent::Exponent;
pub use lanes::{Lanes, LANES};
pub(crate) use normalize::{normalize_lanes, normalize_or};
