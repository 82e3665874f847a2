//! The camera that shows a whole model from a three-quarter view, for pictures of a model
//! that no shot places.

use glam::{DVec3, Vec3};

use crate::geom::PatchLibrary;
use crate::render::{Camera, Projection};

/// The vertical field of view of [`try_three_quarter_camera`], in degrees.
pub const FRAMING_FOV_DEGREES: f32 = 30.0;

/// The share of the image's half-width and half-height the model may fill.
const FILL: f64 = 0.85;

/// Points of every patch of `library`: a 9 × 9 grid over each one's domain.
fn sample_points(library: &PatchLibrary) -> Vec<DVec3> {
    let steps = 8;
    library
        .patches
        .iter()
        .flat_map(|patch| {
            let surface = &patch.surface;
            let domain = surface.domain();
            (0..=steps).flat_map(move |i| {
                (0..=steps).map(move |j| {
                    let (u, v) = domain.lerp(f64::from(i) / 8.0, f64::from(j) / 8.0);
                    surface.point(u, v)
                })
            })
        })
        .filter(|p| p.is_finite())
        .collect()
}

/// The camera looking at `library` from the front right and above, the whole model in view,
/// for an image of aspect `aspect` (width / height).
///
/// With `z` up and the front toward −y (as the shipped models and shots have it), the eye
/// lies along `d = (cos e · sin a, −cos e · cos a, sin e)` from the model, at azimuth `a` = 35°
/// and elevation `e` = 25°, with a [`FRAMING_FOV_DEGREES`] vertical field of view. In the
/// camera's axes (right `r`, up `u`, `d`) a point `p` at `(x, y, z)` from the centre `c` is
/// seen at `x / (D − z)` across from an eye at `c + D·d`, so it fits the view when
/// `D ≥ z + |x| / (f·tx)` and `D ≥ z + |y| / (f·ty)`, with `ty = tan(fov/2)`,
/// `tx = aspect · ty` and `f` = 0.85 the share of the view the model may fill. `D` is the
/// largest of those bounds over a 9 × 9 grid of points on every patch, after `c` is moved
/// across the view to centre the model's projection once. `near` and `far` bracket the
/// points. `None` for a model with no finite point.
#[must_use]
pub fn try_three_quarter_camera(library: &PatchLibrary, aspect: f64) -> Option<Camera> {
    let points = sample_points(library);
    let (low, high) = points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(low, high), &p| (low.min(p), high.max(p)),
    );
    if points.is_empty() {
        return None;
    }
    let (azimuth, elevation) = (35f64.to_radians(), 25f64.to_radians());
    let towards_eye = DVec3::new(
        elevation.cos() * azimuth.sin(),
        -elevation.cos() * azimuth.cos(),
        elevation.sin(),
    );
    let right = (-towards_eye).cross(DVec3::Z).normalize();
    let up = right.cross(-towards_eye);
    let ty = (0.5 * f64::from(FRAMING_FOV_DEGREES).to_radians()).tan();
    let tx = aspect.max(1e-3) * ty;
    // A flat or point-like model still gets a view of some size.
    let size = (high - low).length().max(1e-6);
    let distance = |centre: DVec3| {
        points.iter().fold(1e-3 * size, |d: f64, &p| {
            let q = p - centre;
            let z = q.dot(towards_eye);
            d.max(z + q.dot(right).abs() / (FILL * tx))
                .max(z + q.dot(up).abs() / (FILL * ty))
                .max(z + 1e-3 * size)
        })
    };
    let mut centre = 0.5 * (low + high);
    let d = distance(centre);
    // Where the points are seen, as tangents of the angle off the line of sight.
    let seen = |centre: DVec3, d: f64| {
        points.iter().fold(
            (
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
            ),
            |(x0, x1, y0, y1), &p| {
                let q = p - centre;
                let depth = d - q.dot(towards_eye);
                let (x, y) = (q.dot(right) / depth, q.dot(up) / depth);
                (x0.min(x), x1.max(x), y0.min(y), y1.max(y))
            },
        )
    };
    let (x0, x1, y0, y1) = seen(centre, d);
    centre += d * (0.5 * (x0 + x1) * right + 0.5 * (y0 + y1) * up);
    let d = distance(centre);
    let (nearest, farthest) = points.iter().fold((f64::INFINITY, 0f64), |(n, f), &p| {
        let depth = d - (p - centre).dot(towards_eye);
        (n.min(depth), f.max(depth))
    });
    Some(Camera {
        eye: (centre + d * towards_eye).as_vec3(),
        target: centre.as_vec3(),
        up: Vec3::Z,
        projection: Projection::Perspective {
            fov_y_degrees: FRAMING_FOV_DEGREES,
        },
        near: (0.5 * nearest).max(1e-4 * d) as f32,
        far: (1.5 * farthest + 1e-3 * size) as f32,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{shapes, NamedPatch};

    fn library_of(surface: crate::geom::NurbsSurface) -> PatchLibrary {
        PatchLibrary::new(vec![NamedPatch {
            name: "s".into(),
            trim: None,
            surface,
        }])
    }

    #[test]
    fn the_model_fills_the_view_at_any_aspect() {
        let sphere = library_of(shapes::sphere(DVec3::new(3.0, -1.0, 2.0), 1.5).unwrap());
        let torus = library_of(shapes::torus(2.0, 0.5).unwrap());
        for library in [&sphere, &torus] {
            for aspect in [0.5, 1.0, 16.0 / 9.0] {
                let camera = try_three_quarter_camera(library, aspect).unwrap();
                camera.validate().unwrap();
                let m = camera.view_projection(aspect as f32);
                let mut widest = 0f32;
                for p in sample_points(library) {
                    let ndc = m.project_point3(p.as_vec3());
                    assert!(
                        ndc.x.abs() <= 1.0 && ndc.y.abs() <= 1.0,
                        "{ndc} at {aspect}"
                    );
                    assert!((0.0..1.0).contains(&ndc.z), "{ndc}");
                    widest = widest.max(ndc.x.abs()).max(ndc.y.abs());
                }
                // And the model fills it, but for a border.
                assert!(
                    widest > FILL as f32 - 0.05 && widest <= FILL as f32 + 1e-4,
                    "{widest}"
                );
            }
        }
    }

    #[test]
    fn the_view_is_from_the_front_right_and_above() {
        let sphere = library_of(shapes::sphere(DVec3::ZERO, 1.0).unwrap());
        let camera = try_three_quarter_camera(&sphere, 1.0).unwrap();
        assert!(camera.eye.x > 0.0 && camera.eye.y < 0.0 && camera.eye.z > 0.0);
        assert!(camera.eye.y.abs() > camera.eye.x && camera.eye.x > camera.eye.z);
        assert!(try_three_quarter_camera(&PatchLibrary::default(), 1.0).is_none());
    }
}
