//! A drawn outline: a closed curve of corners and cubic Bézier segments in the tangent
//! coordinates of the highlight vector, checked and flattened to the polygon it encloses.

use glam::DVec2;
use thiserror::Error;

use super::crossing::first_crossing;
use super::flatten::{flatten_cubic, pieces, FLATNESS};
use super::polygon::{polygon_area, PreparedOutline};

/// The largest `|t'|` a point or control point of an outline may have. t' is the tangent part
/// of a unit vector, so `|t'| < 1`; the margin keeps the outline off the tangent plane, where
/// `(H', N) = 0` and t' stops telling H' apart. The bound is a disc, which is convex: a morph
/// between two outlines within it, and every Bézier (inside its control polygon), stays within
/// it too.
pub const OUTLINE_BOUND: f32 = 0.99;

/// The most segments (corners and Béziers) an outline may be written with.
pub const MAX_OUTLINE_SEGMENTS: usize = 1024;

/// The most points the flattened polygon may have: each one costs every shaded point a distance
/// to one more edge.
pub const MAX_FLATTENED_POINTS: usize = 4096;

/// One piece of an outline, from the end of the piece before it (the last piece's end, for the
/// first) to its own end.
///
/// RON: a corner is its point `(x, y)`, a Bézier `Bezier((x1, y1), (x2, y2), (x, y))`: controls,
/// then end.
#[derive(Clone, Debug, PartialEq)]
pub enum Segment<P = f32> {
    /// A straight line to the corner `[x, y]`.
    Corner([P; 2]),
    /// A cubic Bézier with controls `[0]` and `[1]` to the end point `[2]`.
    Bezier([[P; 2]; 3]),
}

/// A closed curve in the tangent coordinates `t' = ((H', du), (H', dv))` of the transformed
/// highlight vector (docs/highlights.md, "Drawn outlines"): the highlight is where t' lies
/// inside it.
#[derive(Clone, Debug, PartialEq)]
pub struct Outline<P = f32> {
    /// The pieces in order; the curve closes from the last piece's end to the first's start.
    pub segments: Vec<Segment<P>>,
}

/// An outline that cannot be drawn.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum OutlineError {
    /// Fewer than three (distinct) points.
    #[error(
        "the outline needs at least 3 distinct points to enclose a region, and it has {count}"
    )]
    TooFew {
        /// Points written (corners and Bézier ends).
        count: usize,
    },
    /// More pieces than [`MAX_OUTLINE_SEGMENTS`].
    #[error("the outline has {count} points, more than the {MAX_OUTLINE_SEGMENTS} allowed")]
    TooMany {
        /// Points written.
        count: usize,
    },
    /// A coordinate that is NaN or infinite.
    #[error(
        "point {point} of the outline has the coordinate {value}, which is not a finite number"
    )]
    NotFinite {
        /// 1-based index of the piece.
        point: usize,
        /// The coordinate.
        value: f32,
    },
    /// A point or control point outside the disc `|t'| ≤ OUTLINE_BOUND`.
    #[error(
        "point {point} of the outline is ({x}, {y}), {length} from the centre, outside the \
         allowed |t'| ≤ {OUTLINE_BOUND}: t' is the tangent part of a unit vector (the disc of ε \
         has radius √(1 − (1 − ε)²))"
    )]
    OutOfBound {
        /// 1-based index of the piece.
        point: usize,
        /// The point's t'.
        x: f32,
        /// Its second component.
        y: f32,
        /// Its length.
        length: f32,
    },
    /// Bézier segments flattened to more than [`MAX_FLATTENED_POINTS`].
    #[error(
        "the outline's Bézier segments flatten to {count} points, more than the \
         {MAX_FLATTENED_POINTS} allowed; use fewer or gentler curves"
    )]
    TooFine {
        /// Points after flattening.
        count: usize,
    },
    /// The flattened outline crosses or touches itself.
    #[error(
        "the outline crosses itself near ({x:.4}, {y:.4}), between the pieces ending at point \
         {first} and point {second}; an outline must be a simple closed curve"
    )]
    Crossing {
        /// 1-based index of the piece one crossing edge belongs to.
        first: usize,
        /// The other one.
        second: usize,
        /// Where they meet.
        x: f64,
        /// Its second coordinate.
        y: f64,
    },
    /// A polygon of no area.
    #[error("the outline encloses no area")]
    NoArea,
}

impl<P> Segment<P> {
    /// The same piece with every coordinate mapped through `f`, controls before the end.
    #[must_use]
    pub fn map<Q>(&self, f: &mut impl FnMut(&P) -> Q) -> Segment<Q> {
        let mut pair = |p: &[P; 2]| [f(&p[0]), f(&p[1])];
        match self {
            Segment::Corner(p) => Segment::Corner(pair(p)),
            Segment::Bezier([c1, c2, end]) => Segment::Bezier([pair(c1), pair(c2), pair(end)]),
        }
    }

