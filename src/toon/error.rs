//! Validation of X-Toon parameters, with messages that name the parameter, its value and the
//! allowed range.

use thiserror::Error;

use super::shape::Abstraction;

/// Why an X-Toon description, texture or abstracted shape cannot be used.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum XToonError {
    /// A parameter is NaN or infinite.
    #[error("{param} is {value}, but it must be a finite number")]
    NotFinite {
        /// The parameter, e.g. `"depth z_min"`.
        param: &'static str,
        /// The value given.
        value: f32,
    },
    /// A finite parameter lies outside its range.
    #[error("{param} is {value}, outside the allowed range {range}{hint}")]
    OutOfRange {
        /// The parameter, e.g. `"depth r"`.
        param: &'static str,
        /// The value given.
        value: f32,
        /// The allowed range in interval notation, e.g. `"(1, inf)"`.
        range: &'static str,
        /// What the ends of the range mean, starting with `"; "`, or empty.
        hint: &'static str,
    },
    /// A smoothed shape with an iteration count outside its range.
    #[error(
        "smoothing iterations is {iterations}, outside the allowed range [1, {MAX_ITERATIONS}]; \
         each iteration moves every control point halfway to the mean of its neighbours"
    )]
    Iterations {
        /// The count given.
        iterations: u32,
    },
    /// A 2D toon texture that cannot be sampled.
    #[error("toon texture: {0}")]
    Texture(String),
    /// A model whose abstracted shape cannot be built.
    #[error("abstracted shape: {0}")]
    Shape(String),
    /// A shape detail prepared with a shape built for another abstraction.
    #[error("the shape detail asks for {wanted:?}, but the shape given was built for {built:?}")]
    ShapeMismatch {
        /// The abstraction the description names.
        wanted: Abstraction,
        /// The abstraction the built shape is of.
        built: Abstraction,
    },
}

/// The most smoothing iterations of [`Abstraction::Smoothed`].
pub const MAX_ITERATIONS: u32 = 1000;

/// The shape of an allowed range; [`check`] turns a violation into an [`XToonError`].
#[derive(Clone, Copy, Debug)]
pub(crate) enum Range {
    /// Any finite value.
    Finite,
    /// `[0, ∞)`.
    NonNegative,
    /// `(0, ∞)`.
    Positive,
    /// `(1, ∞)`.
    AboveOne,
    /// `[1, ∞)`.
    AtLeastOne,
    /// `[0, 1]`.
    Unit,
}

impl Range {
    fn contains(self, x: f32) -> bool {
        match self {
            Range::Finite => true,
            Range::NonNegative => x >= 0.0,
            Range::Positive => x > 0.0,
            Range::AboveOne => x > 1.0,
            Range::AtLeastOne => x >= 1.0,
            Range::Unit => (0.0..=1.0).contains(&x),
        }
    }

    fn notation(self) -> &'static str {
        match self {
            Range::Finite => "(-inf, inf)",
            Range::NonNegative => "[0, inf)",
            Range::Positive => "(0, inf)",
            Range::AboveOne => "(1, inf)",
            Range::AtLeastOne => "[1, inf)",
            Range::Unit => "[0, 1]",
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
) -> Result<(), XToonError> {
    if !value.is_finite() {
        return Err(XToonError::NotFinite { param, value });
    }
    if !range.contains(value) {
        return Err(XToonError::OutOfRange {
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
        let e = check("depth r", 1.0, Range::AboveOne, "; the far end is r·z_min").unwrap_err();
        assert_eq!(
            e.to_string(),
            "depth r is 1, outside the allowed range (1, inf); the far end is r·z_min"
        );
        let e = check("depth z_min", f32::NAN, Range::Positive, "").unwrap_err();
        assert!(matches!(e, XToonError::NotFinite { .. }));
        assert!(check("s", 1.0, Range::AtLeastOne, "").is_ok());
        assert!(check("s", 0.99, Range::AtLeastOne, "").is_err());
        assert!(check("r", 0.0, Range::NonNegative, "").is_ok());
        assert!(check("z", 0.0, Range::Positive, "").is_err());
        assert!(check("w", 1.0, Range::Unit, "").is_ok());
        assert!(check("w", -0.1, Range::Unit, "").is_err());
        assert!(check("c", -1e30, Range::Finite, "").is_ok());
    }
}
