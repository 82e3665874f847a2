//! The renderer's own highlight evaluation ([`PreparedExpr::eval`]) as a [`SphereHighlight`],
//! for callers that compare a render with the region the renderer's formulas give. It is not
//! independent of what it checks: a wrong formula in the highlight operations cancels out.
//! The reference's truth is [`ClosedForm`](super::closed_form::ClosedForm).

use glam::DVec3;

use super::sphere_highlight::SphereHighlight;
use super::sphere_point::SpherePoint;
use crate::highlight::{Footprint, PreparedExpr, TangentFrame};

impl SphereHighlight for PreparedExpr {
    fn coverage_at(&self, point: &SpherePoint, h: DVec3) -> f64 {
        let f = point.frame;
        let frame = TangentFrame::new(f.du.as_vec3(), f.dv.as_vec3(), f.n.as_vec3());
        let shade = self.eval(&frame, point.uv.as_vec2(), h.as_vec3(), Footprint::HARD);
        f64::from(shade.coverage)
    }
}
