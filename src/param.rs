//! Numeric parameters checked against their allowed ranges, with messages that name the
//! parameter, its value and the range — for the highlight operations and the X-Toon tone alike.

use thiserror::Error;

/// A parameter that is not finite or lies outside its range.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum ParamError {
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
        /// The parameter, e.g. `"depth r"`.
        param: &'static str,
        /// The value given.
        value: f32,
        /// The allowed range in interval notation, e.g. `"[0, 1]"`.
        range: &'static str,
        /// What the ends of the range mean, starting with `"; "`, or empty.
        hint: &'static str,
    },
}

/// The largest magnitude of a highlight translation (|α|, |β|) or split (γ). Far below it H is
/// already tangent to the surface to f32 precision; the bound keeps every intermediate vector's
/// squared length finite.
pub const MAX_STEP: f32 = 1e6;

/// The largest component of a linear colour: far above any display's white, and small enough
/// that sums of many samples (a 64-sample pixel, blended layers) stay finite in f32.
pub const MAX_COLOUR: f32 = 1e4;

/// Whether `c` is a usable linear colour component: finite, in `[0, MAX_COLOUR]`.
#[must_use]
pub fn is_colour_component(c: f32) -> bool {
    (0.0..=MAX_COLOUR).contains(&c)
}

/// The shape of an allowed range; [`check`] turns a violation into a [`ParamError`].
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
    /// `[0, MAX_COLOUR]`: a linear colour component.
    Colour,
    /// `(0, 2]`: a highlight's ε.
    Epsilon,
    /// `[−MAX_STEP, MAX_STEP]`.
    Step,
    /// `[0, MAX_STEP]`.
    NonNegativeStep,
}

/// The ends of an allowed range as an editor shows them: `min` and `max` (infinite where the
/// range is unbounded on that side) and whether each end is excluded.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Bounds {
    pub min: f32,
    pub max: f32,
    /// The range excludes `min` (ε > 0, n > 0).
    pub min_open: bool,
    /// The range excludes `max`.
    pub max_open: bool,
}

impl Bounds {
    /// Whether `x` lies in the range: finite, and between the ends as they are included.
    #[must_use]
    pub fn contains(self, x: f32) -> bool {
        let above = if self.min_open {
            x > self.min
        } else {
            x >= self.min
        };
        let below = if self.max_open {
            x < self.max
        } else {
            x <= self.max
        };
        x.is_finite() && above && below
    }
}

impl Range {
    /// The range's ends.
    #[must_use]
    pub(crate) fn bounds(self) -> Bounds {
        let (min, max, min_open, max_open) = match self {
            Range::Finite => (f32::NEG_INFINITY, f32::INFINITY, true, true),
            Range::NonNegative => (0.0, f32::INFINITY, false, true),
            Range::Positive => (0.0, f32::INFINITY, true, true),
            Range::AboveOne => (1.0, f32::INFINITY, true, true),
            Range::AtLeastOne => (1.0, f32::INFINITY, false, true),
            Range::Unit => (0.0, 1.0, false, false),
            Range::Colour => (0.0, MAX_COLOUR, false, false),
            Range::Epsilon => (0.0, 2.0, true, false),
            Range::Step => (-MAX_STEP, MAX_STEP, false, false),
            Range::NonNegativeStep => (0.0, MAX_STEP, false, false),
        };
        Bounds {
            min,
            max,
            min_open,
            max_open,
        }
    }

    fn contains(self, x: f32) -> bool {
        match self {
            Range::Finite => true,
            Range::NonNegative => x >= 0.0,
            Range::Positive => x > 0.0,
            Range::AboveOne => x > 1.0,
            Range::AtLeastOne => x >= 1.0,
            Range::Unit => (0.0..=1.0).contains(&x),
            Range::Colour => is_colour_component(x),
            Range::Epsilon => x > 0.0 && x <= 2.0,
            Range::Step => x.abs() <= MAX_STEP,
            Range::NonNegativeStep => (0.0..=MAX_STEP).contains(&x),
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
            Range::Colour => "[0, 1e4]",
            Range::Epsilon => "(0, 2]",
            Range::Step => "[-1e6, 1e6]",
            Range::NonNegativeStep => "[0, 1e6]",
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
) -> Result<(), ParamError> {
    if !value.is_finite() {
        return Err(ParamError::NotFinite { param, value });
    }
    if !range.contains(value) {
        return Err(ParamError::OutOfRange {
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
    fn bounds_contain_what_the_range_does() {
        let ranges = [
            Range::Finite,
            Range::NonNegative,
            Range::Positive,
            Range::AboveOne,
            Range::AtLeastOne,
            Range::Unit,
            Range::Colour,
            Range::Epsilon,
            Range::Step,
            Range::NonNegativeStep,
        ];
        let probes = [
            -2e6, -1e6, -1.0, -1e-9, 0.0, 1e-9, 0.5, 1.0, 1.5, 2.0, 2.5, 1e6, 2e6,
        ];
        for range in ranges {
            for x in probes {
                assert_eq!(
                    range.bounds().contains(x),
                    range.contains(x),
                    "{range:?} at {x}"
                );
            }
        }
    }

    #[test]
    fn message_names_parameter_value_and_range() {
        let e = check("scale delta (δ)", 1.5, Range::Unit, "; 0 leaves H alone").unwrap_err();
        assert_eq!(
            e.to_string(),
            "scale delta (δ) is 1.5, outside the allowed range [0, 1]; 0 leaves H alone"
        );
    }

    #[test]
    fn non_finite_is_rejected_before_range_and_every_range_has_its_ends() {
        let e = check("alpha", f32::NAN, Range::Finite, "").unwrap_err();
        assert!(matches!(e, ParamError::NotFinite { .. }));
        assert!(e.to_string().contains("must be a finite number"));
        for (range, inside, outside) in [
            (Range::NonNegative, 0.0, -0.1),
            (Range::Positive, 1e-30, 0.0),
            (Range::AboveOne, 1.0001, 1.0),
            (Range::AtLeastOne, 1.0, 0.99),
            (Range::Unit, 1.0, -0.1),
            (Range::Epsilon, 2.0, 0.0),
            (Range::Step, -1e6, 1.1e6),
            (Range::NonNegativeStep, 1e6, -1.0),
        ] {
            let at = |x| check("p", x, range, "");
            assert!(at(inside).is_ok(), "{range:?} {inside}");
            assert!(at(outside).is_err(), "{range:?} {outside}");
        }
        assert_eq!(format!("{MAX_STEP:e}"), "1e6");
    }
}
