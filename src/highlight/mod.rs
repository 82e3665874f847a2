//! Stylized highlights (Anjyo & Hiramitsu 2003; docs/highlights.md): operations on the highlight
//! vector H in a tangent frame, layers, and Boolean post-operations.
//!
//! Pure math over a frame and a few vectors, in f32. A description ([`Op`], [`Layer`], [`Expr`])
//! is generic over its parameter type so that later every number can be an animation track;
//! resolved to `f32` it is validated once by `prepare` into a form evaluated per point
//! ([`PreparedOp`], [`PreparedLayer`], [`PreparedExpr`]). Those evaluate one point per call or,
//! faster, many points per call (`signed_many`, `shape_many`, `eval_many`), applying each op to
//! a chunk of [`LANES`](crate::math::LANES) points held as one array per coordinate.
//!
//! A point is inside a highlight iff `‖N − H'‖² / 2 < ε`, where H' is the op stack applied to the
//! initial H, Blinn's half vector ([`half_vector`]).

mod centre;
mod crossing;
mod designed_light;
mod error;
mod expr;
mod flatten;
mod footprint;
mod frame;
mod half_vector;
mod inside;
mod layer;
mod layer_frame;
mod morph;
mod ops;
mod outline;
mod pin;
mod point_chunk;
mod polygon;
mod shape;
mod shape_map;
mod shape_text;
mod stack;

pub use crate::math::box_coverage;
pub use designed_light::{DesignedLight, HighlightLight, PreparedShadeStack, ShadeStack};
pub use error::HighlightError;
pub(crate) use expr::ChunkScratch;
pub use expr::{Boolean, Expr, PreparedExpr, Shade};
pub use flatten::FLATNESS;
pub use footprint::Footprint;
pub use frame::TangentFrame;
pub use half_vector::{blinn_half_vector, half_vector, virtual_light, Light, View};
pub use inside::{coverage_from_signed, inside, signed_inside};
pub(crate) use layer::LayerScratch;
pub use layer::{Layer, Mask, Paint, PreparedLayer};
pub use layer_frame::{LayerFrame, PreparedFrame, ALONG_TOLERANCE};
pub use morph::{Morph, PreparedMorph};
pub use ops::{Axis, Op, PreparedOp, SquareStyle};
pub use outline::{
    Outline, OutlineError, Segment, MAX_FLATTENED_POINTS, MAX_OUTLINE_SEGMENTS, OUTLINE_BOUND,
};
pub use pin::Pin;
pub(crate) use point_chunk::PointChunk;
pub use polygon::PreparedOutline;
pub use shape::{PreparedShape, Shape};
pub use shape_map::{ShapeMap, SHAPE_MAP_RANGE};
pub use stack::PreparedStack;
