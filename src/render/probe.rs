//! Probing the surface from a texel: how its (u, v) changes from one pixel to the next, which
//! measures how near the sides of its patch's domain it lies and moves a probe's start from it,
//! and where a probe lands on a sample's ray.

use glam::{Mat4, Vec2, Vec3};

use super::gbuffer::GBuffer;
use crate::geom::{Edge, PatchLibrary};

/// How far inside its patch's domain, in pixels by the slope of its (u, v), a texel must lie
/// to be [`away_from_borders`].
const INSIDE_PIXELS: f32 = 3.0;

/// Whether texel `slot` lies [`INSIDE_PIXELS`] or more inside its patch's domain, measured by
/// the slope of its (u, v) ([`uv_slopes`]); not when it has no slope along x or y (no neighbour
/// on its patch there).
#[must_use]
pub(super) fn away_from_borders(gbuffer: &GBuffer, library: &PatchLibrary, slot: u32) -> bool {
    sides_within(gbuffer, library, slot, INSIDE_PIXELS).is_some_and(|near| !near.contains(&true))
}

/// Per side of its patch's domain ([`Edge::ALL`] order), whether texel `slot` lies within
/// `pixels` of it, measured by the slope of its (u, v) ([`uv_slopes`]): not `u − r_u > u₀` for
/// the side `u = u₀`, with `r = (|∂(u, v)/∂x| + |∂(u, v)/∂y|) · pixels`. `None` where it has no
/// slope along x or y (no neighbour on its patch there).
#[must_use]
pub(super) fn sides_within(
    gbuffer: &GBuffer,
    library: &PatchLibrary,
    slot: u32,
    pixels: f32,
) -> Option<[bool; 4]> {
    let t = &gbuffer.texels[slot as usize];
    let (Some(along_x), Some(along_y)) = uv_slopes(gbuffer, slot) else {
        return None;
    };
    let reach = (along_x.abs() + along_y.abs()) * pixels;
    let domain = library.patches[t.patch as usize].surface.domain();
    let (u, v) = (f64::from(t.uv.x), f64::from(t.uv.y));
    let (ru, rv) = (f64::from(reach.x), f64::from(reach.y));
    // Not inside by the reach is within it: a (u, v) that is not a number is near every side.
    Some(Edge::ALL.map(|side| {
        let inside = match side {
            Edge::UMin => u - ru > domain.u.0,
            Edge::UMax => u + ru < domain.u.1,
            Edge::VMin => v - rv > domain.v.0,
            Edge::VMax => v + rv < domain.v.1,
        };
        !inside
    }))
}

/// The change of (u, v) per pixel at texel `slot`, along x and along y: the central (or
/// one-sided) differences to its neighbours on its patch; `None` along an axis where no
/// neighbour is on the patch or (u, v) jumps (a seam of a closed surface). A sample started
/// from the texel's (u, v) moved by them to the sample's offset takes Newton a step or two
/// fewer.
#[must_use]
pub(super) fn uv_slopes(gbuffer: &GBuffer, slot: u32) -> (Option<Vec2>, Option<Vec2>) {
    let t = &gbuffer.texels[slot as usize];
    let (w, h) = (gbuffer.width as usize, gbuffer.height as usize);
    let i = t.pixel as usize;
    let (x, y) = (i % w, i / w);
    let uv_at = |pixel: Option<usize>| {
        let n = gbuffer.texel(pixel?)?;
        (n.patch == t.patch && (n.uv - t.uv).abs().max_element() < SEAM).then_some(n.uv)
    };
    let slope = |before: Option<Vec2>, after: Option<Vec2>| match (before, after) {
        (Some(b), Some(a)) => Some((a - b) * 0.5),
        (Some(b), None) => Some(t.uv - b),
        (None, Some(a)) => Some(a - t.uv),
        (None, None) => None,
    };
    (
        slope(
            uv_at((x > 0).then(|| i - 1)),
            uv_at((x + 1 < w).then(|| i + 1)),
        ),
        slope(
            uv_at((y > 0).then(|| i - w)),
            uv_at((y + 1 < h).then(|| i + w)),
        ),
    )
}

/// The most (u, v) may change between neighbouring pixels and still be taken for a slope rather
/// than a seam.
const SEAM: f32 = 0.25;

/// The depth at which `point` lands on sample `sample` of a `width × height` grid of samples
/// seen through `to_screen`: its NDC depth when it projects within [`HIT_SAMPLES`] of the
/// sample's centre (its ray meets the surface there), `None` otherwise or when not finite.
#[must_use]
pub(super) fn landed_depth(
    to_screen: Mat4,
    point: Vec3,
    sample: u32,
    (width, height): (u32, u32),
) -> Option<f32> {
    let p = to_screen * point.extend(1.0);
    let (x, y) = (
        (p.x / p.w + 1.0) * 0.5 * width as f32,
        (1.0 - p.y / p.w) * 0.5 * height as f32,
    );
    let centre = ((sample % width) as f32 + 0.5, (sample / width) as f32 + 0.5);
    let depth = p.z / p.w;
    // Written so that a point that is not finite is no hit.
    (p.w > 0.0
        && (x - centre.0).abs() <= HIT_SAMPLES
        && (y - centre.1).abs() <= HIT_SAMPLES
        && depth.is_finite())
    .then_some(depth)
}

/// How far, in samples, a grown sample's refined surface point may project from the sample's
/// centre and still count as a hit.
pub(super) const HIT_SAMPLES: f32 = 0.05;
