//! Whether a point of a line shows: no nearer surface hides it in the depth buffer.

use glam::{Mat4, Vec2, Vec4};

use super::super::camera::Camera;
use super::super::raster::VisibilityBuffer;

/// How much nearer, relative to its distance, a surface must be than a point of a line to
/// hide it. The line and the depth buffer come from the same mesh, so a surface at the line
/// differs from it only by f32 rounding (about 1e-6 of the distance); a part in front of
/// another is nearer by a visible fraction of the distance.
const RELATIVE_GAP: f32 = 1e-3;

/// The depth test of line samples against a frame's depth buffer.
pub(crate) struct DepthTest<'a> {
    visibility: &'a VisibilityBuffer,
    /// Samples per pixel side.
    k: u32,
    /// The projection: view distance to NDC depth and back.
    projection: Mat4,
}

impl<'a> DepthTest<'a> {
    /// The test against `visibility`, drawn at `k × k` samples per pixel through `camera`'s
    /// projection.
    #[must_use]
    pub fn new(visibility: &'a VisibilityBuffer, k: u32, camera: &Camera) -> Self {
        let aspect = visibility.width as f32 / visibility.height.max(1) as f32;
        Self {
            visibility,
            k: k.max(1),
            projection: camera.projection_matrix(aspect),
        }
    }

    /// The NDC depth of a point `distance` in front of the eye: `z/w` of `P (0, 0, −d, 1)`.
    #[inline]
    fn ndc_of(&self, distance: f32) -> f32 {
        let clip = self.projection * Vec4::new(0.0, 0.0, -distance, 1.0);
        clip.z / clip.w
    }

    /// The view distance of NDC depth `z`: from `z (w₀ − d P₂₃) = z₀ − d P₂₂`, with
    /// `(z₀, w₀)` the projection of the eye's own position.
    #[inline]
    fn distance_of(&self, z: f32) -> f32 {
        let p = &self.projection;
        let (z_axis, w_axis) = (p.z_axis, p.w_axis);
        // clip = P (0, 0, −d, 1): clip.z = −d z_axis.z + w_axis.z, clip.w = −d z_axis.w + w_axis.w.
        (w_axis.z - z * w_axis.w) / (z_axis.z - z * z_axis.w)
    }

    /// Whether the point at `pixel` (in output pixels) with NDC depth `z` shows: some sample
    /// within `reach` pixels of it (along each axis) sees no surface, or one no nearer than
    /// the point by more than [`RELATIVE_GAP`] of its distance. A silhouette takes a reach of a
    /// pixel: the background or the surface's far side lies within it, while the surface's
    /// near side may be nearer than the silhouette itself; so does an intersection, where two
    /// surfaces meet at an angle and one may turn away within the pixel. A line on one surface
    /// (a border, a crease) takes half a pixel: the samples around its own position show the
    /// surface it lies on, and a line glimpsed through a gap narrower than a pixel does not
    /// show. Where a nearer surface covers the point, every sample around sees it.
    #[must_use]
    pub fn shows(&self, pixel: Vec2, z: f32, reach: f32) -> bool {
        let threshold = self.ndc_of(self.distance_of(z) * (1.0 - RELATIVE_GAP));
        let k = self.k as f32;
        let (w, h) = (self.visibility.width as i64, self.visibility.height as i64);
        // Sample (i, j) is centred at (i + ½, j + ½) in samples.
        let (centre, r) = (pixel * k - 0.5, reach * k);
        let (x0, x1) = ((centre.x - r).ceil() as i64, (centre.x + r).floor() as i64);
        let (y0, y1) = ((centre.y - r).ceil() as i64, (centre.y + r).floor() as i64);
        if x0 < 0 || y0 < 0 || x1 >= w || y1 >= h {
            // Part of the neighbourhood lies outside the image, where nothing is drawn.
            return true;
        }
        (y0..=y1).any(|y| {
            let row = &self.visibility.depth[(y * w) as usize..][..w as usize];
            row[x0 as usize..=x1 as usize]
                .iter()
                .any(|&d| d >= threshold)
        })
    }
}
