//! Knot vectors and B-spline basis functions with derivatives ("The NURBS Book", A2.1–A2.3).

use super::GeomError;

/// The highest derivative order glint evaluates (points, first and second derivatives).
pub const MAX_ORDER: usize = 2;

/// A validated, non-decreasing knot vector for a B-spline of degree `degree` with
/// `count` control points: `count + degree + 1` knots. Clamped and unclamped vectors are both
/// allowed; the parameter domain is `[U[p], U[n]]` (p = degree, n = count), where the basis
/// functions sum to one.
#[derive(Clone, Debug, PartialEq)]
pub struct KnotVector {
    knots: Vec<f64>,
    degree: usize,
    /// `inverse_gaps[(d − 1) · len + i] = 1 / (U[i+d] − U[i])` for `1 ≤ d ≤ p`, 0 where the
    /// gap is empty (or runs past the end): the denominators of the basis recurrences, so that
    /// evaluation multiplies instead of dividing.
    inverse_gaps: Vec<f64>,
}

/// Values and derivatives of the `degree + 1` basis functions that are non-zero at one
/// parameter: `ders[k][j]` is the k-th derivative of `N_{span−p+j, p}`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BasisDerivs {
    /// The knot span `i` with `U[i] ≤ t < U[i+1]` (the last non-empty span at the domain's end).
    pub span: usize,
    /// `ders[k][j]` for derivative order `k ≤ MAX_ORDER`, basis index `j ≤ degree`.
    pub ders: [[f64; MAX_BASIS]; MAX_ORDER + 1],
}

/// Values and first derivatives of the `N = degree + 1` basis functions that are non-zero at one
/// parameter, in arrays of exactly that length ([`KnotVector::first_basis`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct FirstBasis<const N: usize> {
    /// The knot span, as in [`BasisDerivs`].
    pub span: usize,
    /// `N_{span−p+j, p}(t)`.
    pub value: [f64; N],
    /// `N'_{span−p+j, p}(t)`.
    pub slope: [f64; N],
}

/// The largest number of non-zero basis functions at a parameter, i.e. the highest supported
/// degree plus one.
pub const MAX_BASIS: usize = MAX_DEGREE + 1;

/// The highest supported degree. Degree 1 to 9 covers every surface in practice and keeps the
/// per-point work on the stack.
pub const MAX_DEGREE: usize = 9;

impl KnotVector {
    /// Validates `knots` for a B-spline of `degree` with `count` control points.
    ///
    /// Requirements: `1 ≤ degree ≤ MAX_DEGREE`, `count ≥ degree + 1`,
    /// `knots.len() = count + degree + 1`, all knots finite and non-decreasing, no interior knot
    /// of multiplicity above `degree` (the surface would tear there), and a non-empty domain.
    pub fn new(knots: Vec<f64>, degree: usize, count: usize) -> Result<Self, GeomError> {
        if degree == 0 || degree > MAX_DEGREE {
            return Err(GeomError::Degree { degree });
        }
        if count < degree + 1 {
            return Err(GeomError::TooFewControlPoints { degree, count });
        }
        let expected = count + degree + 1;
        if knots.len() != expected {
            return Err(GeomError::KnotCount {
                found: knots.len(),
                expected,
                degree,
                count,
            });
        }
        if let Some(i) = knots.iter().position(|k| !k.is_finite()) {
            return Err(GeomError::KnotNotFinite { index: i });
        }
        if let Some(i) = knots.windows(2).position(|w| w[1] < w[0]) {
            return Err(GeomError::KnotsDecreasing {
                index: i + 1,
                value: knots[i + 1],
                previous: knots[i],
            });
        }
        // Multiplicity inside the domain (ends may be clamped with multiplicity p + 1): the
        // knots are sorted, so equal knots form one run, measured in one pass.
        let mut run_start = 0;
        for i in 0..=knots.len() {
            if i < knots.len() && knots[i] == knots[run_start] {
                continue;
            }
            let multiplicity = i - run_start;
            // The run [run_start, i) holds an index in [degree + 1, count): an interior knot.
            let interior = run_start.max(degree + 1) < i.min(count);
            if interior && multiplicity > degree {
                return Err(GeomError::KnotMultiplicity {
                    value: knots[run_start],
                    multiplicity,
                    degree,
                });
            }
            run_start = i;
        }
        if knots[degree] >= knots[count] {
            return Err(GeomError::EmptyDomain {
                start: knots[degree],
                end: knots[count],
            });
        }
        let len = knots.len();
        let inverse_gaps = (1..=degree)
            .flat_map(|d| {
                let knots = &knots;
                (0..len).map(move |i| match knots.get(i + d) {
                    Some(&end) if end > knots[i] => 1.0 / (end - knots[i]),
                    _ => 0.0,
                })
            })
            .collect();
        Ok(Self {
            knots,
            degree,
            inverse_gaps,
        })
    }

