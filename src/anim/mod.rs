//! Animation tracks: a value that is either constant or keyed at frames, linear between keys and
//! held before the first and after the last (docs/shot-format.md). Knows nothing of what it
//! animates.

mod rotation;
mod track;

pub use rotation::{axis_at, keyed_rotation, UnitAxis};
#[cfg(test)]
pub(crate) use track::fixtures;
pub use track::{Direction, Interpolate, Key, Keyed, Track, TrackError};
