//! Where a surface point lands in a frame: the pixel a patch's (u, v) projects to, and whether
//! the frame shows it there.

use glam::{DVec3, DVec4};

use super::place_error::PlaceError;
use super::RenderJob;
use crate::render::Aovs;

/// How much nearer or farther than the point the surface a frame draws at its pixel may be, as
/// a fraction of the point's distance from the camera, for the point still to count as what
/// the pixel shows: well above the tessellation's chord error and the depth buffer's
/// precision, well below the gap between a lid and the body behind it.
pub const VISIBLE_DEPTH_TOLERANCE: f64 = 0.005;

/// A surface point seen from a frame's camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointInImage {
    /// Where it projects, in pixels from the top left with pixel `(i, j)`'s centre at `(i, j)`
    /// (as `glint place --pixel` reads them); meaningless when it is not `in_front`.
    pub pixel: (f64, f64),
    /// The point is in front of the camera, between its near and far planes.
    pub in_front: bool,
    /// It projects inside the image.
    pub in_image: bool,
    /// The frame shows it: in front, inside the image, and the pixel it falls in draws its
    /// patch at its depth (within [`VISIBLE_DEPTH_TOLERANCE`]); not hidden behind another
    /// surface, not cut away by a trim, not facing away with the surface behind it shown.
    pub visible: bool,
}

impl RenderJob {
    /// Where `(u, v)` of patch `patch` (index into the shot's library) lands at `frame`, posed
    /// as the frame poses it, in the job's image: the projection `p_ndc = VP · p` of the point
    /// to pixels `((x + 1) w / 2 − ½, (1 − y) h / 2 − ½)`, and whether the frame shows it,
    /// from its patch-id and depth images. Errors when the point is not on the model or the
    /// frame cannot be read or rendered.
    pub fn pixel_of(
        &mut self,
        frame: f64,
        patch: usize,
        (u, v): (f64, f64),
    ) -> Result<PointInImage, PlaceError> {
        let (width, height) = (self.settings.width, self.settings.height);
        let state = self.shot.at(frame);
        let Some(named) = state.library.patches.get(patch) else {
            return Err(PlaceError::NoPoint(format!(
                "the model has {} patches, so there is no patch {patch}",
                state.library.patches.len()
            )));
        };
        let domain = named.surface.domain();
        if !domain.contains(u, v) {
            return Err(PlaceError::NoPoint(format!(
                "(u, v) = ({u}, {v}) is outside the domain of {}: u in [{}, {}], v in [{}, {}]",
                named.name, domain.u.0, domain.u.1, domain.v.0, domain.v.1
            )));
        }
        let point = named.surface.point(u, v);
        let view_projection = state
            .camera
            .view_projection(width as f32 / height as f32)
            .as_dmat4();
        let clip = view_projection * DVec4::new(point.x, point.y, point.z, 1.0);
        let ndc = clip.truncate() / clip.w;
        let in_front = clip.w > 0.0 && (0.0..=1.0).contains(&ndc.z);
        let continuous = (
            (ndc.x + 1.0) * 0.5 * f64::from(width),
            (1.0 - ndc.y) * 0.5 * f64::from(height),
        );
        let pixel = (continuous.0 - 0.5, continuous.1 - 0.5);
        let inside = |p: f64, side: u32| p >= 0.0 && p < f64::from(side);
        let in_image = in_front && inside(continuous.0, width) && inside(continuous.1, height);
        let mut visible = false;
        if in_image {
            let aovs = Aovs {
                patch_id: true,
                depth: true,
                ..Aovs::default()
            };
            let image = self.lookup_image(&state, aovs)?;
            let index = continuous.1 as usize * width as usize + continuous.0 as usize;
            let id = image
                .aovs
                .patch_id
                .as_deref()
                .and_then(|ids| ids.get(index));
            let depth = image.aovs.depth.as_deref().and_then(|d| d.get(index));
            if let (Some(&id), Some(&depth)) = (id, depth) {
                let inverse = view_projection.inverse();
                let shown = inverse.project_point3(DVec3::new(ndc.x, ndc.y, f64::from(depth)));
                let eye = state.camera.eye.as_dvec3();
                let (near_shown, near_point) = match state.camera.projection {
                    crate::render::Projection::Perspective { .. } => {
                        (shown.distance(eye), point.distance(eye))
                    }
                    crate::render::Projection::Orthographic { .. } => {
                        let forward = state.camera.forward().as_dvec3();
                        ((shown - eye).dot(forward), (point - eye).dot(forward))
                    }
                };
                visible = id as usize == patch
                    && (near_shown - near_point).abs()
                        <= VISIBLE_DEPTH_TOLERANCE * near_point.abs().max(1e-9);
            }
        }
        Ok(PointInImage {
            pixel,
            in_front,
            in_image,
            visible,
        })
    }
}
