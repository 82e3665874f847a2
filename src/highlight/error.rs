//! Validation of highlight parameters, with messages that name the parameter, its value and the
//! allowed range.

use thiserror::Error;

use super::outline::OutlineError;
use crate::param::ParamError;

/// Why a highlight description cannot be evaluated.
///
/// The messages are meant to be read by the person who wrote the shot: each names the parameter,
/// the value it was given and what it may be.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum HighlightError {
    /// A parameter that is not finite or outside its range.
    #[error(transparent)]
    Param(#[from] ParamError),
    /// A drawn outline that cannot be drawn.
    #[error("outline: {0}")]
    Outline(#[from] OutlineError),
    /// A mask rectangle whose lower bound is not below its upper bound.
    #[error(
        "mask {axis} range is ({min}, {max}), but the first value must be less than the second; \
         write the smaller parameter value first"
    )]
    MaskUnordered {
        /// `"u"` or `"v"`.
        axis: &'static str,
        /// The first (lower) bound given.
        min: f32,
        /// The second (upper) bound given.
        max: f32,
    },
    /// A layer frame's axis that is zero, or too small or large to normalize in f32.
    #[error(
        "frame axis is ({x}, {y}, {z}), which has no direction; give a non-zero vector such as \
         (1.0, 0.0, 0.0), the direction the layer's du follows"
    )]
    AxisWithoutDirection {
        /// The axis's x component as given.
        x: f32,
        /// Its y component.
        y: f32,
        /// Its z component.
        z: f32,
    },
    /// A highlight placed on a point, in a stack with no translation to place it with.
    #[error(
        "the stack has no Translate to place the highlight with; add \
         `Translate(alpha: 0.0, beta: 0.0)` where the highlight should be moved"
    )]
    NoTranslation,
    /// A pinned layer prepared before its translation was solved for its point.
    #[error(
        "the layer is pinned to \"{patch}\", and its translation must be solved for that point \
         before it is drawn (Layer::centred_on)"
    )]
    Unresolved {
        /// The pin's patch as written.
        patch: String,
    },
    /// An error inside a numbered part of a larger description (a layer of an expression, an op
    /// of a stack).
    #[error("{place}: {source}")]
    In {
        /// Where, as a parameter path names it, e.g. `"stack[2] (Scale)"` or `"layers[1]"`.
        place: String,
        /// What is wrong there.
        source: Box<HighlightError>,
    },
}

impl HighlightError {
    /// Wraps `self` with the place it occurred, e.g. `"stack[1] (Split)"`.
    #[must_use]
    pub fn at(self, place: impl Into<String>) -> Self {
        Self::In {
            place: place.into(),
            source: Box::new(self),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::param::{check, Range};

    #[test]
    fn a_place_prefixes_the_parameter_message() {
        let e = HighlightError::from(
            check("scale delta (δ)", 1.5, Range::Unit, "; 0 leaves H alone").unwrap_err(),
        );
        assert_eq!(
            e.at("stack[2] (Scale)").to_string(),
            "stack[2] (Scale): scale delta (δ) is 1.5, outside the allowed range [0, 1]; 0 leaves H alone"
        );
    }
}
