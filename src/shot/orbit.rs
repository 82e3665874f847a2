//! An orbit camera: the eye on a sphere or a cylinder about the target, placed by angles and
//! lengths that are tracks, so that a turntable is two keys.

use glam::DVec3;
use serde::Deserialize;

use crate::anim::Track;
use crate::geom::MAX_COORDINATE;

/// The largest azimuth magnitude, in degrees: thousands of turns, far beyond any shot, and small
/// enough that `cos` and `sin` of it keep their precision in f64.
pub const MAX_AZIMUTH_DEGREES: f64 = 1e6;

/// The largest elevation magnitude, in degrees: short of the poles, where the view direction
/// would be parallel to the world's z axis and a camera with the default `up` could not roll.
pub const MAX_ELEVATION_DEGREES: f64 = 89.0;

/// Where an orbiting eye is, about the camera's target; every number a track, interpolated
/// linearly like every other track, so that between two keys the eye moves at constant angular
/// speed along the sphere's or cylinder's surface.
///
/// Azimuth is in degrees counterclockwise about the world's z axis seen from above, 0 on +x,
/// and may run through any number of turns (−100 to 260 is a full turn and then some). The
/// pole of the sphere and the axis of the cylinder are the world's z axis through the target.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum OrbitSpec {
    /// The eye on the sphere of radius `distance` about the target:
    /// `eye = target + distance (cos e cos a, cos e sin a, sin e)`, with `a` the azimuth and
    /// `e` the elevation above the target's horizontal plane, both in degrees.
    Sphere {
        azimuth: Track<f32>,
        elevation: Track<f32>,
        distance: Track<f32>,
    },
    /// The eye on the cylinder of radius `radius` about the vertical through the target, at
    /// `height` above the target: `eye = target + (radius cos a, radius sin a, height)`.
    Cylinder {
        azimuth: Track<f32>,
        radius: Track<f32>,
        height: Track<f32>,
    },
}

/// One value of an orbit out of its range: the field's name and why.
#[derive(Clone, Debug, PartialEq)]
pub struct OrbitError {
    /// The field: `"azimuth"`, `"elevation"`, `"distance"`, `"radius"` or `"height"`.
    pub field: &'static str,
    pub message: String,
}

