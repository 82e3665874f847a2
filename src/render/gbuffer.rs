//! The G-buffer: per pixel, the nearest surface's patch, (u, v), position and shading frame,
//! filled from the visibility buffer.

use glam::{DVec3, Mat4, Vec2, Vec3};
use rayon::prelude::*;

use super::camera::Camera;
use super::raster::{interpolate, VisibilityBuffer};
use super::settings::FrameMode;
use super::tessellate::Mesh;
use crate::geom::{NurbsSurface, PatchLibrary};
use crate::highlight::TangentFrame;

/// The slot of a pixel no surface covers.
pub const EMPTY: u32 = u32::MAX;

/// One covered pixel of the G-buffer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Texel {
    /// The pixel's index, `y · width + x`.
    pub pixel: u32,
    /// NDC depth in [0, 1].
    pub depth: f32,
    /// Patch index in the library.
    pub patch: u32,
    /// Perspective-correct patch parameters.
    pub uv: Vec2,
    /// World position.
    pub position: Vec3,
    /// The shading frame, turned to face the viewer (two-sided surfaces).
    pub frame: TangentFrame,
}

/// The covered pixels of an image; work per pixel is done for these only.
#[derive(Clone, Debug, PartialEq)]
pub struct GBuffer {
    pub width: u32,
    pub height: u32,
    /// Per pixel (rows from the top): its index in `texels`, or [`EMPTY`].
    pub slot: Vec<u32>,
    /// The covered pixels, in pixel order.
    pub texels: Vec<Texel>,
}

/// Items per parallel job in the per-pixel passes.
pub(crate) const PIXELS_PER_JOB: usize = 2048;

impl GBuffer {
    /// Fills the G-buffer from the visibility buffer of `mesh`. Frames come from the mesh's
    /// vertex frames, or from the patch itself at the pixel's (u, v) ([`FrameMode::Exact`]), or
    /// at (u, v) moved so the surface point lies on the pixel's ray ([`FrameMode::Refined`]).
    /// `inverse_view_projection` maps NDC back to the world, for the pixel rays. Returns the
    /// buffer and the number of frames evaluated on the patches.
    pub fn fill(
        visibility: &VisibilityBuffer,
        mesh: &Mesh,
        library: &PatchLibrary,
        camera: &Camera,
        inverse_view_projection: Mat4,
        mode: FrameMode,
    ) -> (Self, u64) {
        let (width, height) = (visibility.width, visibility.height);
        let covered: Vec<u32> = (0..visibility.triangle.len() as u32)
            .into_par_iter()
            .with_min_len(PIXELS_PER_JOB)
            .filter(|&i| visibility.triangle[i as usize] != u32::MAX)
            .collect();
        let texels: Vec<Texel> = covered
            .par_iter()
            .with_min_len(PIXELS_PER_JOB)
            .map(|&pixel| {
                let i = pixel as usize;
                let triangle = visibility.triangle[i];
                let b = visibility.barycentric[i];
                let [i0, i1, i2] = mesh.triangles[triangle as usize].map(|k| k as usize);
                let patch = mesh.triangle_patch[triangle as usize];
                let mut uv = interpolate(b, mesh.uvs[i0], mesh.uvs[i1], mesh.uvs[i2]);
                let mut position = interpolate(
                    b,
                    mesh.positions[i0],
                    mesh.positions[i1],
                    mesh.positions[i2],
                );
                let surface = &library.patches[patch as usize].surface;
                let (normal, along_u) = match mode {
                    FrameMode::Interpolated => (
                        interpolate(b, mesh.normals[i0], mesh.normals[i1], mesh.normals[i2]),
                        interpolate(
                            b,
                            mesh.tangents_u[i0],
                            mesh.tangents_u[i1],
                            mesh.tangents_u[i2],
                        ),
                    ),
                    FrameMode::Exact => {
                        let f = surface.frame(f64::from(uv.x), f64::from(uv.y));
                        (f.normal.as_vec3(), f.du.as_vec3())
                    }
                    FrameMode::Refined => {
                        let (x, y) = (
                            (i as u32 % width) as f32 + 0.5,
                            (i as u32 / width) as f32 + 0.5,
                        );
                        let ndc =
                            Vec2::new(2.0 * x / width as f32 - 1.0, 1.0 - 2.0 * y / height as f32);
                        let near = inverse_view_projection
                            .project_point3(ndc.extend(0.0))
                            .as_dvec3();
                        let far = inverse_view_projection
                            .project_point3(ndc.extend(1.0))
                            .as_dvec3();
                        let (u, v) = refine_on_ray(
                            surface,
                            (f64::from(uv.x), f64::from(uv.y)),
                            near,
                            far - near,
                        );
                        let f = surface.frame(u, v);
                        uv = Vec2::new(u as f32, v as f32);
                        position = f.point.as_vec3();
                        (f.normal.as_vec3(), f.du.as_vec3())
                    }
                };
                let toward_eye = camera.toward_eye(position);
                Texel {
                    pixel,
                    depth: visibility.depth[i],
                    patch,
                    uv,
                    position,
                    frame: facing_frame(normal, along_u, toward_eye),
                }
            })
            .collect();
        let evaluated = match mode {
            FrameMode::Interpolated => 0,
            FrameMode::Exact | FrameMode::Refined => texels.len() as u64,
        };
        let mut slot = vec![EMPTY; visibility.triangle.len()];
        for (k, t) in texels.iter().enumerate() {
            slot[t.pixel as usize] = k as u32;
        }
        (
            Self {
                width,
                height,
                slot,
                texels,
            },
            evaluated,
        )
    }

