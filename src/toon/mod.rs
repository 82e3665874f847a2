//! Tone (docs/xtoon.md): how bright and in which colour a surface is drawn — cel bands over `n·l`,
//! or X-Toon (Barla, Thollot & Markosian 2006): a 2D toon texture over `(n·l, D)` with the
//! detail D from a detail map, and shape detail that blends the shading normal toward an
//! abstracted shape.
//!
//! Pure math over a point, its normal and a few vectors. As in `highlight`, an X-Toon
//! description ([`XToon`], [`DetailMap`], [`ShapeDetail`]) is generic over its parameter type so
//! that every number can be an animation track; resolved to `f32` it is validated by `prepare`
//! into the form evaluated per point ([`PreparedXToon`]), placed in the frame's view once
//! ([`PreparedXToon::in_view`]). What needs the model's points — its principal box, its
//! smoothed control net — is built once per model ([`Abstraction::build`]).

mod abstraction;
mod cel;
mod detail;
mod error;
mod grid;
mod normal_average;
mod point_run;
mod shape;
mod smooth;
mod texture;
pub mod texture_families;
mod xtoon;

pub use abstraction::{Abstraction, MAX_ITERATIONS};
pub use cel::{CelRamp, ToneError};
pub use detail::{DetailMap, PreparedDetail, ViewDetail};
pub use error::XToonError;
pub(crate) use point_run::PointRun;
pub use shape::{AbstractShape, HighlightFrame, PreparedShape, PrincipalBox, ShapeDetail};
pub use smooth::SmoothedNormals;
pub use texture::{ToonTexture, MAX_TEXTURE_SIDE};
pub use xtoon::{PreparedXToon, ViewXToon, XToon};
