//! The G-buffer: per pixel, the nearest surface's patch, (u, v), position and shading frame,
//! filled from the visibility buffer.

use glam::{DVec3, Mat4, Vec2, Vec3};
use rayon::prelude::*;

use super::camera::Camera;
use super::facing::{faces_away, facing_frame, facing_patch_frame, NO_FRAME};
use super::raster::{interpolate, VisibilityBuffer};
use super::settings::FrameMode;
use super::tessellate::Mesh;
use crate::geom::{Frame, NurbsSurface, PatchLibrary, RaySearch, ALL_EVALUATIONS};
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
    /// Whether `frame` was turned: the eye sees the back of the surface here, its own normal
    /// facing away. A probe started from the texel looks for that side of the surface
    /// ([`Frames::front_sheet`]); where a pixel's neighbourhood shows both sides of a patch
    /// (it folds over there), the probes started about it are cleared of it. False while
    /// `frame` holds the mesh's normal unturned.
    pub back: bool,
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
}

/// Items per parallel job in the per-pixel passes.
pub(crate) const PIXELS_PER_JOB: usize = 2048;

/// What a texel holds before it is filled.
pub(super) const UNFILLED: Texel = Texel {
    pixel: 0,
    depth: 0.0,
    patch: 0,
    uv: Vec2::ZERO,
    position: Vec3::ZERO,
    frame: TangentFrame::new(Vec3::X, Vec3::Y, Vec3::Z),
    back: false,
};

/// How much of its frame a sample needs, when frames are evaluated on the patches
/// ([`FrameMode::Exact`] or [`FrameMode::Refined`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Evaluate {
    /// The frame in full: evaluated on the patch, refined onto the ray with every step needed.
    #[default]
    Full,
    /// Whether the ray meets the surface near the mesh's (u, v): refined within
    /// [`PROBE_EVALUATIONS`], so that a ray passing beside the surface costs little.
    Probe,
    /// A [`Evaluate::Probe`] that also gives up at the first Newton step that does not halve
    /// its distance from the ray and leaves it more than [`STALL_PIXELS`] away
    /// ([`RaySearch::stall_beyond`]): for a sample that other starts may still reach.
    QuickProbe,
    /// Only where the surface is: the mesh's interpolated frame, as [`FrameMode::Interpolated`]
    /// gives it (for samples whose depth and normal matter, not their shading).
    Mesh,
}

/// How far from its ray, in pixels of the image probed, a [`Evaluate::QuickProbe`] may stall
/// and still go on: a ray that grazes the sphere at its outline beside a pole may stall
/// farther than a pixel or two and still land (with one or two, the sphere's outline pixel
/// beside a pole lost two of its 16 samples); eight lose none there, and save a third less.
pub const STALL_PIXELS: f64 = 4.0;

/// Surface evaluations a [`Evaluate::Probe`] spends at most: from a start within a sample of
/// the ray, Newton's steps land on it in two or three.
pub const PROBE_EVALUATIONS: u32 = 5;

/// What filling the texels of one block of pixels needs to know.
struct Fill<'a> {
    visibility: &'a VisibilityBuffer,
    mesh: &'a Mesh,
    frames: Frames<'a>,
    /// Per pixel, how much of its frame to evaluate (`None`: all of every frame).
    evaluate: Option<&'a [Evaluate]>,
    /// An earlier fill whose texels are kept where they are the same.
    earlier: Option<Earlier<'a>>,
}

/// An earlier fill of a G-buffer of the same size, camera and frame mode, from `visibility`,
/// whose texels on the patches `patches` marks (one flag per patch) are kept where the
/// visibility is the same: those patches' mesh (grids, vertices and their frames) and surfaces
/// being the ones it was filled from, a texel is a function of its pixel's visibility alone.
#[derive(Clone, Copy)]
pub(super) struct Earlier<'a> {
    pub visibility: &'a VisibilityBuffer,
    pub gbuffer: &'a GBuffer,
    pub patches: &'a [bool],
}

/// What evaluating texels' frames on their patches needs to know: the texels' `pixel` indices
/// are those of a `size` image seen through the view-projection inverted here.
struct Frames<'a> {
    library: &'a PatchLibrary,
    camera: &'a Camera,
    inverse_view_projection: Mat4,
    size: (u32, u32),
    mode: FrameMode,
}