    /// A full image from one value per texel: `values[k]` at texel k's pixel, `background`
    /// elsewhere.
    pub fn gather<T: Copy + Send + Sync>(&self, values: &[T], background: T) -> Vec<T> {
        self.slot
            .par_iter()
            .with_min_len(PIXELS_PER_JOB)
            .map(|&slot| {
                if slot == EMPTY {
                    background
                } else {
                    values[slot as usize]
                }
            })
            .collect()
    }

    /// The texel at pixel index `pixel`, if a surface covers it.
    pub fn texel(&self, pixel: usize) -> Option<&Texel> {
        let slot = self.slot[pixel];
        (slot != EMPTY).then(|| &self.texels[slot as usize])
    }

    /// The texel at (x, y), if a surface covers it.
    pub fn at(&self, x: u32, y: u32) -> Option<&Texel> {
        self.texel((y * self.width + x) as usize)
    }
}

/// Newton steps moving `(u, v)` until `S(u, v)` lies on the ray `origin + t direction`.
///
/// With `e1, e2` orthonormal and across the ray, the residual `f = ((S − o)·e1, (S − o)·e2)` has
/// the Jacobian `J = [[Su·e1, Sv·e1], [Su·e2, Sv·e2]]`; each step solves `J Δ = f` and sets
/// `(u, v) −= Δ`, clamped to the domain. Stops when the step is below 1e-12; gives up (returning
/// the start) when J is singular, a step is longer than a tenth of the domain, or
/// [`REFINE_STEPS`] steps did not converge.
pub fn refine_on_ray(
    surface: &NurbsSurface,
    start: (f64, f64),
    origin: DVec3,
    direction: DVec3,
) -> (f64, f64) {
    let domain = surface.domain();
    let Some(d) = direction.try_normalize() else {
        return start;
    };
    let (e1, e2) = d.any_orthonormal_pair();
    let reach = 0.1 * (domain.u.1 - domain.u.0).max(domain.v.1 - domain.v.0);
    let (mut u, mut v) = start;
    for _ in 0..REFINE_STEPS {
        let s = surface.derivs(u, v, 1);
        let r = s.point - origin;
        let (f1, f2) = (r.dot(e1), r.dot(e2));
        let (a, b, c, e) = (s.su.dot(e1), s.sv.dot(e1), s.su.dot(e2), s.sv.dot(e2));
        let det = a * e - b * c;
        if det.abs() <= 1e-300 || !det.is_finite() {
            return start;
        }
        let (step_u, step_v) = ((e * f1 - b * f2) / det, (a * f2 - c * f1) / det);
        let length = step_u.abs() + step_v.abs();
        if length > reach || !length.is_finite() {
            return start;
        }
        u = (u - step_u).clamp(domain.u.0, domain.u.1);
        v = (v - step_v).clamp(domain.v.0, domain.v.1);
        if step_u.abs() + step_v.abs() < 1e-12 {
            return (u, v);
        }
    }
    (u, v)
}

/// The most Newton steps [`refine_on_ray`] takes; from a tessellated start it converges in two
/// or three.
pub const REFINE_STEPS: usize = 4;

/// An orthonormal frame from a normal and a direction along u, turned toward the viewer:
/// `N = normalize(n)`, flipped when `N·V < 0` (the back of a two-sided surface);
/// `du = normalize(a − (a·N) N)`; `dv = N × du`. Degenerate input falls back to any frame
/// around the viewer direction, never NaN.
pub fn facing_frame(n: Vec3, along_u: Vec3, toward_eye: Vec3) -> TangentFrame {
    let length_squared = n.length_squared();
    if !(length_squared > f32::MIN_POSITIVE && length_squared.is_finite()) {
        let normal = toward_eye.normalize_or(Vec3::Z);
        let du = normal.any_orthonormal_vector();
        return TangentFrame::new(du, normal.cross(du), normal);
    }
    // The projection uses `1/|n|²` and the normal `1/|n|`, so the two normalizations do not
    // wait for each other: `du ∝ a − (a·n) n / |n|²`.
    let inverse_squared = length_squared.recip();
    let facing = if n.dot(toward_eye) < 0.0 { -1.0 } else { 1.0 };
    let normal = n * (facing * inverse_squared.sqrt());
    let du = (along_u - (along_u.dot(n) * inverse_squared) * n)
        .try_normalize()
        .unwrap_or_else(|| normal.any_orthonormal_vector());
    TangentFrame::new(du, normal.cross(du), normal)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refinement_puts_the_surface_point_on_the_ray() {
        let sphere = crate::geom::shapes::sphere(DVec3::ZERO, 1.0).unwrap();
        let target = sphere.point(0.3, 0.6);
        let origin = DVec3::new(0.2, -4.0, 0.7);
        let (u, v) = refine_on_ray(&sphere, (0.31, 0.59), origin, target - origin);
        assert!(
            (u - 0.3).abs() < 1e-10 && (v - 0.6).abs() < 1e-10,
            "({u}, {v})"
        );
        // A ray that misses the surface nearby: the start is kept.
        let start = (0.31, 0.59);
        assert_eq!(
            refine_on_ray(&sphere, start, origin, DVec3::new(0.0, 0.0, 1.0)),
            start
        );
    }

    #[test]
    fn facing_frame_is_orthonormal_and_faces_the_viewer() {
        let f = facing_frame(Vec3::new(0.0, 0.0, -2.0), Vec3::new(1.0, 0.0, 0.3), Vec3::Z);
        assert_eq!(f.n, Vec3::Z);
        assert!((f.du - Vec3::X).length() < 1e-6);
        assert!((f.du.cross(f.dv) - f.n).length() < 1e-6);
        let g = facing_frame(Vec3::ZERO, Vec3::ZERO, Vec3::Y);
        assert!(g.n.is_finite() && g.du.is_finite() && (g.du.dot(g.n)).abs() < 1e-6);
    }
}
