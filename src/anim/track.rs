use std::fmt;
use std::marker::PhantomData;

use glam::{DVec3, Vec3};
use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// A value that can be keyed: built from its numeric components as written in a file, and
/// interpolated between two keys.
pub trait Interpolate: Copy {
    /// How many numbers the value is written with (1 for a scalar, 3 for a vector).
    const COMPONENTS: usize;

    /// The value written as `components` (exactly [`Self::COMPONENTS`] finite numbers).
    fn from_components(components: &[f64]) -> Result<Self, String>;

    /// The value a fraction `t ∈ [0, 1]` of the way from `a` to `b`.
    fn interpolate(a: Self, b: Self, t: f64) -> Self;
}

/// `n` as an f32, refused where it leaves the f32 range.
fn single(n: f64) -> Result<f32, String> {
    let single = n as f32;
    if single.is_finite() {
        Ok(single)
    } else {
        Err(format!(
            "{n} is not allowed: values must be finite numbers within the f32 range"
        ))
    }
}

impl Interpolate for f32 {
    const COMPONENTS: usize = 1;

    fn from_components(c: &[f64]) -> Result<Self, String> {
        single(c[0])
    }

    /// `a + t (b − a)`, exact at both ends (in f32).
    fn interpolate(a: Self, b: Self, t: f64) -> Self {
        let t = t as f32;
        if t >= 1.0 {
            b
        } else {
            a + t * (b - a)
        }
    }
}

impl Interpolate for Vec3 {
    const COMPONENTS: usize = 3;

    fn from_components(c: &[f64]) -> Result<Self, String> {
        Ok(Vec3::new(single(c[0])?, single(c[1])?, single(c[2])?))
    }

    /// Componentwise `a + t (b − a)`, exact at both ends (in f32).
    fn interpolate(a: Self, b: Self, t: f64) -> Self {
        let t = t as f32;
        if t >= 1.0 {
            b
        } else {
            a + t * (b - a)
        }
    }
}

impl Interpolate for f64 {
    const COMPONENTS: usize = 1;

    fn from_components(c: &[f64]) -> Result<Self, String> {
        Ok(c[0])
    }

    /// `a + t (b − a)`, exact at both ends.
    fn interpolate(a: Self, b: Self, t: f64) -> Self {
        if t >= 1.0 {
            b
        } else {
            a + t * (b - a)
        }
    }
}

impl Interpolate for DVec3 {
    const COMPONENTS: usize = 3;

    fn from_components(c: &[f64]) -> Result<Self, String> {
        Ok(DVec3::new(c[0], c[1], c[2]))
    }

    /// Componentwise `a + t (b − a)`, exact at both ends.
    fn interpolate(a: Self, b: Self, t: f64) -> Self {
        if t >= 1.0 {
            b
        } else {
            a + t * (b - a)
        }
    }
}

/// A unit direction, written as any non-zero vector and interpolated along the great circle.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Direction(pub Vec3);

impl Interpolate for Direction {
    const COMPONENTS: usize = 3;

    fn from_components(c: &[f64]) -> Result<Self, String> {
        Vec3::new(single(c[0])?, single(c[1])?, single(c[2])?)
            .try_normalize()
            .map(Direction)
            .ok_or_else(|| format!("the direction ({}, {}, {}) has no length", c[0], c[1], c[2]))
    }

    /// Spherical linear interpolation, `sin((1−t)Ω)/sin Ω · a + sin(tΩ)/sin Ω · b` with
    /// `cos Ω = a·b`; linear (then normalized) where Ω is too small for the quotient, and
    /// turning about an axis across `a` when the two are opposite.
    fn interpolate(Direction(a): Self, Direction(b): Self, t: f64) -> Self {
        let t = t as f32;
        if t >= 1.0 {
            return Direction(b);
        }
        let cos = a.dot(b).clamp(-1.0, 1.0);
        if cos > 0.9995 {
            return Direction(a.lerp(b, t).normalize());
        }
        // The plane of the turn: b's part across a, or any axis across a when b = −a.
        let across = (b - cos * a)
            .try_normalize()
            .unwrap_or_else(|| a.any_orthonormal_vector());
        let angle = t * cos.acos();
        Direction(a * angle.cos() + across * angle.sin())
    }
}

/// One key: the value at a frame.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Key<T> {
    pub frame: f64,
    pub value: T,
}

