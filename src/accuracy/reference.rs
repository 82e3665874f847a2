//! The analytic reference: the unit sphere about the origin, ray-cast through each pixel, with
//! the highlight evaluated in closed form on its analytic frame (east, north, outward;
//! [`ClosedForm`](super::closed_form::ClosedForm)), independently of the renderer's highlight
//! code. The NURBS sphere renders of the same view are measured against it.

use std::sync::Arc;

use glam::{DVec3, Mat4, Vec2, Vec3};
use rayon::prelude::*;

use super::sphere_highlight::SphereHighlight;
use super::sphere_point::SpherePoint;
use crate::geom::{shapes, NamedPatch, PatchLibrary};
use crate::highlight::{Light, PreparedExpr};
use crate::render::{Aovs, Camera, PatchLook, Projection, Scene, Tone};
use crate::toon::CelRamp;

/// The unit sphere about the origin seen by a camera and lit by a directional light; by default
/// ([`AnalyticSphere::new`]) from the −y axis, 5 units away, lit from the front left and above.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AnalyticSphere {
    camera: Camera,
    /// The unit direction toward the light.
    light: Vec3,
    /// Clip space back to the world, for the pixel rays (square images).
    inverse_view_projection: Mat4,
}

impl AnalyticSphere {
    /// The standard view with the given projection.
    pub fn new(projection: Projection) -> Self {
        let camera = Camera {
            eye: Vec3::new(0.0, -5.0, 0.0),
            target: Vec3::ZERO,
            up: Vec3::Z,
            projection,
            near: 0.5,
            far: 20.0,
        };
        Self::seen_by(camera, Vec3::new(0.35, -1.0, 0.45))
    }

    /// The sphere seen by `camera` (square images) and lit from the direction `towards_light`
    /// (normalized here).
    pub fn seen_by(camera: Camera, towards_light: Vec3) -> Self {
        Self {
            camera,
            light: towards_light.normalize(),
            inverse_view_projection: camera.view_projection(1.0).inverse(),
        }
    }

    pub fn camera(&self) -> Camera {
        self.camera
    }

    /// The unit direction toward the light.
    pub fn light(&self) -> Vec3 {
        self.light
    }

    /// The exact NURBS unit sphere, one patch named `sphere`.
    pub fn library() -> Arc<PatchLibrary> {
        Arc::new(PatchLibrary {
            patches: vec![NamedPatch {
                name: "sphere".into(),
                trim: None,
                surface: shapes::sphere(DVec3::ZERO, 1.0)
                    .expect("the unit sphere has a positive radius"),
            }],
            groups: Vec::new(),
        })
    }

