//! A point in clip space as a point of the image in pixels.

use glam::{Vec2, Vec4};

/// A point of the image in pixels (pixel `(i, j)`'s centre at `(i + 0.5, j + 0.5)`) and its NDC
/// depth, from a point in clip space; None at or behind the eye.
#[inline]
#[must_use]
pub(super) fn to_screen(clip: Vec4, (w, h): (u32, u32)) -> Option<(Vec2, f32)> {
    if clip.w <= 1e-6 || !clip.is_finite() {
        return None;
    }
    let ndc = clip.truncate() / clip.w;
    Some((
        Vec2::new(
            (ndc.x + 1.0) * 0.5 * w as f32,
            (1.0 - ndc.y) * 0.5 * h as f32,
        ),
        ndc.z,
    ))
}