/// A constant, or keys in increasing frame order: linear between keys, held before the first
/// and after the last.
///
/// RON: a constant is written as the value itself (`0.3`, `(0.0, 1.0, 2.0)`); keys as a list of
/// `(frame, value)` pairs, `[(1, 0.0), (24, 0.3)]`. Frames may be fractional.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub enum Track<T> {
    Constant(T),
    Keys(Vec<Key<T>>),
}

/// A track that cannot be used.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum TrackError {
    #[error("a keyed track needs at least one key; write a constant value instead of []")]
    NoKeys,
    #[error("keys must be in increasing frame order, but frame {frame} follows frame {previous}")]
    Unordered { frame: f64, previous: f64 },
    #[error("{what} is {value}, but it must be a finite number")]
    NotFinite { what: &'static str, value: f64 },
}

impl<T: Interpolate> Track<T> {
    /// The value at `frame` (fractional frames allowed). Between keys `k` and `k+1`,
    /// `interpolate(v_k, v_{k+1}, (f − f_k) / (f_{k+1} − f_k))`; the first value before the
    /// first key, the last after the last.
    #[must_use]
    pub fn at(&self, frame: f64) -> T {
        let keys = match self {
            Track::Constant(value) => return *value,
            Track::Keys(keys) => keys,
        };
        let after = keys.partition_point(|k| k.frame <= frame);
        match (after.checked_sub(1).map(|i| &keys[i]), keys.get(after)) {
            (Some(a), Some(b)) => {
                let t = (frame - a.frame) / (b.frame - a.frame);
                T::interpolate(a.value, b.value, t)
            }
            (Some(last), None) => last.value,
            (None, Some(first)) => first.value,
            (None, None) => unreachable!("a keyed track has at least one key"),
        }
    }

    /// The frames of its keys (none for a constant): between two consecutive ones every
    /// component moves monotonically, so checking the values there checks them everywhere.
    pub fn key_frames(&self) -> impl Iterator<Item = f64> + '_ {
        let keys: &[Key<T>] = match self {
            Track::Constant(_) => &[],
            Track::Keys(keys) => keys,
        };
        keys.iter().map(|k| k.frame)
    }

    /// Checks the keys: at least one, finite frames in strictly increasing order.
    pub fn validate(&self) -> Result<(), TrackError> {
        let Track::Keys(keys) = self else {
            return Ok(());
        };
        if keys.is_empty() {
            return Err(TrackError::NoKeys);
        }
        let mut previous = f64::NEG_INFINITY;
        for key in keys {
            if !key.frame.is_finite() {
                return Err(TrackError::NotFinite {
                    what: "a key frame",
                    value: key.frame,
                });
            }
            if key.frame <= previous {
                return Err(TrackError::Unordered {
                    frame: key.frame,
                    previous,
                });
            }
            previous = key.frame;
        }
        Ok(())
    }
}

/// A track seen only for where it is keyed, whatever its value type: what a visitor over a
/// shot's parameters needs to check the values at every key.
pub trait Keyed {
    /// Calls `f` with the frame of each key, in order (never for a constant).
    fn for_each_key(&self, f: &mut dyn FnMut(f64));
}

impl<T: Interpolate> Keyed for Track<T> {
    fn for_each_key(&self, f: &mut dyn FnMut(f64)) {
        self.key_frames().for_each(f);
    }
}

impl<T> From<T> for Track<T> {
    fn from(value: T) -> Self {
        Track::Constant(value)
    }
}

/// One element of a list as written: a bare number (a component of a constant vector) or a
/// `(frame, value)` key.
enum Element {
    Number(f64),
    Key(f64, Vec<f64>),
}

