//! Tone: how bright a surface is drawn from `n·l`, as cel bands.

mod cel;

pub use cel::{CelRamp, ToneError};
