//! How a layer's shape is written in RON: `Disc`, `Outline([…])` of corners and Béziers, or
//! keyed whole outlines `OutlineKeys([(frame, […]), …])` read into a [`Morph`].

use serde::de::value::SeqDeserializer;
use serde::de::{self, Deserializer, IntoDeserializer};
use serde::ser::{SerializeTupleVariant, Serializer};
use serde::{Deserialize, Serialize};

use std::sync::Arc;

use super::morph::Morph;
use super::outline::{Outline, Segment};
use super::shape::Shape;

/// A piece as written, before its numbers become parameters.
#[derive(Deserialize)]
#[serde(
    untagged,
    expecting = "a corner (x, y) or a Bezier((x1, y1), (x2, y2), (x, y))"
)]
enum SegmentText {
    Corner(f64, f64),
    Curve(CurveText),
}

/// A Bézier piece as written.
#[derive(Deserialize)]
enum CurveText {
    Bezier((f64, f64), (f64, f64), (f64, f64)),
}

/// A shape as written.
#[derive(Deserialize)]
enum ShapeText {
    Disc,
    Outline(Vec<SegmentText>),
    OutlineKeys(Vec<(f64, Vec<SegmentText>)>),
}

impl SegmentText {
    /// The piece with its numbers, controls before the end.
    fn numbers(&self) -> Segment<f64> {
        match self {
            SegmentText::Corner(x, y) => Segment::Corner([*x, *y]),
            SegmentText::Curve(CurveText::Bezier(a, b, c)) => {
                Segment::Bezier([[a.0, a.1], [b.0, b.1], [c.0, c.1]])
            }
        }
    }
}

/// The pieces of one key, checked against the first key: as many, of the same kinds.
fn same_pieces(first: (f64, &[Segment<f64>]), key: (f64, &[Segment<f64>])) -> Result<(), String> {
    if first.1.len() != key.1.len() {
        return Err(format!(
            "the outline key at frame {} has {} points but the key at frame {} has {}; keys \
             morph point by point, so every key needs the same number of points",
            first.0,
            first.1.len(),
            key.0,
            key.1.len()
        ));
    }
    if let Some(k) = (0..key.1.len()).find(|&k| !first.1[k].same_kind(&key.1[k])) {
        return Err(format!(
            "point {} is a {} in the outline key at frame {} but a {} in the key at frame {}; \
             keys morph point by point, so each point must be of the same kind in every key",
            k + 1,
            kind(&first.1[k]),
            first.0,
            kind(&key.1[k]),
            key.0
        ));
    }
    Ok(())
}

/// "corner" or "Bezier".
fn kind<P>(segment: &Segment<P>) -> &'static str {
    match segment {
        Segment::Corner(_) => "corner",
        Segment::Bezier(_) => "Bezier",
    }
}

/// The numbers of `segments` in the order [`Segment::map`] visits them.
fn flat(segments: &[Segment<f64>]) -> Vec<f64> {
    let mut numbers = Vec::new();
    for segment in segments {
        let _visited: Segment<()> = segment.map(&mut |v| numbers.push(*v));
    }
    numbers
}

/// The keyed outlines `keys` as a [`Morph`]: the keys as f32 outlines, and its position a
/// parameter keyed `[(frame, index), …]` at every key's frame, read as any keyed number is, so
/// that between keys k and k + 1 it reads `k + s`.
fn keyed<'de, P: Deserialize<'de>>(keys: &[(f64, Vec<Segment<f64>>)]) -> Result<Morph<P>, String> {
    let Some(first) = keys.first() else {
        return Err(
            "OutlineKeys needs at least one (frame, outline) key; write Outline([…]) \
                    for an outline that does not move"
                .to_string(),
        );
    };
    for (frame, segments) in keys {
        if !frame.is_finite() {
            return Err(format!(
                "an outline key's frame is {frame}, but it must be finite"
            ));
        }
        if let Some(v) = flat(segments).iter().find(|v| !(**v as f32).is_finite()) {
            return Err(format!(
                "the outline key at frame {frame} has the coordinate {v}, which is not a finite number"
            ));
        }
    }
    for pair in keys.windows(2) {
        if pair[1].0 <= pair[0].0 {
            return Err(format!(
                "outline keys must be in increasing frame order, but frame {} follows frame {}",
                pair[1].0, pair[0].0
            ));
        }
    }
    for key in &keys[1..] {
        same_pieces((first.0, &first.1), (key.0, &key.1))?;
    }
    let track: Vec<Vec<f64>> = keys
        .iter()
        .enumerate()
        .map(|(k, (frame, _))| vec![*frame, k as f64])
        .collect();
    let seq: SeqDeserializer<_, de::value::Error> = track.into_deserializer();
    let position = P::deserialize(seq).map_err(|e| {
        format!(
            "keyed outlines (OutlineKeys) are read in a shot, where parameters can be keyed: {e}"
        )
    })?;
    let outlines: Vec<(f64, Outline)> = keys
        .iter()
        .map(|(frame, segments)| {
            let segments = segments.iter().map(|s| s.map(&mut |v| *v as f32)).collect();
            (*frame, Outline { segments })
        })
        .collect();
    Ok(Morph {
        keys: Arc::from(outlines),
        position,
    })
}

