//! The surface point a patch's highlight is solved at: its half vector from the light the
//! patch's highlight entry reads, as the renderer shades it.

use glam::Vec2;

use super::frame_state::FrameState;
use super::validated::Shot;
use crate::highlight::{DesignedLight, HighlightLight};
use crate::render::SurfacePoint;

impl Shot {
    /// The point at `uv` of patch `patch` as posed in `state`, seen by its camera, with the half
    /// vector the patch's highlight starts from there: from the scene's light, or, where the
    /// patch's highlight entry reads the designed light (`light: Designed`), from `L'` of the
    /// shade entries that pick the patch, read at the state's frame ([`DesignedLight`]).
    ///
    /// What `place`, pins and tune solve on is then what the renderer draws
    /// ([`Scene::highlight_light`](crate::render::Scene::highlight_light)). A shade stack that
    /// does not prepare (an operation out of range, which rendering the frame reports) leaves
    /// the scene's light.
    #[must_use]
    pub fn highlight_point(
        &self,
        state: &FrameState,
        patch: usize,
        uv: (f64, f64),
    ) -> SurfacePoint {
        let surface = &state.library.patches[patch].surface;
        let point = SurfacePoint::new(surface, uv, &state.camera, &state.light);
        let reads = self
            .highlight_of(patch)
            .map(|entry| self.highlight_light(entry))
            .unwrap_or_default();
        match reads {
            HighlightLight::Plain => point,
            HighlightLight::Designed => {
                let stacks = self
                    .shade_of(patch)
                    .iter()
                    .map(|&e| state.shade.get(e as usize)?.prepare().ok())
                    .collect::<Option<Vec<_>>>();
                let Some(stacks) = stacks else {
                    return point;
                };
                // The (u, v) the point was evaluated at, in its patch's domain.
                let domain = surface.domain();
                let at = Vec2::new(
                    uv.0.clamp(domain.u.0, domain.u.1) as f32,
                    uv.1.clamp(domain.v.0, domain.v.1) as f32,
                );
                let l = state.light.direction(point.position, point.frame.n);
                let designed = DesignedLight::new(stacks).light(&point.frame, at, l);
                point.lit_from(designed, &state.camera)
            }
        }
    }
}
