//! An instance's or a part's transform read at a frame, as a point map, and the ranges its
//! tracks must keep.

use glam::{DQuat, DVec3};

use super::file::TransformSpec;
use crate::anim::{keyed_rotation, Keyed, Track};
use crate::geom::MAX_COORDINATE;

/// The smallest scale of a transform.
pub(super) const MIN_SCALE: f64 = 1e-6;
/// The largest scale of a transform.
pub(super) const MAX_SCALE: f64 = 1e6;

/// A transform at one frame: `p ↦ translate + pivot + R (scale · (p − pivot))`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Placement {
    pub translate: DVec3,
    pub rotation: DQuat,
    pub scale: f64,
    pub pivot: DVec3,
}

impl Placement {
    /// `translate + pivot + R (scale · (p − pivot))`; `translate + R (scale · p)` exactly when
    /// the pivot is the origin.
    #[must_use]
    pub fn apply(&self, p: DVec3) -> DVec3 {
        if self.pivot == DVec3::ZERO {
            self.translate + self.rotation * (self.scale * p)
        } else {
            self.translate + self.pivot + self.rotation * (self.scale * (p - self.pivot))
        }
    }
}

impl TransformSpec {
    /// Every track read at `frame`, the rotation as [`keyed_rotation`] reads the axis and the
    /// angle together.
    #[must_use]
    pub fn at(&self, frame: f64) -> Placement {
        Placement {
            translate: self.translate.at(frame),
            rotation: keyed_rotation(&self.axis, &self.degrees, frame),
            scale: self.scale.at(frame),
            pivot: self.pivot.at(frame),
        }
    }

    /// Whether some track is keyed.
    #[must_use]
    pub fn is_keyed(&self) -> bool {
        self.key_frames().next().is_some()
    }

    /// The frames of every key of every track, in no particular order.
    pub fn key_frames(&self) -> impl Iterator<Item = f64> + '_ {
        let mut frames = Vec::new();
        let tracks: [&dyn Keyed; 5] = [
            &self.translate,
            &self.axis,
            &self.degrees,
            &self.scale,
            &self.pivot,
        ];
        for track in tracks {
            track.for_each_key(&mut |f| frames.push(f));
        }
        frames.into_iter()
    }

    /// Checks every value the tracks are written with: translations, pivots and angles within
    /// ±[`MAX_COORDINATE`], a non-zero axis, a scale in [[`MIN_SCALE`], [`MAX_SCALE`]]. Between
    /// keys every track moves monotonically (the axis along a great circle between non-zero
    /// keys), so this checks every frame. The error names the field and the frame.
    pub(super) fn check(&self) -> Result<(), (&'static str, String)> {
        let within = |x: f64| x.is_finite() && x.abs() <= MAX_COORDINATE;
        let at = |frame: Option<f64>| frame.map_or(String::new(), |f| format!(" at frame {f}"));
        for (field, track) in [("translate", &self.translate), ("pivot", &self.pivot)] {
            for (frame, p) in values(track) {
                if !p.to_array().into_iter().all(within) {
                    return Err((
                        field,
                        format!(
                            "the {field} ({}, {}, {}){} must lie within ±{MAX_COORDINATE:e}",
                            p.x,
                            p.y,
                            p.z,
                            at(frame)
                        ),
                    ));
                }
            }
        }
        for (frame, a) in values(&self.axis) {
            if !(a.to_array().into_iter().all(within) && a.length_squared() > 0.0) {
                return Err((
                    "axis",
                    format!(
                    "the axis ({}, {}, {}){} must be a non-zero vector within ±{MAX_COORDINATE:e}",
                    a.x, a.y, a.z, at(frame)
                ),
                ));
            }
        }
        for (frame, d) in values(&self.degrees) {
            if !within(d) {
                return Err((
                    "degrees",
                    format!(
                        "the angle {d}°{} must lie within ±{MAX_COORDINATE:e}",
                        at(frame)
                    ),
                ));
            }
        }
        for (frame, s) in values(&self.scale) {
            if !(MIN_SCALE..=MAX_SCALE).contains(&s) {
                return Err((
                    "scale",
                    format!(
                        "the scale {s}{} must lie in [{MIN_SCALE:e}, {MAX_SCALE:e}]",
                        at(frame)
                    ),
                ));
            }
        }
        Ok(())
    }

    /// How far from the origin the transform can carry a point within `radius` of it, at any
    /// frame: the largest, over the stretches between consecutive keys, of
    /// `max|translate| + max|pivot| + max scale · (radius + max|pivot|)`, each maximum taken
    /// over the stretch's two ends. The tracks are linear over a stretch, so each length is
    /// largest at an end, and a rotation keeps lengths: no frame carries the point farther.
    #[must_use]
    pub fn reach(&self, radius: f64) -> f64 {
        let mut frames: Vec<f64> = self.key_frames().collect();
        frames.sort_by(f64::total_cmp);
        frames.dedup();
        if frames.is_empty() {
            frames.push(0.0);
        }
        let ends = |f: f64| {
            (
                self.translate.at(f).length(),
                self.pivot.at(f).length(),
                self.scale.at(f),
            )
        };
        let stretch = |a: f64, b: f64| {
            let ((ta, pa, sa), (tb, pb, sb)) = (ends(a), ends(b));
            let pivot = pa.max(pb);
            ta.max(tb) + pivot + sa.max(sb) * (radius + pivot)
        };
        let first = frames[0];
        frames
            .windows(2)
            .map(|w| stretch(w[0], w[1]))
            .fold(stretch(first, first), f64::max)
    }
}