impl<'de, P: Deserialize<'de> + From<f32>> Deserialize<'de> for Shape<P> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let text = ShapeText::deserialize(deserializer)?;
        let numbers =
            |pieces: &[SegmentText]| pieces.iter().map(SegmentText::numbers).collect::<Vec<_>>();
        match text {
            ShapeText::Disc => Ok(Shape::Disc),
            ShapeText::Outline(pieces) => Ok(Shape::Outline(Outline {
                segments: numbers(&pieces)
                    .iter()
                    .map(|s| s.map(&mut |v| P::from(*v as f32)))
                    .collect(),
            })),
            ShapeText::OutlineKeys(keys) => {
                let keys: Vec<(f64, Vec<Segment<f64>>)> = keys
                    .iter()
                    .map(|(f, pieces)| (*f, numbers(pieces)))
                    .collect();
                keyed(&keys).map(Shape::Morph).map_err(de::Error::custom)
            }
        }
    }
}

/// A piece written as RON reads it: a corner as the tuple `(x, y)`, a Bézier as
/// `Bezier((x1, y1), (x2, y2), (x, y))`.
struct SegmentOut<'a, P>(&'a Segment<P>);

impl<P: Serialize> Serialize for SegmentOut<'_, P> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self.0 {
            Segment::Corner([x, y]) => (x, y).serialize(serializer),
            Segment::Bezier([a, b, c]) => {
                let mut v = serializer.serialize_tuple_variant("CurveText", 0, "Bezier", 3)?;
                v.serialize_field(&(&a[0], &a[1]))?;
                v.serialize_field(&(&b[0], &b[1]))?;
                v.serialize_field(&(&c[0], &c[1]))?;
                v.end()
            }
        }
    }
}

