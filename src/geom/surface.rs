//! Rational tensor-product B-spline (NURBS) surfaces: points and partial derivatives up to second
//! order ("The NURBS Book", A3.6 on homogeneous points, then A4.4's rational quotient rule).

use glam::{DVec3, DVec4};

use super::knots::{BasisDerivs, KnotVector, MAX_BASIS, MAX_ORDER};
use super::GeomError;

/// The largest magnitude of a control point's coordinate (and of a shape's size): a model a
/// million units across, far beyond any scene, with every product and sum of the evaluation
/// finite and f32 pixels still precise.
pub const MAX_COORDINATE: f64 = 1e6;

/// The smallest weight of a control point.
pub const MIN_WEIGHT: f64 = 1e-6;

/// The largest weight of a control point: with [`MIN_WEIGHT`], weights within twelve orders of
/// magnitude of each other.
pub const MAX_WEIGHT: f64 = 1e6;

/// A NURBS surface `S(u,v) = Σ N_i,p(u) N_j,q(v) w_ij P_ij / Σ N_i,p(u) N_j,q(v) w_ij`.
///
/// The control net has `count_u` rows (index i, along u) of `count_v` points (index j, along v).
/// Points are stored homogeneous, `(w x, w y, w z, w)`.
#[derive(Clone, Debug, PartialEq)]
pub struct NurbsSurface {
    knots_u: KnotVector,
    knots_v: KnotVector,
    /// Row-major homogeneous net: entry `i * count_v + j`.
    net: Vec<DVec4>,
    /// Whether a weight differs from 1 (otherwise the surface is a polynomial B-spline).
    rational: bool,
}

/// The point and partial derivatives of a surface at one parameter. Second derivatives are zero
/// when only first order was asked for.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SurfaceDerivs {
    pub point: DVec3,
    pub su: DVec3,
    pub sv: DVec3,
    pub suu: DVec3,
    pub suv: DVec3,
    pub svv: DVec3,
}

/// The net contracted along u for one v-span: `rows[l][k]` for the l-th control point of the
/// span along v and derivative order k in u (see [`NurbsSurface::contract_u`]).
pub(crate) type ContractedRows = [[DVec4; MAX_ORDER + 1]; MAX_BASIS];

/// Homogeneous derivatives `A^(k,l)` with `k + l ≤ 2`, as sums over the columns of a span.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Homogeneous {
    a: DVec4,
    au: DVec4,
    av: DVec4,
    auu: DVec4,
    auv: DVec4,
    avv: DVec4,
}

impl Homogeneous {
    /// Adds one column's u-contraction `column[k]` weighted by its v basis derivatives
    /// `nv(l)`: `A^(k,l) += N^(l)(v) column[k]`, for `k + l ≤ order`.
    #[inline]
    pub(super) fn add_column(
        &mut self,
        column: &[DVec4; MAX_ORDER + 1],
        nv: impl Fn(usize) -> f64,
        order: usize,
    ) {
        let n0 = nv(0);
        self.a += column[0] * n0;
        if order >= 1 {
            let n1 = nv(1);
            self.au += column[1] * n0;
            self.av += column[0] * n1;
            if order >= 2 {
                self.auu += column[2] * n0;
                self.auv += column[1] * n1;
                self.avv += column[0] * nv(2);
            }
        }
    }

    /// The rational quotient rule (A4.4) with `S − O = A/w`:
    /// `Su = (Au − wu S)/w`, `Sv = (Av − wv S)/w`, `Suu = (Auu − 2 wu Su − wuu S)/w`,
    /// `Suv = (Auv − wu Sv − wv Su − wuv S)/w`, `Svv = (Avv − 2 wv Sv − wvv S)/w`.
    /// Orders above `order` are left zero.
    #[inline]
    pub(super) fn rational(&self, origin: DVec3, order: usize) -> SurfaceDerivs {
        let inv_w = 1.0 / self.a.w;
        let local = self.a.truncate() * inv_w;
        let mut d = SurfaceDerivs {
            point: origin + local,
            ..SurfaceDerivs::default()
        };
        if order == 0 {
            return d;
        }
        let (au, av) = (self.au, self.av);
        d.su = (au.truncate() - au.w * local) * inv_w;
        d.sv = (av.truncate() - av.w * local) * inv_w;
        if order == 1 {
            return d;
        }
        let (auu, auv, avv) = (self.auu, self.auv, self.avv);
        d.suu = (auu.truncate() - 2.0 * au.w * d.su - auu.w * local) * inv_w;
        d.suv = (auv.truncate() - au.w * d.sv - av.w * d.su - auv.w * local) * inv_w;
        d.svv = (avv.truncate() - 2.0 * av.w * d.sv - avv.w * local) * inv_w;
        d
    }
}