/// A track's values as written: its constant (no frame), or each key with its frame.
fn values<T: Copy>(track: &Track<T>) -> Vec<(Option<f64>, T)> {
    match track {
        Track::Constant(v) => vec![(None, *v)],
        Track::Keys(keys) => keys.iter().map(|k| (Some(k.frame), k.value)).collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::anim::Key;

    #[test]
    fn the_pivot_stays_put_and_the_origin_pivot_is_the_plain_formula() {
        let spec = TransformSpec {
            degrees: Track::Constant(90.0),
            pivot: Track::Constant(DVec3::new(1.0, 0.0, 0.0)),
            ..TransformSpec::default()
        };
        let placed = spec.at(1.0);
        assert!((placed.apply(DVec3::X) - DVec3::X).length() < 1e-15);
        // (2, 0, 0) is 1 from the pivot along x: a quarter turn about z puts it at (1, 1, 0).
        let p = placed.apply(DVec3::new(2.0, 0.0, 0.0));
        assert!((p - DVec3::new(1.0, 1.0, 0.0)).length() < 1e-15, "{p}");
        let plain = TransformSpec {
            translate: Track::Constant(DVec3::new(0.5, -2.0, 3.0)),
            axis: Track::Constant(DVec3::new(1.0, 2.0, 2.0)),
            degrees: Track::Constant(33.0),
            scale: Track::Constant(0.8),
            ..TransformSpec::default()
        };
        let q = DVec3::new(0.3, 0.7, -1.1);
        let rotation =
            DQuat::from_axis_angle(DVec3::new(1.0, 2.0, 2.0).normalize(), 33f64.to_radians());
        assert_eq!(
            plain.at(7.0).apply(q),
            DVec3::new(0.5, -2.0, 3.0) + rotation * (0.8 * q)
        );
    }

    #[test]
    fn reach_bounds_every_frame() {
        let spec = TransformSpec {
            translate: Track::Keys(vec![
                Key {
                    frame: 0.0,
                    value: DVec3::new(-3.0, 0.0, 0.0),
                },
                Key {
                    frame: 10.0,
                    value: DVec3::new(5.0, 1.0, 0.0),
                },
            ]),
            degrees: Track::Keys(vec![
                Key {
                    frame: 0.0,
                    value: 0.0,
                },
                Key {
                    frame: 10.0,
                    value: 270.0,
                },
            ]),
            scale: Track::Keys(vec![
                Key {
                    frame: 0.0,
                    value: 2.0,
                },
                Key {
                    frame: 10.0,
                    value: 0.5,
                },
            ]),
            pivot: Track::Constant(DVec3::new(0.0, 1.0, 0.0)),
            ..TransformSpec::default()
        };
        let reach = spec.reach(1.5);
        let corners = [-1.5, 1.5];
        for i in 0..=100 {
            let placed = spec.at(f64::from(i) / 10.0);
            for &x in &corners {
                for &y in &corners {
                    let p = DVec3::new(x, y, 0.0).normalize() * 1.5;
                    assert!(placed.apply(p).length() <= reach + 1e-12);
                }
            }
        }
    }

    #[test]
    fn values_out_of_range_are_named_with_their_frame() {
        let spec = TransformSpec {
            scale: Track::Keys(vec![
                Key {
                    frame: 1.0,
                    value: 1.0,
                },
                Key {
                    frame: 9.0,
                    value: 0.0,
                },
            ]),
            ..TransformSpec::default()
        };
        let (field, message) = spec.check().unwrap_err();
        assert_eq!(field, "scale");
        assert!(message.contains("at frame 9"), "{message}");
        let zero_axis = TransformSpec {
            axis: Track::Keys(vec![
                Key {
                    frame: 1.0,
                    value: DVec3::Z,
                },
                Key {
                    frame: 4.0,
                    value: DVec3::ZERO,
                },
            ]),
            ..TransformSpec::default()
        };
        assert_eq!(zero_axis.check().unwrap_err().0, "axis");
    }
}