impl<'de> Deserialize<'de> for Element {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct ElementVisitor;
        impl<'de> Visitor<'de> for ElementVisitor {
            type Value = Element;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a number or a (frame, value) key")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Element, E> {
                Ok(Element::Number(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Element, E> {
                Ok(Element::Number(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Element, E> {
                Ok(Element::Number(v as f64))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Element, A::Error> {
                let frame: f64 = seq
                    .next_element()?
                    .ok_or_else(|| de::Error::custom("a key is written (frame, value)"))?;
                let value: Numbers = seq
                    .next_element()?
                    .ok_or_else(|| de::Error::custom("a key is written (frame, value)"))?;
                if seq.next_element::<de::IgnoredAny>()?.is_some() {
                    return Err(de::Error::custom(
                        "a key is written (frame, value), with nothing after the value",
                    ));
                }
                Ok(Element::Key(frame, value.0))
            }
        }
        deserializer.deserialize_any(ElementVisitor)
    }
}

/// A value as written: one number, or a tuple of numbers.
struct Numbers(Vec<f64>);

impl<'de> Deserialize<'de> for Numbers {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct NumbersVisitor;
        impl<'de> Visitor<'de> for NumbersVisitor {
            type Value = Numbers;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a number or a tuple of numbers")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Numbers, E> {
                Ok(Numbers(vec![v]))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Numbers, E> {
                Ok(Numbers(vec![v as f64]))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Numbers, E> {
                Ok(Numbers(vec![v as f64]))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Numbers, A::Error> {
                let mut numbers = Vec::new();
                while let Some(n) = seq.next_element::<f64>()? {
                    numbers.push(n);
                }
                Ok(Numbers(numbers))
            }
        }
        deserializer.deserialize_any(NumbersVisitor)
    }
}

/// The value written as `numbers`, checked: the right count, all finite.
fn value_from<T: Interpolate>(numbers: &[f64]) -> Result<T, String> {
    if numbers.len() != T::COMPONENTS {
        return Err(if T::COMPONENTS == 1 {
            format!(
                "expected a number or keys [(frame, value), …], found {} numbers",
                numbers.len()
            )
        } else {
            format!(
                "expected {n} numbers (x, y, z) or keys [(frame, (x, y, z)), …], found {} numbers",
                numbers.len(),
                n = T::COMPONENTS
            )
        });
    }
    if let Some(n) = numbers.iter().find(|n| !n.is_finite()) {
        return Err(format!("{n} is not allowed: values must be finite numbers"));
    }
    T::from_components(numbers)
}

impl<'de, T: Interpolate> Deserialize<'de> for Track<T> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct TrackVisitor<T>(PhantomData<T>);
        impl<'de, T: Interpolate> Visitor<'de> for TrackVisitor<T> {
            type Value = Track<T>;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                if T::COMPONENTS == 1 {
                    f.write_str("a number, or keys [(frame, value), …]")
                } else {
                    f.write_str("a vector (x, y, z), or keys [(frame, (x, y, z)), …]")
                }
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Track<T>, E> {
                value_from(&[v]).map(Track::Constant).map_err(E::custom)
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Track<T>, E> {
                self.visit_f64(v as f64)
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Track<T>, E> {
                self.visit_f64(v as f64)
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Track<T>, A::Error> {
                let mut numbers = Vec::new();
                let mut keys = Vec::new();
                while let Some(element) = seq.next_element::<Element>()? {
                    match element {
                        Element::Number(n) => numbers.push(n),
                        Element::Key(frame, value) => keys.push(Key {
                            frame,
                            value: value_from(&value).map_err(de::Error::custom)?,
                        }),
                    }
                }
                let track = match (numbers.is_empty(), keys.is_empty()) {
                    (false, false) => {
                        return Err(de::Error::custom(
                            "a track is either a constant value or a list of (frame, value) keys, not a mix",
                        ))
                    }
                    (false, true) => Track::Constant(value_from(&numbers).map_err(de::Error::custom)?),
                    (true, _) => Track::Keys(keys),
                };
                track.validate().map_err(de::Error::custom)?;
                Ok(track)
            }
        }
        deserializer.deserialize_any(TrackVisitor(PhantomData))
    }
}

/// Tracks the unit tests build.
#[cfg(test)]
pub(crate) mod fixtures {
    use super::{Key, Track};

    /// The keyed track of `pairs`, each a frame and its value, in the order given.
    pub(crate) fn keys(pairs: &[(f64, f32)]) -> Track<f32> {
        Track::Keys(
            pairs
                .iter()
                .map(|&(frame, value)| Key { frame, value })
                .collect(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::fixtures::keys;
    use super::*;

    #[test]
    fn exact_at_keys_mean_halfway_held_outside() {
        let t = keys(&[(1.0, 0.25), (11.0, 0.75), (21.0, -0.5)]);
        assert_eq!(t.at(1.0), 0.25);
        assert_eq!(t.at(11.0), 0.75);
        assert_eq!(t.at(21.0), -0.5);
        assert_eq!(t.at(6.0), 0.5);
        assert_eq!(t.at(16.0), 0.125);
        assert_eq!(t.at(-100.0), 0.25);
        assert_eq!(t.at(1e9), -0.5);
    }

    #[test]
    fn ron_constants_and_keys_parse_to_the_same_values() {
        let scalar: Track<f32> = ron::from_str("0.5").unwrap();
        assert_eq!(scalar, Track::Constant(0.5));
        let keyed: Track<f32> = ron::from_str("[(1, 0.0), (24.5, 2)]").unwrap();
        assert_eq!(keyed, keys(&[(1.0, 0.0), (24.5, 2.0)]));
        let vector: Track<Vec3> = ron::from_str("(1, 2.5, -3)").unwrap();
        assert_eq!(vector, Track::Constant(Vec3::new(1.0, 2.5, -3.0)));
        let moving: Track<Vec3> = ron::from_str("[(0, (2, 0, -1)), (10, (1, 2, 3))]").unwrap();
        assert_eq!(moving.at(5.0), Vec3::new(1.5, 1.0, 1.0));
    }

    #[test]
    fn malformed_tracks_say_what_is_expected() {
        let error = |text: &str| ron::from_str::<Track<Vec3>>(text).unwrap_err().to_string();
        assert!(
            error("(1, 2)").contains("expected 3 numbers"),
            "{}",
            error("(1, 2)")
        );
        assert!(error("[(1, (0, 0, 0)), 3]").contains("not a mix"));
        assert!(error("[(2, (0, 0, 0)), (1, (0, 0, 1))]").contains("frame 1 follows frame 2"));
        assert!(error("[]").contains("at least one key"));
        let scalar = ron::from_str::<Track<f32>>("[(1, 2, 3)]")
            .unwrap_err()
            .to_string();
        assert!(scalar.contains("nothing after the value"), "{scalar}");
        let huge = ron::from_str::<Track<f32>>("1e300")
            .unwrap_err()
            .to_string();
        assert!(huge.contains("finite"), "{huge}");
        // What each part of a track may be, named where something else is written.
        let scalar_error = |text: &str| ron::from_str::<Track<f32>>(text).unwrap_err().to_string();
        for (text, expected) in [
            ("\"x\"", "a number, or keys [(frame, value), …] but found"),
            (
                "[(1, 0.0), \"x\"]",
                "a number or a (frame, value) key but found",
            ),
            ("[(1, \"x\")]", "a number or a tuple of numbers but found"),
        ] {
            assert!(
                scalar_error(text).contains(expected),
                "{text}: {}",
                scalar_error(text)
            );
        }
        assert!(error("\"x\"").contains("a vector (x, y, z), or keys"));
    }

    #[test]
    fn directions_turn_along_the_great_circle_at_constant_speed() {
        let a = Direction(Vec3::X);
        let b = Direction(Vec3::Y);
        for i in 0..=8 {
            let t = i as f32 / 8.0;
            let d = Direction::interpolate(a, b, f64::from(t)).0;
            assert!((d.length() - 1.0).abs() < 1e-6);
            let angle = d.y.atan2(d.x);
            assert!(
                (angle - t * std::f32::consts::FRAC_PI_2).abs() < 1e-5,
                "{t}: {angle}"
            );
        }
        // Off the axes, at an obtuse angle: in the plane of the two, at t of the angle from the
        // first and the rest from the second.
        let (p, q) = (
            Vec3::new(1.0, 2.0, 3.0).normalize(),
            Vec3::new(-2.0, 1.0, -0.5).normalize(),
        );
        let whole = p.angle_between(q);
        let plane = p.cross(q).normalize();
        for i in 1..8 {
            let t = i as f32 / 8.0;
            let d = Direction::interpolate(Direction(p), Direction(q), f64::from(t)).0;
            assert!(d.dot(plane).abs() < 1e-6, "{t}: {d}");
            assert!((d.angle_between(p) - t * whole).abs() < 1e-5, "{t}: {d}");
            assert!(
                (d.angle_between(q) - (1.0 - t) * whole).abs() < 1e-5,
                "{t}: {d}"
            );
        }
        // Directions a milliradian apart: acos of their cosine in f32 would lose about a tenth of
        // the angle, the linear path keeps the halfway direction to a microradian.
        let angle = 1e-3f32;
        let near = Direction(Vec3::new(angle.cos(), angle.sin(), 0.0));
        let half = Direction::interpolate(a, near, 0.5).0;
        assert!((half.y.atan2(half.x) - 0.5 * angle).abs() < 1e-6, "{half}");
        let opposite = Direction::interpolate(a, Direction(-Vec3::X), 0.5).0;
        assert!(opposite.is_finite() && opposite.dot(Vec3::X).abs() < 1e-6);
        assert!(Direction::from_components(&[0.0f64, 0.0, 0.0]).is_err());
    }
}
