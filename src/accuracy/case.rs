//! What one measurement of the ladder looks at: a pose of camera and light ([`Pose`]) with a
//! highlight stack ([`Stack`]), the pair a [`Case`].

use std::fmt;

use glam::{DVec3, Vec3};

use super::reference::AnalyticSphere;
use super::stack::Stack;
use crate::render::{Camera, Projection};

/// Where the camera stands and where the light puts the highlight on the unit sphere.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pose {
    /// The standard view ([`AnalyticSphere::new`], 30° field of view): the highlight near the
    /// centre of the disc, lit from the front left and above.
    Front,
    /// The standard camera, lit so that the highlight's centre sits `degrees` from the
    /// direction toward the eye, up and to the right: toward the limb, foreshortened.
    OffCentre { degrees: u32 },
    /// Seen from 50° above the equator, lit so that the highlight's centre is the pole, where
    /// the sphere's patch edge collapses to a point.
    Pole,
    /// As [`Pose::Pole`], the highlight's centre 5° from the pole.
    NearPole,
    /// A 75° field of view from 2.6 units, turned so that the sphere sits in the image's lower
    /// right corner, cut by two borders, with the highlight's centre near the corner.
    WideAngle,
}

impl Pose {
    /// The camera of this pose (square images).
    #[must_use]
    pub fn camera(self) -> Camera {
        let standard = AnalyticSphere::new(Projection::Perspective {
            fov_y_degrees: 30.0,
        })
        .camera();
        match self {
            Pose::Front | Pose::OffCentre { .. } => standard,
            Pose::Pole | Pose::NearPole => {
                let elevation = 50f32.to_radians();
                Camera {
                    eye: 5.0 * Vec3::new(0.0, -elevation.cos(), elevation.sin()),
                    ..standard
                }
            }
            Pose::WideAngle => Camera {
                eye: Vec3::new(0.0, -2.6, 0.0),
                target: Vec3::new(-1.4, 0.0, 0.9),
                projection: Projection::Perspective {
                    fov_y_degrees: 75.0,
                },
                near: 0.1,
                ..standard
            },
        }
    }

    /// The point of the sphere where the highlight's centre sits (`N = H` there), if the pose
    /// places it.
    #[must_use]
    pub fn highlight_centre(self) -> Option<DVec3> {
        let along = |axis: DVec3, toward: DVec3, degrees: f64| {
            let (sin, cos) = degrees.to_radians().sin_cos();
            axis * cos + toward.normalize() * sin
        };
        match self {
            Pose::Front => None,
            Pose::OffCentre { degrees } => Some(along(
                DVec3::NEG_Y,
                DVec3::new(1.0, 0.0, 1.0),
                f64::from(degrees),
            )),
            Pose::Pole => Some(DVec3::Z),
            Pose::NearPole => Some(along(DVec3::Z, DVec3::X, 5.0)),
            Pose::WideAngle => Some(DVec3::new(0.0, -0.9, -0.4).normalize()),
        }
    }

    /// The unit direction toward the light. Where the pose places the highlight at `P`, the
    /// mirror of the eye direction `V = (E − P)/|E − P|` about the normal `N = P`:
    /// `L = 2(N·V)N − V`, so that `H = (L + V)/|L + V| = N` at `P`.
    #[must_use]
    pub fn light(self) -> Vec3 {
        let front = Vec3::new(0.35, -1.0, 0.45).normalize();
        let Some(n) = self.highlight_centre() else {
            return front;
        };
        let v = (self.camera().eye.as_dvec3() - n).normalize();
        (2.0 * n.dot(v) * n - v).normalize().as_vec3()
    }

    /// The analytic sphere seen and lit in this pose.
    #[must_use]
    pub fn sphere(self) -> AnalyticSphere {
        AnalyticSphere::seen_by(self.camera(), self.light())
    }
}

