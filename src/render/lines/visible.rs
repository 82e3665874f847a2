//! Whether a point of a line shows: no nearer surface hides it in the depth buffer.

use glam::{Mat4, Vec2, Vec4};

use super::super::camera::Camera;
use super::super::raster::VisibilityBuffer;

/// How much nearer, relative to its distance, a surface must be than a point of a line to
/// hide it. The line and the depth buffer come from the same mesh, so a surface at the line
/// differs from it only by f32 rounding (about 1e-6 of the distance); a part in front of
/// another is nearer by a visible fraction of the distance.
const RELATIVE_GAP: f32 = 1e-3;

/// How much farther than its own reach the depth test of an open border looks
/// ([`DepthTest::shows_open`]), in pixels: to a silhouette's reach.
const OPEN_BORDER_EXTRA: f32 = 0.5;

/// How much nearer than an open border, in pixel widths at its distance, its own patch may be
/// about it and still be taken for the patch seen edge-on toward it ([`DepthTest::shows_open`]):
/// half a pixel off the border, a patch turned 3.6° or more from edge-on is nearer by less (the
/// half pixel over tan 3.6° ≈ 1/16). Farther in front, the patch is another part of itself
/// hiding the border, as the near side of a tube hides the far half of its rim.
const EDGE_ON_PIXELS: f32 = 8.0;

/// The depth test of line samples against a frame's depth buffer.
pub(crate) struct DepthTest<'a> {
    visibility: &'a VisibilityBuffer,
    /// Per triangle of the mesh the buffer was drawn from, its patch.
    triangle_patch: &'a [u32],
    /// Samples per pixel side.
    k: u32,
    /// The projection: view distance to NDC depth and back.
    projection: Mat4,
}

impl<'a> DepthTest<'a> {
    /// The test against `visibility`, drawn at `k × k` samples per pixel through `camera`'s
    /// projection from a mesh whose triangles lie on `triangle_patch`.
    #[must_use]
    pub fn new(
        visibility: &'a VisibilityBuffer,
        triangle_patch: &'a [u32],
        k: u32,
        camera: &Camera,
    ) -> Self {
        let aspect = visibility.width as f32 / visibility.height.max(1) as f32;
        Self {
            visibility,
            triangle_patch,
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
        let threshold = self.threshold(z);
        self.samples(pixel, reach)
            .is_none_or(|mut samples| samples.any(|s| self.visibility.depth[s] >= threshold))
    }

    /// Whether the point at `pixel` with NDC depth `z` of a line inside a surface's outline (a
    /// light contour) shows: some sample within `reach` pixels of it sees a surface no nearer
    /// than the point by more than [`RELATIVE_GAP`] of its distance. The background does not
    /// show such a line: near a silhouette, a line on the surface's far side has background
    /// within reach of it, but the near side covers it.
    #[must_use]
    pub fn shows_on_surface(&self, pixel: Vec2, z: f32, reach: f32) -> bool {
        let threshold = self.threshold(z);
        self.samples(pixel, reach).is_some_and(|mut samples| {
            samples.any(|s| {
                let depth = self.visibility.depth[s];
                depth >= threshold && depth.is_finite()
            })
        })
    }

    /// Whether the point at `pixel` with NDC depth `z` of an open border on `patch` (its
    /// surface ends there, nothing continues it) shows: as [`shows`](Self::shows) within
    /// `reach`, or within `reach` and [`OPEN_BORDER_EXTRA`] more, as a silhouette is tested,
    /// where every sample within `reach` that is nearer lies on `patch` itself and by less
    /// than [`EDGE_ON_PIXELS`] pixel widths. Seen edge-on, a patch is a little nearer than its
    /// own border over the pixels about it, and what lies past the border shows a little
    /// farther off; a border behind another surface, or behind another part of its own patch,
    /// stays hidden.
    #[must_use]
    pub fn shows_open(&self, pixel: Vec2, z: f32, reach: f32, patch: u32) -> bool {
        let threshold = self.threshold(z);
        let Some(samples) = self.samples(pixel, reach) else {
            return true;
        };
        let distance = self.distance_of(z);
        let edge_on = distance - EDGE_ON_PIXELS * self.pixel_width(distance);
        let mut own = true;
        for s in samples {
            let depth = self.visibility.depth[s];
            if depth >= threshold {
                return true;
            }
            let triangle = self.visibility.triangle[s] as usize;
            own &= self.triangle_patch.get(triangle) == Some(&patch)
                && self.distance_of(depth) >= edge_on;
        }
        own && self.shows(pixel, z, reach + OPEN_BORDER_EXTRA)
    }

    /// The width of an output pixel, in world units, at `distance` in front of the eye:
    /// `2 w / (P₁₁ h)` for the image's `h` rows, with `w` the clip `w` there (the distance
    /// itself in perspective, 1 in orthographic projection).
    fn pixel_width(&self, distance: f32) -> f32 {
        let p = &self.projection;
        let w = -distance * p.z_axis.w + p.w_axis.w;
        let rows = (self.visibility.height / self.k).max(1) as f32;
        2.0 * w / (p.y_axis.y * rows)
    }

    /// The NDC depth below which a sample hides a point at NDC depth `z`: nearer by
    /// [`RELATIVE_GAP`] of its distance.
    fn threshold(&self, z: f32) -> f32 {
        self.ndc_of(self.distance_of(z) * (1.0 - RELATIVE_GAP))
    }

    /// The indices of the samples within `reach` pixels of `pixel` along each axis; `None` where
    /// part of that window lies outside the image, where nothing is drawn.
    fn samples(&self, pixel: Vec2, reach: f32) -> Option<impl Iterator<Item = usize>> {
        let k = self.k as f32;
        let (w, h) = (self.visibility.width as i64, self.visibility.height as i64);
        // Sample (i, j) is centred at (i + ½, j + ½) in samples.
        let (centre, r) = (pixel * k - 0.5, reach * k);
        let (x0, x1) = ((centre.x - r).ceil() as i64, (centre.x + r).floor() as i64);
        let (y0, y1) = ((centre.y - r).ceil() as i64, (centre.y + r).floor() as i64);
        if x0 < 0 || y0 < 0 || x1 >= w || y1 >= h {
            return None;
        }
        let w = w as usize;
        Some(
            (y0 as usize..=y1 as usize)
                .flat_map(move |y| (x0 as usize..=x1 as usize).map(move |x| y * w + x)),
        )
    }
}

#[cfg(test)]
mod tests {
    use glam::{Vec2, Vec3};

