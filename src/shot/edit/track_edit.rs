//! An edit of one track — make it a constant, key it at a frame, delete its key at a frame — and
//! the track it makes of a parsed one.

use glam::Vec3;

use crate::anim::{Interpolate, Key, Track};

/// What to do to one track. Values are written as in the file: a number `0.25`, or a vector or
/// colour `(1.0, 0.98, 0.9)`.
#[derive(Clone, Debug, PartialEq)]
pub enum TrackEdit {
    /// Make the track this constant; its keys, if any, go.
    Set(String),
    /// Key the track at `frame`: a key at that frame is replaced, and a constant becomes the
    /// single key `[(frame, value)]`.
    Key { frame: f64, value: String },
    /// Delete the key at `frame`; deleting the last key leaves the constant it held.
    Delete { frame: f64 },
}

/// A [`TrackEdit`] with its value read as `T`.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum ValueEdit<T> {
    Set(T),
    Key(f64, T),
    Delete(f64),
}

impl<T> ValueEdit<T> {
    /// The same edit with its value mapped through `f`.
    pub fn try_map<U, E>(&self, f: impl FnOnce(&T) -> Result<U, E>) -> Result<ValueEdit<U>, E> {
        Ok(match self {
            ValueEdit::Set(value) => ValueEdit::Set(f(value)?),
            ValueEdit::Key(frame, value) => ValueEdit::Key(*frame, f(value)?),
            ValueEdit::Delete(frame) => ValueEdit::Delete(*frame),
        })
    }
}

impl TrackEdit {
    /// The edit with its value read as `components` numbers (1 for a number, 3 for a vector),
    /// each a finite `f32`. `Err` says what is wrong with the value.
    pub(super) fn read(&self, components: usize) -> Result<ValueEdit<Vec<f32>>, String> {
        let read = |value: &String| read_value(value, components);
        match self {
            TrackEdit::Set(value) => Ok(ValueEdit::Set(read(value)?)),
            TrackEdit::Key { frame, value } => Ok(ValueEdit::Key(*frame, read(value)?)),
            TrackEdit::Delete { frame } => Ok(ValueEdit::Delete(*frame)),
        }
    }

    /// The frame the edit keys or deletes at, if any.
    #[must_use]
    pub fn frame(&self) -> Option<f64> {
        match self {
            TrackEdit::Set(_) => None,
            TrackEdit::Key { frame, .. } | TrackEdit::Delete { frame } => Some(*frame),
        }
    }
}

/// `value` read as a track's constant of `components` numbers, as the shot reader reads one.
fn read_value(value: &str, components: usize) -> Result<Vec<f32>, String> {
    let single = "a single value, not keys (the frame is given apart)";
    let read = if components == 1 {
        match ron::from_str::<Track<f32>>(value) {
            Ok(Track::Constant(x)) => Ok(vec![x]),
            Ok(Track::Keys(_)) => Err(single.to_string()),
            Err(e) => Err(e.code.to_string()),
        }
    } else {
        match ron::from_str::<Track<Vec3>>(value) {
            Ok(Track::Constant(v)) => Ok(v.to_array().to_vec()),
            Ok(Track::Keys(_)) => Err(single.to_string()),
            Err(e) => Err(e.code.to_string()),
        }
    };
    read.map_err(|reason| format!("the value `{value}` cannot be used: {reason}"))
}