impl fmt::Display for Pose {
    /// `front`, `off-centre 50°`, `pole`, `near pole`, `wide angle`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Pose::Front => f.write_str("front"),
            Pose::OffCentre { degrees } => write!(f, "off-centre {degrees}°"),
            Pose::Pole => f.write_str("pole"),
            Pose::NearPole => f.write_str("near pole"),
            Pose::WideAngle => f.write_str("wide angle"),
        }
    }
}

/// One view the ladder measures: a highlight stack in a pose.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Case {
    pub pose: Pose,
    pub stack: Stack,
}

impl Case {
    /// The five stacks in the front pose: highlights near the centre of the disc.
    #[must_use]
    pub fn centred() -> Vec<Case> {
        Stack::CENTRED
            .iter()
            .map(|&stack| Case {
                pose: Pose::Front,
                stack,
            })
            .collect()
    }

    /// The views chosen to be hard: highlights 30°, 50° and 70° off centre, at and around the
    /// pole, near the border of a wide-angle view, a thin crescent, ε = 10⁻³, a split into
    /// four, and a keyed translation read at fractional frames.
    #[must_use]
    pub fn hard() -> Vec<Case> {
        let case = |pose, stack| Case { pose, stack };
        vec![
            case(Pose::OffCentre { degrees: 30 }, Stack::Identity),
            case(Pose::OffCentre { degrees: 50 }, Stack::Square),
            case(Pose::OffCentre { degrees: 70 }, Stack::Identity),
            case(Pose::Pole, Stack::Identity),
            case(Pose::NearPole, Stack::TranslateScale),
            case(Pose::WideAngle, Stack::Identity),
            case(Pose::Front, Stack::ThinCrescent),
            case(Pose::OffCentre { degrees: 30 }, Stack::Tiny),
            case(Pose::Front, Stack::SplitFour),
            case(Pose::OffCentre { degrees: 30 }, Stack::Keyed { frame: 2.5 }),
            case(Pose::Front, Stack::Keyed { frame: 6.25 }),
        ]
    }

    /// [`Case::centred`] then [`Case::hard`].
    #[must_use]
    pub fn all() -> Vec<Case> {
        let mut all = Self::centred();
        all.extend(Self::hard());
        all
    }
}

impl fmt::Display for Case {
    /// The stack in its pose: `identity (off-centre 30°)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} ({})", self.stack, self.pose)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_pose_puts_the_half_vector_on_the_normal_at_its_centre() {
        for pose in [
            Pose::OffCentre { degrees: 30 },
            Pose::OffCentre { degrees: 70 },
            Pose::Pole,
            Pose::NearPole,
            Pose::WideAngle,
        ] {
            let p = pose.highlight_centre().unwrap();
            let camera = pose.camera();
            let v = camera.toward_eye(p.as_vec3());
            let h = crate::highlight::half_vector(pose.light(), v);
            assert!(h.dot(p.as_vec3()) > 1.0 - 1e-6, "{pose}: H = {h}, N = {p}");
            // The centre faces the eye, and the angle from the view of the sphere's centre is
            // the pose's.
            assert!(v.dot(p.as_vec3()) > 0.1, "{pose}");
        }
        let p = Pose::OffCentre { degrees: 50 }.highlight_centre().unwrap();
        assert!((p.dot(DVec3::NEG_Y) - 50f64.to_radians().cos()).abs() < 1e-12);
    }

    #[test]
    fn every_hard_case_shows_its_highlight_and_a_silhouette_at_256() {
        for case in Case::hard() {
            let sphere = case.pose.sphere();
            let mattes = sphere.mattes(&case.stack.reference_expression(), 64, 2, 2);
            let sum = |m: &[f32]| m.iter().map(|&c| f64::from(c)).sum::<f64>();
            let (silhouette, highlight) = (sum(&mattes.silhouette), sum(&mattes.highlight));
            // At 64² a 256² image's areas are a sixteenth: a highlight of at least 16 pixels
            // there is one of a pixel here.
            assert!(highlight > 1.0, "{case}: highlight {highlight}");
            assert!(
                silhouette > 4.0 * highlight,
                "{case}: {silhouette} {highlight}"
            );
        }
    }
}