/// The control point derivatives are measured from, with its net index (i, j).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LocalOrigin {
    pub index: (usize, usize),
    pub point: DVec3,
}

/// The parameter rectangle `[u0, u1] × [v0, v1]` a surface is defined on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Domain {
    pub u: (f64, f64),
    pub v: (f64, f64),
}

impl Domain {
    /// Whether (u, v) lies in the closed rectangle.
    pub fn contains(&self, u: f64, v: f64) -> bool {
        (self.u.0..=self.u.1).contains(&u) && (self.v.0..=self.v.1).contains(&v)
    }

    /// The centre of the rectangle.
    pub fn center(&self) -> (f64, f64) {
        (0.5 * (self.u.0 + self.u.1), 0.5 * (self.v.0 + self.v.1))
    }

    /// The parameter at fractions `(s, t) ∈ [0,1]²` of the rectangle.
    pub fn lerp(&self, s: f64, t: f64) -> (f64, f64) {
        (
            self.u.0 + s * (self.u.1 - self.u.0),
            self.v.0 + t * (self.v.1 - self.v.0),
        )
    }

    /// The fractions `(s, t)` of the rectangle at parameter `(u, v)`, the inverse of
    /// [`lerp`](Self::lerp); 0 along a side of no width.
    #[must_use]
    pub fn unlerp(&self, (u, v): (f64, f64)) -> (f64, f64) {
        let fraction = |x: f64, (a, b): (f64, f64)| if b > a { (x - a) / (b - a) } else { 0.0 };
        (fraction(u, self.u), fraction(v, self.v))
    }
}

impl NurbsSurface {
    /// Builds a surface from degrees, knot vectors, the control net `points[i][j]` (i along u,
    /// j along v) and optional weights of the same shape (all 1 when `None`: a non-rational
    /// B-spline). Coordinates must lie within ±[`MAX_COORDINATE`] and weights in
    /// `[MIN_WEIGHT, MAX_WEIGHT]`, so that every homogeneous sum stays finite and precise.
    pub fn new(
        degree_u: usize,
        degree_v: usize,
        knots_u: Vec<f64>,
        knots_v: Vec<f64>,
        points: &[Vec<DVec3>],
        weights: Option<&[Vec<f64>]>,
    ) -> Result<Self, GeomError> {
        let count_u = points.len();
        let count_v = points.first().map_or(0, Vec::len);
        let knots_u = KnotVector::new(knots_u, degree_u, count_u).map_err(|e| e.along("u"))?;
        let knots_v = KnotVector::new(knots_v, degree_v, count_v).map_err(|e| e.along("v"))?;
        let net_size_error = |rows: usize, columns: usize| GeomError::NetSize {
            rows,
            columns,
            expected_rows: count_u,
            expected_columns: count_v,
        };
        if let Some(row) = points.iter().find(|row| row.len() != count_v) {
            return Err(net_size_error(count_u, row.len()));
        }
        if let Some(w) = weights {
            if w.len() != count_u {
                return Err(net_size_error(w.len(), w.first().map_or(0, Vec::len)));
            }
            if let Some(row) = w.iter().find(|row| row.len() != count_v) {
                return Err(net_size_error(count_u, row.len()));
            }
        }
        let mut net = Vec::with_capacity(count_u * count_v);
        for (i, row) in points.iter().enumerate() {
            for (j, p) in row.iter().enumerate() {
                if !(p.is_finite() && p.abs().max_element() <= MAX_COORDINATE) {
                    return Err(GeomError::PointNotFinite { i, j });
                }
                let weight = weights.map_or(1.0, |w| w[i][j]);
                if !(MIN_WEIGHT..=MAX_WEIGHT).contains(&weight) {
                    return Err(GeomError::Weight { i, j, weight });
                }
                net.push((*p * weight).extend(weight));
            }
        }
        Ok(Self {
            knots_u,
            knots_v,
            rational: net.iter().any(|h| h.w != 1.0),
            net,
        })
    }