    /// The clamped uniform knot vector on [0, 1] for `count` control points: `degree + 1`
    /// zeros, evenly spaced interior knots, `degree + 1` ones (a Bezier curve when
    /// `count = degree + 1`).
    pub fn clamped_uniform(degree: usize, count: usize) -> Result<Self, GeomError> {
        let spans = count.saturating_sub(degree).max(1);
        let knots = (0..count + degree + 1)
            .map(|i| (i.saturating_sub(degree) as f64 / spans as f64).min(1.0))
            .collect();
        Self::new(knots, degree, count)
    }

    /// `1 / (U[i+d] − U[i])`, or 0 for an empty gap.
    #[inline]
    fn inverse_gap(&self, i: usize, d: usize) -> f64 {
        self.inverse_gaps[(d - 1) * self.knots.len() + i]
    }

    /// The degree p.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The knots.
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// The number of control points n this vector serves: `len − p − 1`.
    pub fn count(&self) -> usize {
        self.knots.len() - self.degree - 1
    }

    /// The number of non-empty knot spans in the domain: the `i` in `p ≤ i < n` with
    /// `U[i] < U[i+1]`.
    #[must_use]
    pub fn span_count(&self) -> usize {
        (self.degree..self.count())
            .filter(|&i| self.knots[i] < self.knots[i + 1])
            .count()
    }

