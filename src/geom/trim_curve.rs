//! A trim curve: a rational B-spline in a patch's (u, v) plane, and the polyline that follows it
//! within a tolerance.

use glam::{DVec2, DVec3};

use super::{GeomError, KnotVector, MAX_WEIGHT, MIN_WEIGHT};
use crate::math::distance_to_segment;

/// The most pieces one knot span of a trim curve is cut into when it is followed by a
/// polyline: 2¹⁰, enough for a quarter circle to stay within 10⁻⁸ of its radius.
const MAX_PIECES_PER_SPAN: u32 = 1 << 10;

/// A rational B-spline curve in the (u, v) plane, written with homogeneous control points
/// `(u·w, v·w, w)`, evaluated over `range` (a part of its knots' domain):
/// `C(t) = (Σ Nᵢ(t) Pᵢ.x, Σ Nᵢ(t) Pᵢ.y) / Σ Nᵢ(t) Pᵢ.z`.
#[derive(Clone, Debug, PartialEq)]
pub struct TrimCurve {
    knots: KnotVector,
    /// Homogeneous control points `(u·w, v·w, w)`, every w in `[MIN_WEIGHT, MAX_WEIGHT]`.
    points: Vec<DVec3>,
    range: (f64, f64),
}

impl TrimCurve {
    /// A curve of `order` (degree + 1) with the homogeneous control points `points` and
    /// `points.len() + order` knots, evaluated over `range`, which must lie within the knots'
    /// domain and not be empty. Every weight must lie in `[MIN_WEIGHT, MAX_WEIGHT]`, as a
    /// surface's do.
    pub fn new(
        order: usize,
        knots: Vec<f64>,
        points: Vec<DVec3>,
        range: (f64, f64),
    ) -> Result<Self, GeomError> {
        let degree = order.saturating_sub(1);
        let knots = KnotVector::new(knots, degree, points.len())?;
        let weighted = |w: f64| (MIN_WEIGHT..=MAX_WEIGHT).contains(&w);
        if let Some(i) = points.iter().position(|p| !p.is_finite() || !weighted(p.z)) {
            return Err(GeomError::Weight {
                i,
                j: 0,
                weight: points[i].z,
            });
        }
        let (lo, hi) = knots.domain();
        if !(range.0 < range.1 && lo <= range.0 && range.1 <= hi) {
            return Err(GeomError::EmptyDomain {
                start: range.0,
                end: range.1,
            });
        }
        Ok(Self {
            knots,
            points,
            range,
        })
    }

    /// The point `C(t)`.
    #[must_use]
    pub fn point(&self, t: f64) -> DVec2 {
        let basis = self.knots.basis_derivs(t, 0);
        let p = self.knots.degree();
        let first = basis.span - p;
        let h: DVec3 = (0..=p)
            .map(|j| self.points[first + j] * basis.ders[0][j])
            .sum();
        DVec2::new(h.x, h.y) / h.z
    }

    /// The curve's first and last points, `C(range.0)` and `C(range.1)`.
    #[must_use]
    pub fn ends(&self) -> [DVec2; 2] {
        [self.point(self.range.0), self.point(self.range.1)]
    }

    /// The polyline that follows the curve within `tolerance`, from `C(range.0)` to
    /// `C(range.1)`, appended to `out` without its first point (the end of what `out` holds).
    ///
    /// Each knot span inside the range is followed on its own, since the curve may turn a
    /// corner at a knot: a degree-1 span is its chord; a higher one is halved until the point
    /// at the middle of each piece lies within `tolerance` of the piece's chord, at least
    /// four pieces and at most 2¹⁰ a span.
    pub fn follow(&self, tolerance: f64, out: &mut Vec<DVec2>) {
        let knots = self.knots.knots();
        let mut cuts: Vec<f64> = knots
            .iter()
            .copied()
            .filter(|&k| self.range.0 < k && k < self.range.1)
            .collect();
        cuts.dedup();
        cuts.insert(0, self.range.0);
        cuts.push(self.range.1);
        let linear = self.knots.degree() == 1;
        for span in cuts.windows(2) {
            let (a, b) = (span[0], span[1]);
            if linear {
                out.push(self.point(b));
                continue;
            }
            let pieces = 4;
            for k in 0..pieces {
                let t0 = a + (b - a) * f64::from(k) / f64::from(pieces);
                let t1 = a + (b - a) * f64::from(k + 1) / f64::from(pieces);
                self.follow_piece(t0, t1, tolerance, MAX_PIECES_PER_SPAN / pieces, out);
            }
        }
    }

