//! A rotation keyed as an axis track and an angle track, read as one rotation that turns at
//! constant angular speed between keys.

use glam::{DQuat, DVec3};

use super::track::Track;

/// The rotation `R(axis, degrees)` of two tracks, read as one rotation (docs/shot-format.md,
/// "Moving instances and parts"):
///
/// - its keys are the frames where either track is keyed; at a key `f_k` the rotation is
///   `q_k = R(a_k, θ_k)`, with `θ_k` the angle track there and `a_k` the axis track there, whose
///   direction turns along the great circle between its own keys (so an axis keyed from `z` to
///   `−z` passes through a perpendicular axis, never through zero);
/// - between keys `f_k` and `f_{k+1}`, with `t = (f − f_k) / (f_{k+1} − f_k)`: when
///   `a_k = a_{k+1}`, `R(a_k, θ(f))` — a turn about the one axis at constant angular speed,
///   through as many turns as the angles say; otherwise `slerp(q_k, q_{k+1}, t)` — the shortest
///   turn from one orientation to the other, at constant angular speed;
/// - before the first key and after the last, held.
///
/// Every axis must be non-zero (the shot checks this at every key).
#[must_use]
pub fn keyed_rotation(axis: &Track<DVec3>, degrees: &Track<f64>, frame: f64) -> DQuat {
    let (before, after) = bracketing_keys(axis, degrees, frame);
    let held = |at: f64| DQuat::from_axis_angle(axis_at(axis, at), degrees.at(at).to_radians());
    match (before, after) {
        (Some(a), Some(b)) => {
            let (axis_a, axis_b) = (axis_at(axis, a), axis_at(axis, b));
            if axis_a == axis_b {
                DQuat::from_axis_angle(axis_a, degrees.at(frame).to_radians())
            } else {
                let t = (frame - a) / (b - a);
                held(a).slerp(held(b), t)
            }
        }
        // Held outside the keys, and a constant throughout: R(a, θ) read where the frame is.
        _ => DQuat::from_axis_angle(axis_at(axis, frame), degrees.at(frame).to_radians()),
    }
}

/// The last key frame of either track at or before `frame` and the first after it; None on a
/// side without one.
fn bracketing_keys(
    axis: &Track<DVec3>,
    degrees: &Track<f64>,
    frame: f64,
) -> (Option<f64>, Option<f64>) {
    let mut before: Option<f64> = None;
    let mut after: Option<f64> = None;
    for key in axis.key_frames().chain(degrees.key_frames()) {
        if key <= frame {
            before = Some(before.map_or(key, |b| b.max(key)));
        } else {
            after = Some(after.map_or(key, |a| a.min(key)));
        }
    }
    (before, after)
}

/// The unit axis at `frame`: the axis track's direction, turning along the great circle between
/// its keys at constant speed ([`UnitAxis::interpolate`]).
#[must_use]
pub fn axis_at(axis: &Track<DVec3>, frame: f64) -> DVec3 {
    match axis {
        Track::Constant(a) => a.normalize(),
        Track::Keys(keys) => {
            let after = keys.partition_point(|k| k.frame <= frame);
            match (after.checked_sub(1).map(|i| &keys[i]), keys.get(after)) {
                (Some(a), Some(b)) => {
                    let t = (frame - a.frame) / (b.frame - a.frame);
                    UnitAxis::interpolate(
                        UnitAxis(a.value.normalize()),
                        UnitAxis(b.value.normalize()),
                        t,
                    )
                    .0
                }
                (Some(last), None) => last.value.normalize(),
                (None, Some(first)) => first.value.normalize(),
                (None, None) => DVec3::Z,
            }
        }
    }
}

/// A unit axis in f64, interpolated along the great circle.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UnitAxis(pub DVec3);

