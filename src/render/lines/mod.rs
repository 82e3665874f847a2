//! [`Stage::Outline`](super::Stage::Outline): ink lines as anti-aliased strokes along curves
//! found on the mesh — silhouettes, creases, borders, material borders, intersections and light
//! contours — kept where the depth buffer shows them (or drawn in their hidden style where it
//! does not).
//!
//! The curves are decided on the surface, not by comparing neighbouring pixels, so that a line
//! does not break up when the view turns: a silhouette is where `N·(P − E)` changes sign
//! ([`contour`]), a border or crease is a piece of a patch's domain boundary ([`border`]) or of
//! a trimmed patch's trim loops ([`trim_border`]) — a material border where its two sides'
//! materials differ — an intersection is where two patches pass through each other ([`intersection`], found once per
//! mesh: [`MeshLines`]), a light contour where the tone's `N·L` crosses a band threshold
//! ([`light_contour`]).
//! Pieces that share an end are joined into lines ([`chain`]); each line is cut into samples
//! half a pixel apart, each kept when no nearer surface hides it ([`visible`]), and each
//! visible stretch is drawn as capsules of the line's width ([`stroke`]): where capsules meet,
//! the joins are round. Where a style draws hidden lines, the hidden samples are given the
//! number of surfaces in front of them ([`occlusion`]), and the stretches behind few enough are
//! drawn in the hidden style, cut into dashes ([`dashes`]). Each patch's [`LineStyle`] says
//! which kinds of line it draws, how wide, in what colour, with what taper and how where
//! hidden; a piece on two patches (a seam, an intersection) is drawn by the wider of the styles
//! that draw its kind.

mod border;
mod chain;
mod contour;
mod dashes;
mod grid_shape;
mod intersection;
mod kept_silhouettes;
mod light_contour;
mod occlusion;
mod piece;
mod screen;
mod stroke;
mod trim_border;
mod vector;
mod visible;

use glam::{Mat4, Vec3, Vec4};
use rayon::prelude::*;

use super::camera::Camera;
use super::colour::{premultiplied, straight};
use super::line_style::{Dash, LineKind, LineStyle};
use super::raster::VisibilityBuffer;
use super::scene::{Outlines, PatchLook};
use super::tessellate::Mesh;
use crate::geom::PatchLibrary;
use crate::highlight::Light;
use grid_shape::GridShape;
use occlusion::Occluders;
use piece::{OnScreen, Piece};
use stroke::Capsule;
use visible::DepthTest;

pub(super) use intersection::Meeting;
use intersection::PairMeetings;
pub(super) use kept_silhouettes::KeptSilhouettes;
pub use vector::{part_of, VectorLines, VectorStroke};

/// The lines of a frame: per output pixel their coverage and colour.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct LineImage {
    /// Per pixel, the lines' coverage in [0, 1].
    pub alpha: Vec<f32>,
    /// The lines' colours, linear RGB: per patch its lines' colour, then per patch its hidden
    /// lines' colour; or a single one when every one of those is the same.
    palette: Vec<Vec3>,
    /// Per pixel, its colour's index in `palette`; empty when the palette has one colour.
    colour: Vec<u32>,
    /// The image's width in pixels.
    width: usize,
    /// Per band of [`stroke::BAND`] rows, how many pixels the lines ink.
    band_inked: Vec<u32>,
    /// How many pixels the lines ink (coverage above 0).
    pub inked: u64,
    /// The same lines as strokes.
    pub vector: std::sync::Arc<VectorLines>,
}

impl LineImage {
    /// Whether pixel `p` is wholly inked: nothing under it shows.
    #[must_use]
    pub fn hides(&self, p: usize) -> bool {
        self.alpha[p] >= 1.0
    }

