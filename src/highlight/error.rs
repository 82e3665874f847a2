//! Validation of highlight parameters, with messages that name the parameter, its value and the
//! allowed range.

use thiserror::Error;

/// Why a highlight description cannot be evaluated.
///
/// The messages are meant to be read by the person who wrote the shot: each names the parameter,
/// the value it was given and what it may be.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum HighlightError {
    /// A parameter is NaN or infinite.
    #[error("{param} is {value}, but it must be a finite number")]
    NotFinite {
        /// The parameter, e.g. `"scale delta (δ)"`.
        param: &'static str,
        /// The value given.
        value: f32,
    },
    /// A finite parameter lies outside its range.
    #[error("{param} is {value}, outside the allowed range {range}{hint}")]
    OutOfRange {
        /// The parameter, e.g. `"scale delta (δ)"`.
        param: &'static str,
        /// The value given.
        value: f32,
        /// The allowed range in interval notation, e.g. `"[0, 1]"`.
        range: &'static str,
        /// What the ends of the range mean, starting with `"; "`, or empty.
        hint: &'static str,
    },
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
    /// An error inside a numbered part of a larger description (a layer of an expression, an op
    /// of a stack).
    #[error("{place}: {source}")]
    In {
        /// Where, e.g. `"op 3 (Scale)"` or `"layer 2"`.
        place: String,
        /// What is wrong there.
        source: Box<HighlightError>,
    },
}

impl HighlightError {
    /// Wraps `self` with the place it occurred, e.g. `"op 2 (Split)"`.
    #[must_use]
    pub fn at(self, place: impl Into<String>) -> Self {
        Self::In {
            place: place.into(),
            source: Box::new(self),
        }
    }
}

/// The largest |α|, |β| of a translation and γ of a split. Far below it H is already tangent to
/// the surface to f32 precision; the bound keeps every intermediate vector's squared length
/// finite.
pub const MAX_STEP: f32 = 1e6;

/// The shape of an allowed range; `check` turns a violation into a [`HighlightError`].
#[derive(Clone, Copy, Debug)]
pub(crate) enum Range {
    /// Any finite value.
    Finite,
    /// `[0, ∞)`.
    NonNegative,
    /// `[−MAX_STEP, MAX_STEP]`.
    Step,
    /// `[0, MAX_STEP]`.
    NonNegativeStep,
    /// `(0, ∞)`.
    Positive,
    /// `[0, 1]`.
    Unit,
    /// `(0, 2]`.
    Epsilon,
}

impl Range {
    fn contains(self, x: f32) -> bool {
        match self {
            Range::Finite => true,
            Range::NonNegative => x >= 0.0,
            Range::Step => x.abs() <= MAX_STEP,
            Range::NonNegativeStep => (0.0..=MAX_STEP).contains(&x),
            Range::Positive => x > 0.0,
            Range::Unit => (0.0..=1.0).contains(&x),
            Range::Epsilon => x > 0.0 && x <= 2.0,
        }
    }

    fn notation(self) -> &'static str {
        match self {
            Range::Finite => "(-inf, inf)",
            Range::NonNegative => "[0, inf)",
            Range::Step => "[-1e6, 1e6]",
            Range::NonNegativeStep => "[0, 1e6]",
            Range::Positive => "(0, inf)",
            Range::Unit => "[0, 1]",
            Range::Epsilon => "(0, 2]",
        }
    }
}

/// Checks that `value` is finite and in `range`; `hint` explains the range to the reader
/// (starting with `"; "`, or empty).
pub(crate) fn check(
    param: &'static str,
    value: f32,
    range: Range,
    hint: &'static str,
) -> Result<(), HighlightError> {
    if !value.is_finite() {
        return Err(HighlightError::NotFinite { param, value });
    }
    if !range.contains(value) {
        return Err(HighlightError::OutOfRange {
            param,
            value,
            range: range.notation(),
            hint,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn message_names_parameter_value_and_range() {
        let e = check("scale delta (δ)", 1.5, Range::Unit, "; 0 leaves H alone").unwrap_err();
        let msg = e.at("op 3 (Scale)").to_string();
        assert_eq!(
            msg,
            "op 3 (Scale): scale delta (δ) is 1.5, outside the allowed range [0, 1]; 0 leaves H alone"
        );
    }

    #[test]
    fn non_finite_is_rejected_before_range() {
        let e = check("alpha", f32::NAN, Range::Finite, "").unwrap_err();
        assert!(matches!(e, HighlightError::NotFinite { .. }));
        assert!(e.to_string().contains("must be a finite number"));
        assert!(check("eps", 0.0, Range::Epsilon, "").is_err());
        assert!(check("eps", 2.0, Range::Epsilon, "").is_ok());
        assert!(check("n", 0.0, Range::Positive, "").is_err());
        assert!(check("gamma", 0.0, Range::NonNegative, "").is_ok());
        assert!(check("gamma", -0.1, Range::NonNegative, "").is_err());
        assert_eq!(format!("{MAX_STEP:e}"), "1e6");
        assert!(check("alpha", -1e6, Range::Step, "").is_ok());
        assert!(check("alpha", 1.1e6, Range::Step, "").is_err());
        assert!(check("gamma", 1e6, Range::NonNegativeStep, "").is_ok());
        assert!(check("gamma", -1.0, Range::NonNegativeStep, "").is_err());
    }
}
