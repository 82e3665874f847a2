//! Why a surface description was rejected.

use thiserror::Error;

/// A surface description glint cannot evaluate. Each message names the offending value and what
/// would be accepted.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum GeomError {
    #[error("degree {degree} is not supported: use a degree from 1 to {max}", max = super::knots::MAX_DEGREE)]
    Degree { degree: usize },
    #[error("degree {degree} needs at least {} control points in that direction, found {count}", degree + 1)]
    TooFewControlPoints { degree: usize, count: usize },
    #[error("{found} knots given, but degree {degree} with {count} control points needs {expected} (control points + degree + 1)")]
    KnotCount {
        found: usize,
        expected: usize,
        degree: usize,
        count: usize,
    },
    #[error("knot {index} is not a finite number")]
    KnotNotFinite { index: usize },
    #[error("knots must not decrease: knot {index} is {value} after {previous}")]
    KnotsDecreasing {
        index: usize,
        value: f64,
        previous: f64,
    },
    #[error("interior knot {value} is repeated {multiplicity} times; degree {degree} allows at most {degree} (more would tear the surface)")]
    KnotMultiplicity {
        value: f64,
        multiplicity: usize,
        degree: usize,
    },
    #[error("the knots give an empty parameter domain [{start}, {end}]")]
    EmptyDomain { start: f64, end: f64 },
    #[error("control net is {rows} rows of {columns}, expected {expected_rows} rows (u) of {expected_columns} points (v)")]
    NetSize {
        rows: usize,
        columns: usize,
        expected_rows: usize,
        expected_columns: usize,
    },
    #[error("control point [{i}][{j}] is not finite, or has a coordinate beyond ±1e6 (the largest glint draws)")]
    PointNotFinite { i: usize, j: usize },
    #[error("weight [{i}][{j}] is {weight}; weights must lie in [1e-6, 1e6]")]
    Weight { i: usize, j: usize, weight: f64 },
    #[error("a torus needs minor_radius < major_radius, got minor_radius {minor} with major_radius {major}")]
    TorusTube { major: f64, minor: f64 },
    #[error("{direction} direction: {source}")]
    Along {
        direction: &'static str,
        source: Box<GeomError>,
    },
    #[error("{name} must be greater than 0 and at most 1e6, got {value}")]
    NotPositive { name: &'static str, value: f64 },
}

impl GeomError {
    /// This error, said of the knot vector or degree along `direction` ("u" or "v").
    pub fn along(self, direction: &'static str) -> Self {
        GeomError::Along {
            direction,
            source: Box::new(self),
        }
    }
}