    /// The scene rendering `library` (from [`Self::library`]) with `highlight` in this view: a
    /// two-tone cel ramp, no outlines, the given AOVs.
    pub fn scene<'a>(
        &self,
        library: &'a PatchLibrary,
        highlight: &PreparedExpr,
        aovs: Aovs,
    ) -> Scene<'a> {
        Scene {
            library,
            looks: vec![PatchLook {
                designed_light: None,
                lines: None,
                tone: Tone::Cel(CelRamp::two_tone(Vec3::splat(0.2), Vec3::splat(0.6), 0.0)),
                highlight: Some(highlight.clone()),
            }],
            camera: self.camera,
            light: Light::Directional {
                towards: self.light,
            },
            outlines: None,
            aovs,
            materials: Vec::new(),
        }
    }

    /// Where the ray through the image point `(x, y)` (in pixels from the top left corner of a
    /// `size × size` image) first meets the sphere: the smaller root of `|o + t d| = 1`,
    /// `t = −(o·d) − sqrt((o·d)² − (|o|² − 1))`, with `o` on the near plane and `d` unit.
    pub fn hit(&self, size: u32, x: f32, y: f32) -> Option<DVec3> {
        let inverse = self.inverse_view_projection;
        let ndc = Vec2::new(2.0 * x / size as f32 - 1.0, 1.0 - 2.0 * y / size as f32);
        let near = inverse.project_point3(ndc.extend(0.0)).as_dvec3();
        let far = inverse.project_point3(ndc.extend(1.0)).as_dvec3();
        let d = (far - near).try_normalize()?;
        let b = near.dot(d);
        let disc = b * b - (near.length_squared() - 1.0);
        (disc >= 0.0).then(|| near + (-b - disc.sqrt()) * d)
    }

    /// The unit vector from the sphere point `p` toward the eye, in f64: `normalize(eye − p)`
    /// under perspective, `normalize(eye − target)` under orthographic projection.
    #[must_use]
    pub fn toward_eye(&self, p: DVec3) -> DVec3 {
        let along_sight = (self.camera.eye - self.camera.target)
            .as_dvec3()
            .normalize();
        match self.camera.projection {
            Projection::Perspective { .. } => (self.camera.eye.as_dvec3() - p)
                .try_normalize()
                .unwrap_or(along_sight),
            Projection::Orthographic { .. } => along_sight,
        }
    }

    /// Blinn's half vector at the sphere point `p`, in f64: `H = normalize(L + V)` for this
    /// view's light L and [`toward_eye`](Self::toward_eye) V; where `L = −V`, a unit vector
    /// perpendicular to V (docs/highlights.md).
    #[must_use]
    pub fn half_vector_at(&self, p: DVec3) -> DVec3 {
        let v = self.toward_eye(p);
        let l = self.light.as_dvec3().normalize();
        (l + v)
            .try_normalize()
            .unwrap_or_else(|| v.any_orthonormal_vector())
    }

    /// Whether the sphere point `p` lies inside `highlight` (coverage above ½), evaluated at its
    /// [`SpherePoint`] (the analytic frame east, north, outward and the NURBS sphere's (u, v))
    /// with [`half_vector_at`](Self::half_vector_at).
    pub fn inside(&self, highlight: &impl SphereHighlight, p: DVec3) -> bool {
        highlight.coverage_at(&SpherePoint::at(p), self.half_vector_at(p)) > 0.5
    }

    /// The fraction of `k × k` sub-pixel samples (at `((i + ½)/k, (j + ½)/k)` within the pixel)
    /// inside the highlight, per pixel of a `size × size` image, rows from the top. With `k = 1`
    /// it is the pixel-centre classification; with large `k` the true area coverage.
    pub fn coverage(&self, highlight: &impl SphereHighlight, size: u32, k: u32) -> Vec<f32> {
        let samples = k.max(1) * k.max(1);
        (0..size * size)
            .into_par_iter()
            .map(|i| self.sample_counts(highlight, size, i, k).1 as f32 / samples as f32)
            .collect()
    }

    /// Of the `k × k` samples of pixel `i` (at `((i + ½)/k, (j + ½)/k)` within it) of a
    /// `size × size` image: how many hit the sphere, and how many of those lie in `highlight`.
    fn sample_counts(
        &self,
        highlight: &impl SphereHighlight,
        size: u32,
        i: u32,
        k: u32,
    ) -> (u32, u32) {
        let k = k.max(1);
        let (px, py) = ((i % size) as f32, (i / size) as f32);
        (0..k * k).fold((0, 0), |(sphere, inside), s| {
            let sx = px + ((s % k) as f32 + 0.5) / k as f32;
            let sy = py + ((s / k) as f32 + 0.5) / k as f32;
            match self.hit(size, sx, sy) {
                Some(p) => (sphere + 1, inside + u32::from(self.inside(highlight, p))),
                None => (sphere, inside),
            }
        })
    }

    /// The fraction of each pixel of a `size × size` image covered by the sphere (its
    /// silhouette) and by `highlight`, rows from the top. Each pixel is sampled `k × k` times
    /// (as [`Self::coverage`]); a pixel partly covered by either, or whose counts differ from a
    /// neighbour's, is sampled again `refined × refined` times, so that the boundary pixels,
    /// where the measures are decided, carry the finer estimate.
    pub fn mattes(
        &self,
        highlight: &impl SphereHighlight,
        size: u32,
        k: u32,
        refined: u32,
    ) -> Mattes {
        let count = |i: u32, k: u32| self.sample_counts(highlight, size, i, k);
        let coarse: Vec<(u32, u32)> = (0..size * size)
            .into_par_iter()
            .map(|i| count(i, k))
            .collect();
        let all = k.max(1) * k.max(1);
        let edge = |i: u32| {
            let (x, y) = (i % size, i / size);
            let own = coarse[i as usize];
            let partial = |(sphere, inside): (u32, u32)| {
                (0 < sphere && sphere < all) || (0 < inside && inside < all)
            };
            let neighbours = [
                (x > 0).then(|| i - 1),
                (x + 1 < size).then(|| i + 1),
                (y > 0).then(|| i - size),
                (y + 1 < size).then(|| i + size),
            ];
            partial(own)
                || neighbours
                    .into_iter()
                    .flatten()
                    .any(|n| coarse[n as usize] != own)
        };
        let fractions: Vec<(f32, f32)> = (0..size * size)
            .into_par_iter()
            .map(|i| {
                let (samples, (sphere, inside)) = if edge(i) {
                    (refined.max(1) * refined.max(1), count(i, refined))
                } else {
                    (all, coarse[i as usize])
                };
                (
                    sphere as f32 / samples as f32,
                    inside as f32 / samples as f32,
                )
            })
            .collect();
        let (silhouette, highlight) = fractions.into_iter().unzip();
        Mattes {
            silhouette,
            highlight,
        }
    }

    /// The angles, in degrees, between rendered normals (the normal AOV of a `size × size`
    /// frame with `k × k` samples per pixel, zero where nothing was drawn) and the sphere's
    /// normal at the hit of the ray through the sample the AOV comes from (sample
    /// `(⌊k/2⌋, ⌊k/2⌋)`): their largest and their mean. Pixels the sphere or the render leaves
    /// empty are skipped; `None` when none is left.
    pub fn normal_errors(&self, normals: &[Vec3], size: u32, k: u32) -> Option<NormalErrors> {
        let offset = ((k / 2) as f32 + 0.5) / k as f32;
        let (max, sum, count) = normals
            .par_iter()
            .enumerate()
            .filter_map(|(i, n)| {
                let n = n.as_dvec3().try_normalize()?;
                let (x, y) = ((i as u32 % size) as f32, (i as u32 / size) as f32);
                let truth = self.hit(size, x + offset, y + offset)?.normalize();
                Some(n.dot(truth).clamp(-1.0, 1.0).acos().to_degrees())
            })
            .fold(
                || (0.0f64, 0.0f64, 0usize),
                |(max, sum, count), angle| (max.max(angle), sum + angle, count + 1),
            )
            .reduce(
                || (0.0, 0.0, 0),
                |a, b| (a.0.max(b.0), a.1 + b.1, a.2 + b.2),
            );
        (count > 0).then(|| NormalErrors {
            max_degrees: max,
            mean_degrees: sum / count as f64,
        })
    }
}