    use super::*;
    use crate::render::camera::Projection;

    /// Triangle k of the frames lies on patch k.
    const TRIANGLE_PATCH: [u32; 2] = [0, 1];

    /// The camera of the tests: at the origin looking down −z through a 10° perspective.
    fn camera() -> Camera {
        Camera {
            eye: Vec3::ZERO,
            target: Vec3::NEG_Z,
            up: Vec3::Y,
            projection: Projection::Perspective {
                fov_y_degrees: 10.0,
            },
            near: 0.1,
            far: 100.0,
        }
    }

    /// A 9 × 9 one-sample frame through [`camera`] whose every sample holds what `seen(x, y)`
    /// says: `Some((triangle, pixel widths nearer than 10 units))`, or nothing.
    fn frame(seen: impl Fn(usize, usize) -> Option<(u32, f32)>) -> VisibilityBuffer {
        let mut visibility = VisibilityBuffer {
            width: 9,
            height: 9,
            depth: vec![f32::INFINITY; 81],
            triangle: vec![u32::MAX; 81],
            barycentric: vec![[0.0; 2]; 81],
        };
        let camera = camera();
        let test = DepthTest::new(&visibility, &TRIANGLE_PATCH, 1, &camera);
        let width = test.pixel_width(10.0);
        let depths: Vec<Option<(u32, f32)>> = (0..81)
            .map(|s| {
                seen(s % 9, s / 9)
                    .map(|(triangle, nearer)| (triangle, test.ndc_of(10.0 - nearer * width)))
            })
            .collect();
        for (s, seen) in depths.iter().enumerate() {
            if let Some((triangle, depth)) = *seen {
                visibility.depth[s] = depth;
                visibility.triangle[s] = triangle;
            }
        }
        visibility
    }