    /// `colour` (straight alpha, one per pixel) with the lines over it:
    /// `premultiplied = α_l rgb_l + (1 − α_l) α rgb`, `α' = α_l + (1 − α_l) α`.
    /// Bands without ink are skipped.
    pub fn composite(&self, colour: &mut [Vec4]) {
        let band = self.width * stroke::BAND;
        if band == 0 {
            return;
        }
        colour
            .par_chunks_mut(band)
            .zip(self.alpha.par_chunks(band))
            .enumerate()
            .filter(|(b, _)| self.band_inked[*b] > 0)
            .for_each(|(b, (colours, alpha))| {
                for (k, (c, &a)) in colours.iter_mut().zip(alpha).enumerate() {
                    if a > 0.0 {
                        let line = (self.colour_at(b * band + k) * a).extend(a);
                        *c = straight(line + premultiplied(*c) * (1.0 - a));
                    }
                }
            });
    }

    /// The colour of the line at pixel `p`.
    #[inline]
    #[must_use]
    pub fn colour_at(&self, p: usize) -> Vec3 {
        match self.colour.get(p) {
            Some(&index) => self.palette[index as usize],
            None => self.palette.first().copied().unwrap_or(Vec3::ZERO),
        }
    }

    /// The lines alone, straight alpha: the outline AOV.
    #[must_use]
    pub fn alone(&self) -> Vec<Vec4> {
        self.alpha
            .iter()
            .enumerate()
            .map(|(p, &a)| {
                if a > 0.0 {
                    self.colour_at(p).extend(a)
                } else {
                    Vec4::ZERO
                }
            })
            .collect()
    }
}

/// What the lines keep of a mesh from one frame to the next: the curves along which its
/// patches pass through one another, which depend on the mesh alone, pair of patches by pair.
#[derive(Debug, Default)]
pub(super) struct MeshLines {
    /// The [`Tessellator::generation`](super::tessellate::Tessellator::generation) of the mesh
    /// they were found on.
    generation: u64,
    /// Per patch, its grid on that mesh.
    grids: Vec<GridShape>,
    /// The meetings of the pairs that meet, in pair order.
    pairs: Vec<PairMeetings>,
    /// The meetings of every pair, in pair order.
    intersections: Vec<Meeting>,
}

/// How the intersections of a frame's mesh were had: found again on a new mesh, keeping the
/// pairs of patches whose grids stayed, or kept whole from the mesh they were found on.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum IntersectionsFound {
    /// The mesh is the one they were found on.
    Cached,
    /// Found on a new mesh: `kept` pairs of patches taken from before, `tested` intersected
    /// again.
    Again { kept: usize, tested: usize },
}

impl MeshLines {
    /// The intersections of `mesh` (of `library`'s patches, whose trims they respect), of
    /// tessellation `generation`: found again only when the mesh is not the one they were found
    /// on, and then only for the pairs of patches one of whose grids is not bit for bit the one
    /// the last were found on (the patches of a model keep their trims when it moves).
    pub fn intersections(
        &mut self,
        mesh: &Mesh,
        library: &PatchLibrary,
        generation: u64,
    ) -> (&[Meeting], IntersectionsFound) {
        let mut how = IntersectionsFound::Cached;
        if self.generation != generation || generation == 0 {
            let patches = mesh.grids.len();
            let same: Vec<bool> = if self.grids.len() == patches {
                (0..patches)
                    .into_par_iter()
                    .map(|p| self.grids[p].is_in(mesh, p))
                    .collect()
            } else {
                vec![false; patches]
            };
            let before = std::mem::take(&mut self.pairs);
            let found = intersection::intersections_keeping(mesh, library, &same, &before);
            self.grids.resize_with(patches, GridShape::default);
            for (p, _) in same.iter().enumerate().filter(|(_, &s)| !s) {
                self.grids[p] = GridShape::of(mesh, p);
            }
            self.intersections = found
                .pairs
                .iter()
                .flat_map(|p| p.meetings.iter().copied())
                .collect();
            self.pairs = found.pairs;
            self.generation = generation;
            how = IntersectionsFound::Again {
                kept: found.kept,
                tested: found.tested,
            };
        }
        (&self.intersections, how)
    }
}

