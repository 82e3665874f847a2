//! Keyed whole outlines: where between its keys a frame is, and the value a frame between two
//! keys takes, which keeps what both keys cover.

use std::sync::Arc;

use glam::{Vec2, Vec3};

use super::outline::{Outline, OutlineError, Segment};
use super::polygon::PreparedOutline;
use crate::anim::{Key, Track};

/// Outlines keyed at frames, morphing point by point between consecutive keys.
///
/// The keys are fixed; what moves is `position`, a parameter keyed at every key's frame with
/// the key's 0-based index, so that read at a frame between keys k and k + 1 it is `k + s`, s
/// the fraction of the way between them, as any keyed number is (held before the first key and
/// after the last).
#[derive(Clone, Debug, PartialEq)]
pub struct Morph<P = f32> {
    /// `(frame, outline)` in increasing frame order, at least one, every outline with the same
    /// pieces (as many, of the same kinds in the same places).
    pub keys: Arc<[(f64, Outline)]>,
    /// Where between the keys the outline is: `k + s`, between key k and key k + 1 at the
    /// fraction s.
    pub position: P,
}

impl<P> Morph<P> {
    /// The frames of its keys, in order.
    pub fn key_frames(&self) -> impl Iterator<Item = f64> + '_ {
        self.keys.iter().map(|(frame, _)| *frame)
    }

    /// The same keys with the position mapped through `f`.
    #[must_use]
    pub fn map<Q>(&self, f: impl FnOnce(&P) -> Q) -> Morph<Q> {
        Morph {
            keys: Arc::clone(&self.keys),
            position: f(&self.position),
        }
    }
}

impl Morph<Track<f32>> {
    /// The morph of `keys` as a shot reads `OutlineKeys([…])`: its position keyed
    /// `[(frame, index), …]` at every key's frame. The keys are taken as given: in increasing
    /// frame order, with the same pieces, is the caller's to keep.
    #[must_use]
    pub fn from_keys(keys: Vec<(f64, Outline)>) -> Self {
        let position = Track::Keys(
            keys.iter()
                .enumerate()
                .map(|(k, (frame, _))| Key {
                    frame: *frame,
                    value: k as f32,
                })
                .collect(),
        );
        Morph {
            keys: Arc::from(keys),
            position,
        }
    }
}

/// Where a morph is: on one key, or strictly between two.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Span {
    /// On key k (or held at it, before the first or after the last).
    On(usize),
    /// Between key k and key k + 1, at the fraction s ∈ (0, 1).
    Between(usize, f32),
}

impl Morph<f32> {
    /// Where the position lies: clamped to `[0, n − 1]` for n keys, on key `⌊p⌋` when the
    /// position is a whole number (or not a finite one), else between it and the next at
    /// `s = p − ⌊p⌋`.
    fn span(&self) -> Span {
        let last = self.keys.len().saturating_sub(1);
        let p = self.position;
        if !p.is_finite() || p <= 0.0 {
            return Span::On(0);
        }
        if p >= last as f32 {
            return Span::On(last);
        }
        let k = p.floor();
        let s = p - k;
        // Whole below `last`, so k + 1 ≤ last.
        let k = k as usize;
        if s > 0.0 {
            Span::Between(k, s)
        } else {
            Span::On(k)
        }
    }

    /// The frames of the two keys the position lies strictly between, and the fraction `s` of
    /// the way from the first to the second; None on a key (or held at one).
    #[must_use]
    pub fn try_between_keys(&self) -> Option<(f64, f64, f32)> {
        match self.span() {
            Span::On(_) => None,
            Span::Between(k, s) => Some((self.keys[k].0, self.keys[k + 1].0, s)),
        }
    }

    /// The outline of the keys' points moved linearly to the position: on a key, that key;
    /// between keys a and b at s, every coordinate `a + s (b − a)` (in f32, as a keyed number).
    #[must_use]
    pub fn lerped(&self) -> Outline {
        match self.span() {
            Span::On(k) => self.keys[k].1.clone(),
            Span::Between(k, s) => lerp(&self.keys[k].1, &self.keys[k + 1].1, s),
        }
    }

