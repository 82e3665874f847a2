//! Outlines: ink lines where the G-buffer is discontinuous — silhouettes against the background
//! and against farther surfaces, creases, and (optionally) borders between patches.

use glam::{Vec3, Vec4};
use rayon::prelude::*;

use super::gbuffer::{GBuffer, Texel, EMPTY, PIXELS_PER_JOB};
use super::scene::Outlines;

/// Relative jump in the second difference of inverse view depth that marks an occlusion edge.
/// Inverse depth is affine in screen space across a plane, so its second difference vanishes on
/// smooth surfaces and is large where a nearer surface overlaps a farther one.
const DEPTH_JUMP: f32 = 0.02;

/// The data and working memory of the outline pass, kept from one frame to the next.
#[derive(Debug, Default)]
pub(super) struct OutlineBuffers {
    /// Per texel of the G-buffer, what the edge tests compare: filled with the G-buffer
    /// ([`GBuffer::fill`]) when the frame draws outlines.
    pub surfaces: Vec<EdgeSurface>,
    /// Per pixel, whether it differs from its right or lower neighbour.
    edges: Vec<bool>,
}

impl OutlineBuffers {
    /// Per pixel of the last image lines were drawn on, whether a line runs from it (the
    /// pixels the lines are centred on).
    pub(super) fn edges(&self) -> &[bool] {
        &self.edges
    }
}

/// What the edge tests read of a texel, packed.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct EdgeSurface {
    patch: u32,
    normal: Vec3,
    /// `1 / ((P − eye)·forward)`.
    inverse_depth: f32,
}

impl EdgeSurface {
    /// The edge surface of texel `t`, seen from `eye` looking along the unit `forward`.
    #[inline]
    pub(super) fn of(t: &Texel, eye: Vec3, forward: Vec3) -> Self {
        Self {
            patch: t.patch,
            normal: t.frame.n,
            inverse_depth: 1.0 / (t.position - eye).dot(forward).max(1e-6),
        }
    }
}

/// Inks lines `outlines.width` pixels wide over `colour` (an image of the G-buffer's size):
/// every pixel within `(width − 1)/2` of an edge pixel becomes `rgb = outlines.colour`, `α = 1`.
/// `buffers` must hold the edge surfaces of the G-buffer's texels.
pub(super) fn draw_outlines(
    gbuffer: &GBuffer,
    outlines: &Outlines,
    colour: &mut [Vec4],
    buffers: &mut OutlineBuffers,
) {
    find_edges(gbuffer, outlines, buffers);
    let edges = &buffers.edges;
    let (w, h) = (gbuffer.width as usize, gbuffer.height as usize);
    // The disc of the line around an edge pixel, row by row: (dy, largest |dx|).
    let radius = ((outlines.width.max(1.0) - 1.0) * 0.5).max(0.0);
    let reach = radius.ceil() as i64;
    let disc: Vec<(i64, i64)> = (-reach..=reach)
        .filter_map(|dy| {
            (0..=reach)
                .rev()
                .find(|&dx| (dx * dx + dy * dy) as f32 <= radius * radius + 1e-3)
                .map(|dx| (dy, dx))
        })
        .collect();
    colour
        .par_chunks_mut(w)
        .with_min_len(PIXELS_PER_JOB.div_ceil(w))
        .enumerate()
        .for_each_init(Vec::new, |inked: &mut Vec<bool>, (y, row)| {
            inked.clear();
            inked.resize(w, false);
            let mut any = false;
            for &(dy, dx) in &disc {
                let Some(edge_row) = (y as i64 + dy)
                    .try_into()
                    .ok()
                    .filter(|&y: &usize| y < h)
                    .map(|y| &edges[y * w..][..w])
                else {
                    continue;
                };
                for (x, _) in edge_row.iter().enumerate().filter(|(_, &edge)| edge) {
                    let (x0, x1) = (x.saturating_sub(dx as usize), (x + dx as usize).min(w - 1));
                    inked[x0..=x1].fill(true);
                    any = true;
                }
            }
            if any {
                for (c, _) in row.iter_mut().zip(inked.iter()).filter(|(_, &ink)| ink) {
                    *c = c.truncate().lerp(outlines.colour, 1.0).extend(1.0);
                }
            }
        });
}

/// Marks the pixels that differ from their right or lower neighbour: exactly one of the two is
/// covered; or both are, on different patches (with patch borders on), or on one patch with
/// normals turning by more than the crease angle. A covered pixel whose inverse depth has a
/// jump in its second difference across it, along a row or a column, is marked too: a nearer
/// surface overlaps a farther one there.
fn find_edges(gbuffer: &GBuffer, outlines: &Outlines, buffers: &mut OutlineBuffers) {
    let (w, h) = (gbuffer.width as usize, gbuffer.height as usize);
    let surfaces = &buffers.surfaces;
    assert_eq!(surfaces.len(), gbuffer.texels.len(), "no edge surfaces");
    let crease_cos = outlines.crease_degrees.to_radians().cos();
    let differs = |a: u32, b: u32| -> bool {
        if b == EMPTY {
            return true;
        }
        let (a, b) = (&surfaces[a as usize], &surfaces[b as usize]);
        (outlines.patch_borders && a.patch != b.patch)
            || (a.patch == b.patch && a.normal.dot(b.normal) < crease_cos)
    };
    let occludes = |before: u32, here: u32, after: u32| -> bool {
        if before == EMPTY || after == EMPTY {
            return false;
        }
        let depth = |s: u32| surfaces[s as usize].inverse_depth;
        let (a, c, b) = (depth(before), depth(here), depth(after));
        (a + b - 2.0 * c).abs() > DEPTH_JUMP * c
    };
    let row = |y: usize| &gbuffer.slot[y * w..][..w];
    buffers.edges.resize(w * h, false);
    buffers
        .edges
        .par_chunks_mut(w)
        .with_min_len(PIXELS_PER_JOB.div_ceil(w))
        .enumerate()
        .for_each(|(y, edges)| {
            let (here, above, below) = (
                row(y),
                (y > 0).then(|| row(y - 1)),
                (y + 1 < h).then(|| row(y + 1)),
            );
            for (x, edge) in edges.iter_mut().enumerate() {
                let s = here[x];
                let right = (x + 1 < w).then(|| here[x + 1]);
                let down = below.map(|b| b[x]);
                *edge = if s == EMPTY {
                    right.is_some_and(|r| r != EMPTY) || down.is_some_and(|d| d != EMPTY)
                } else {
                    right.is_some_and(|r| differs(s, r))
                        || down.is_some_and(|d| differs(s, d))
                        || (x > 0 && right.is_some_and(|r| occludes(here[x - 1], s, r)))
                        || above.zip(down).is_some_and(|(a, d)| occludes(a[x], s, d))
                };
            }
        });
}
