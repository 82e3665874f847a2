//! What the analytic reference classifies the sphere's points with: a highlight's coverage at
//! a [`SpherePoint`] for a given initial highlight vector.

use glam::DVec3;

use super::closed_form::ClosedForm;
use super::sphere_point::SpherePoint;

/// A highlight the reference can evaluate at a point of the unit sphere.
pub trait SphereHighlight: Sync {
    /// The coverage in [0, 1], opacity included, at `point` with the unit initial highlight
    /// vector `h`, with a hard edge (or the layers' feathers).
    #[must_use]
    fn coverage_at(&self, point: &SpherePoint, h: DVec3) -> f64;
}

/// The independent evaluation: [`ClosedForm::shade`] on the point's analytic frame and (u, v).
impl SphereHighlight for ClosedForm {
    fn coverage_at(&self, point: &SpherePoint, h: DVec3) -> f64 {
        self.shade(point.frame, point.uv, h).coverage
    }
}