    /// Whether the point of an open border on patch 0 at the centre of sample (4, 4) of the
    /// [`frame`] `seen`, 10 units away, shows within half a pixel: to [`DepthTest::shows`], and
    /// to [`DepthTest::shows_open`].
    fn open_border_shows(seen: impl Fn(usize, usize) -> Option<(u32, f32)>) -> (bool, bool) {
        let (visibility, camera) = (frame(seen), camera());
        let test = DepthTest::new(&visibility, &TRIANGLE_PATCH, 1, &camera);
        let (point, z) = (Vec2::splat(4.5), test.ndc_of(10.0));
        (test.shows(point, z, 0.5), test.shows_open(point, z, 0.5, 0))
    }

    /// Whether the point of a line inside an outline at the centre of sample (4, 4) of the
    /// [`frame`] `seen`, 10 units away, shows within half a pixel.
    fn shows_on_surface(seen: impl Fn(usize, usize) -> Option<(u32, f32)>) -> bool {
        let (visibility, camera) = (frame(seen), camera());
        let test = DepthTest::new(&visibility, &TRIANGLE_PATCH, 1, &camera);
        test.shows_on_surface(Vec2::splat(4.5), test.ndc_of(10.0), 0.5)
    }

    #[test]
    fn a_line_inside_an_outline_shows_on_a_surface_at_its_depth_and_not_on_background() {
        // The surface it lies on, all about it or at its own sample alone.
        assert!(shows_on_surface(|_, _| Some((0, 0.0))));
        assert!(shows_on_surface(
            |x, y| (x == 4 && y == 4).then_some((0, 0.0))
        ));
        // Farther surfaces do not hide it.
        assert!(shows_on_surface(|_, _| Some((1, -3.0))));
        // Background alone, where a silhouette would show.
        assert!(!shows_on_surface(|_, _| None));
        assert!(open_border_shows(|_, _| None).0);
        // A nearer surface over it, by a pixel width (5 % of the distance).
        assert!(!shows_on_surface(|_, _| Some((1, 1.0))));
    }

    #[test]
    fn points_in_the_first_and_last_rows_and_columns_are_tested_on_their_samples() {
        // A nearer surface over the whole frame hides a point in any pixel whose samples within
        // reach are on the image; a window reaching past the image shows the point.
        let visibility = frame(|_, _| Some((1, 1.0)));
        let camera = camera();
        let test = DepthTest::new(&visibility, &TRIANGLE_PATCH, 1, &camera);
        let z = test.ndc_of(10.0);
        for (x, y) in [
            (4.5, 4.5),
            (0.5, 4.5),
            (4.5, 0.5),
            (8.5, 4.5),
            (4.5, 8.5),
            (0.5, 0.5),
        ] {
            let pixel = Vec2::new(x, y);
            assert!(!test.shows(pixel, z, 0.5), "{pixel}");
            assert_eq!(test.shows(pixel, z, 1.0), (x, y) != (4.5, 4.5), "{pixel}");
        }
        // A point at its depth on the surface shows in the corner pixels.
        let visibility = frame(|_, _| Some((0, 0.0)));
        let test = DepthTest::new(&visibility, &TRIANGLE_PATCH, 1, &camera);
        for corner in [Vec2::splat(0.5), Vec2::splat(8.5)] {
            assert!(test.shows_on_surface(corner, z, 0.5), "{corner}");
        }
    }

    #[test]
    fn an_open_border_shows_past_its_own_patch_seen_edge_on_and_no_other() {
        // Its patch, half a pixel nearer, up to the point's column; the background past it.
        let edge_on = |x: usize, _| (x <= 4).then_some((0, 0.5));
        assert_eq!(open_border_shows(edge_on), (false, true));
        // Nearer than an edge-on patch would be: another part of the patch hides it.
        let folded = |x: usize, _| (x <= 4).then_some((0, 2.0 * EDGE_ON_PIXELS));
        assert_eq!(open_border_shows(folded), (false, false));
        // Another patch in front hides it.
        let other = |x: usize, _| (x <= 4).then_some((1, 0.5));
        assert_eq!(open_border_shows(other), (false, false));
        // The background lies farther than a silhouette's reach.
        let far = |x: usize, _| (x <= 5).then_some((0, 0.5));
        assert_eq!(open_border_shows(far), (false, false));
        // Its own patch at its depth shows it, as any line.
        let flat = |x: usize, _| (x <= 4).then_some((0, 0.0));
        assert_eq!(open_border_shows(flat), (true, true));
    }
}
