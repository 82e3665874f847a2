//! What a layer's highlight vector is tested against: the ε-disc around N, a drawn outline, or
//! keyed outlines morphing (read from and written to RON in `shape_text`).

use super::error::HighlightError;
use super::morph::{Morph, Prepared, PreparedMorph};
use super::outline::Outline;
use super::polygon::PreparedOutline;

/// The region a layer's `H'` must fall in.
///
/// RON: `Disc` (the default), `Outline([(0.0, 0.12), (0.05, 0.0), Bezier((…), (…), (…)), …])`,
/// or, in a shot, keyed whole outlines `OutlineKeys([(1, [ … ]), (24, [ … ])])`: every key with
/// the same pieces (as many, corners and Béziers in the same places), morphing point by point
/// between keys ([`PreparedMorph`]) and held before the first and after the last, as any track.
#[derive(Clone, Debug, PartialEq)]
pub enum Shape<P = f32> {
    /// `‖N − H'‖²/2 < ε`: the highlight of Anjyo & Hiramitsu 2003.
    Disc,
    /// `t' = ((H', du), (H', dv))` inside the outline, with `(H', N) > 0`.
    Outline(Outline<P>),
    /// Keyed outlines ([`Morph`]): between two keys, inside the outline of their points moved
    /// linearly and wherever both keys are ([`PreparedMorph`]).
    Morph(Morph<P>),
}

// Written out: a derived `Default` would ask `P: Default` of every parameter type.
#[allow(clippy::derivable_impls)]
impl<P> Default for Shape<P> {
    fn default() -> Self {
        Shape::Disc
    }
}

impl<P> Shape<P> {
    /// Whether it is the disc (what a layer that does not say has).
    #[must_use]
    pub fn is_disc(&self) -> bool {
        matches!(self, Shape::Disc)
    }

    /// The same shape with every coordinate mapped through `f`.
    #[must_use]
    pub fn map<Q>(&self, f: impl FnMut(&P) -> Q) -> Shape<Q> {
        match self {
            Shape::Disc => Shape::Disc,
            Shape::Outline(o) => Shape::Outline(o.map(f)),
            Shape::Morph(m) => Shape::Morph(m.map(f)),
        }
    }
}

/// A shape made ready to evaluate ([`Shape::prepare`]).
#[derive(Clone, Debug, PartialEq)]
pub enum PreparedShape {
    /// The ε-disc: the layer's `s = ε − ‖N − H'‖²/2`.
    Disc,
    /// A drawn outline's polygon, or keyed outlines on a key.
    Outline(PreparedOutline),
    /// Keyed outlines strictly between two keys.
    Morph(PreparedMorph),
}

impl Shape<f32> {
    /// Checks the shape: the disc always passes, an outline as [`Outline::validate`] says,
    /// keyed outlines as [`Morph::validate`] (the keys at or around the position).
    pub fn validate(&self) -> Result<(), HighlightError> {
        match self {
            Shape::Disc => Ok(()),
            Shape::Outline(o) => Ok(o.validate()?),
            Shape::Morph(m) => Ok(m.validate()?),
        }
    }

    /// The shape made ready to evaluate, an outline's values checked but not whether it
    /// crosses itself ([`Outline::prepare`]).
    pub fn prepare(&self) -> Result<PreparedShape, HighlightError> {
        match self {
            Shape::Disc => Ok(PreparedShape::Disc),
            Shape::Outline(o) => Ok(PreparedShape::Outline(o.prepare()?)),
            Shape::Morph(m) => Ok(match m.prepare()? {
                Prepared::Key(o) => PreparedShape::Outline(o),
                Prepared::Between(m) => PreparedShape::Morph(m),
            }),
        }
    }
}
