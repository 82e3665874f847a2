//! Where two patches meet, each near a side of its domain that nothing continues: they may
//! leave a gap between them there thinner than a pixel, which no pixel centre sees.

use rayon::prelude::*;

use crate::geom::{Edge, PatchLibrary};
use crate::render::gbuffer::{GBuffer, Texel, EMPTY, PIXELS_PER_JOB};
use crate::render::neighbourhood::around;
use crate::render::probe::sides_within;
use crate::render::tessellate::Mesh;

/// How near an open side of its patch's domain, in pixels by the slope of its (u, v), a texel
/// beside another patch must lie for the pair's pixels to be drawn at k × k samples.
const OPEN_SIDE_PIXELS: f32 = 1.5;

/// Per patch of `library`, whether each side of its domain ([`Edge::ALL`] order) has a piece of
/// boundary in `mesh` that no other patch continues (the mesh's boundary pieces with nothing
/// across).
#[must_use]
pub(in crate::render) fn open_sides(mesh: &Mesh, library: &PatchLibrary) -> Vec<[bool; 4]> {
    let mut open = vec![[false; 4]; library.patches.len()];
    for edge in mesh.borders.iter().filter(|e| e.across.is_none()) {
        let domain = library.patches[edge.patch as usize].surface.domain();
        let (a, b) = (mesh.uvs[edge.a as usize], mesh.uvs[edge.b as usize]);
        let on = |x: f32, y: f32, at: f64, span: f64| {
            let near = |t: f32| (f64::from(t) - at).abs() <= 1e-6 * span;
            near(x) && near(y)
        };
        let (du, dv) = (domain.u.1 - domain.u.0, domain.v.1 - domain.v.0);
        for (k, side) in Edge::ALL.into_iter().enumerate() {
            open[edge.patch as usize][k] |= match side {
                Edge::UMin => on(a.x, b.x, domain.u.0, du),
                Edge::UMax => on(a.x, b.x, domain.u.1, du),
                Edge::VMin => on(a.y, b.y, domain.v.0, dv),
                Edge::VMax => on(a.y, b.y, domain.v.1, dv),
            };
        }
    }
    open
}

/// Per pixel of `gbuffer`'s image, whether it shows a patch and one of its eight neighbours
/// shows another, each texel within [`OPEN_SIDE_PIXELS`] of an open side of its own patch
/// (`open`, per patch as [`open_sides`] gives it). Two patches that end there side by side
/// (doors in a body) may leave a gap thinner than a pixel, through which what lies behind
/// shows, and both may have one colour: the colours of the pixel centres show neither the gap
/// nor the edge. Where one of them goes on, what shows past the other's end is the one that
/// goes on. `drawn`, per texel when known, says which were drawn right at one sample: their
/// neighbourhoods lie on their own patches, and they are passed over.
#[must_use]
pub(in crate::render) fn beside_open_sides(
    gbuffer: &GBuffer,
    library: &PatchLibrary,
    open: &[[bool; 4]],
    drawn: Option<&[bool]>,
) -> Vec<bool> {
    let (w, h) = (gbuffer.width as usize, gbuffer.height as usize);
    let mut marked = vec![false; w * h];
    if !open.iter().flatten().any(|&o| o) {
        return marked;
    }
    // Per texel, whether it shows a patch with an open side beside another patch, near that
    // side: each texel's slopes are taken once.
    let beside_another = |t: &Texel| {
        around(t.pixel as usize, (w, h))
            .any(|n| gbuffer.texel(n).is_some_and(|other| other.patch != t.patch))
    };
    let near: Vec<bool> = gbuffer
        .texels
        .par_iter()
        .enumerate()
        .with_min_len(PIXELS_PER_JOB)
        .map(|(slot, t)| {
            open[t.patch as usize].contains(&true)
                && !drawn.is_some_and(|d| d[slot])
                && beside_another(t)
                && near_open_side(gbuffer, library, open, slot as u32)
        })
        .collect();
    let pixels: Vec<usize> = gbuffer
        .texels
        .par_iter()
        .zip(&near)
        .with_min_len(PIXELS_PER_JOB)
        .filter(|(_, &near)| near)
        .filter_map(|(t, _)| {
            let p = t.pixel as usize;
            around(p, (w, h))
                .any(|n| {
                    let slot = gbuffer.slot[n];
                    slot != EMPTY
                        && gbuffer.texels[slot as usize].patch != t.patch
                        && near[slot as usize]
                })
                .then_some(p)
        })
        .collect();
    for p in pixels {
        marked[p] = true;
    }
    marked
}

/// Whether texel `slot` lies within [`OPEN_SIDE_PIXELS`] of an open side of its patch's
/// domain, by the slope of its (u, v) ([`sides_within`]); when it has no slope along x or y,
/// near any open side.
fn near_open_side(
    gbuffer: &GBuffer,
    library: &PatchLibrary,
    open: &[[bool; 4]],
    slot: u32,
) -> bool {
    let sides = open[gbuffer.texels[slot as usize].patch as usize];
    if !sides.contains(&true) {
        return false;
    }
    sides_within(gbuffer, library, slot, OPEN_SIDE_PIXELS)
        .is_none_or(|near| near.iter().zip(sides).any(|(&near, open)| near && open))
}