/// Per pixel, the fraction of its area covered, rows from the top ([`AnalyticSphere::mattes`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Mattes {
    /// By the sphere: the reference for a frame's alpha.
    pub silhouette: Vec<f32>,
    /// By the highlight: the reference for the matte AOV.
    pub highlight: Vec<f32>,
}

/// How far rendered normals are from the sphere's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NormalErrors {
    pub max_degrees: f64,
    pub mean_degrees: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn central_ray_hits_the_front_pole_and_corner_rays_miss() {
        let sphere = AnalyticSphere::new(Projection::Orthographic { height: 2.4 });
        let p = sphere.hit(100, 50.0, 50.0).unwrap();
        assert!((p - DVec3::NEG_Y).length() < 1e-5, "{p}");
        assert!(sphere.hit(100, 0.5, 0.5).is_none());
        // 1/1.2 of the half height to the right: x = 1/1.2 · 1.2 = 1 is the rim.
        let rim = sphere.hit(1000, 500.0 + 500.0 / 1.2 - 1.0, 500.0).unwrap();
        assert!(rim.x > 0.99 && rim.y.abs() < 0.15, "{rim}");
    }

    #[test]
    fn the_refined_silhouette_has_the_disc_s_area() {
        // Orthographic, 2.4 units tall: the unit sphere is a disc of radius size / 2.4 pixels.
        let sphere = AnalyticSphere::new(Projection::Orthographic { height: 2.4 });
        let size = 64;
        let radius = f64::from(size) / 2.4;
        let expr = super::super::closed_form::ClosedForm::try_new(&crate::highlight::Expr::Layer(
            crate::highlight::Layer::new(vec![], 0.04, [1.0, 1.0, 1.0]),
        ))
        .unwrap();
        let mattes = sphere.mattes(&expr, size, 4, 32);
        let area: f64 = mattes.silhouette.iter().map(|&c| f64::from(c)).sum();
        let disc = std::f64::consts::PI * radius * radius;
        // 4 × 4 samples alone are off by up to a sixteenth of a pixel per boundary pixel.
        assert!((area - disc).abs() < 0.5, "{area} vs {disc}");
        let coarse: f64 = sphere
            .mattes(&expr, size, 4, 4)
            .silhouette
            .iter()
            .map(|&c| f64::from(c))
            .sum();
        assert!(
            (area - disc).abs() < (coarse - disc).abs(),
            "{area} {coarse} {disc}"
        );
        let highlight: f64 = mattes.highlight.iter().map(|&c| f64::from(c)).sum();
        assert!(highlight > 10.0 && highlight < area, "{highlight}");
        // Where no sample of a pixel or its neighbours is on an edge, both agree with 4 × 4.
        let k4 = sphere.coverage(&expr, size, 4);
        let centre = (size / 2 * size + size / 2) as usize;
        assert_eq!(mattes.silhouette[centre], 1.0);
        assert_eq!(mattes.silhouette[0], 0.0);
        assert_eq!(mattes.highlight[0], k4[0]);
    }
}
