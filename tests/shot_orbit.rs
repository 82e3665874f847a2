//! The orbit camera: its eye stays on its sphere between keys and turns at constant speed, and
//! the shipped turntable and rising-camera shots, rewritten as orbits, see the teapot as their
//! old eye keys did.

use glam::{Vec2, Vec3};
use glint::render::Camera;
use glint::shot::load_shot;

use crate::common::repo_file;

/// The eye keys `shots/teapot_turntable.ron` had before its camera became an orbit: points on a
/// circle about the z axis, keyed every 4 frames.
const TURNTABLE_EYES: &[(f64, [f32; 3])] = &[
    (1.0, [-1.563, -8.863, 4.5]),
    (5.0, [-0.776, -8.966, 4.5]),
    (9.0, [0.017, -9.0, 4.5]),
    (13.0, [0.809, -8.964, 4.5]),
    (17.0, [1.595, -8.857, 4.5]),
    (21.0, [2.369, -8.683, 4.5]),
    (25.0, [3.125, -8.44, 4.5]),
    (29.0, [3.856, -8.132, 4.5]),
    (33.0, [4.557, -7.761, 4.5]),
    (37.0, [5.223, -7.329, 4.5]),
    (41.0, [5.848, -6.841, 4.5]),
    (45.0, [6.428, -6.299, 4.5]),
    (49.0, [6.958, -5.709, 4.5]),
    (53.0, [7.433, -5.074, 4.5]),
    (57.0, [7.851, -4.399, 4.5]),
    (61.0, [8.208, -3.691, 4.5]),
    (65.0, [8.502, -2.954, 4.5]),
    (69.0, [8.729, -2.193, 4.5]),
    (73.0, [8.888, -1.416, 4.5]),
    (77.0, [8.978, -0.628, 4.5]),
    (81.0, [8.998, 0.165, 4.5]),
    (85.0, [8.949, 0.957, 4.5]),
    (89.0, [8.83, 1.742, 4.5]),
    (93.0, [8.642, 2.513, 4.5]),
    (96.0, [8.457, 3.078, 4.5]),
];

/// The eye keys `shots/teapot_rising_camera.ron` had: straight up in front of the teapot.
const RISING_EYES: &[(f64, [f32; 3])] =
    &[(1.0, [-1.563, -8.863, 4.5]), (24.0, [-1.563, -8.863, 6.5])];

/// Where `point` falls on a `width × height` image seen by `camera`, in pixels; None behind it.
fn project(camera: &Camera, point: Vec3, (width, height): (u32, u32)) -> Option<Vec2> {
    let clip = camera.view_projection(width as f32 / height as f32) * point.extend(1.0);
    (clip.w > 0.0).then(|| {
        let ndc = Vec2::new(clip.x, clip.y) / clip.w;
        Vec2::new(
            (ndc.x + 1.0) * 0.5 * width as f32,
            (1.0 - ndc.y) * 0.5 * height as f32,
        )
    })
}

/// The farthest any of `points` moves on the image between `a` and `b`, in pixels: a bound on
/// how far the silhouette of a surface through them can move.
fn farthest_move(a: &Camera, b: &Camera, points: &[Vec3], size: (u32, u32)) -> f32 {
    points
        .iter()
        .map(|&p| match (project(a, p, size), project(b, p, size)) {
            (Some(pa), Some(pb)) => pa.distance(pb),
            _ => f32::INFINITY,
        })
        .fold(0.0, f32::max)
}

/// For every old key of `shot`, the teapot seen from the orbit at that frame against the old
/// eye: no point of its surface (17 × 17 per patch) moves more than half a pixel.
fn matches_old_keys(shot: &str, old: &[(f64, [f32; 3])]) {
    let shot = load_shot(&repo_file(shot)).unwrap_or_else(|e| panic!("{e}"));
    assert!(shot.orbit().is_some(), "the shot's camera orbits");
    let size = (shot.settings.width, shot.settings.height);
    let mut points = Vec::new();
    for patch in &shot.library.patches {
        let domain = patch.surface.domain();
        for i in 0..=16 {
            for j in 0..=16 {
                let u = domain.u.0 + (domain.u.1 - domain.u.0) * f64::from(i) / 16.0;
                let v = domain.v.0 + (domain.v.1 - domain.v.0) * f64::from(j) / 16.0;
                points.push(patch.surface.point(u, v).as_vec3());
            }
        }
    }
    for &(frame, eye) in old {
        let orbit = shot.camera_at(frame);
        let before = Camera {
            eye: Vec3::from(eye),
            ..orbit
        };
        let moved = farthest_move(&before, &orbit, &points, size);
        assert!(
            moved <= 0.5,
            "frame {frame}: the teapot moves {moved} px (eye {} against {:?})",
            orbit.eye,
            eye
        );
    }
}

#[test]
fn the_turntable_orbit_sees_the_teapot_as_its_old_eye_keys_did() {
    matches_old_keys("shots/teapot_turntable.ron", TURNTABLE_EYES);
}

#[test]
fn the_rising_camera_on_its_cylinder_sees_the_teapot_as_its_old_eye_keys_did() {
    matches_old_keys("shots/teapot_rising_camera.ron", RISING_EYES);
}

#[test]
fn midpoint_frames_lie_on_the_sphere_at_the_mean_azimuth() {
    let shot = load_shot(&repo_file("shots/teapot_turntable.ron")).unwrap();
    let Some(glint::shot::OrbitSpec::Sphere {
        azimuth,
        elevation,
        distance,
    }) = shot.orbit()
    else {
        panic!("the turntable orbits on a sphere");
    };
    let keys: Vec<f64> = azimuth.key_frames().collect();
    assert_eq!(keys.len(), 2, "a turntable is two keys");
    let (first, last) = (keys[0], keys[1]);
    let (a0, a1) = (f64::from(azimuth.at(first)), f64::from(azimuth.at(last)));
    let radius = f64::from(distance.at(first));
    let target = shot.camera_at(first).target.as_dvec3();
    for t in [0.5, 0.25, 0.75, 0.1] {
        let frame = first + t * (last - first);
        let offset = shot.eye_at(frame) - target;
        assert!(
            (offset.length() - radius).abs() <= 1e-9,
            "frame {frame}: {} from the target, not {radius}",
            offset.length()
        );
        // The azimuth read back from the eye is the keys' mean at the midpoint.
        let want = a0 + t * (a1 - a0);
        let got = offset.y.atan2(offset.x).to_degrees();
        let turn = (got - want).rem_euclid(360.0);
        assert!(
            turn.min(360.0 - turn) < 1e-4,
            "frame {frame}: azimuth {got}, not {want}"
        );
        let up = (offset.z / radius).asin().to_degrees();
        assert!((up - f64::from(elevation.at(frame))).abs() < 1e-4);
    }
    // An eye track between the same two keys cuts the chord: far inside the sphere.
    let (e0, e1) = (shot.eye_at(first), shot.eye_at(last));
    let chord = (e0 + e1) / 2.0 - target;
    assert!(chord.length() < radius * 0.9, "{chord}");
}
