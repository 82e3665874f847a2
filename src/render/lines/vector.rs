//! Vector lines: the strokes a frame's lines are drawn with, as polylines in image coordinates,
//! for a 2D pipeline to clean, re-ink and colour.
//!
//! They are the capsules the frame draws ([`stroke`](super::stroke)), regrouped: along each
//! visible stretch of a chain, the capsules of one colour, opacity, kind and part that follow
//! one another make one polyline with a width at each point. A stretch at full width is one
//! polyline of one width; each taper, where the width runs down to an end, is a polyline of
//! its own whose width changes point by point. Hidden lines are polylines of their own, whole:
//! their dash pattern goes with them, and where along its stretch each starts.

use glam::{Vec2, Vec3};

use super::chain::Drawn;
use super::piece::Piece;
use crate::geom::PatchLibrary;
use crate::render::line_style::{Dash, LineKind, LineStyle};

/// Points of one polyline closer than this (pixels) are the same point: the capsules of a
/// stretch share their ends exactly, so this only absorbs rounding.
const SAME_END: f32 = 1e-3;

/// The visible lines of a frame as strokes.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VectorLines {
    /// The image, in pixels: the strokes' coordinates run over `[0, width] × [0, height]`,
    /// `y` down, pixel `(i, j)` covering `[i, i + 1] × [j, j + 1]`.
    pub size: (u32, u32),
    /// The parts the strokes are grouped by, named ([`part_of`]).
    pub parts: Vec<String>,
    /// The strokes, in the order the frame draws them.
    pub strokes: Vec<VectorStroke>,
}

/// One stroke: a polyline with a width at each point, drawn with round caps and joins.
#[derive(Clone, Debug, PartialEq)]
pub struct VectorStroke {
    pub kind: LineKind,
    /// Its part, an index into [`VectorLines::parts`].
    pub part: u32,
    /// Linear RGB.
    pub colour: Vec3,
    /// Coverage inside the stroke, in [0, 1] (a crease fades with its angle).
    pub opacity: f32,
    /// At least two points (equal for a dot).
    pub points: Vec<Vec2>,
    /// The stroke's width in pixels at each of `points`.
    pub widths: Vec<f32>,
    /// Whether the polyline closes on itself: its last point joins its first.
    pub closed: bool,
    /// Whether it is a hidden line (behind some surface), drawn in its dash pattern.
    pub hidden: bool,
    /// The dash pattern it is drawn in ([`Dash::SOLID`] for a visible line).
    pub dash: Dash,
    /// How far along its pattern it starts (pixels): where along its stretch its first
    /// point lies.
    pub dash_offset: f32,
}

impl VectorStroke {
    /// Its width when it is the same at every point: a stroke at full width, not a taper.
    #[must_use]
    pub fn uniform_width(&self) -> Option<f32> {
        let first = *self.widths.first()?;
        self.widths.iter().all(|&w| w == first).then_some(first)
    }
}

/// The part a patch's lines are grouped under: the smallest named group of the library that
/// holds the patch (the first of equals), or the patch's own name when no group does.
#[must_use]
pub fn part_of(library: &PatchLibrary, patch: usize) -> &str {
    library
        .groups
        .iter()
        .filter(|g| g.patches.binary_search(&patch).is_ok())
        .min_by_key(|g| g.patches.len())
        .map_or(library.patches[patch].name.as_str(), |g| g.name.as_str())
}

impl VectorLines {
    /// The strokes of `drawn` (each chain's capsules, in drawing order) and then of `hidden`
    /// (its hidden stretches, in the colours after the styles' own), whose pieces are
    /// `pieces`, coloured and grouped by the styles and parts of `library`'s patches.
    #[must_use]
    pub(super) fn of(
        (drawn, hidden): (&[Drawn], &[Drawn]),
        pieces: &[Piece],
        (styles, library): (&[LineStyle], &PatchLibrary),
        size: (u32, u32),
    ) -> Self {
        let mut lines = VectorLines {
            size,
            ..Self::default()
        };
        // Per patch, its part's index, found when a stroke first needs it.
        let mut part_index: Vec<Option<u32>> = vec![None; library.patches.len()];
        let mut part = |patch: usize, parts: &mut Vec<String>| -> u32 {
            *part_index[patch].get_or_insert_with(|| {
                let name = part_of(library, patch);
                match parts.iter().position(|p| p == name) {
                    Some(k) => k as u32,
                    None => {
                        parts.push(name.to_string());
                        (parts.len() - 1) as u32
                    }
                }
            })
        };
        let count = styles.len();
        let chains = drawn.iter().map(|d| (d, false));
        for (chain, is_hidden) in chains.chain(hidden.iter().map(|d| (d, true))) {
            for (range, whole_loop) in &chain.stretches {
                let first = lines.strokes.len();
                let mut open: Option<VectorStroke> = None;
                // How far along the stretch the capsule starts.
                let mut along = 0.0f32;
                for k in range.clone() {
                    let c = &chain.capsules[k];
                    let style = c.colour as usize % count.max(1);
                    let (colour, dash) = match (is_hidden, styles[style].hidden) {
                        (true, Some(h)) => (h.colour, h.dash),
                        (true, None) | (false, _) => (styles[style].colour, Dash::SOLID),
                    };
                    let stroke = VectorStroke {
                        kind: pieces[chain.pieces[k] as usize].kind,
                        part: part(style, &mut lines.parts),
                        colour,
                        opacity: c.opacity,
                        points: vec![c.a, c.b],
                        widths: vec![2.0 * c.radii[0], 2.0 * c.radii[1]],
                        closed: false,
                        hidden: is_hidden,
                        dash,
                        dash_offset: along,
                    };
                    along += c.a.distance(c.b);
                    // A capsule of one radius goes on a stroke of that width; one whose radius
                    // changes, on a taper.
                    let tapered = c.radii[0] != c.radii[1];
                    let continues = open.as_ref().is_some_and(|o| {
                        o.kind == stroke.kind
                            && o.hidden == stroke.hidden
                            && o.dash == stroke.dash
                            && o.part == stroke.part
                            && o.colour == stroke.colour
                            && o.opacity == stroke.opacity
                            && o.points.last().is_some_and(|p| p.distance(c.a) <= SAME_END)
                            && match (o.uniform_width(), tapered) {
                                (Some(w), false) => w == stroke.widths[0],
                                // A taper goes on while its capsules taper.
                                (None, true) => true,
                                // A taper's first capsule starts it.
                                (Some(_), true) | (None, false) => false,
                            }
                    });
                    if continues {
                        if let Some(o) = open.as_mut() {
                            o.points.push(c.b);
                            o.widths.push(2.0 * c.radii[1]);
                        }
                        continue;
                    }
                    lines.strokes.extend(open.take());
                    open = Some(stroke);
                }
                lines.strokes.extend(open.take());
                // A closed line drawn whole as one polyline closes.
                if *whole_loop && lines.strokes.len() == first + 1 {
                    let stroke = &mut lines.strokes[first];
                    let (start, end) = (stroke.points[0], stroke.points[stroke.points.len() - 1]);
                    if start.distance(end) <= SAME_END && stroke.points.len() > 2 {
                        stroke.points.pop();
                        stroke.closed = true;
                    }
                }
            }
        }
        lines
    }
}