    /// The parameter domain `[U[p], U[n]]`.
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.count()])
    }

    /// The knot span index i with `U[i] ≤ t < U[i+1]`, `p ≤ i < n` (A2.1); `t` at or past the
    /// domain's end maps to the last non-empty span, `t` before its start to the first.
    pub fn find_span(&self, t: f64) -> usize {
        let n = self.count();
        let p = self.degree;
        if t >= self.knots[n] {
            // The last span with U[i] < U[i+1].
            let mut i = n - 1;
            while self.knots[i] >= self.knots[i + 1] {
                i -= 1;
            }
            return i;
        }
        if t <= self.knots[p] {
            let mut i = p;
            while self.knots[i] >= self.knots[i + 1] {
                i += 1;
            }
            return i;
        }
        // Binary search for U[i] ≤ t < U[i+1] in [p, n).
        let (mut low, mut high) = (p, n);
        while high - low > 1 {
            let mid = (low + high) / 2;
            if t < self.knots[mid] {
                high = mid;
            } else {
                low = mid;
            }
        }
        low
    }

    /// The non-zero basis functions at `t` and their derivatives up to `order ≤ MAX_ORDER`.
    ///
    /// The values come from the triangular recurrence (A2.2) in the span `i` of `t`, keeping the
    /// functions of degrees p − 1 and p − 2 on the way; derivatives from the lower degrees
    /// (The NURBS Book, eq. 2.9):
    /// `N'_{i,p} = p [N_{i,p−1}/(U[i+p] − U[i]) − N_{i+1,p−1}/(U[i+p+1] − U[i+1])]`,
    /// and `N''_{i,p}` by the same rule applied to the derivatives of degree p − 1, with a term
    /// over a zero knot difference taken as 0. Orders above `order` are left zero.
    pub fn basis_derivs(&self, t: f64, order: usize) -> BasisDerivs {
        let p = self.degree;
        let span = self.find_span(t);
        let order = order.min(MAX_ORDER);
        let mut ders = [[0.0; MAX_BASIS]; MAX_ORDER + 1];
        let mut basis = [0.0; MAX_BASIS];
        let mut below = [[0.0; MAX_BASIS]; MAX_ORDER]; // degrees p − 1 and p − 2
        let (mut left, mut right) = ([0.0; MAX_BASIS], [0.0; MAX_BASIS]);
        basis[0] = 1.0;
        for j in 1..=p {
            if j + MAX_ORDER > p {
                below[p - j] = basis; // degree j − 1 = p − (p − j + 1)
            }
            self.raise_degree(span, t, j, &mut basis, &mut left, &mut right);
        }
        ders[0] = basis;
        if order == 0 {
            return BasisDerivs { span, ders };
        }
        // below[0] has degree p − 1, below[1] degree p − 2 (when p ≥ 2).
        ders[1] = self.differentiate(span, p, &below[0]);
        if order >= 2 && p >= 2 {
            let lower_derivs = self.differentiate(span, p - 1, &below[1]);
            ders[2] = self.differentiate(span, p, &lower_derivs);
        }
        BasisDerivs { span, ders }
    }

    /// The values and first derivatives of the `N = degree + 1` basis functions non-zero at `t`:
    /// [`basis_derivs`](Self::basis_derivs) to first order, with arrays of exactly `N` entries
    /// so that every loop has a fixed trip count (the evaluation of small degrees). The same
    /// operations in the same order, so the same values.
    #[inline(always)]
    pub(crate) fn first_basis<const N: usize>(&self, t: f64) -> FirstBasis<N> {
        debug_assert_eq!(self.degree + 1, N, "basis arrays sized for another degree");
        let p = N - 1;
        let span = self.find_span(t);
        let mut value = [0.0; N];
        let mut lower = [0.0; N]; // degree p − 1
        let (mut left, mut right) = ([0.0; N], [0.0; N]);
        value[0] = 1.0;
        for j in 1..=p {
            if j == p {
                lower = value;
            }
            self.raise_degree(span, t, j, &mut value, &mut left, &mut right);
        }
        FirstBasis {
            span,
            value,
            slope: self.differentiate(span, p, &lower),
        }
    }

    /// Step j of the triangular recurrence (A2.2) in place: `basis[..j]`, the degree j − 1
    /// functions non-zero in `span`, becomes `basis[..=j]` of degree j. `left[j] = t −
    /// U[span+1−j]` and `right[j] = U[span+j] − t` are recorded for the later steps; the
    /// denominator `right[r+1] + left[j−r]` is the knot gap `U[span+r+1] − U[span+1−j+r]`.
    #[inline(always)]
    fn raise_degree<const N: usize>(
        &self,
        span: usize,
        t: f64,
        j: usize,
        basis: &mut [f64; N],
        left: &mut [f64; N],
        right: &mut [f64; N],
    ) {
        left[j] = t - self.knots[span + 1 - j];
        right[j] = self.knots[span + j] - t;
        let mut saved = 0.0;
        for r in 0..j {
            let temp = basis[r] * self.inverse_gap(span + 1 - j + r, j);
            basis[r] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        basis[j] = saved;
    }

    /// Applies `f_{i,d} = d [g_{i,d−1}/(U[i+d] − U[i]) − g_{i+1,d−1}/(U[i+d+1] − U[i+1])]` to the
    /// `d` values `g` of degree d − 1 that are non-zero in `span` (indices `span − d + 1 ..=
    /// span`), giving the `d + 1` values of degree d (indices `span − d ..= span`).
    #[inline(always)]
    fn differentiate<const N: usize>(&self, span: usize, d: usize, g: &[f64; N]) -> [f64; N] {
        let mut out = [0.0; N];
        let first = span - d;
        for (k, slot) in out.iter_mut().enumerate().take(d + 1) {
            let i = first + k;
            let left_term = if k > 0 {
                g[k - 1] * self.inverse_gap(i, d)
            } else {
                0.0
            };
            let right_term = if k < d {
                g[k] * self.inverse_gap(i + 1, d)
            } else {
                0.0
            };
            *slot = d as f64 * (left_term - right_term);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cubic() -> KnotVector {
        KnotVector::new(
            vec![0.0, 0.0, 0.0, 0.0, 0.3, 0.3, 0.7, 1.0, 1.0, 1.0, 1.0],
            3,
            7,
        )
        .unwrap()
    }

    #[test]
    fn basis_is_a_partition_of_unity_and_derivatives_sum_to_zero() {
        let kv = cubic();
        for i in 0..=100 {
            let t = i as f64 / 100.0;
            let b = kv.basis_derivs(t, 2);
            let sums: Vec<f64> = (0..3).map(|k| b.ders[k][..4].iter().sum()).collect();
            assert!((sums[0] - 1.0).abs() < 1e-14, "t={t}: {sums:?}");
            assert!(
                sums[1].abs() < 1e-10 && sums[2].abs() < 1e-8,
                "t={t}: {sums:?}"
            );
            assert!(b.ders[0][..4].iter().all(|&n| n >= -1e-15));
        }
    }

    #[test]
    fn basis_derivatives_match_finite_differences() {
        let kv = cubic();
        let h = 1e-6;
        for &t in &[0.05, 0.2, 0.45, 0.55, 0.85, 0.95] {
            let b = kv.basis_derivs(t, 2);
            let (bm, bp) = (kv.basis_derivs(t - h, 2), kv.basis_derivs(t + h, 2));
            assert_eq!(bm.span, b.span);
            assert_eq!(bp.span, b.span);
            for j in 0..4 {
                let d1 = (bp.ders[0][j] - bm.ders[0][j]) / (2.0 * h);
                let d2 = (bp.ders[1][j] - bm.ders[1][j]) / (2.0 * h);
                assert!((d1 - b.ders[1][j]).abs() < 1e-6, "t={t} j={j}");
                assert!((d2 - b.ders[2][j]).abs() < 1e-4, "t={t} j={j}");
            }
        }
    }

    #[test]
    fn spans_cover_the_domain_including_its_end() {
        let kv = cubic();
        assert_eq!(kv.find_span(0.0), 3);
        assert_eq!(kv.find_span(0.3), 5);
        assert_eq!(kv.find_span(0.2999), 3);
        assert_eq!(kv.find_span(1.0), 6);
        assert_eq!(kv.domain(), (0.0, 1.0));
    }

    #[test]
    fn unclamped_vector_has_the_inner_domain() {
        let kv = KnotVector::new((0..8).map(f64::from).collect(), 2, 5).unwrap();
        assert_eq!(kv.domain(), (2.0, 5.0));
        let b = kv.basis_derivs(2.0, 0);
        assert!((b.ders[0][..3].iter().sum::<f64>() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn invalid_vectors_are_rejected_with_the_reason() {
        assert!(matches!(
            KnotVector::new(vec![0.0, 0.0, 1.0, 1.0, 1.0], 2, 3),
            Err(GeomError::KnotCount {
                found: 5,
                expected: 6,
                ..
            })
        ));
        assert!(matches!(
            KnotVector::new(vec![0.0, 0.0, 0.5, 0.4, 1.0, 1.0], 1, 4),
            Err(GeomError::KnotsDecreasing { index: 3, .. })
        ));
        assert!(matches!(
            KnotVector::new(vec![0.0, 0.0, 0.5, 0.5, 1.0, 1.0], 1, 4),
            Err(GeomError::KnotMultiplicity { .. })
        ));
        assert!(matches!(
            KnotVector::new(vec![0.0; 4], 1, 2),
            Err(GeomError::EmptyDomain { .. })
        ));
        assert!(matches!(
            KnotVector::new(vec![0.0; 4], 0, 3),
            Err(GeomError::Degree { degree: 0 })
        ));
    }

    #[test]
    fn clamped_uniform_is_bezier_for_minimal_count() {
        let kv = KnotVector::clamped_uniform(3, 4).unwrap();
        assert_eq!(kv.knots(), &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0]);
        let kv = KnotVector::clamped_uniform(2, 5).unwrap();
        assert_eq!(
            kv.knots(),
            &[0.0, 0.0, 0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0, 1.0, 1.0]
        );
    }

    #[test]
    fn interior_multiplicity_is_found_as_counting_each_knot_would() {
        // Every non-decreasing vector over {0, 1, 2, 3} of up to 9 knots, every degree: the
        // one-pass check agrees with counting, for each interior index, the knots equal to it.
        fn vectors(len: usize, from: u8, out: &mut Vec<Vec<f64>>, prefix: &mut Vec<f64>) {
            if prefix.len() == len {
                out.push(prefix.clone());
                return;
            }
            for v in from..4 {
                prefix.push(f64::from(v));
                vectors(len, v, out, prefix);
                prefix.pop();
            }
        }
        let mut checked = 0;
        for len in 4..=9 {
            let mut all = Vec::new();
            vectors(len, 0, &mut all, &mut Vec::new());
            for knots in all {
                for degree in 1..len / 2 {
                    let count = len - degree - 1;
                    let torn = ((degree + 1)..count)
                        .any(|i| knots.iter().filter(|&&k| k == knots[i]).count() > degree);
                    let found = matches!(
                        KnotVector::new(knots.clone(), degree, count),
                        Err(GeomError::KnotMultiplicity { .. })
                    );
                    assert_eq!(found, torn, "{knots:?} degree {degree}");
                    checked += 1;
                }
            }
        }
        assert!(checked > 1000, "{checked}");
    }
}