    /// Checks the keys the position lies on or between, as drawn ([`Outline::validate`]): on
    /// a key's frame, that key alone.
    pub fn validate(&self) -> Result<(), OutlineError> {
        match self.span() {
            Span::On(k) => self.keys[k].1.validate(),
            Span::Between(k, _) => {
                self.keys[k].1.validate()?;
                self.keys[k + 1].1.validate()
            }
        }
    }

    /// On a key, its outline made ready ([`Outline::prepare`]); between keys, the morph's
    /// three polygons ([`PreparedMorph`]). The values are checked, not whether an outline
    /// crosses itself.
    pub(super) fn prepare(&self) -> Result<Prepared, OutlineError> {
        match self.span() {
            Span::On(k) => Ok(Prepared::Key(self.keys[k].1.prepare()?)),
            Span::Between(k, s) => {
                let (a, b) = (&self.keys[k].1, &self.keys[k + 1].1);
                let (from, to) = (a.prepare()?, b.prepare()?);
                let between = lerp(a, b, s).prepare()?;
                let scale = from.scale() + s * (to.scale() - from.scale());
                Ok(Prepared::Between(PreparedMorph {
                    between,
                    from,
                    to,
                    scale,
                }))
            }
        }
    }
}

/// What [`Morph::prepare`] makes: a key's outline, or a frame strictly between two keys.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Prepared {
    /// On a key: that key's polygon.
    Key(PreparedOutline),
    /// Between two keys.
    Between(PreparedMorph),
}

/// `a + s (b − a)` for every coordinate of two outlines with the same pieces (`b`'s pieces
/// past `a`'s count are ignored; a piece of another kind is taken at `a`'s).
fn lerp(a: &Outline, b: &Outline, s: f32) -> Outline {
    let mix = |p: [f32; 2], q: [f32; 2]| [p[0] + s * (q[0] - p[0]), p[1] + s * (q[1] - p[1])];
    Outline {
        segments: a
            .segments
            .iter()
            .zip(&b.segments)
            .map(|pair| match pair {
                (Segment::Corner(p), Segment::Corner(q)) => Segment::Corner(mix(*p, *q)),
                (Segment::Bezier(p), Segment::Bezier(q)) => {
                    Segment::Bezier([mix(p[0], q[0]), mix(p[1], q[1]), mix(p[2], q[2])])
                }
                (own, _) => own.clone(),
            })
            .collect(),
    }
}

/// A frame strictly between keys a and b at the fraction s: the polygon of the lerped points
/// and the two keys' own, under one scale.
///
/// The signed value is
///
/// ```text
/// s(l) = c · max( d_between(l), min(d_a(l), d_b(l)) )      c = c_a + s (c_b − c_a)
/// ```
///
/// with d each polygon's signed distance ([`PreparedOutline::distance_at`]) and c_a, c_b the
/// keys' scales. Inside wherever the lerped outline is, and wherever both keys are: a lerp of
/// points alone cuts across what both keys cover (a star turned between its keys loses the
/// parts of its tips the two keys share). The max and min of distances are 1-Lipschitz as each
/// is, so under the one scale the value falls across its edge as a distance does, and its zero
/// set is made of pieces of the three polygons' edges: corners stay sharp. It tends to each
/// key's value at that key (the lerped polygon tends to the key, which then bounds the min).
#[derive(Clone, Debug, PartialEq)]
pub struct PreparedMorph {
    between: PreparedOutline,
    from: PreparedOutline,
    to: PreparedOutline,
    scale: f32,
}

impl PreparedMorph {
    /// The signed value of the stack's unit output `l` in the layer's frame (N is +z), in the
    /// units of a disc's `s` (see the type).
    #[inline]
    #[must_use]
    pub fn signed(&self, l: Vec3) -> f32 {
        let both = self.from.distance_at(l).min(self.to.distance_at(l));
        self.scale * self.between.distance_at(l).max(both)
    }

