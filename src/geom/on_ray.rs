//! The parameters of the surface point a ray passes through, found by Newton steps from a
//! nearby start.

use glam::DVec3;

use super::surface::NurbsSurface;

/// The most Newton steps [`NurbsSurface::try_refine_on_ray`] takes; from a tessellated start
/// it converges in two or three.
pub const REFINE_STEPS: usize = 4;

impl NurbsSurface {
    /// `(u, v)` near `start` whose surface point lies on the ray `origin + t direction`, by
    /// Newton steps; `None` where the steps cannot go on (the caller keeps its start).
    ///
    /// With `e1, e2` orthonormal and across the ray, the residual `f = ((S − o)·e1, (S − o)·e2)`
    /// has the Jacobian `J = [[Su·e1, Sv·e1], [Su·e2, Sv·e2]]`; each step solves `J Δ = f` and
    /// sets `(u, v) −= Δ`, clamped to the domain. Stops when the step is below 1e-12, and after
    /// [`REFINE_STEPS`] steps returns where it got to. `None` when the direction is zero, J is
    /// singular or not finite, or a step is longer than a tenth of the domain (the ray passes
    /// the surface elsewhere, or misses it).
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
        let (mut u, mut v) = start;
        for _ in 0..REFINE_STEPS {
            let s = self.derivs(u, v, 1);
            let r = s.point - origin;
            let (f1, f2) = (r.dot(e1), r.dot(e2));
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
            u = (u - step_u).clamp(domain.u.0, domain.u.1);
            v = (v - step_v).clamp(domain.v.0, domain.v.1);
            if step_u.abs() + step_v.abs() < 1e-12 {
                return Some((u, v));
            }
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