/// Per-job scratch for evaluating a run of frames on one patch.
#[derive(Default)]
struct FrameScratch {
    /// Per pixel of the block being filled, whether its texel was kept from the earlier fill.
    kept: Vec<bool>,
    starts: Vec<(f64, f64)>,
    searches: Vec<RaySearch>,
    params: Vec<(f64, f64)>,
    frames: Vec<Frame>,
}

impl GBuffer {
    /// Fills the G-buffer from the visibility buffer of `mesh`, reusing its memory. Frames come
    /// from the mesh's vertex frames, or from the patch itself at the pixel's (u, v)
    /// ([`FrameMode::Exact`]), or at (u, v) moved so the surface point lies on the pixel's ray
    /// ([`FrameMode::Refined`]), the pixel's ray cast through `view_projection` (the camera's,
    /// or a window of it: [`Window`](super::antialias::window::Window)).
    /// `evaluate`, one per pixel, says how much of each frame to evaluate (`None`: all).
    /// Returns the number of frames evaluated on the patches.
    ///
    /// Blocks of pixels are filled in parallel: each block counts its covered pixels, and the
    /// running sum of the counts says where its texels start, so texels stay in pixel order.
    #[allow(clippy::too_many_arguments)]
    pub fn fill(
        &mut self,
        visibility: &VisibilityBuffer,
        mesh: &Mesh,
        library: &PatchLibrary,
        camera: &Camera,
        view_projection: Mat4,
        mode: FrameMode,
        evaluate: Option<&[Evaluate]>,
    ) -> u64 {
        let surfaces = (visibility, mesh, library);
        self.fill_keeping(surfaces, camera, view_projection, mode, evaluate, None)
            .0
    }

    /// [`GBuffer::fill`], keeping the texels of `earlier` where its visibility is bit for bit
    /// this one's on a patch it marks: the texel is the one a fill would make, not made again.
    /// Returns the frames evaluated on the patches and the texels kept.
    pub(super) fn fill_keeping(
        &mut self,
        (visibility, mesh, library): (&VisibilityBuffer, &Mesh, &PatchLibrary),
        camera: &Camera,
        view_projection: Mat4,
        mode: FrameMode,
        evaluate: Option<&[Evaluate]>,
        earlier: Option<Earlier>,
    ) -> (u64, u64) {
        let earlier = earlier.filter(|e| {
            e.visibility.triangle.len() == visibility.triangle.len()
                && e.gbuffer.slot.len() == visibility.triangle.len()
                && e.patches.len() == mesh.grids.len()
        });
        (self.width, self.height) = (visibility.width, visibility.height);
        let counts: Vec<usize> = visibility
            .triangle
            .par_chunks(PIXELS_PER_JOB)
            .map(|block| block.iter().filter(|&&t| t != EMPTY).count())
            .collect();
        let covered = counts.iter().sum();
        self.texels.resize(covered, UNFILLED);
        self.slot.resize(visibility.triangle.len(), EMPTY);
        let mut blocks = Vec::with_capacity(counts.len());
        let (mut rest, mut first) = (&mut self.texels[..], 0);
        for &count in &counts {
            let (texels, tail) = std::mem::take(&mut rest).split_at_mut(count);
            blocks.push((first as u32, texels));
            (rest, first) = (tail, first + count);
        }
        let fill = Fill {
            visibility,
            mesh,
            frames: Frames {
                library,
                camera,
                inverse_view_projection: view_projection.inverse(),
                size: (visibility.width, visibility.height),
                mode,
            },
            evaluate,
            earlier,
        };
        let kept: u64 = blocks
            .into_par_iter()
            .zip(self.slot.par_chunks_mut(PIXELS_PER_JOB))
            .enumerate()
            .map_init(
                FrameScratch::default,
                |scratch, (block, ((first, texels), slots))| {
                    fill.block(block * PIXELS_PER_JOB, first, texels, slots, scratch)
                },
            )
            .sum();
        let frames = match (mode, evaluate) {
            (FrameMode::Interpolated, _) => 0,
            (FrameMode::Exact | FrameMode::Refined, None) => self.texels.len() as u64 - kept,
            (FrameMode::Exact | FrameMode::Refined, Some(evaluate)) => {
                self.texels
                    .iter()
                    .filter(|t| evaluate[t.pixel as usize] != Evaluate::Mesh)
                    .filter(|t| fill.kept(t.pixel as usize).is_none())
                    .count() as u64
            }
        };
        (frames, kept)
    }

