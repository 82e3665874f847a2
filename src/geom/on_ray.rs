//! The parameters of the surface point a ray passes through, found by Newton steps from a
//! nearby start.

use glam::DVec3;

use super::surface::NurbsSurface;

/// The most Newton steps [`NurbsSurface::try_refine_on_ray`] takes; from a tessellated start
/// it converges in one to three, more where the ray grazes the surface.
pub const REFINE_STEPS: usize = 8;

/// The residual, relative to the distance along the ray, at which a point counts as on it:
/// 10⁻⁷ rad, far below any pixel.
const ON_RAY: f64 = 1e-7;

/// Halvings of a Newton step that does not bring the point nearer the ray before giving up.
const HALVINGS: usize = 6;

impl NurbsSurface {
    /// `(u, v)` near `start` whose surface point lies on the ray `origin + t direction`, by
    /// damped Newton steps; `None` where the steps cannot go on (the caller keeps its start).
    ///
    /// With `e1, e2` orthonormal and across the ray, the residual `f = ((S − o)·e1, (S − o)·e2)`
    /// has the Jacobian `J = [[Su·e1, Sv·e1], [Su·e2, Sv·e2]]`; each step solves `J Δ = f` and
    /// moves `(u, v) −= t Δ`, clamped to the domain, with `t = 1, ½, ¼, …` the first that makes
    /// `|f|` smaller (up to 6 halvings): where the ray grazes the surface, J is nearly singular
    /// and the full step overshoots. Stops once `|f| ≤ 10⁻⁷ |S − o|`, and after [`REFINE_STEPS`]
    /// steps, or when no halving helps (the ray passes beside the surface), returns the nearest
    /// point it found. `None` when the direction is zero, J is singular or not finite, or a
    /// step is longer than a tenth of the domain (the ray passes the surface elsewhere).
    #[must_use]
    pub fn try_refine_on_ray(
        &self,
        start: (f64, f64),
        origin: DVec3,
        direction: DVec3,
    ) -> Option<(f64, f64)> {
        let domain = self.domain();
        let d = direction.try_normalize()?;
        let (e1, e2) = d.any_orthonormal_pair();
        let reach = 0.1 * (domain.u.1 - domain.u.0).max(domain.v.1 - domain.v.0);
        let residual = |point: DVec3| {
            let r = point - origin;
            (r.dot(e1), r.dot(e2), r.length())
        };
        let (mut u, mut v) = start;
        let mut s = self.derivs(u, v, 1);
        let (mut f1, mut f2, mut distance) = residual(s.point);
        for _ in 0..REFINE_STEPS {
            let error = f1.hypot(f2);
            if error <= ON_RAY * distance {
                break;
            }
            let (a, b, c, e) = (s.su.dot(e1), s.sv.dot(e1), s.su.dot(e2), s.sv.dot(e2));
            let det = a * e - b * c;
            if det.abs() <= 1e-300 || !det.is_finite() {
                return None;
            }
            let (step_u, step_v) = ((e * f1 - b * f2) / det, (a * f2 - c * f1) / det);
            let length = step_u.abs() + step_v.abs();
            if length > reach || !length.is_finite() {
                return None;
            }
            let mut t = 1.0;
            let mut better = None;
            for _ in 0..=HALVINGS {
                let nu = (u - t * step_u).clamp(domain.u.0, domain.u.1);
                let nv = (v - t * step_v).clamp(domain.v.0, domain.v.1);
                let ns = self.derivs(nu, nv, 1);
                let (g1, g2, g_distance) = residual(ns.point);
                if g1.hypot(g2) < error {
                    better = Some((nu, nv, ns, g1, g2, g_distance));
                    break;
                }
                t *= 0.5;
            }
            let Some((nu, nv, ns, g1, g2, g_distance)) = better else {
                break;
            };
            (u, v, s, f1, f2, distance) = (nu, nv, ns, g1, g2, g_distance);
        }
        Some((u, v))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refinement_puts_the_surface_point_on_the_ray() {
        let sphere = crate::geom::shapes::sphere(DVec3::ZERO, 1.0).unwrap();
        let target = sphere.point(0.3, 0.6);
        let origin = DVec3::new(0.2, -4.0, 0.7);
        let (u, v) = sphere
            .try_refine_on_ray((0.31, 0.59), origin, target - origin)
            .unwrap();
        assert!(
            (u - 0.3).abs() < 1e-10 && (v - 0.6).abs() < 1e-10,
            "({u}, {v})"
        );
        // A ray that misses the surface nearby, and no ray at all.
        let start = (0.31, 0.59);
        assert_eq!(sphere.try_refine_on_ray(start, origin, DVec3::Z), None);
        assert_eq!(sphere.try_refine_on_ray(start, origin, DVec3::ZERO), None);
    }
}