    /// The knot vector along u.
    pub fn knots_u(&self) -> &KnotVector {
        &self.knots_u
    }

    /// The knot vector along v.
    pub fn knots_v(&self) -> &KnotVector {
        &self.knots_v
    }

    /// Number of control points along u (rows of the net).
    pub fn count_u(&self) -> usize {
        self.knots_u.count()
    }

    /// Number of control points along v (points per row).
    pub fn count_v(&self) -> usize {
        self.knots_v.count()
    }

    /// Whether a weight differs from 1; otherwise the surface is a polynomial B-spline, whose
    /// homogeneous weight sums are 1.
    pub fn is_rational(&self) -> bool {
        self.rational
    }

    /// Control point `P_ij` as stored, homogeneous: `(w_ij P_ij, w_ij)`.
    #[inline]
    pub(super) fn homogeneous_point(&self, i: usize, j: usize) -> DVec4 {
        self.net[i * self.count_v() + j]
    }

    /// Control point `P_ij` (Euclidean) and its weight `w_ij`.
    pub fn control_point(&self, i: usize, j: usize) -> (DVec3, f64) {
        let h = self.net[i * self.count_v() + j];
        (h.truncate() / h.w, h.w)
    }

    /// The control points (without weights), row by row: `(i, j)` in the order
    /// `(0, 0), (0, 1), …, (1, 0), …`.
    pub fn control_points(&self) -> impl Iterator<Item = DVec3> + '_ {
        self.net.iter().map(|h| h.truncate() / h.w)
    }

    /// The parameter domain.
    pub fn domain(&self) -> Domain {
        Domain {
            u: self.knots_u.domain(),
            v: self.knots_v.domain(),
        }
    }

    /// The surface point S(u, v).
    pub fn point(&self, u: f64, v: f64) -> DVec3 {
        self.derivs(u, v, 0).point
    }

    /// The point and partial derivatives up to `order` (0, 1 or 2) at (u, v).
    pub fn derivs(&self, u: f64, v: f64, order: usize) -> SurfaceDerivs {
        let bu = self.knots_u.basis_derivs(u, order);
        let bv = self.knots_v.basis_derivs(v, order);
        self.derivs_from_basis(&bu, &bv, order)
    }

    /// The point and derivatives up to `order` from precomputed basis values: the homogeneous
    /// derivatives `A^(k,l) = Σ_j N^(l)_j(v) Σ_i N^(k)_i(u) (w_ij (P_ij − O), w_ij)` (A3.6),
    /// then the quotient rule (A4.4).
    ///
    /// The origin O is the corner of the span's control net nearest the parameter
    /// (`local_origin`). The quotient rule is translation invariant, and
    /// measuring from a nearby control point keeps the sums free of cancellation: derivatives do
    /// not lose digits when a model sits far from the world origin, and beside a collapsed edge
    /// (a pole) the collapsed row contributes exact zeros.
    pub fn derivs_from_basis(
        &self,
        bu: &BasisDerivs,
        bv: &BasisDerivs,
        order: usize,
    ) -> SurfaceDerivs {
        let order = order.min(MAX_ORDER);
        let (p, q) = (self.knots_u.degree(), self.knots_v.degree());
        let count_v = self.count_v();
        let (i0, j0) = (bu.span - p, bv.span - q);
        let origin = self.local_origin(bu, bv);
        let origin4 = origin.point.extend(0.0);
        let mut h = Homogeneous::default();
        // Column by column: the u-contraction of column l (as `contract_u` forms it), then its
        // share of the v-contraction (as `derivs_from_rows` adds it), so that grid and direct
        // evaluation add the same terms in the same order.
        for l in 0..=q {
            let mut column = [DVec4::ZERO; MAX_ORDER + 1];
            for i in 0..=p {
                let pw = self.net[(i0 + i) * count_v + j0 + l];
                let local = pw - origin4 * pw.w;
                for (k, c) in column.iter_mut().enumerate().take(order + 1) {
                    *c += local * bu.ders[k][i];
                }
            }
            h.add_column(&column, |k| bv.ders[k][l], order);
        }
        h.rational(origin.point, order)
    }

    /// The control point at the corner of the span's net nearest the parameter: the end of each
    /// span whose basis function is larger there.
    pub(crate) fn local_origin(&self, bu: &BasisDerivs, bv: &BasisDerivs) -> LocalOrigin {
        let nearest_end = |b: &BasisDerivs, degree: usize| {
            if b.ders[0][0] >= b.ders[0][degree] {
                0
            } else {
                degree
            }
        };
        let (p, q) = (self.knots_u.degree(), self.knots_v.degree());
        let i = bu.span - p + nearest_end(bu, p);
        let j = bv.span - q + nearest_end(bv, q);
        let corner = self.net[i * self.count_v() + j];
        LocalOrigin {
            index: (i, j),
            point: corner.truncate() / corner.w,
        }
    }

    /// The net relative to `origin`, contracted along u for the v-span `span_v`:
    /// `rows[k][l] = Σ_i N^(k)_i(u) (w (P − O), w)[i0 + i][j0 + l]` for `k ≤ order`.
    pub(crate) fn contract_u(
        &self,
        bu: &BasisDerivs,
        span_v: usize,
        origin: LocalOrigin,
        order: usize,
    ) -> ContractedRows {
        let order = order.min(MAX_ORDER);
        let (p, q) = (self.knots_u.degree(), self.knots_v.degree());
        let count_v = self.count_v();
        let (i0, j0) = (bu.span - p, span_v - q);
        let origin4 = origin.point.extend(0.0);
        let mut rows = [[DVec4::ZERO; MAX_ORDER + 1]; MAX_BASIS];
        for i in 0..=p {
            let net_row = &self.net[(i0 + i) * count_v + j0..][..=q];
            for (column, &pw) in rows.iter_mut().zip(net_row) {
                let local = pw - origin4 * pw.w;
                for (k, c) in column.iter_mut().enumerate().take(order + 1) {
                    *c += local * bu.ders[k][i];
                }
            }
        }
        rows
    }

    /// The point and derivatives up to `order` from u-contracted rows ([`Self::contract_u`]):
    /// the v-contraction `A^(k,l) = Σ_j N^(l)_j(v) rows[j][k]`, then the quotient rule.
    pub(crate) fn derivs_from_rows(
        &self,
        rows: &ContractedRows,
        bv: &BasisDerivs,
        origin: LocalOrigin,
        order: usize,
    ) -> SurfaceDerivs {
        let order = order.min(MAX_ORDER);
        let mut h = Homogeneous::default();
        for (l, column) in rows.iter().enumerate().take(self.knots_v.degree() + 1) {
            h.add_column(column, |k| bv.ders[k][l], order);
        }
        h.rational(origin.point, order)
    }

    /// Whether `other` is this surface with (maybe) other control points: the same knots, net
    /// and weights (compared bit for bit).
    #[must_use]
    pub fn same_but_points(&self, other: &Self) -> bool {
        self.knots_u == other.knots_u
            && self.knots_v == other.knots_v
            && self.net.len() == other.net.len()
            && self
                .net
                .iter()
                .zip(&other.net)
                .all(|(a, b)| a.w.to_bits() == b.w.to_bits())
    }

    /// The surface with its control points replaced by `points`, in the order of
    /// [`NurbsSurface::control_points`] (weights and knots unchanged); None when the count is not
    /// the net's.
    #[must_use]
    pub fn try_with_points(&self, points: &[DVec3]) -> Option<Self> {
        if points.len() != self.net.len() {
            return None;
        }
        let net = self
            .net
            .iter()
            .zip(points)
            .map(|(h, p)| (*p * h.w).extend(h.w))
            .collect();
        Some(Self {
            knots_u: self.knots_u.clone(),
            knots_v: self.knots_v.clone(),
            net,
            rational: self.rational,
        })
    }

    /// The surface with every control point mapped by `f` (weights unchanged). Exact for affine
    /// maps, since rational surfaces are affinely invariant.
    pub fn map_points(&self, f: impl Fn(DVec3) -> DVec3) -> Self {
        let net = self
            .net
            .iter()
            .map(|h| (f(h.truncate() / h.w) * h.w).extend(h.w))
            .collect();
        Self {
            knots_u: self.knots_u.clone(),
            knots_v: self.knots_v.clone(),
            net,
            rational: self.rational,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bilinear() -> NurbsSurface {
        let points = vec![
            vec![DVec3::new(0.0, 0.0, 0.0), DVec3::new(0.0, 1.0, 0.0)],
            vec![DVec3::new(2.0, 0.0, 0.0), DVec3::new(2.0, 1.0, 1.0)],
        ];
        NurbsSurface::new(
            1,
            1,
            vec![0.0, 0.0, 1.0, 1.0],
            vec![0.0, 0.0, 1.0, 1.0],
            &points,
            None,
        )
        .unwrap()
    }

    #[test]
    fn bilinear_patch_matches_its_closed_form() {
        // S = (2u, v, uv): Su = (2, 0, v), Sv = (0, 1, u), Suv = (0, 0, 1), Suu = Svv = 0.
        let s = bilinear();
        let d = s.derivs(0.25, 0.75, 2);
        assert!((d.point - DVec3::new(0.5, 0.75, 0.1875)).length() < 1e-15);
        assert!((d.su - DVec3::new(2.0, 0.0, 0.75)).length() < 1e-15);
        assert!((d.sv - DVec3::new(0.0, 1.0, 0.25)).length() < 1e-15);
        assert!((d.suv - DVec3::Z).length() < 1e-15);
        assert!(d.suu.length() < 1e-15 && d.svv.length() < 1e-15);
    }

    #[test]
    fn net_shape_and_weights_are_checked() {
        let points = vec![vec![DVec3::ZERO; 2], vec![DVec3::ZERO; 3]];
        let knots = vec![0.0, 0.0, 1.0, 1.0];
        assert!(matches!(
            NurbsSurface::new(1, 1, knots.clone(), knots.clone(), &points, None),
            Err(GeomError::NetSize { columns: 3, .. })
        ));
        let points = vec![vec![DVec3::ZERO; 2]; 2];
        let weights = vec![vec![1.0, 1.0], vec![1.0, 0.0]];
        assert!(matches!(
            NurbsSurface::new(1, 1, knots.clone(), knots, &points, Some(&weights)),
            Err(GeomError::Weight { i: 1, j: 1, .. })
        ));
    }

    #[test]
    fn control_points_round_trip_through_homogeneous_storage() {
        let points = vec![vec![DVec3::new(1.0, 2.0, 3.0), DVec3::X], vec![DVec3::Y; 2]];
        let weights = vec![vec![0.5, 1.0], vec![2.0, 1.0]];
        let knots = vec![0.0, 0.0, 1.0, 1.0];
        let s = NurbsSurface::new(1, 1, knots.clone(), knots, &points, Some(&weights)).unwrap();
        let (p, w) = s.control_point(0, 0);
        assert!((p - DVec3::new(1.0, 2.0, 3.0)).length() < 1e-15);
        assert_eq!(w, 0.5);
        assert_eq!(s.control_point(1, 0).1, 2.0);
    }

    /// A rational bicubic over non-uniform knots (an interior knot in u, doubled in v), with
    /// weights from 0.3 to 4: every term of the quotient rule matters.
    fn rational_bicubic() -> NurbsSurface {
        let points: Vec<Vec<DVec3>> = (0..5)
            .map(|i| {
                (0..5)
                    .map(|j| {
                        let (x, y) = (i as f64, j as f64);
                        DVec3::new(x + 0.1 * y, y - 0.2 * x, (0.7 * x).sin() * (0.5 * y).cos())
                    })
                    .collect()
            })
            .collect();
        let weights: Vec<Vec<f64>> = (0..5)
            .map(|i| {
                (0..5)
                    .map(|j| 0.3 + ((i * 7 + j * 3) % 5) as f64 * 0.9)
                    .collect()
            })
            .collect();
        NurbsSurface::new(
            3,
            3,
            vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0],
            vec![0.0, 0.0, 0.0, 0.0, 0.6, 1.0, 1.0, 1.0, 1.0],
            &points,
            Some(&weights),
        )
        .unwrap()
    }

    #[test]
    fn rational_derivatives_are_the_differences_of_the_orders_below() {
        // Central differences: of the point for the first derivatives, of the first for the
        // second; a step of 1e-5 leaves an error near 1e-9 of the values.
        let s = rational_bicubic();
        assert!(s.is_rational());
        let h = 1e-5;
        for (u, v) in [(0.2, 0.3), (0.55, 0.8), (0.9, 0.1), (0.3, 0.65)] {
            let d = s.derivs(u, v, 2);
            let (up, um) = (s.derivs(u + h, v, 2), s.derivs(u - h, v, 2));
            let (vp, vm) = (s.derivs(u, v + h, 2), s.derivs(u, v - h, 2));
            let difference = |plus: DVec3, minus: DVec3| (plus - minus) / (2.0 * h);
            for (name, estimate, exact) in [
                ("Su", difference(up.point, um.point), d.su),
                ("Sv", difference(vp.point, vm.point), d.sv),
                ("Suu", difference(up.su, um.su), d.suu),
                ("Suv", difference(vp.su, vm.su), d.suv),
                ("Svu", difference(up.sv, um.sv), d.suv),
                ("Svv", difference(vp.sv, vm.sv), d.svv),
            ] {
                let error = (estimate - exact).length();
                assert!(
                    error < 1e-7 * (1.0 + exact.length()),
                    "{name} at ({u}, {v}): {estimate} vs {exact}"
                );
            }
            // Lower orders asked for: the same values, and nothing above them.
            let first = s.derivs(u, v, 1);
            assert_eq!((first.point, first.su, first.sv), (d.point, d.su, d.sv));
            assert_eq!(
                (first.suu, first.suv, first.svv),
                (DVec3::ZERO, DVec3::ZERO, DVec3::ZERO)
            );
            let zeroth = s.derivs(u, v, 0);
            assert_eq!((zeroth.point, zeroth.su), (d.point, DVec3::ZERO));
        }
    }

    #[test]
    fn a_collapsed_edge_has_exactly_zero_derivative_along_it() {
        // A rational patch, linear in u and quadratic in v, whose v = 0 row collapses to one point
        // far from the origin. Measured from the span's nearest corner, that row contributes
        // exact zeros at either end of u.
        let points = [
            [
                DVec3::ZERO,
                DVec3::new(-1.0, 0.5, 0.0),
                DVec3::new(-1.0, 1.0, 1.0),
            ],
            [
                DVec3::ZERO,
                DVec3::new(1.0, 0.5, 0.0),
                DVec3::new(1.0, 1.0, 1.0),
            ],
        ];
        let weights = vec![vec![1.0, 0.5, 2.0], vec![3.0, 0.25, 1.0]];
        let knots_v = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
        let s = NurbsSurface::new(
            1,
            2,
            vec![0.0, 0.0, 1.0, 1.0],
            knots_v,
            &points
                .iter()
                .map(|r| r.iter().map(|p| *p + DVec3::splat(3e5)).collect())
                .collect::<Vec<_>>(),
            Some(&weights),
        )
        .unwrap();
        for u in [0.0, 0.1, 0.3, 0.5, 0.7, 0.9, 1.0] {
            let d = s.derivs(u, 0.0, 2);
            assert_eq!(d.su, DVec3::ZERO, "u = {u}");
            assert_eq!(d.suu, DVec3::ZERO, "u = {u}");
            assert_eq!(d.point, DVec3::splat(3e5), "u = {u}");
        }
    }

    #[test]
    fn moved_points_move_the_surface_and_keep_its_weights() {
        let s = rational_bicubic();
        let shift = DVec3::new(-4.0, 0.5, 2.25);
        let moved = s.map_points(|p| 2.0 * p + shift);
        assert_eq!(moved.is_rational(), s.is_rational());
        for (u, v) in [(0.0, 0.0), (0.3, 0.7), (1.0, 0.5)] {
            let (a, b) = (s.point(u, v), moved.point(u, v));
            assert!((b - (2.0 * a + shift)).length() < 1e-12, "({u}, {v})");
        }
        for i in 0..5 {
            assert_eq!(moved.control_point(i, 2).1, s.control_point(i, 2).1);
        }
    }

    #[test]
    fn unit_weights_make_a_polynomial_surface() {
        assert!(!bilinear().is_rational());
        let points = vec![vec![DVec3::ZERO, DVec3::X], vec![DVec3::Y, DVec3::ONE]];
        let knots = vec![0.0, 0.0, 1.0, 1.0];
        let ones = vec![vec![1.0; 2]; 2];
        let s = NurbsSurface::new(1, 1, knots.clone(), knots.clone(), &points, Some(&ones));
        assert!(!s.unwrap().is_rational());
        let one_off = vec![vec![1.0, 1.0], vec![1.0, 1.5]];
        let s = NurbsSurface::new(1, 1, knots.clone(), knots, &points, Some(&one_off));
        assert!(s.unwrap().is_rational());
    }

    #[test]
    fn coordinates_and_weights_are_accepted_up_to_their_bounds_and_not_past() {
        let knots = vec![0.0, 0.0, 1.0, 1.0];
        let net = |p: DVec3| vec![vec![DVec3::ZERO, DVec3::X], vec![DVec3::Y, p]];
        let build = |p: DVec3, w: f64| {
            NurbsSurface::new(
                1,
                1,
                knots.clone(),
                knots.clone(),
                &net(p),
                Some(&[vec![1.0, 1.0], vec![1.0, w]]),
            )
        };
        assert!(build(DVec3::splat(-MAX_COORDINATE), 1.0).is_ok());
        assert!(build(DVec3::new(0.0, MAX_COORDINATE, 0.0), 1.0).is_ok());
        assert!(matches!(
            build(
                DVec3::new(0.0, 0.0, MAX_COORDINATE * (1.0 + f64::EPSILON)),
                1.0
            ),
            Err(GeomError::PointNotFinite { i: 1, j: 1 })
        ));
        assert!(build(DVec3::ONE, MIN_WEIGHT).is_ok() && build(DVec3::ONE, MAX_WEIGHT).is_ok());
        for w in [MIN_WEIGHT * 0.999, MAX_WEIGHT * 1.001, f64::NAN] {
            assert!(matches!(
                build(DVec3::ONE, w),
                Err(GeomError::Weight { i: 1, j: 1, .. })
            ));
        }
        // Weights of the wrong shape: too few rows, a short row.
        let points = net(DVec3::ONE);
        let few = vec![vec![1.0; 2]];
        assert!(matches!(
            NurbsSurface::new(1, 1, knots.clone(), knots.clone(), &points, Some(&few)),
            Err(GeomError::NetSize {
                rows: 1,
                columns: 2,
                expected_rows: 2,
                expected_columns: 2
            })
        ));
        let short = vec![vec![1.0; 2], vec![1.0]];
        assert!(matches!(
            NurbsSurface::new(1, 1, knots.clone(), knots, &points, Some(&short)),
            Err(GeomError::NetSize {
                rows: 2,
                columns: 1,
                ..
            })
        ));
    }

    #[test]
    fn a_domain_knows_its_inside_centre_and_fractions() {
        let d = Domain {
            u: (1.0, 3.0),
            v: (-2.0, 0.0),
        };
        assert!(d.contains(1.0, -2.0) && d.contains(3.0, 0.0) && d.contains(2.0, -1.0));
        assert!(!d.contains(0.999, -1.0) && !d.contains(3.001, -1.0));
        assert!(!d.contains(2.0, -2.001) && !d.contains(2.0, 0.001));
        assert_eq!(d.center(), (2.0, -1.0));
        assert_eq!(d.lerp(0.25, 0.75), (1.5, -0.5));
        assert_eq!(d.lerp(0.0, 1.0), (1.0, 0.0));
    }
}