impl OrbitSpec {
    /// The eye at `frame` for a target at `target`, in f64 from the tracks' values
    /// ([`OrbitSpec::Sphere`], [`OrbitSpec::Cylinder`] give the formulas).
    #[must_use]
    pub fn eye_at(&self, target: DVec3, frame: f64) -> DVec3 {
        match self {
            OrbitSpec::Sphere {
                azimuth,
                elevation,
                distance,
            } => {
                let a = f64::from(azimuth.at(frame)).to_radians();
                let e = f64::from(elevation.at(frame)).to_radians();
                let d = f64::from(distance.at(frame));
                target + d * DVec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin())
            }
            OrbitSpec::Cylinder {
                azimuth,
                radius,
                height,
            } => {
                let a = f64::from(azimuth.at(frame)).to_radians();
                let r = f64::from(radius.at(frame));
                let h = f64::from(height.at(frame));
                target + DVec3::new(r * a.cos(), r * a.sin(), h)
            }
        }
    }

    /// Calls `f` with every track of the orbit, azimuth first. The fields are named one by
    /// one, so a new field does not compile until it is visited here.
    pub fn for_each_track(&self, f: &mut dyn FnMut(&'static str, &Track<f32>)) {
        match self {
            OrbitSpec::Sphere {
                azimuth,
                elevation,
                distance,
            } => {
                f("azimuth", azimuth);
                f("elevation", elevation);
                f("distance", distance);
            }
            OrbitSpec::Cylinder {
                azimuth,
                radius,
                height,
            } => {
                f("azimuth", azimuth);
                f("radius", radius);
                f("height", height);
            }
        }
    }

    /// Checks the values at `frame`: an azimuth within ±[`MAX_AZIMUTH_DEGREES`], an elevation
    /// within ±[`MAX_ELEVATION_DEGREES`], a distance or radius in `(0, MAX_COORDINATE]` and a
    /// height within ±`MAX_COORDINATE`. Every value is linear between keys, so checking at the
    /// keys checks every frame.
    pub fn check_at(&self, frame: f64) -> Result<(), OrbitError> {
        let azimuth = Bound::Within(MAX_AZIMUTH_DEGREES, " degrees");
        let checks: [(&'static str, &Track<f32>, Bound); 3] = match self {
            OrbitSpec::Sphere {
                azimuth: a,
                elevation,
                distance,
            } => [
                ("azimuth", a, azimuth),
                (
                    "elevation",
                    elevation,
                    Bound::Within(
                        MAX_ELEVATION_DEGREES,
                        " degrees (at ±90 the view would be along the orbit's axis)",
                    ),
                ),
                ("distance", distance, Bound::Length),
            ],
            OrbitSpec::Cylinder {
                azimuth: a,
                radius,
                height,
            } => [
                ("azimuth", a, azimuth),
                ("radius", radius, Bound::Length),
                ("height", height, Bound::Within(MAX_COORDINATE, "")),
            ],
        };
        for (field, track, bound) in checks {
            let value = f64::from(track.at(frame));
            let (ok, range) = match bound {
                Bound::Within(most, unit) => (value.abs() <= most, format!("within ±{most}{unit}")),
                Bound::Length => (
                    value > 0.0 && value <= MAX_COORDINATE,
                    format!("above 0 and at most {MAX_COORDINATE:e}"),
                ),
            };
            if !ok {
                return Err(OrbitError {
                    field,
                    message: format!(
                        "the orbit's {field} is {value} at frame {frame}, but it must be {range}"
                    ),
                });
            }
        }
        Ok(())
    }
}

/// The range of one orbit value.
#[derive(Clone, Copy)]
enum Bound {
    /// `[−most, most]`, with the unit shown after the number.
    Within(f64, &'static str),
    /// `(0, MAX_COORDINATE]`.
    Length,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::anim::fixtures::keys;
    use crate::anim::Track;

    #[test]
    fn a_sphere_orbit_keeps_its_distance_and_turns_at_constant_speed() {
        let target = DVec3::new(0.5, -1.0, 1.4);
        let orbit = OrbitSpec::Sphere {
            azimuth: keys(&[(1.0, -100.0), (97.0, 260.0)]),
            elevation: keys(&[(1.0, 10.0), (97.0, 40.0)]),
            distance: Track::Constant(9.5),
        };
        for frame in [1.0, 13.5, 40.0, 49.0, 96.25] {
            let eye = orbit.eye_at(target, frame);
            let offset = eye - target;
            assert!((offset.length() - 9.5).abs() < 1e-12, "{frame}: {offset}");
            // The azimuth read back from the eye, against the linear track.
            let t = (frame - 1.0) / 96.0;
            let want = (-100.0 + 360.0 * t).to_radians();
            let got = offset.y.atan2(offset.x);
            let turn = (got - want).rem_euclid(std::f64::consts::TAU);
            assert!(turn.min(std::f64::consts::TAU - turn) < 1e-6, "{frame}");
            let elevation = (offset.z / 9.5).asin().to_degrees();
            assert!((elevation - (10.0 + 30.0 * t)).abs() < 1e-4, "{frame}");
        }
    }

    #[test]
    fn a_cylinder_orbit_rises_in_a_straight_line_when_only_its_height_is_keyed() {
        let target = DVec3::new(0.0, 0.0, 1.4);
        let orbit = OrbitSpec::Cylinder {
            azimuth: Track::Constant(-100.0),
            radius: Track::Constant(9.0),
            height: keys(&[(1.0, 3.1), (24.0, 5.1)]),
        };
        let (a, b) = (orbit.eye_at(target, 1.0), orbit.eye_at(target, 24.0));
        let mid = orbit.eye_at(target, 12.5);
        assert!((mid - (a + b) / 2.0).length() < 1e-6, "{mid}");
        let radial = (a - target).truncate().length();
        assert!((radial - 9.0).abs() < 1e-12);
    }

    #[test]
    fn values_out_of_range_name_their_field() {
        let orbit = OrbitSpec::Sphere {
            azimuth: Track::Constant(0.0),
            elevation: keys(&[(1.0, 0.0), (10.0, 90.0)]),
            distance: Track::Constant(5.0),
        };
        assert!(orbit.check_at(1.0).is_ok());
        let error = orbit.check_at(10.0).unwrap_err();
        assert_eq!(error.field, "elevation");
        assert!(error.message.contains("89"), "{}", error.message);
        let flat = OrbitSpec::Cylinder {
            azimuth: Track::Constant(f32::NAN),
            radius: Track::Constant(0.0),
            height: Track::Constant(0.0),
        };
        assert_eq!(flat.check_at(1.0).unwrap_err().field, "azimuth");
        let flat = OrbitSpec::Cylinder {
            azimuth: Track::Constant(0.0),
            radius: Track::Constant(0.0),
            height: Track::Constant(0.0),
        };
        assert_eq!(flat.check_at(1.0).unwrap_err().field, "radius");
    }
}