/// The track `edit` makes of `old`: `Set(v)` the constant v; `Key(f, v)` the keys of `old`
/// with the one at f replaced by v or v inserted in frame order (a constant becomes `[(f, v)]`);
/// `Delete(f)` the keys without the one at f (the last key leaves the constant it held).
/// `Err` with the frames of `old`'s keys when it has none at the frame to delete.
pub(super) fn edited<T: Interpolate>(
    old: &Track<T>,
    edit: &ValueEdit<T>,
) -> Result<Track<T>, Vec<f64>> {
    let keys: &[Key<T>] = match old {
        Track::Constant(_) => &[],
        Track::Keys(keys) => keys,
    };
    match *edit {
        ValueEdit::Set(value) => Ok(Track::Constant(value)),
        ValueEdit::Key(frame, value) => {
            let mut keys = keys.to_vec();
            let at = keys.partition_point(|k| k.frame < frame);
            match keys.get_mut(at) {
                Some(key) if key.frame == frame => key.value = value,
                _ => keys.insert(at, Key { frame, value }),
            }
            Ok(Track::Keys(keys))
        }
        ValueEdit::Delete(frame) => {
            let at = keys
                .iter()
                .position(|k| k.frame == frame)
                .ok_or_else(|| keys.iter().map(|k| k.frame).collect::<Vec<_>>())?;
            Ok(match keys {
                [only] => Track::Constant(only.value),
                many => {
                    let mut kept = many.to_vec();
                    kept.remove(at);
                    Track::Keys(kept)
                }
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::anim::fixtures::keys;

    #[test]
    fn keying_replaces_inserts_in_order_and_turns_a_constant_into_one_key() {
        let old = keys(&[(1.0, 0.5), (17.0, 0.25)]);
        assert_eq!(
            edited(&old, &ValueEdit::Key(17.0, 0.75)),
            Ok(keys(&[(1.0, 0.5), (17.0, 0.75)]))
        );
        assert_eq!(
            edited(&old, &ValueEdit::Key(9.5, 0.0)),
            Ok(keys(&[(1.0, 0.5), (9.5, 0.0), (17.0, 0.25)]))
        );
        assert_eq!(
            edited(&old, &ValueEdit::Key(-3.0, 1.0)),
            Ok(keys(&[(-3.0, 1.0), (1.0, 0.5), (17.0, 0.25)]))
        );
        assert_eq!(
            edited(&Track::Constant(0.1), &ValueEdit::Key(12.0, 0.3)),
            Ok(keys(&[(12.0, 0.3)]))
        );
        assert_eq!(edited(&old, &ValueEdit::Set(0.2)), Ok(Track::Constant(0.2)));
    }

    #[test]
    fn deleting_the_last_key_leaves_its_value_and_a_missing_key_is_refused() {
        let old = keys(&[(1.0, 0.5), (17.0, 0.25)]);
        assert_eq!(
            edited(&old, &ValueEdit::Delete(1.0)),
            Ok(keys(&[(17.0, 0.25)]))
        );
        assert_eq!(
            edited(&keys(&[(17.0, 0.25)]), &ValueEdit::Delete(17.0)),
            Ok(Track::Constant(0.25))
        );
        assert_eq!(edited(&old, &ValueEdit::Delete(2.0)), Err(vec![1.0, 17.0]));
        assert_eq!(
            edited(&Track::Constant(0.5), &ValueEdit::Delete(1.0)),
            Err(vec![])
        );
    }

    #[test]
    fn values_are_read_as_the_track_reads_them() {
        let set = |v: &str, n| TrackEdit::Set(v.to_string()).read(n);
        assert_eq!(set("0.25", 1), Ok(ValueEdit::Set(vec![0.25])));
        assert_eq!(set("3", 1), Ok(ValueEdit::Set(vec![3.0])));
        assert_eq!(
            set("(1, 0.98, 0.9)", 3),
            Ok(ValueEdit::Set(vec![1.0, 0.98, 0.9]))
        );
        assert!(set("(1, 2)", 3).unwrap_err().contains("expected 3 numbers"));
        assert!(set("x", 1).is_err());
        assert!(set("1e300", 1).unwrap_err().contains("finite"));
        assert!(set("[(1, 0.5)]", 1).unwrap_err().contains("not keys"));
        assert_eq!(
            TrackEdit::Delete { frame: 4.0 }.read(3),
            Ok(ValueEdit::Delete(4.0))
        );
    }
}
