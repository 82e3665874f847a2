//! The G-buffer: per pixel, the nearest surface's patch, (u, v), position and shading frame,
//! filled from the visibility buffer.

use glam::{DVec3, Mat4, Vec2, Vec3};
use rayon::prelude::*;

use super::camera::Camera;
use super::outline::EdgeSurface;
use super::raster::{interpolate, VisibilityBuffer};
use super::settings::FrameMode;
use super::tessellate::Mesh;
use crate::geom::{Frame, NurbsSurface, PatchLibrary};
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
#[derive(Clone, Debug, Default, PartialEq)]
pub struct GBuffer {
    pub width: u32,
    pub height: u32,
    /// Per pixel (rows from the top): its index in `texels`, or `EMPTY` (`u32::MAX`).
    pub slot: Vec<u32>,
    /// The covered pixels, in pixel order.
    pub texels: Vec<Texel>,
    /// Per texel, what the outline pass compares: filled when the frame draws outlines, empty
    /// otherwise.
    pub(crate) edge_surfaces: Vec<EdgeSurface>,
}

/// Items per parallel job in the per-pixel passes.
pub(crate) const PIXELS_PER_JOB: usize = 2048;

/// What a texel holds before it is filled.
const UNFILLED: Texel = Texel {
    pixel: 0,
    depth: 0.0,
    patch: 0,
    uv: Vec2::ZERO,
    position: Vec3::ZERO,
    frame: TangentFrame::new(Vec3::X, Vec3::Y, Vec3::Z),
};

/// What filling the texels of one block of pixels needs to know.
struct Fill<'a> {
    visibility: &'a VisibilityBuffer,
    mesh: &'a Mesh,
    library: &'a PatchLibrary,
    camera: &'a Camera,
    inverse_view_projection: Mat4,
    mode: FrameMode,
    /// Whether to fill the edge surfaces, and the line of sight `(eye, forward)` they are seen
    /// along.
    edges: Option<(Vec3, Vec3)>,
}

/// Per-job scratch for evaluating a run of frames on one patch.
#[derive(Default)]
struct FrameScratch {
    params: Vec<(f64, f64)>,
    frames: Vec<Frame>,
}

