//! A highlight layer's drawn outline written into a file's text: the plain `Outline([…])`, or a
//! key of `OutlineKeys([(frame, […]), …])` replaced or inserted in frame order; the points
//! written to [`OUTLINE_DECIMALS`] places.

use std::ops::Range;

use super::number_text::{decimal_text, frame_text};
use super::track_splice::{insert_item, Splice};
use crate::anim::Track;
use crate::formats::ron_paths::try_item_spans;
use crate::formats::ron_paths::Step::{self, Field, Index};
use crate::highlight::{Morph, Outline, Segment, Shape};

/// The decimal places an outline's coordinates are written with: t′ is the tangent part of a
/// unit vector, so 10⁻⁴ is a hundredth of a pixel across a highlight a hundred pixels wide.
pub const OUTLINE_DECIMALS: usize = 4;

/// `points` as they read back once written: each coordinate rounded to [`OUTLINE_DECIMALS`]
/// places and read as the shot reader reads it (as an f64, then an f32).
#[must_use]
pub(super) fn rounded(points: &[[f32; 2]]) -> Vec<[f32; 2]> {
    let read = |x: f32| {
        decimal_text(x, OUTLINE_DECIMALS)
            .parse::<f64>()
            .map_or(x, |v| v as f32)
    };
    points.iter().map(|&[x, y]| [read(x), read(y)]).collect()
}

/// `[(x, y), (x, y), …]`: the corners as an outline's list of pieces.
fn pieces_text(points: &[[f32; 2]]) -> String {
    let n = |x: f32| decimal_text(x, OUTLINE_DECIMALS);
    let written: Vec<String> = points
        .iter()
        .map(|&[x, y]| format!("({}, {})", n(x), n(y)))
        .collect();
    format!("[{}]", written.join(", "))
}

/// `(frame, [(x, y), …])`: one key of `OutlineKeys`.
fn key_text(frame: f64, points: &[[f32; 2]]) -> String {
    format!("({}, {})", frame_text(frame), pieces_text(points))
}

/// The `shape` field that holds `points` alone: `shape: Outline([…])` without a frame,
/// `shape: OutlineKeys([(frame, […])])` with one.
#[must_use]
pub(super) fn shape_field_text(key: Option<f64>, points: &[[f32; 2]]) -> String {
    match key {
        None => format!("shape: Outline({})", pieces_text(points)),
        Some(frame) => format!("shape: OutlineKeys([{}])", key_text(frame, points)),
    }
}

/// The frames of a keyed outline's keys; `None` for the disc and a plain outline.
#[must_use]
pub(super) fn key_frames(shape: &Shape<Track<f32>>) -> Option<Vec<f64>> {
    match shape {
        Shape::Morph(morph) => Some(morph.key_frames().collect()),
        Shape::Disc | Shape::Outline(_) => None,
    }
}

/// Why the corners `points` cannot become the key at `frame` of the keyed outline `morph`:
/// keys morph point by point, so every key needs as many points, each of the same kind. The
/// message names the key at `frame` and another key.
pub(super) fn check_key(
    morph: &Morph<Track<f32>>,
    frame: f64,
    points: &[[f32; 2]],
) -> Result<(), String> {
    let Some((other, outline)) = morph.keys.iter().find(|(f, _)| *f != frame) else {
        // The only key is the one replaced.
        return Ok(());
    };
    let (had, count) = (outline.segments.len(), points.len());
    if had != count {
        return Err(format!(
            "the outline key at frame {} would have {count} points but the key at frame {} \
             has {had}; keys morph point by point, so every key needs the same number of \
             points",
            frame_text(frame),
            frame_text(*other)
        ));
    }
    if let Some(k) = outline
        .segments
        .iter()
        .position(|s| matches!(s, Segment::Bezier(_)))
    {
        return Err(format!(
            "point {} is a Bezier in the outline key at frame {} but a corner in the drawn key \
             at frame {}; keys morph point by point, so each point must be of the same kind in \
             every key",
            k + 1,
            frame_text(*other),
            frame_text(frame)
        ));
    }
    Ok(())
}

/// The shape `shape` becomes with the corners `points`: the plain outline of them without
/// `key`; with `key`, a keyed outline's key there (a key at that frame replaced, or the key
/// inserted in frame order; `points` as many as its pieces, [`check_key`]), and the disc or a
/// plain outline made the one key there, as a constant track keyed becomes its one key.
pub(super) fn reshaped(shape: &mut Shape<Track<f32>>, key: Option<f64>, points: &[[f32; 2]]) {
    let drawn = Outline {
        segments: points.iter().map(|&p| Segment::Corner(p)).collect(),
    };
    let Some(frame) = key else {
        *shape = Shape::Outline(drawn.map(|&x| Track::Constant(x)));
        return;
    };
    let mut keys: Vec<(f64, Outline)> = match shape {
        Shape::Morph(morph) => morph.keys.to_vec(),
        Shape::Disc | Shape::Outline(_) => Vec::new(),
    };
    let at = keys.partition_point(|(f, _)| *f < frame);
    match keys.get_mut(at) {
        Some((f, outline)) if *f == frame => *outline = drawn,
        _ => keys.insert(at, (frame, drawn)),
    }
    *shape = Shape::Morph(Morph::from_keys(keys));
}

/// The splice that writes `points` as the key at `frame` of the `OutlineKeys` list of the
/// layer written at `layer` (keyed at `frames`, in order): the item of a key at that frame
/// replaced, or the new key inserted before the first key after it. `None` when the list is
/// not written as it reads.
pub(super) fn key_splice(
    text: &str,
    layer: &[Step<'_>],
    frames: &[f64],
    frame: f64,
    points: &[[f32; 2]],
) -> Option<Splice> {
    let mut list = layer.to_vec();
    list.extend([Field("shape"), Index(0)]);
    let items: Vec<Range<usize>> =
        try_item_spans(text, &list).filter(|items| items.len() == frames.len())?;
    let item = key_text(frame, points);
    let at = frames.partition_point(|&f| f < frame);
    if frames.get(at) == Some(&frame) {
        return Some(Splice {
            span: items[at].clone(),
            text: item,
        });
    }
    insert_item(text, &items, Some(at), &item)
}