    /// Whether two pieces are of the same kind (what keys must share to morph point by point).
    #[must_use]
    pub fn same_kind<Q>(&self, other: &Segment<Q>) -> bool {
        matches!(
            (self, other),
            (Segment::Corner(_), Segment::Corner(_)) | (Segment::Bezier(_), Segment::Bezier(_))
        )
    }
}

impl<P> Outline<P> {
    /// The same outline with every coordinate mapped through `f`, piece by piece.
    #[must_use]
    pub fn map<Q>(&self, mut f: impl FnMut(&P) -> Q) -> Outline<Q> {
        Outline {
            segments: self.segments.iter().map(|s| s.map(&mut f)).collect(),
        }
    }
}

impl Segment<f32> {
    /// The piece's points as written: the controls then the end for a Bézier.
    fn points(&self) -> Vec<[f32; 2]> {
        match self {
            Segment::Corner(p) => vec![*p],
            Segment::Bezier(p) => p.to_vec(),
        }
    }

    /// Its end point.
    fn end(&self) -> DVec2 {
        let [x, y] = match self {
            Segment::Corner(p) => *p,
            Segment::Bezier([_, _, end]) => *end,
        };
        DVec2::new(f64::from(x), f64::from(y))
    }
}

/// `[x, y]` as a vector.
fn vector([x, y]: [f32; 2]) -> DVec2 {
    DVec2::new(f64::from(x), f64::from(y))
}

impl Outline<f32> {
    /// The outline's values checked and flattened: at least 3 and at most
    /// [`MAX_OUTLINE_SEGMENTS`] pieces, every coordinate finite, every point and control point
    /// within `|t'| ≤ OUTLINE_BOUND`, at most [`MAX_FLATTENED_POINTS`] after flattening. These
    /// hold along a morph once they hold at its keys. Returns the polygon — each corner, and
    /// each Bézier flattened to within `FLATNESS × d` (d the diagonal of the bounding box of
    /// every point written), consecutive repeats dropped — with, for each point, the 0-based
    /// piece it belongs to, and `d²`.
    fn flattened(&self) -> Result<(Vec<DVec2>, Vec<usize>, f64), OutlineError> {
        let count = self.segments.len();
        if count < 3 {
            return Err(OutlineError::TooFew { count });
        }
        if count > MAX_OUTLINE_SEGMENTS {
            return Err(OutlineError::TooMany { count });
        }
        let (mut low, mut high) = (DVec2::INFINITY, DVec2::NEG_INFINITY);
        for (k, segment) in self.segments.iter().enumerate() {
            for [x, y] in segment.points() {
                if let Some(value) = [x, y].into_iter().find(|v| !v.is_finite()) {
                    return Err(OutlineError::NotFinite {
                        point: k + 1,
                        value,
                    });
                }
                let length = f64::from(x).hypot(f64::from(y));
                if length > f64::from(OUTLINE_BOUND) {
                    return Err(OutlineError::OutOfBound {
                        point: k + 1,
                        x,
                        y,
                        length: length as f32,
                    });
                }
                low = low.min(vector([x, y]));
                high = high.max(vector([x, y]));
            }
        }
        let tolerance = FLATNESS * (high - low).length();
        let (mut points, mut owner) = (Vec::new(), Vec::new());
        let mut start = self.segments[count - 1].end();
        for (k, segment) in self.segments.iter().enumerate() {
            let pieces_of = match segment {
                Segment::Corner(p) => vec![vector(*p)],
                Segment::Bezier([c1, c2, end]) => {
                    let cubic = [start, vector(*c1), vector(*c2), vector(*end)];
                    let n = pieces(cubic, tolerance);
                    if points.len() + n > MAX_FLATTENED_POINTS {
                        return Err(OutlineError::TooFine {
                            count: points.len() + n,
                        });
                    }
                    flatten_cubic(cubic, n)
                }
            };
            for p in pieces_of {
                if points.last() != Some(&p) {
                    points.push(p);
                    owner.push(k);
                }
            }
            start = segment.end();
        }
        if points.len() > MAX_FLATTENED_POINTS {
            return Err(OutlineError::TooFine {
                count: points.len(),
            });
        }
        // The curve closes on its own start: a last point equal to the first is the same one.
        if points.len() > 1 && points.first() == points.last() {
            points.pop();
            owner.pop();
        }
        Ok((points, owner, (high - low).length_squared()))
    }

