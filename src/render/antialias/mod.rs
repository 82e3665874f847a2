//! [`Stage::Supersample`](super::Stage::Supersample) under adaptive anti-aliasing: which pixels of
//! the one-sample image more samples could change, and those pixels drawn again at K × K
//! samples, from rasterized tiles or from the surface points around them.

mod contrast;
mod dilate;
mod near_border;
mod open_side;
mod resolved;
mod seeded;
mod supersample;
mod window;

pub(super) use supersample::{supersample, SupersampleInput};