impl GBuffer {
    /// Fills the G-buffer from the visibility buffer of `mesh`, reusing its memory. Frames come
    /// from the mesh's vertex frames, or from the patch itself at the pixel's (u, v)
    /// ([`FrameMode::Exact`]), or at (u, v) moved so the surface point lies on the pixel's ray
    /// ([`FrameMode::Refined`]), the pixel's ray cast from `camera`. With `edges`, the edge
    /// surfaces are filled too, while each texel is at hand.
    /// Returns the number of frames evaluated on the patches.
    ///
    /// Blocks of pixels are filled in parallel: each block counts its covered pixels, and the
    /// running sum of the counts says where its texels start, so texels stay in pixel order.
    pub fn fill(
        &mut self,
        visibility: &VisibilityBuffer,
        mesh: &Mesh,
        library: &PatchLibrary,
        camera: &Camera,
        mode: FrameMode,
        edges: bool,
    ) -> u64 {
        (self.width, self.height) = (visibility.width, visibility.height);
        let counts: Vec<usize> = visibility
            .triangle
            .par_chunks(PIXELS_PER_JOB)
            .map(|block| block.iter().filter(|&&t| t != EMPTY).count())
            .collect();
        let covered = counts.iter().sum();
        self.texels.resize(covered, UNFILLED);
        self.edge_surfaces
            .resize(if edges { covered } else { 0 }, EdgeSurface::default());
        self.slot.resize(visibility.triangle.len(), EMPTY);
        let mut blocks = Vec::with_capacity(counts.len());
        let (mut rest, mut first) = (&mut self.texels[..], 0);
        let mut rest_edges = &mut self.edge_surfaces[..];
        for &count in &counts {
            let (texels, tail) = std::mem::take(&mut rest).split_at_mut(count);
            let (edges, edges_tail) =
                std::mem::take(&mut rest_edges).split_at_mut(if edges { count } else { 0 });
            blocks.push((first as u32, texels, edges));
            (rest, rest_edges, first) = (tail, edges_tail, first + count);
        }
        let aspect = visibility.width as f32 / visibility.height as f32;
        let fill = Fill {
            visibility,
            mesh,
            library,
            camera,
            inverse_view_projection: camera.view_projection(aspect).inverse(),
            mode,
            edges: edges.then(|| (camera.eye, camera.forward())),
        };
        blocks
            .into_par_iter()
            .zip(self.slot.par_chunks_mut(PIXELS_PER_JOB))
            .enumerate()
            .for_each_init(
                FrameScratch::default,
                |scratch, (block, ((first, texels, edges), slots))| {
                    fill.block(block * PIXELS_PER_JOB, first, texels, slots, scratch);
                    if let Some((eye, forward)) = fill.edges {
                        for (e, t) in edges.iter_mut().zip(texels.iter()) {
                            *e = EdgeSurface::of(t, eye, forward);
                        }
                    }
                },
            );
        match mode {
            FrameMode::Interpolated => 0,
            FrameMode::Exact | FrameMode::Refined => self.texels.len() as u64,
        }
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

impl Fill<'_> {
    /// Fills the slots of the pixels from `start` on and their texels, numbered from `first`.
    fn block(
        &self,
        start: usize,
        first: u32,
        texels: &mut [Texel],
        slots: &mut [u32],
        scratch: &mut FrameScratch,
    ) {
        let mut k = 0;
        for (i, slot) in (start..).zip(slots.iter_mut()) {
            let triangle = self.visibility.triangle[i];
            if triangle == EMPTY {
                *slot = EMPTY;
                continue;
            }
            *slot = first + k as u32;
            texels[k] = self.texel(i, triangle);
            k += 1;
        }
        if self.mode != FrameMode::Interpolated {
            self.exact_frames(texels, scratch);
        }
    }

    /// The texel of pixel `i`, covered by `triangle`: patch, (u, v) and position interpolated
    /// from the mesh, and with [`FrameMode::Interpolated`] the frame too.
    fn texel(&self, i: usize, triangle: u32) -> Texel {
        let mesh = self.mesh;
        let b = self.visibility.barycentric[i];
        let [i0, i1, i2] = mesh.triangles[triangle as usize].map(|k| k as usize);
        let position = interpolate(
            b,
            mesh.positions[i0],
            mesh.positions[i1],
            mesh.positions[i2],
        );
        let frame = match self.mode {
            FrameMode::Interpolated => facing_frame(
                interpolate(b, mesh.normals[i0], mesh.normals[i1], mesh.normals[i2]),
                interpolate(
                    b,
                    mesh.tangents_u[i0],
                    mesh.tangents_u[i1],
                    mesh.tangents_u[i2],
                ),
                self.camera.eye_direction(position),
            ),
            FrameMode::Exact | FrameMode::Refined => UNFILLED.frame,
        };
        Texel {
            pixel: i as u32,
            depth: self.visibility.depth[i],
            patch: mesh.triangle_patch[triangle as usize],
            uv: interpolate(b, mesh.uvs[i0], mesh.uvs[i1], mesh.uvs[i2]),
            position,
            frame,
        }
    }

    /// The frames of `texels` evaluated on their patches, a run of texels on one patch at a
    /// time; with [`FrameMode::Refined`], at (u, v) refined onto the pixel's ray, which also
    /// moves the texel's (u, v) and position there.
    fn exact_frames(&self, texels: &mut [Texel], scratch: &mut FrameScratch) {
        let refined = self.mode == FrameMode::Refined;
        for run in texels.chunk_by_mut(|a, b| a.patch == b.patch) {
            let surface = &self.library.patches[run[0].patch as usize].surface;
            scratch.params.clear();
            scratch.params.extend(run.iter().map(|t| {
                let uv = (f64::from(t.uv.x), f64::from(t.uv.y));
                if refined {
                    self.on_ray(surface, t.pixel, uv)
                } else {
                    uv
                }
            }));
            scratch.frames.resize(run.len(), NO_FRAME);
            surface.frames(&scratch.params, &mut scratch.frames);
            for ((t, f), &(u, v)) in run.iter_mut().zip(&scratch.frames).zip(&scratch.params) {
                if refined {
                    t.uv = Vec2::new(u as f32, v as f32);
                    t.position = f.point.as_vec3();
                }
                t.frame = facing_patch_frame(f, self.camera.eye_direction(t.position));
            }
        }
    }

    /// (u, v) near `start` whose surface point lies on the ray through the centre of pixel
    /// `pixel` ([`refine_on_ray`]).
    fn on_ray(&self, surface: &NurbsSurface, pixel: u32, start: (f64, f64)) -> (f64, f64) {
        let (width, height) = (self.visibility.width, self.visibility.height);
        let (x, y) = ((pixel % width) as f32 + 0.5, (pixel / width) as f32 + 0.5);
        let ndc = Vec2::new(2.0 * x / width as f32 - 1.0, 1.0 - 2.0 * y / height as f32);
        let unproject = |z: f32| {
            self.inverse_view_projection
                .project_point3(ndc.extend(z))
                .as_dvec3()
        };
        let (near, far) = (unproject(0.0), unproject(1.0));
        refine_on_ray(surface, start, near, far - near)
    }
}

/// A frame to fill scratch buffers with before evaluation overwrites it.
const NO_FRAME: Frame = Frame {
    point: DVec3::ZERO,
    normal: DVec3::Z,
    du: DVec3::X,
    dv: DVec3::Y,
    degenerate: false,
};

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
/// `du = normalize(a − (a·N) N)`; `dv = N × du`. `toward_eye` is V at any length (only its
/// direction counts). Degenerate input falls back to any frame around the viewer direction,
/// never NaN.
pub fn facing_frame(n: Vec3, along_u: Vec3, toward_eye: Vec3) -> TangentFrame {
    let Some((normal, inverse_squared)) = facing(n, toward_eye) else {
        let normal = unfacing_fallback(toward_eye);
        let du = normal.any_orthonormal_vector();
        return TangentFrame::new(du, normal.cross(du), normal);
    };
    // The projection uses `1/|n|²` and the normal `1/|n|`, so the two normalizations do not
    // wait for each other: `du ∝ a − (a·n) n / |n|²`.
    let du = (along_u - (along_u.dot(n) * inverse_squared) * n)
        .try_normalize()
        .unwrap_or_else(|| normal.any_orthonormal_vector());
    TangentFrame::new(du, normal.cross(du), normal)
}

/// An evaluated patch frame — orthonormal and right-handed, in f64 — in f32 and turned toward
/// the viewer: `(du, s dv, s N)` with `s = −1` where `N·V < 0`. This is [`facing_frame`] of it
/// without normalizing again; a frame whose axes are not unit to within 10⁻⁵ after rounding
/// goes through [`facing_frame`].
fn facing_patch_frame(f: &Frame, toward_eye: Vec3) -> TangentFrame {
    let (n, du, dv) = (f.normal.as_vec3(), f.du.as_vec3(), f.dv.as_vec3());
    let unit = |v: Vec3| (v.length_squared() - 1.0).abs() < 1e-5;
    if !(unit(n) && unit(du) && unit(dv)) {
        return facing_frame(n, du, toward_eye);
    }
    let s = if n.dot(toward_eye) < 0.0 { -1.0 } else { 1.0 };
    TangentFrame::new(du, dv * s, n * s)
}

/// The normal of [`facing_frame`] alone, for shading that needs no tangents.
pub(crate) fn facing_normal(n: Vec3, toward_eye: Vec3) -> Vec3 {
    facing(n, toward_eye).map_or_else(|| unfacing_fallback(toward_eye), |(normal, _)| normal)
}

/// `normalize(n)` turned toward the viewer, and `1/|n|²`; `None` when `n` is zero or not
/// finite.
#[inline]
fn facing(n: Vec3, toward_eye: Vec3) -> Option<(Vec3, f32)> {
    let length_squared = n.length_squared();
    if !(length_squared > f32::MIN_POSITIVE && length_squared.is_finite()) {
        return None;
    }
    let inverse_squared = length_squared.recip();
    let facing = if n.dot(toward_eye) < 0.0 { -1.0 } else { 1.0 };
    Some((n * (facing * inverse_squared.sqrt()), inverse_squared))
}

/// The normal where no normal is given: the viewer direction.
fn unfacing_fallback(toward_eye: Vec3) -> Vec3 {
    toward_eye.normalize_or(Vec3::Z)
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
    fn patch_frames_turn_like_facing_frames_without_normalizing_again() {
        let sphere = crate::geom::shapes::sphere(DVec3::new(0.5, 0.0, -1.0), 2.0).unwrap();
        let params: Vec<(f64, f64)> = (0..200)
            .map(|k| ((k as f64 * 0.618).fract(), (k as f64 * 0.371).fract()))
            .collect();
        let mut frames = vec![NO_FRAME; params.len()];
        sphere.frames(&params, &mut frames);
        let mut flipped = 0;
        for f in &frames {
            for eye in [Vec3::new(0.0, -9.0, 1.0), Vec3::new(3.0, 4.0, -2.0)] {
                let toward_eye = eye - f.point.as_vec3();
                let got = facing_patch_frame(f, toward_eye);
                let want = facing_frame(f.normal.as_vec3(), f.du.as_vec3(), toward_eye);
                for (a, b) in [(got.du, want.du), (got.dv, want.dv), (got.n, want.n)] {
                    assert!((a - b).length() < 1e-6, "{a} vs {b}");
                }
                flipped += usize::from(got.n.dot(f.normal.as_vec3()) < 0.0);
            }
        }
        assert!(flipped > 50, "{flipped}");
        // Not a unit frame: the general construction takes over, and gives no NaN.
        let broken = Frame {
            normal: DVec3::new(f64::NAN, 0.0, 0.0),
            ..NO_FRAME
        };
        let f = facing_patch_frame(&broken, Vec3::Z);
        assert!(f.n.is_finite() && f.du.is_finite() && f.dv.is_finite());
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
