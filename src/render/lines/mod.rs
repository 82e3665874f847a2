//! [`Stage::Outline`](super::Stage::Outline): ink lines as anti-aliased strokes along curves
//! found on the mesh — silhouettes, creases, borders and intersections — kept where the depth
//! buffer shows them.
//!
//! The curves are decided on the surface, not by comparing neighbouring pixels, so that a line
//! does not break up when the view turns: a silhouette is where `N·(P − E)` changes sign
//! ([`contour`]), a border or crease is a piece of a patch's domain boundary ([`border`]), an
//! intersection is where two patches pass through each other ([`intersection`], found once per
//! mesh: [`MeshLines`]).
//! Pieces that share an end are joined into lines ([`chain`]); each line is cut into samples
//! half a pixel apart, each kept when no nearer surface hides it ([`visible`]), and each
//! visible stretch is drawn as capsules of the line's width ([`stroke`]): where capsules meet,
//! the joins are round.

mod border;
mod chain;
mod contour;
mod intersection;
mod piece;
mod stroke;
mod visible;

use glam::{Mat4, Vec2, Vec3, Vec4};
use rayon::prelude::*;

use super::camera::Camera;
use super::gbuffer::PIXELS_PER_JOB;
use super::raster::VisibilityBuffer;
use super::renderer::{premultiplied, straight};
use super::scene::Outlines;
use super::tessellate::Mesh;
use crate::geom::PatchLibrary;
use piece::{LineKind, Piece};
use stroke::Capsule;
use visible::DepthTest;

/// The lines of a frame: per output pixel their coverage and colour.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct LineImage {
    /// Per pixel, the lines' coverage in [0, 1].
    pub alpha: Vec<f32>,
    /// Linear RGB of the lines.
    pub colour: Vec3,
    /// How many pixels the lines ink (coverage above 0).
    pub inked: u64,
}

impl LineImage {
    /// Whether pixel `p` is wholly inked: nothing under it shows.
    #[must_use]
    pub fn hides(&self, p: usize) -> bool {
        self.alpha[p] >= 1.0
    }

    /// `colour` (straight alpha, one per pixel) with the lines over it:
    /// `premultiplied = α_l rgb_l + (1 − α_l) α rgb`, `α' = α_l + (1 − α_l) α`.
    pub fn composite(&self, colour: &mut [Vec4]) {
        colour
            .par_iter_mut()
            .zip(&self.alpha)
            .with_min_len(PIXELS_PER_JOB)
            .filter(|(_, &a)| a > 0.0)
            .for_each(|(c, &a)| {
                let line = (self.colour * a).extend(a);
                *c = straight(line + premultiplied(*c) * (1.0 - a));
            });
    }

    /// The lines alone, straight alpha: the outline AOV.
    #[must_use]
    pub fn alone(&self) -> Vec<Vec4> {
        self.alpha
            .iter()
            .map(|&a| {
                if a > 0.0 {
                    self.colour.extend(a)
                } else {
                    Vec4::ZERO
                }
            })
            .collect()
    }
}

/// What the lines keep of a mesh from one frame to the next: the curves along which its
/// patches pass through one another, which depend on the mesh alone.
#[derive(Debug, Default)]
pub(super) struct MeshLines {
    /// The [`Tessellator::generation`](super::tessellate::Tessellator::generation) of the mesh
    /// they were found on.
    generation: u64,
    intersections: Vec<[Vec3; 2]>,
}

impl MeshLines {
    /// The intersections of `mesh`, of tessellation `generation`: found again only when the
    /// mesh is not the one they were found on.
    pub fn intersections(&mut self, mesh: &Mesh, generation: u64) -> &[[Vec3; 2]] {
        if self.generation != generation || generation == 0 {
            self.intersections = intersection::intersections(mesh);
            self.generation = generation;
        }
        &self.intersections
    }
}

/// What the lines are found on and tested against.
pub(super) struct LineInput<'a> {
    pub library: &'a PatchLibrary,
    pub mesh: &'a Mesh,
    /// Where the mesh's patches pass through one another ([`MeshLines::intersections`]).
    pub intersections: &'a [[Vec3; 2]],
    pub camera: &'a Camera,
    pub view_projection: Mat4,
    /// The frame's depth, `k × k` samples per pixel.
    pub visibility: &'a VisibilityBuffer,
    pub k: u32,
    /// The image in pixels.
    pub size: (u32, u32),
}

/// The lines `outlines` asks for, over an image of `input.size` pixels.
#[must_use]
pub(super) fn draw_lines(input: &LineInput, outlines: &Outlines) -> LineImage {
    let mut pieces: Vec<Piece> = contour::silhouettes(
        input.mesh,
        input.library,
        input.camera,
        input.view_projection,
        input.size,
    );
    pieces.extend(border::borders_and_creases(
        input.mesh,
        input.library,
        input.camera,
        input.view_projection,
        input.size,
        outlines,
    ));
    pieces.extend(input.intersections.iter().map(|&[a, b]| Piece {
        ends: [a.as_dvec3(), b.as_dvec3()],
        on_mesh: [a, b],
        opacity: 1.0,
        kind: LineKind::Intersection,
    }));
    let (w, h) = input.size;
    let depth = DepthTest::new(input.visibility, input.k, input.camera);
    let radius = 0.5 * outlines.width.max(1.0);
    let screen: Vec<_> = pieces
        .par_iter()
        .with_min_len(256)
        .map(|piece| piece.on_screen(input.view_projection, input.size, radius))
        .collect();
    let shows: Vec<Vec<bool>> = screen
        .par_iter()
        .with_min_len(64)
        .map(|on| {
            on.as_ref()
                .map_or_else(Vec::new, |on| chain::sample_piece(on, &depth))
        })
        .collect();
    let capsules: Vec<Capsule> = chain::chains(&pieces)
        .par_iter()
        .flat_map_iter(|line| chain::visible_capsules(line, &screen, &shows, radius))
        .collect();
    let mut alpha = vec![0.0; w as usize * h as usize];
    stroke::draw(&capsules, (w, h), &mut alpha);
    let inked = alpha.iter().filter(|&&a| a > 0.0).count() as u64;
    LineImage {
        alpha,
        colour: outlines.colour,
        inked,
    }
}

/// A point of the image in pixels (pixel `(i, j)`'s centre at `(i + 0.5, j + 0.5)`) and its NDC
/// depth, from a point in clip space; None at or behind the eye.
#[inline]
fn to_screen(clip: Vec4, (w, h): (u32, u32)) -> Option<(Vec2, f32)> {
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
