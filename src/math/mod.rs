//! Numerical building blocks the highlight model and the tone share: vectors side by side in
//! lanes, guarded normalization, and exponents raised by multiplication where they are integers.

mod exponent;
mod lanes;
mod normalize;

pub(crate) use exponent::int_pow;
pub use exponent::Exponent;
pub use lanes::{Lanes, LANES};
pub(crate) use normalize::{normalize_lanes, normalize_or};