impl UnitAxis {
    /// `sin((1−t)Ω)/sin Ω · a + sin(tΩ)/sin Ω · b` with `cos Ω = a·b`, exact at both ends; linear
    /// (then normalized) where Ω is too small for the quotient, and turning about an axis across
    /// `a` when the two are opposite.
    #[must_use]
    pub fn interpolate(UnitAxis(a): Self, UnitAxis(b): Self, t: f64) -> Self {
        if t <= 0.0 {
            return UnitAxis(a);
        }
        if t >= 1.0 {
            return UnitAxis(b);
        }
        let cos = a.dot(b).clamp(-1.0, 1.0);
        if cos > 1.0 - 1e-12 {
            return UnitAxis(a.lerp(b, t).normalize());
        }
        let across = (b - cos * a)
            .try_normalize()
            .unwrap_or_else(|| a.any_orthonormal_vector());
        let angle = t * cos.acos();
        UnitAxis(a * angle.cos() + across * angle.sin())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::anim::Key;

    fn keys<T: Copy>(pairs: &[(f64, T)]) -> Track<T> {
        Track::Keys(
            pairs
                .iter()
                .map(|&(frame, value)| Key { frame, value })
                .collect(),
        )
    }

    /// The angle of `q` about `axis` (q must turn about it), in degrees in (−180, 180].
    fn degrees_about(q: DQuat, axis: DVec3) -> f64 {
        let (a, angle) = q.to_axis_angle();
        let signed = if a.dot(axis) < 0.0 { -angle } else { angle };
        let d = signed.to_degrees();
        if d > 180.0 {
            d - 360.0
        } else {
            d
        }
    }

    #[test]
    fn one_axis_turns_at_constant_speed_through_whole_turns() {
        let axis = Track::Constant(DVec3::new(0.0, 0.0, 2.0));
        let degrees = keys(&[(1.0, 0.0), (25.0, 540.0)]);
        for f in 1..=25 {
            let expected = 540.0 * f64::from(f - 1) / 24.0;
            let q = keyed_rotation(&axis, &degrees, f64::from(f));
            // The x axis turned by the expected angle, modulo whole turns.
            let x = q * DVec3::X;
            let (c, s) = (expected.to_radians().cos(), expected.to_radians().sin());
            assert!((x - DVec3::new(c, s, 0.0)).length() < 1e-12, "{f}: {x}");
        }
        // Same bits as a rotation placed by hand at the midpoint.
        let mid = keyed_rotation(&axis, &keys(&[(1.0, 0.0), (25.0, 90.0)]), 13.0);
        assert_eq!(mid, DQuat::from_axis_angle(DVec3::Z, 45f64.to_radians()));
        // Held outside the keys.
        assert_eq!(
            keyed_rotation(&axis, &degrees, -10.0),
            DQuat::from_axis_angle(DVec3::Z, 0.0)
        );
    }

    #[test]
    fn a_changing_axis_turns_the_shortest_way_at_constant_speed() {
        let axis = keys(&[(0.0, DVec3::Z), (10.0, DVec3::X)]);
        let degrees = Track::Constant(90.0);
        let (qa, qb) = (
            DQuat::from_axis_angle(DVec3::Z, 90f64.to_radians()),
            DQuat::from_axis_angle(DVec3::X, 90f64.to_radians()),
        );
        let whole = qa.angle_between(qb);
        for i in 0..=10 {
            let q = keyed_rotation(&axis, &degrees, f64::from(i));
            let t = f64::from(i) / 10.0;
            assert!((q.angle_between(qa) - t * whole).abs() < 1e-9, "{i}");
            assert!(
                (q.angle_between(qb) - (1.0 - t) * whole).abs() < 1e-9,
                "{i}"
            );
        }
    }

    #[test]
    fn opposite_axes_never_pass_through_zero() {
        let axis = keys(&[(0.0, DVec3::Z), (10.0, -DVec3::Z)]);
        for i in 0..=20 {
            let a = axis_at(&axis, f64::from(i) / 2.0);
            assert!((a.length() - 1.0).abs() < 1e-12, "{i}: {a}");
        }
        let q = keyed_rotation(&axis, &keys(&[(0.0, 30.0), (10.0, 30.0)]), 5.0);
        assert!(q.is_finite() && q.is_normalized());
    }

    #[test]
    fn keys_of_either_track_are_keys_of_the_rotation() {
        // The angle keyed at 0 and 10, the axis at 5 only: about the held axis the angle runs
        // linearly, so at 2.5 the turn is a quarter of 80°.
        let axis = keys(&[(5.0, DVec3::Y)]);
        let degrees = keys(&[(0.0, 0.0), (10.0, 80.0)]);
        let q = keyed_rotation(&axis, &degrees, 2.5);
        assert!((degrees_about(q, DVec3::Y) - 20.0).abs() < 1e-12);
    }
}