/// What the lines are found on and tested against.
pub(super) struct LineInput<'a> {
    pub library: &'a PatchLibrary,
    pub mesh: &'a Mesh,
    /// Where the mesh's patches pass through one another ([`MeshLines::intersections`]).
    pub intersections: &'a [Meeting],
    pub camera: &'a Camera,
    pub view_projection: Mat4,
    /// The frame's depth, `k × k` samples per pixel.
    pub visibility: &'a VisibilityBuffer,
    pub k: u32,
    /// The image in pixels.
    pub size: (u32, u32),
    /// Per patch of the library, how its lines are drawn.
    pub styles: &'a [LineStyle],
    /// Per patch of the library, its material ([`Scene::materials`]: empty, one material).
    ///
    /// [`Scene::materials`]: super::Scene::materials
    pub materials: &'a [u32],
    /// The light, and per patch of the library its look: what light contours follow.
    pub light: (&'a Light, &'a [PatchLook]),
}

/// Whether some patch draws lines of `kind`.
#[must_use]
pub(super) fn draws(styles: &[LineStyle], kind: LineKind) -> bool {
    styles.iter().any(|s| s.draws(kind))
}

/// The patch whose style draws `piece`: of the patches it lies on, those whose style draws its
/// kind at a width above 0, the widest (the first of equals); None when none does.
#[must_use]
fn style_of(piece: &Piece, styles: &[LineStyle]) -> Option<u32> {
    let [p, q] = piece.patches;
    let draws = |k: u32| {
        let style = &styles[k as usize];
        style.draws(piece.kind).then_some((style.width, k))
    };
    match (draws(p), draws(q)) {
        (Some((wp, p)), Some((wq, q))) => Some(if wq > wp || (wq == wp && q < p) { q } else { p }),
        (Some((_, k)), None) | (None, Some((_, k))) => Some(k),
        (None, None) => None,
    }
}