    /// Checks the outline as drawn and returns its flattened polygon: its values (as
    /// [`prepare`](Self::prepare) does: piece counts, finite coordinates within
    /// [`OUTLINE_BOUND`], at most [`MAX_FLATTENED_POINTS`] after flattening), and that it is a
    /// simple closed curve — at least 3 distinct points, no crossing (a sweep along x over the
    /// flattened edges, docs/highlights.md), some area.
    pub fn polygon(&self) -> Result<Vec<DVec2>, OutlineError> {
        let (points, owner, diagonal_squared) = self.flattened()?;
        if points.len() < 3 {
            return Err(OutlineError::TooFew {
                count: points.len(),
            });
        }
        // Edge j runs from points[j] to points[j + 1], within the piece that ends at or after
        // points[j + 1].
        let piece_of_edge = |j: usize| owner[(j + 1) % owner.len()] + 1;
        if let Some((i, j, at)) = first_crossing(&points) {
            let (first, second) = (piece_of_edge(i), piece_of_edge(j));
            return Err(OutlineError::Crossing {
                first: first.min(second),
                second: first.max(second),
                x: at.x,
                y: at.y,
            });
        }
        let area = polygon_area(&points).abs();
        if area <= 1e-12 * diagonal_squared.max(f64::MIN_POSITIVE) {
            return Err(OutlineError::NoArea);
        }
        Ok(points)
    }

    /// Checks the outline as drawn ([`polygon`](Self::polygon)).
    pub fn validate(&self) -> Result<(), OutlineError> {
        self.polygon().map(|_| ())
    }

    /// The outline made ready to evaluate, its values checked (piece counts, finite coordinates
    /// within [`OUTLINE_BOUND`], at most [`MAX_FLATTENED_POINTS`] after flattening) but not its
    /// simplicity: a frame between two keys of a morph may cross itself or collapse, and is
    /// then filled by the non-zero winding rule ([`PreparedOutline::distance`]); the keys
    /// themselves are checked with [`validate`](Self::validate).
    pub fn prepare(&self) -> Result<PreparedOutline, OutlineError> {
        Ok(PreparedOutline::new(&self.flattened()?.0))
    }
}

/// The outline of straight pieces through `points`: what tests draw.
#[cfg(test)]
#[must_use]
pub(crate) fn corners(points: &[(f32, f32)]) -> Outline {
    Outline {
        segments: points
            .iter()
            .map(|&(x, y)| Segment::Corner([x, y]))
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_square_flattens_to_its_corners() {
        let sq = corners(&[(0.0, 0.0), (0.2, 0.0), (0.2, 0.2), (0.0, 0.2)]);
        assert_eq!(sq.polygon().unwrap().len(), 4);
    }

    #[test]
    fn bad_outlines_are_refused_with_the_reason() {
        let e = corners(&[(0.0, 0.0), (0.1, 0.0)]).validate().unwrap_err();
        assert_eq!(e, OutlineError::TooFew { count: 2 });
        let e = corners(&[(0.0, 0.0), (0.1, f32::NAN), (0.0, 0.1)])
            .validate()
            .unwrap_err();
        assert!(matches!(e, OutlineError::NotFinite { point: 2, .. }), "{e}");
        let e = corners(&[(0.0, 0.0), (0.995, 0.0), (0.0, 0.1)])
            .validate()
            .unwrap_err();
        assert!(
            matches!(e, OutlineError::OutOfBound { point: 2, .. }),
            "{e}"
        );
        let bow = corners(&[(0.0, 0.0), (0.2, 0.2), (0.2, 0.0), (0.0, 0.2)]);
        let e = bow.validate().unwrap_err();
        let OutlineError::Crossing {
            first,
            second,
            x,
            y,
        } = e
        else {
            panic!("{e}")
        };
        // Edge 1 → 2 (ending at point 2) crosses edge 3 → 4 (ending at point 4) at the middle.
        assert_eq!((first, second), (2, 4));
        assert!((x - 0.1).abs() < 1e-6 && (y - 0.1).abs() < 1e-6);
        let flat = corners(&[(0.0, 0.0), (0.1, 0.1), (0.2, 0.2), (0.3, 0.3)]);
        assert!(flat.validate().is_err());
    }

    #[test]
    fn a_looping_bezier_is_caught_after_flattening() {
        // Controls crossed over: the cubic from (0, 0) to (0.2, 0) loops on itself.
        let looped = Outline {
            segments: vec![
                Segment::Corner([0.0, 0.0]),
                Segment::Bezier([[0.4, 0.2], [-0.2, 0.2], [0.2, 0.0]]),
                Segment::Corner([0.1, -0.2]),
            ],
        };
        assert!(matches!(
            looped.validate(),
            Err(OutlineError::Crossing { .. })
        ));
        // The same with the controls in order is a simple dome.
        let dome = Outline {
            segments: vec![
                Segment::Corner([0.0, 0.0]),
                Segment::Bezier([[0.0, 0.2], [0.2, 0.2], [0.2, 0.0]]),
                Segment::Corner([0.1, -0.2]),
            ],
        };
        let points = dome.polygon().unwrap();
        assert!(points.len() > 10);
        // The Bézier starts from the corner (0, 0) before it.
        assert_eq!(points[0], DVec2::ZERO);
    }
}