    /// The signed distance to the morph's region at `t'` (see the type), unscaled.
    #[must_use]
    pub fn distance(&self, t: Vec2) -> f32 {
        let both = self.from.distance(t).min(self.to.distance(t));
        self.between.distance(t).max(both)
    }
}

#[cfg(test)]
mod tests {
    use super::super::outline::corners;
    use super::*;

    fn morph(position: f32) -> Morph {
        // A square, then the same square moved right by 0.2, then grown.
        let square = |x: f32, r: f32| corners(&[(x - r, -r), (x + r, -r), (x + r, r), (x - r, r)]);
        Morph {
            keys: Arc::from(vec![
                (1.0, square(0.0, 0.1)),
                (5.0, square(0.2, 0.1)),
                (9.0, square(0.2, 0.3)),
            ]),
            position,
        }
    }

    #[test]
    fn the_position_picks_a_key_or_the_two_around_it() {
        assert_eq!(morph(-3.0).span(), Span::On(0));
        assert_eq!(morph(0.0).span(), Span::On(0));
        assert_eq!(morph(1.0).span(), Span::On(1));
        assert_eq!(morph(1.25).span(), Span::Between(1, 0.25));
        assert_eq!(morph(1.25).try_between_keys(), Some((5.0, 9.0, 0.25)));
        assert_eq!(morph(1.0).try_between_keys(), None);
        assert_eq!(morph(2.0).span(), Span::On(2));
        assert_eq!(morph(7.0).span(), Span::On(2));
        assert_eq!(morph(f32::NAN).span(), Span::On(0));
        // Halfway between the first two keys the square is halfway along.
        let Segment::Corner(p) = morph(0.5).lerped().segments[0] else {
            panic!()
        };
        assert!(
            (p[0] - 0.0).abs() < 1e-6 && (p[1] + 0.1).abs() < 1e-6,
            "{p:?}"
        );
    }

    #[test]
    fn between_keys_the_value_covers_the_lerp_and_what_both_keys_cover() {
        let Ok(Prepared::Between(m)) = morph(0.5).prepare() else {
            panic!("halfway is between keys")
        };
        // The lerped square spans x ∈ [0, 0.2]; both keys cover x ∈ [0.1, 0.1] only (a line):
        // the value is the lerped square's distance.
        assert!((m.distance(Vec2::new(0.1, 0.0)) - 0.1).abs() < 1e-6);
        assert!((m.distance(Vec2::new(-0.05, 0.0)) + 0.05).abs() < 1e-6);
        // Between a square and the same square grown about the same centre, the grown key
        // holds the small one, and the lerp holds it too: the value is the lerp's.
        let Ok(Prepared::Between(g)) = morph(1.5).prepare() else {
            panic!()
        };
        assert!((g.distance(Vec2::new(0.2, 0.0)) - 0.2).abs() < 1e-6);
        // The scale is the mean of the keys' at s = 1/2.
        let (a, b) = (
            morph(1.0).keys[1].1.prepare().unwrap(),
            morph(2.0).keys[2].1.prepare().unwrap(),
        );
        assert!((g.scale - 0.5 * (a.scale() + b.scale())).abs() < 1e-6);
    }

    #[test]
    fn a_square_turned_between_keys_keeps_the_corners_both_keys_share() {
        // A square turned by 90° point by point: the lerp at the midpoint is the square shrunk
        // to half its size and turned 45° (every point halfway along the chord to the next
        // corner's place); both keys are the same square, which must stay covered.
        let a = corners(&[(-0.2, -0.2), (0.2, -0.2), (0.2, 0.2), (-0.2, 0.2)]);
        let b = corners(&[(0.2, -0.2), (0.2, 0.2), (-0.2, 0.2), (-0.2, -0.2)]);
        let m = Morph {
            keys: Arc::from(vec![(1.0, a), (2.0, b)]),
            position: 0.5,
        };
        let Ok(Prepared::Between(p)) = m.prepare() else {
            panic!()
        };
        let corner = Vec2::new(0.18, 0.18);
        assert!(p.between.distance(corner) < 0.0, "the lerp alone leaves it");
        assert!((p.distance(corner) - 0.02).abs() < 1e-6);
    }
}