/// The lines `outlines` and the patches' styles ask for, over an image of `input.size` pixels,
/// drawn into the buffers of `recycled` (an earlier frame's lines, if any) rather than new ones;
/// the silhouettes of the patches `silhouettes` holds as they are now are kept from it.
#[must_use]
pub(super) fn draw_lines(
    input: &LineInput,
    outlines: &Outlines,
    (recycled, silhouettes): (Option<LineImage>, &mut KeptSilhouettes),
) -> LineImage {
    let styles = input.styles;
    let draws_silhouettes = |patch: u32| styles[patch as usize].draws(LineKind::Silhouette);
    let mut pieces: Vec<Piece> = silhouettes.silhouettes(
        draws_silhouettes,
        input.mesh,
        input.library,
        (input.camera, input.view_projection, input.size),
    );
    pieces.extend(border::borders_and_creases(
        input.mesh,
        input.library,
        input.camera,
        input.view_projection,
        input.size,
        (outlines, styles, input.materials),
    ));
    pieces.extend(trim_border::trim_borders(
        input.mesh,
        input.library,
        input.view_projection,
        input.size,
        styles,
    ));
    if draws(styles, LineKind::LightContour) {
        pieces.extend(light_contour::light_contours(
            |patch| styles[patch as usize].draws(LineKind::LightContour),
            input.light,
            (input.mesh, input.library),
            input.camera,
            (input.view_projection, input.size),
        ));
    }
    pieces.extend(input.intersections.iter().map(|m| Piece {
        ends: m.ends.map(|p| p.as_dvec3()),
        on_mesh: m.ends,
        opacity: 1.0,
        kind: LineKind::Intersection,
        open: false,
        patches: m.patches,
    }));
    let (pieces, style): (Vec<Piece>, Vec<u32>) = pieces
        .into_iter()
        .filter_map(|piece| style_of(&piece, styles).map(|s| (piece, s)))
        .unzip();
    let (w, h) = input.size;
    let depth = DepthTest::new(
        input.visibility,
        &input.mesh.triangle_patch,
        input.k,
        input.camera,
    );
    let screen: Vec<_> = pieces
        .par_iter()
        .zip(&style)
        .with_min_len(256)
        .map(|(piece, &s)| piece.on_screen(input.view_projection, input.size, styles, s))
        .collect();
    // Per piece, how many surfaces may hide it where it is still drawn (0: it is not drawn
    // where hidden).
    let most: Vec<u32> = pieces
        .iter()
        .zip(&style)
        .map(|(piece, &s)| {
            styles[s as usize]
                .hidden_lines(piece.kind)
                .map_or(0, |h| h.levels)
        })
        .collect();
    let occluders = most.iter().any(|&m| m > 0).then(|| {
        Occluders::new(
            (input.mesh, input.library),
            input.camera,
            input.view_projection,
            input.size,
        )
    });
    let levels: Vec<Vec<u8>> = screen
        .par_iter()
        .zip(&most)
        .with_min_len(64)
        .map(|(on, &most)| {
            let hidden = occluders.as_ref().filter(|_| most > 0).map(|o| (o, most));
            on.as_ref()
                .map_or_else(Vec::new, |on| chain::sample_piece(on, &depth, hidden))
        })
        .collect();
    let chains = chain::chains(&pieces);
    let drawn: Vec<chain::Drawn> = chains
        .par_iter()
        .map(|line| chain::visible_capsules(line, &screen, &levels, |_, level| level == 0))
        .collect();
    // Hidden stretches: in the hidden style of the patch whose style draws them, its colour
    // after the styles' own in the palette.
    let hidden: Vec<chain::Drawn> = match &occluders {
        Some(_) => {
            let count = styles.len() as u32;
            let hidden_screen: Vec<Option<OnScreen>> = screen
                .iter()
                .zip(&pieces)
                .map(|(on, piece)| {
                    let on = on.as_ref()?;
                    let h = styles[on.style as usize].hidden_lines(piece.kind)?;
                    Some(on.hidden(0.5 * h.width, count + on.style))
                })
                .collect();
            chains
                .par_iter()
                .map(|line| {
                    chain::visible_capsules(line, &hidden_screen, &levels, |piece, level| {
                        (1..=most[piece]).contains(&u32::from(level))
                    })
                })
                .collect()
        }
        None => Vec::new(),
    };
    let hidden_colour = |s: &LineStyle| s.hidden.map_or(s.colour, |h| h.colour);
    let vector = VectorLines::of(
        (&drawn, &hidden),
        &pieces,
        (styles, input.library),
        input.size,
    );
    let dash_of = |colour: u32| {
        let s = colour as usize % styles.len().max(1);
        styles[s].hidden.map_or(Dash::SOLID, |h| h.dash)
    };
    let mut capsules: Vec<Capsule> = drawn.into_iter().flat_map(|d| d.capsules).collect();
    capsules.extend(hidden.iter().flat_map(|d| dashes::dashed(d, dash_of)));
    let colours = styles
        .iter()
        .map(|s| s.colour)
        .chain(styles.iter().map(hidden_colour));
    let one_colour = colours
        .clone()
        .zip(colours.clone().skip(1))
        .all(|(a, b)| a == b);
    let palette: Vec<Vec3> = if one_colour {
        styles.first().map(|s| s.colour).into_iter().collect()
    } else {
        colours.collect()
    };
    if one_colour {
        capsules.iter_mut().for_each(|c| c.colour = 0);
    }
    let pixels = w as usize * h as usize;
    let (mut alpha, mut colour) = recycled.map_or_else(Default::default, |r| (r.alpha, r.colour));
    alpha.clear();
    alpha.resize(pixels, 0.0);
    colour.clear();
    if !one_colour {
        colour.resize(pixels, 0);
    }
    let band_inked = stroke::draw(&capsules, (w, h), &mut alpha, &mut colour);
    LineImage {
        alpha,
        palette,
        colour,
        width: w as usize,
        inked: band_inked.iter().map(|&n| u64::from(n)).sum(),
        band_inked,
        vector: std::sync::Arc::new(vector),
    }
}
