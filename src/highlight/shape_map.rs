//! A held shape: the linear map of a layer's tangent coordinates that keeps the surface its
//! highlight covers about a pin as it was at another frame.

use glam::{Mat2, Vec2};
use nalgebra::Matrix2;

/// The map `M` a pinned layer that holds its shape ([`Pin::hold`](super::Pin::hold)) applies
/// right after its placing translation: `t ← M t` on the tangential coordinates of the vector
/// leaving it, which is `p ← M p` on its gnomonic coordinates `p = t / h_n` (the point where
/// the direction meets the tangent plane `h_n = 1`), since the normal coordinate stays.
///
/// Around the pin, the gnomonic coordinates `p_F(x)` of the vector leaving the placing
/// translation at surface point `x` on frame F, and `p_K(x)` on the held frame K, are two
/// smooth maps of the surface that both send the pin to 0. With `M p_F(x) = p_K(x)` at every x
/// near the pin, every operation after the translation sees at F what it saw at K, so the
/// highlight covers the same surface about the pin: the same size, aspect and direction. A
/// 2 × 2 map can do this only to first order; [`try_fit`](Self::try_fit) finds the one that does it
/// best in the least-squares sense over points spread across the held highlight, which is
/// closer over the highlight's whole extent than the derivatives at the pin.
///
/// The operations of Anjyo & Hiramitsu 2003 cannot make this map: a directional scaling only
/// stretches a highlight (δ ∈ [0, 1]), and rotation turns it whole. The map is their
/// rotations and scalings in one, stretching or shrinking along any two axes; it acts where
/// the placing translation ends, so no written operation's index moves.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapeMap {
    /// `M`, acting on column vectors `(t_u, t_v)`.
    pub matrix: Mat2,
}

/// The least and greatest factor a held shape stretches its highlight by along any axis: a
/// view that leaves the surface about the pin edge-on needs more than any drawing shows, and
/// the bound keeps the map's inverse finite.
pub const SHAPE_MAP_RANGE: (f64, f64) = (1e-3, 1e3);

impl ShapeMap {
    /// The identity map: the shape as the view makes it.
    pub const IDENTITY: ShapeMap = ShapeMap {
        matrix: Mat2::IDENTITY,
    };

    /// The map `M` minimising `Σ ‖M a − b‖²` over the pairs `(a, b)`, the normal equations
    /// `M = (Σ b aᵀ)(Σ a aᵀ)⁻¹` solved in f64, its singular values then brought into
    /// [`SHAPE_MAP_RANGE`] with its singular directions kept. `None` when the pairs do not span
    /// the plane (fewer than two independent `a`, or any value not finite).
    #[must_use]
    pub fn try_fit(pairs: &[(Vec2, Vec2)]) -> Option<ShapeMap> {
        let (mut aa, mut ba) = (Matrix2::<f64>::zeros(), Matrix2::<f64>::zeros());
        for (a, b) in pairs {
            let a = nalgebra::Vector2::new(f64::from(a.x), f64::from(a.y));
            let b = nalgebra::Vector2::new(f64::from(b.x), f64::from(b.y));
            aa += a * a.transpose();
            ba += b * a.transpose();
        }
        if !(aa.iter().all(|x| x.is_finite()) && ba.iter().all(|x| x.is_finite())) {
            return None;
        }
        // A spread too thin to tell the two directions apart: relative to its largest axis.
        let scale = aa.trace();
        if scale <= 0.0 || aa.determinant() <= 1e-10 * scale * scale {
            return None;
        }
        Self::try_new(ba * aa.try_inverse()?)
    }

    /// The map `m` with its singular values brought into [`SHAPE_MAP_RANGE`], its singular
    /// directions kept. `None` when `m` is not finite.
    #[must_use]
    pub fn try_new(m: Matrix2<f64>) -> Option<ShapeMap> {
        if !m.iter().all(|x| x.is_finite()) {
            return None;
        }
        let svd = m.svd(true, true);
        let (u, v_t) = (svd.u?, svd.v_t?);
        let clamped = svd
            .singular_values
            .map(|s| s.clamp(SHAPE_MAP_RANGE.0, SHAPE_MAP_RANGE.1));
        let m = u * Matrix2::from_diagonal(&clamped) * v_t;
        let matrix = Mat2::from_cols(
            Vec2::new(m[(0, 0)] as f32, m[(1, 0)] as f32),
            Vec2::new(m[(0, 1)] as f32, m[(1, 1)] as f32),
        );
        matrix.is_finite().then_some(ShapeMap { matrix })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_map_is_found_again_from_points_it_maps() {
        let m = Mat2::from_cols(Vec2::new(2.0, 0.5), Vec2::new(-0.3, 0.7));
        let pairs: Vec<(Vec2, Vec2)> = (0..12)
            .map(|i| {
                let a = Vec2::from_angle(i as f32 * 0.5) * (0.1 + 0.02 * i as f32);
                (a, m * a)
            })
            .collect();
        let fitted = ShapeMap::try_fit(&pairs).unwrap().matrix;
        assert!(fitted.abs_diff_eq(m, 1e-5), "{fitted} vs {m}");
    }

    #[test]
    fn least_squares_splits_the_difference_of_points_that_disagree() {
        // b = 2a on one point and 4a on its mirror image: along that line M stretches by 3.
        let a = Vec2::new(0.2, 0.0);
        let pairs = [(a, 2.0 * a), (-a, -4.0 * a), (Vec2::Y * 0.1, Vec2::Y * 0.1)];
        let m = ShapeMap::try_fit(&pairs).unwrap().matrix;
        assert!((m * Vec2::X - Vec2::new(3.0, 0.0)).length() < 1e-5, "{m}");
        assert!((m * Vec2::Y - Vec2::Y).length() < 1e-5, "{m}");
    }

    #[test]
    fn stretches_beyond_the_range_are_brought_into_it_along_their_own_axes() {
        // Along (1, 1) the points ask for a factor of 10⁵, across it for 1.
        let d = Vec2::new(1.0, 1.0).normalize();
        let e = d.perp();
        let pairs = [(0.1 * d, 1e4 * d), (0.1 * e, 0.1 * e), (-0.1 * d, -1e4 * d)];
        let m = ShapeMap::try_fit(&pairs).unwrap().matrix;
        let along = m * d;
        assert!(
            (along.length() - SHAPE_MAP_RANGE.1 as f32).abs() < 0.5,
            "{along}"
        );
        assert!(along.normalize().dot(d) > 0.9999, "{along}");
        assert!((m * e - e).length() < 1e-4, "{m}");
    }

    #[test]
    fn points_on_one_line_or_not_finite_give_no_map() {
        let line = [
            (Vec2::X * 0.1, Vec2::X * 0.2),
            (Vec2::X * 0.2, Vec2::X * 0.4),
        ];
        assert_eq!(ShapeMap::try_fit(&line), None);
        assert_eq!(ShapeMap::try_fit(&[]), None);
        let nan = [(Vec2::X, Vec2::X), (Vec2::Y, Vec2::new(f32::NAN, 0.0))];
        assert_eq!(ShapeMap::try_fit(&nan), None);
    }
}