    /// The frames of `texels` in `mode`, as [`fill`](Self::fill) evaluates them: with
    /// [`FrameMode::Refined`] each texel is moved onto its pixel's ray and takes the frame
    /// there — each holds its patch, the (u, v) to start from, a normal facing the eye (in
    /// `frame.n`: where the refined point faces away, the near crossing is looked for, unless
    /// [`Texel::back`] says the start is on the back of the surface) and its
    /// `pixel` index in a `size` image seen through `view_projection`, and each search spends
    /// what `evaluate` allows; with [`FrameMode::Exact`] the frame on the patch at each texel's
    /// (u, v); with [`FrameMode::Interpolated`] they stay as they are. Texels on one patch are
    /// best kept together. Returns the frames evaluated.
    pub(super) fn evaluate_frames(
        texels: &mut [Texel],
        library: &PatchLibrary,
        camera: &Camera,
        view_projection: Mat4,
        size: (u32, u32),
        mode: FrameMode,
        evaluate: Evaluate,
    ) -> u64 {
        if mode == FrameMode::Interpolated {
            return 0;
        }
        let frames = Frames {
            library,
            camera,
            inverse_view_projection: view_projection.inverse(),
            size,
            mode,
        };
        texels.par_chunks_mut(PIXELS_PER_JOB).for_each_init(
            FrameScratch::default,
            |scratch, chunk| {
                frames.exact_frames(chunk, &|_| evaluate, &|_| false, scratch);
            },
        );
        match evaluate {
            Evaluate::Mesh => 0,
            Evaluate::Full | Evaluate::Probe | Evaluate::QuickProbe => texels.len() as u64,
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

    /// Keeps the texels `keep` marks (one flag per texel) and empties the pixels of the
    /// others; texels stay in pixel order.
    pub(super) fn retain(&mut self, keep: &[bool]) {
        let mut kept = 0;
        for (k, &keep) in keep.iter().enumerate().take(self.texels.len()) {
            let t = self.texels[k];
            if keep {
                self.texels[kept] = t;
                self.slot[t.pixel as usize] = kept as u32;
                kept += 1;
            } else {
                self.slot[t.pixel as usize] = EMPTY;
            }
        }
        self.texels.truncate(kept);
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
    /// Fills the slots of the pixels from `start` on and their texels, numbered from `first`;
    /// returns how many texels were kept from the earlier fill ([`Fill::kept`], asked once a
    /// pixel).
    fn block(
        &self,
        start: usize,
        first: u32,
        texels: &mut [Texel],
        slots: &mut [u32],
        scratch: &mut FrameScratch,
    ) -> u64 {
        let mut kept = std::mem::take(&mut scratch.kept);
        kept.clear();
        kept.resize(slots.len(), false);
        let mut k = 0;
        for ((i, slot), kept) in (start..).zip(slots.iter_mut()).zip(&mut kept) {
            let triangle = self.visibility.triangle[i];
            if triangle == EMPTY {
                *slot = EMPTY;
                continue;
            }
            *slot = first + k as u32;
            texels[k] = match self.kept(i) {
                Some(texel) => {
                    *kept = true;
                    texel
                }
                None => self.texel(i, triangle),
            };
            k += 1;
        }
        if self.frames.mode != FrameMode::Interpolated {
            let evaluate = |t: &Texel| {
                self.evaluate
                    .map_or(Evaluate::Full, |e| e[t.pixel as usize])
            };
            let was_kept = |t: &Texel| kept[t.pixel as usize - start];
            self.frames
                .exact_frames(texels, &evaluate, &was_kept, scratch);
        }
        let count = kept.iter().filter(|&&k| k).count() as u64;
        scratch.kept = kept;
        count
    }

    /// The earlier fill's texel of pixel `i`, where it is kept: the pixel's triangle is on a
    /// patch the earlier fill marks, and its triangle, depth and barycentrics are bit for bit
    /// those the earlier fill saw.
    fn kept(&self, i: usize) -> Option<Texel> {
        let earlier = self.earlier.as_ref()?;
        let triangle = self.visibility.triangle[i];
        let patch = *self.mesh.triangle_patch.get(triangle as usize)?;
        let was = earlier.visibility;
        let same = earlier.patches[patch as usize]
            && was.triangle[i] == triangle
            && was.depth[i].to_bits() == self.visibility.depth[i].to_bits()
            && was.barycentric[i].map(f32::to_bits)
                == self.visibility.barycentric[i].map(f32::to_bits);
        if !same {
            return None;
        }
        earlier.gbuffer.texel(i).copied()
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
        let evaluate = self.evaluate.map_or(Evaluate::Full, |e| e[i]);
        let mode = match (self.frames.mode, evaluate) {
            (_, Evaluate::Mesh) => FrameMode::Interpolated,
            (mode, Evaluate::Full | Evaluate::Probe | Evaluate::QuickProbe) => mode,
        };
        let normal = || interpolate(b, mesh.normals[i0], mesh.normals[i1], mesh.normals[i2]);
        let (frame, back) = match mode {
            // The mesh's normal, kept until the exact frame replaces it: refined frames compare
            // the side of the surface they land on with the side the mesh shows.
            FrameMode::Refined => (TangentFrame::new(Vec3::X, Vec3::Y, normal()), false),
            FrameMode::Interpolated => {
                let (n, toward_eye) = (normal(), self.frames.camera.eye_direction(position));
                let along_u = interpolate(
                    b,
                    mesh.tangents_u[i0],
                    mesh.tangents_u[i1],
                    mesh.tangents_u[i2],
                );
                (
                    facing_frame(n, along_u, toward_eye),
                    faces_away(n, toward_eye),
                )
            }
            FrameMode::Exact => (UNFILLED.frame, false),
        };
        Texel {
            pixel: i as u32,
            depth: self.visibility.depth[i],
            patch: mesh.triangle_patch[triangle as usize],
            uv: interpolate(b, mesh.uvs[i0], mesh.uvs[i1], mesh.uvs[i2]),
            position,
            frame,
            back,
        }
    }
}

impl Frames<'_> {
    /// The frames of `texels` evaluated on their patches, a run of texels on one patch at a
    /// time; with [`FrameMode::Refined`], at (u, v) refined onto the pixel's ray, which also
    /// moves the texel's (u, v) and position there; `evaluate` says how much of each.
    fn exact_frames(
        &self,
        texels: &mut [Texel],
        evaluate: &dyn Fn(&Texel) -> Evaluate,
        kept: &dyn Fn(&Texel) -> bool,
        scratch: &mut FrameScratch,
    ) {
        let refined = self.mode == FrameMode::Refined;
        let skipped = |t: &Texel| evaluate(t) == Evaluate::Mesh || kept(t);
        let runs = texels.chunk_by_mut(|a, b| a.patch == b.patch && skipped(a) == skipped(b));
        for run in runs {
            if skipped(&run[0]) {
                continue;
            }
            let surface = &self.library.patches[run[0].patch as usize].surface;
            scratch.params.resize(run.len(), (0.0, 0.0));
            scratch.frames.resize(run.len(), NO_FRAME);
            let start = |t: &Texel| (f64::from(t.uv.x), f64::from(t.uv.y));
            if refined {
                scratch.searches.clear();
                scratch.searches.extend(run.iter().map(|t| {
                    let (origin, direction) = self.ray(t.pixel);
                    let (evaluations, stall_beyond) = match evaluate(t) {
                        Evaluate::Probe => (PROBE_EVALUATIONS, f64::INFINITY),
                        Evaluate::QuickProbe => {
                            let across = self.across_pixel(t.pixel, (origin, direction));
                            let pixel = across(t.position.as_dvec3());
                            (PROBE_EVALUATIONS, STALL_PIXELS * pixel)
                        }
                        Evaluate::Full | Evaluate::Mesh => (ALL_EVALUATIONS, f64::INFINITY),
                    };
                    RaySearch {
                        start: start(t),
                        origin,
                        direction,
                        evaluations,
                        stall_beyond,
                    }
                }));
                surface.frames_on_rays(&scratch.searches, &mut scratch.params, &mut scratch.frames);
            } else {
                scratch.starts.clear();
                scratch.starts.extend(run.iter().map(start));
                scratch.params.copy_from_slice(&scratch.starts);
                surface.frames(&scratch.params, &mut scratch.frames);
            }
            let searches = scratch
                .searches
                .iter()
                .map(Some)
                .chain(std::iter::repeat(None));
            for (((t, f), &(u, v)), search) in run
                .iter_mut()
                .zip(&scratch.frames)
                .zip(&scratch.params)
                .zip(searches)
            {
                let (mut f, mut uv) = (*f, (u, v));
                // A probe that found no point on its ray has its answer: the ray misses.
                let missed = || {
                    matches!(evaluate(t), Evaluate::Probe | Evaluate::QuickProbe)
                        && search.is_some_and(|s| !on_ray(f.point, s.origin, s.direction))
                };
                if refined && !missed() {
                    if let Some((front, at)) = self.front_sheet(surface, t, &f, uv) {
                        (f, uv) = (front, at);
                    }
                    t.uv = Vec2::new(uv.0 as f32, uv.1 as f32);
                    t.position = f.point.as_vec3();
                }
                let toward_eye = self.camera.eye_direction(t.position);
                t.frame = facing_patch_frame(&f, toward_eye);
                t.back = faces_away(f.normal.as_vec3(), toward_eye);
            }
        }
    }

    /// The width of pixel `pixel` (whose ray is `ray`) about a point: the distance from the
    /// ray to the next pixel's ray (the previous one's in the last column) at the point's
    /// distance along it, `|Δo + ((p − o)·d̂) Δd̂|` with `Δ` the change from one ray to the
    /// other and `d̂` the unit direction.
    fn across_pixel(&self, pixel: u32, ray: (DVec3, DVec3)) -> impl Fn(DVec3) -> f64 {
        let width = self.size.0;
        let next = if pixel % width + 1 < width {
            pixel + 1
        } else {
            pixel.saturating_sub(1)
        };
        let (origin, direction) = ray;
        let (o2, d2) = self.ray(next);
        let d = direction.normalize_or_zero();
        let (delta_o, delta_d) = (o2 - origin, d2.normalize_or_zero() - d);
        move |p: DVec3| (delta_o + (p - origin).dot(d) * delta_d).length()
    }

    /// The pixel's ray through its centre, `(origin, direction)` from the near plane to the far.
    fn ray(&self, pixel: u32) -> (DVec3, DVec3) {
        let (width, height) = self.size;
        let (x, y) = ((pixel % width) as f32 + 0.5, (pixel / width) as f32 + 0.5);
        let ndc = Vec2::new(2.0 * x / width as f32 - 1.0, 1.0 - 2.0 * y / height as f32);
        let unproject = |z: f32| {
            self.inverse_view_projection
                .project_point3(ndc.extend(z))
                .as_dvec3()
        };
        let (near, far) = (unproject(0.0), unproject(1.0));
        (near, far - near)
    }

    /// Where a ray grazes a surface it crosses it twice, close together, and the mesh point
    /// lies between the crossings; Newton steps from it may land on the far one. When the
    /// refined frame `f` at `refined` faces away from the eye while the start `t` (still
    /// holding its (u, v) and position: a texel of the mesh with its normal, or a probe with
    /// the frame of the texel it started from) faces it, this refines again from the start
    /// mirrored through its (u, v), `2 start − refined`, and returns that frame and (u, v) if
    /// it faces the eye and lies nearer along the ray. `None` keeps `f`.
    ///
    /// A probe from a texel whose frame was turned ([`Texel::back`]) starts on the back of the
    /// surface: landing on a side that faces away is what it looks for, not a sign that it
    /// crossed to a far sheet, and it is not refined again.
    fn front_sheet(
        &self,
        surface: &NurbsSurface,
        t: &Texel,
        f: &Frame,
        refined: (f64, f64),
    ) -> Option<(Frame, (f64, f64))> {
        let eye = self.camera.eye.as_dvec3();
        let mesh_faces = !t.back && t.frame.n.dot(self.camera.eye_direction(t.position)) > 0.0;
        if !mesh_faces || f.normal.dot(eye - f.point) >= 0.0 {
            return None;
        }
        let start = (f64::from(t.uv.x), f64::from(t.uv.y));
        let mirrored = (2.0 * start.0 - refined.0, 2.0 * start.1 - refined.1);
        let domain = surface.domain();
        let mirrored = (
            mirrored.0.clamp(domain.u.0, domain.u.1),
            mirrored.1.clamp(domain.v.0, domain.v.1),
        );
        let (origin, direction) = self.ray(t.pixel);
        let at = surface.try_refine_on_ray(mirrored, origin, direction)?;
        let front = surface.frame(at.0, at.1);
        let d = direction.normalize();
        let nearer = (front.point - origin).dot(d) < (f.point - origin).dot(d);
        (front.normal.dot(eye - front.point) > 0.0 && nearer && on_ray(front.point, origin, d))
            .then_some((front, at))
    }
}

/// Whether `point` lies on the ray from `origin` along `direction`, within 10⁻⁶ of its distance
/// from the origin.
fn on_ray(point: DVec3, origin: DVec3, direction: DVec3) -> bool {
    let r = point - origin;
    r.reject_from(direction).length() <= 1e-6 * r.length()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::fixtures::{self, ball_library, mesh_in_view};
    use crate::render::raster::{RasterOptions, Rasterizer, Viewport};

    #[test]
    fn each_sample_gets_the_frame_its_evaluation_asks_for() {
        let library = ball_library();
        let camera = Camera {
            eye: Vec3::new(0.3, -5.0, 0.8),
            ..fixtures::camera()
        };
        let (width, height) = (64, 64);
        let (mesh, view_projection, clip) = mesh_in_view(&library, &camera, (width, height), 0.5);
        let mesh = &mesh;
        let mut visibility = VisibilityBuffer::default();
        Rasterizer::default().rasterize_into(
            Viewport { width, height },
            &clip,
            &mesh.triangles,
            &RasterOptions::default(),
            &mut visibility,
        );
        let fill = |mode, evaluate: Option<&[Evaluate]>| {
            let mut g = GBuffer::default();
            let frames = g.fill(
                &visibility,
                mesh,
                &library,
                &camera,
                view_projection,
                mode,
                evaluate,
            );
            (g, frames)
        };
        let (mesh_frames, none) = fill(FrameMode::Interpolated, None);
        let (full, all) = fill(FrameMode::Refined, None);
        assert_eq!(none, 0);
        assert_eq!(all, full.texels.len() as u64);
        // Each of the four ways, a pixel in four.
        let evaluate: Vec<Evaluate> = (0..width * height)
            .map(|i| {
                [
                    Evaluate::Full,
                    Evaluate::Probe,
                    Evaluate::Mesh,
                    Evaluate::QuickProbe,
                ][i as usize % 4]
            })
            .collect();
        let (mixed, frames) = fill(FrameMode::Refined, Some(&evaluate));
        let (mut counted, mut probes, mut agreed) = (0, 0, 0);
        for ((m, f), i) in mixed
            .texels
            .iter()
            .zip(&full.texels)
            .zip(&mesh_frames.texels)
        {
            assert_eq!(m.pixel, f.pixel);
            match evaluate[m.pixel as usize] {
                Evaluate::Full => assert_eq!(m, f),
                // From a mesh within half a pixel of the surface, a probe lands where the full
                // search does, or (where the ray grazes the sphere) gives up off the ray.
                Evaluate::Probe | Evaluate::QuickProbe => {
                    let (origin, direction) = camera.ray_through(
                        (
                            f64::from(m.pixel % width) + 0.5,
                            f64::from(m.pixel / width) + 0.5,
                        ),
                        (width, height),
                    );
                    let landed = on_ray(m.position.as_dvec3(), origin, direction);
                    if (m.uv - f.uv).length() < 1e-5 {
                        assert!((m.frame.n - f.frame.n).length() < 1e-4);
                        agreed += 1;
                    } else {
                        assert!(!landed, "{} {}", m.uv, f.uv);
                    }
                    probes += 1;
                }
                Evaluate::Mesh => assert_eq!(m, i),
            }
            counted += u64::from(evaluate[m.pixel as usize] != Evaluate::Mesh);
        }
        assert_eq!(frames, counted);
        assert!(counted > 100 && counted < mixed.texels.len() as u64);
        assert!(
            agreed * 20 >= probes * 19,
            "{agreed} of {probes} probes agree"
        );
    }

    #[test]
    fn a_probe_from_the_back_keeps_to_the_back_and_one_from_the_front_finds_the_near_sheet() {
        let library = ball_library();
        let surface = &library.patches[0].surface;
        let camera = fixtures::camera();
        let size = (64, 64);
        let eye = camera.eye.as_dvec3();
        // A ray that grazes the ball: it crosses it twice, close together.
        let (pixel, (origin, direction)) = (0..size.0 * size.1)
            .map(|p| {
                let centre = (f64::from(p % size.0) + 0.5, f64::from(p / size.0) + 0.5);
                (p, camera.ray_through(centre, size))
            })
            .find(|(_, (o, d))| {
                let d = d.normalize();
                let miss = (*o - o.dot(d) * d).length();
                miss > 0.995 && miss < 0.9995
            })
            .unwrap();
        let d = direction.normalize();
        let middle = origin - origin.dot(d) * d;
        let half = (1.0 - middle.length_squared()).sqrt();
        let (near, far) = (middle - half * d, middle + half * d);
        // Each crossing's (u, v): the nearest of a grid, refined onto the ray.
        let domain = surface.domain();
        let grid: Vec<(f64, f64)> = (0..=200)
            .flat_map(|i| (0..=200).map(move |j| (f64::from(i) / 200.0, f64::from(j) / 200.0)))
            .map(|(s, t)| domain.lerp(s, t))
            .collect();
        let crossing = |p: DVec3| {
            let start = grid
                .iter()
                .copied()
                .min_by(|a, b| {
                    let distance = |&(u, v): &(f64, f64)| surface.point(u, v).distance(p);
                    distance(a).total_cmp(&distance(b))
                })
                .unwrap();
            let uv = surface.try_refine_on_ray(start, origin, direction).unwrap();
            assert!(surface.point(uv.0, uv.1).distance(p) < 1e-6);
            uv
        };
        let (near_uv, far_uv) = (crossing(near), crossing(far));
        let faces = |uv: (f64, f64)| {
            let f = surface.frame(uv.0, uv.1);
            f.normal.dot(eye - f.point) > 0.0
        };
        assert!(faces(near_uv) && !faces(far_uv));
        // A start between them, a little nearer the far one: Newton steps land there first,
        // and the start mirrored through it lies nearer the near one.
        let start = (
            near_uv.0 + 0.55 * (far_uv.0 - near_uv.0),
            near_uv.1 + 0.55 * (far_uv.1 - near_uv.1),
        );
        let probe = |back: bool| {
            let position = surface.point(start.0, start.1).as_vec3();
            // A frame turned toward the eye, as a texel's is.
            let n = (camera.eye - position).normalize();
            let du = n.any_orthonormal_vector();
            let mut texels = [Texel {
                pixel,
                uv: Vec2::new(start.0 as f32, start.1 as f32),
                position,
                frame: TangentFrame::new(du, n.cross(du), n),
                back,
                ..UNFILLED
            }];
            GBuffer::evaluate_frames(
                &mut texels,
                &library,
                &camera,
                camera.view_projection(1.0),
                size,
                FrameMode::Refined,
                Evaluate::Probe,
            );
            texels[0]
        };
        let (from_back, from_front) = (probe(true), probe(false));
        // The crossings lie about 0.19 apart, and a probe lands within 10⁻⁴ of one.
        assert!(from_back.back && from_back.position.as_dvec3().distance(far) < 1e-3);
        assert!(!from_front.back && from_front.position.as_dvec3().distance(near) < 1e-3);
    }
}