    /// The piece `[t0, t1]`, halved while its middle lies more than `tolerance` from its chord
    /// and `budget` allows more than one piece.
    fn follow_piece(&self, t0: f64, t1: f64, tolerance: f64, budget: u32, out: &mut Vec<DVec2>) {
        let (p0, p1) = (self.point(t0), self.point(t1));
        let tm = 0.5 * (t0 + t1);
        let pm = self.point(tm);
        if budget <= 1 || distance_to_segment(pm, p0, p1) <= tolerance {
            out.push(p1);
            return;
        }
        self.follow_piece(t0, tm, tolerance, budget / 2, out);
        self.follow_piece(tm, t1, tolerance, budget / 2, out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The unit circle about (0.5, 0.5) of radius `r` as nine homogeneous points, counter-clockwise.
    fn circle(r: f64) -> TrimCurve {
        let w = 0.5f64.sqrt();
        let corners = [
            (1.0, 0.0, 1.0),
            (1.0, 1.0, w),
            (0.0, 1.0, 1.0),
            (-1.0, 1.0, w),
            (-1.0, 0.0, 1.0),
            (-1.0, -1.0, w),
            (0.0, -1.0, 1.0),
            (1.0, -1.0, w),
            (1.0, 0.0, 1.0),
        ];
        let points = corners
            .iter()
            .map(|&(x, y, w)| DVec3::new((0.5 + r * x) * w, (0.5 + r * y) * w, w))
            .collect();
        let knots = vec![
            0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0,
        ];
        TrimCurve::new(3, knots, points, (0.0, 1.0)).unwrap()
    }

    #[test]
    fn a_rational_quadratic_circle_is_followed_within_the_tolerance() {
        let curve = circle(0.3);
        let mut polyline = vec![curve.point(0.0)];
        curve.follow(1e-7, &mut polyline);
        let centre = DVec2::splat(0.5);
        // Every vertex is on the circle (the curve is exact) and every chord's middle is
        // within the tolerance of it.
        for w in polyline.windows(2) {
            assert!(((w[0] - centre).length() - 0.3).abs() < 1e-12);
            let mid = 0.5 * (w[0] + w[1]);
            assert!(0.3 - (mid - centre).length() <= 1.01e-7);
        }
        assert!((polyline[0] - polyline[polyline.len() - 1]).length() < 1e-12);
        // Counter-clockwise: the area by the shoelace formula is +πr² (to the chords' error),
        // whatever point it is taken about, since the polyline is closed.
        let area: f64 = polyline
            .windows(2)
            .map(|w| w[0].perp_dot(w[1]))
            .sum::<f64>()
            * 0.5;
        let shifted: f64 = polyline
            .windows(2)
            .map(|w| (w[0] - centre).perp_dot(w[1] - centre))
            .sum::<f64>()
            * 0.5;
        assert!(
            (shifted - std::f64::consts::PI * 0.09).abs() < 1e-5,
            "{shifted}"
        );
        assert!((area - shifted).abs() < 1e-9);
    }

    #[test]
    fn a_degree_one_curve_is_its_control_polygon_and_bad_curves_are_refused() {
        let square = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0), (0.0, 0.0)];
        let points: Vec<DVec3> = square.iter().map(|&(u, v)| DVec3::new(u, v, 1.0)).collect();
        let knots = vec![0.0, 0.0, 1.0, 2.0, 3.0, 4.0, 4.0];
        let curve = TrimCurve::new(2, knots.clone(), points.clone(), (0.0, 4.0)).unwrap();
        let mut polyline = vec![curve.point(0.0)];
        curve.follow(1e-9, &mut polyline);
        let expected: Vec<DVec2> = square.iter().map(|&(u, v)| DVec2::new(u, v)).collect();
        assert_eq!(polyline, expected);
        let mut zero_weight = points.clone();
        zero_weight[2].z = 0.0;
        assert!(TrimCurve::new(2, knots.clone(), zero_weight, (0.0, 4.0)).is_err());
        assert!(TrimCurve::new(2, knots.clone(), points.clone(), (0.0, 5.0)).is_err());
        assert!(TrimCurve::new(2, knots[1..].to_vec(), points, (0.0, 4.0)).is_err());
    }
}
