//! How many vectors are worked on side by side.

/// The most vectors [`Lanes`](super::Lanes) holds, and how many `normalize_lanes` works on at
/// once.
pub const LANES: usize = 64;