/// `Disc`, `Outline([…])` with each coordinate as its parameter type writes itself, or keyed
/// outlines as `OutlineKeys([(frame, […]), …])` (their position follows from the frames).
impl<P: Serialize> Serialize for Shape<P> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self {
            Shape::Disc => serializer.serialize_unit_variant("Shape", 0, "Disc"),
            Shape::Outline(o) => {
                let pieces: Vec<SegmentOut<'_, P>> = o.segments.iter().map(SegmentOut).collect();
                serializer.serialize_newtype_variant("Shape", 1, "Outline", &pieces)
            }
            Shape::Morph(m) => {
                let keys: Vec<(f64, Vec<SegmentOut<'_, f32>>)> = m
                    .keys
                    .iter()
                    .map(|(frame, o)| (*frame, o.segments.iter().map(SegmentOut).collect()))
                    .collect();
                serializer.serialize_newtype_variant("Shape", 2, "OutlineKeys", &keys)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::anim::Track;

    #[test]
    fn corners_and_beziers_read_and_write_back() {
        let text = "Outline([(0.0, 0.1), (0.1, -0.05), Bezier((0.05, -0.1), (-0.05, -0.1), (-0.1, -0.05))])";
        let shape: Shape = ron::from_str(text).unwrap();
        let Shape::Outline(o) = &shape else {
            panic!("{shape:?}")
        };
        assert_eq!(o.segments[0], Segment::Corner([0.0, 0.1]));
        assert_eq!(
            o.segments[2],
            Segment::Bezier([[0.05, -0.1], [-0.05, -0.1], [-0.1, -0.05]])
        );
        let written = ron::to_string(&shape).unwrap();
        assert_eq!(ron::from_str::<Shape>(&written).unwrap(), shape);
        assert_eq!(ron::from_str::<Shape>("Disc").unwrap(), Shape::Disc);
        assert!(
            ron::from_str::<Shape>("Outline([(0.0, 0.1), Curve((0, 0), (0, 0), (0, 0))])").is_err()
        );
        assert!(ron::from_str::<Shape>("Outline([(0.0, 0.1, 0.2)])").is_err());
    }

    #[test]
    fn keys_become_a_position_between_them_and_write_back_as_keys() {
        let text = "OutlineKeys([(1, [(0.0, 0.1), (0.1, 0.0), (0.0, -0.1)]), \
                    (3, [(0.0, 0.3), (0.3, 0.0), (0.0, -0.1)])])";
        let shape: Shape<Track<f32>> = ron::from_str(text).unwrap();
        let at = |frame: f64| shape.map(|t| t.at(frame));
        let Shape::Morph(morph) = at(2.0) else {
            panic!()
        };
        assert_eq!(morph.position, 0.5);
        let mid = morph.lerped();
        // Halfway between the keys, each coordinate is the mean of its two keys'.
        let want = [[0.0, 0.2], [0.2, 0.0], [0.0, -0.1]];
        for (segment, want) in mid.segments.iter().zip(want) {
            let Segment::Corner(p) = segment else {
                panic!("{segment:?}")
            };
            assert!((p[0] - want[0]).abs() < 1e-6 && (p[1] - want[1]).abs() < 1e-6);
        }
        // Written back as keys, read back the same.
        let written = ron::to_string(&shape.map(|t| t.at(1.0))).unwrap();
        assert!(written.starts_with("OutlineKeys("), "{written}");
        let again: Shape<Track<f32>> = ron::from_str(&written).unwrap();
        assert_eq!(again.map(|t| t.at(2.0)), at(2.0));
        // Alone, a layer has no keys to read.
        let e = ron::from_str::<Shape>(text).unwrap_err().to_string();
        assert!(e.contains("read in a shot"), "{e}");
    }

    #[test]
    fn keys_given_read_as_the_same_keys_written() {
        let text = "OutlineKeys([(2, [(0.0, 0.1), (0.1, 0.0), (0.0, -0.1)]), \
                    (6, [(0.0, 0.3), (0.3, 0.0), (0.0, -0.1)])])";
        let read: Shape<Track<f32>> = ron::from_str(text).unwrap();
        let Shape::Morph(read) = read else {
            panic!("{read:?}")
        };
        let made = Morph::from_keys(read.keys.to_vec());
        assert_eq!(made, read);
        assert_eq!(made.key_frames().collect::<Vec<_>>(), vec![2.0, 6.0]);
        // A quarter of the way: position 0.25.
        assert_eq!(made.map(|t| t.at(3.0)).position, 0.25);
    }

    #[test]
    fn keys_of_different_counts_or_kinds_are_refused_naming_both_frames() {
        let text = "OutlineKeys([(1, [(0.0, 0.1), (0.1, 0.0), (0.0, -0.1)]), \
                    (12, [(0.0, 0.3), (0.3, 0.0), (0.0, -0.1), (-0.1, 0.0)])])";
        let e = ron::from_str::<Shape<Track<f32>>>(text)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("frame 1 has 3 points but the key at frame 12 has 4"),
            "{e}"
        );
        let text = "OutlineKeys([(1, [(0.0, 0.1), (0.1, 0.0), (0.0, -0.1)]), \
                    (5, [(0.0, 0.3), Bezier((0, 0), (0, 0), (0.3, 0.0)), (0.0, -0.1)])])";
        let e = ron::from_str::<Shape<Track<f32>>>(text)
            .unwrap_err()
            .to_string();
        assert!(e.contains("point 2 is a corner in the outline key at frame 1 but a Bezier in the key at frame 5"), "{e}");
        let text = "OutlineKeys([(5, [(0.0, 0.1), (0.1, 0.0), (0.0, -0.1)]), \
                    (5, [(0.0, 0.3), (0.3, 0.0), (0.0, -0.1)])])";
        let e = ron::from_str::<Shape<Track<f32>>>(text)
            .unwrap_err()
            .to_string();
        assert!(e.contains("increasing frame order"), "{e}");
    }
}
