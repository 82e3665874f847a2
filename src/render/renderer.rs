//! One frame, stage by stage: tessellate (cached), rasterize, fill the G-buffer, shade, outline,
//! resolve. Stages the scene does not use do not run.

use std::ops::{Add, Mul};

use glam::{Vec2, Vec3, Vec4};
use rayon::prelude::*;
use rayon::ThreadPool;

use super::gbuffer::{GBuffer, PIXELS_PER_JOB};
use super::outline::{draw_outlines, OutlineBuffers};
use super::plan::{Plan, Surfaces};
use super::raster::{RasterOptions, Rasterizer, Viewport, VisibilityBuffer};
use super::scene::{Outlines, Scene};
use super::settings::{Antialias, Settings};
use super::shade::{shade, ShadeBuffers, Shaded};
use super::stats::{timed, RenderStats, StageStats};
use super::tessellate::Tessellator;
use super::visibility_shade::shade_visibility;
use super::RenderError;
use crate::geom::PatchLibrary;

/// A rendered frame at output resolution.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderedFrame {
    pub width: u32,
    pub height: u32,
    /// Linear RGB with straight alpha (0 on the background), rows from the top.
    pub colour: Vec<Vec4>,
    pub aovs: AovImages,
    pub stats: RenderStats,
}

/// The AOVs a scene asked for (`None` for the others). Under supersampling the matte is the
/// average of a pixel's samples; the others are taken from its central sample.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AovImages {
    pub matte: Option<Vec<f32>>,
    /// Patch index per pixel, `u32::MAX` on the background.
    pub patch_id: Option<Vec<u32>>,
    /// NDC depth per pixel, `f32::INFINITY` on the background.
    pub depth: Option<Vec<f32>>,
    pub normal: Option<Vec<Vec3>>,
    pub uv: Option<Vec<Vec2>>,
    /// `N·H` of the initial half vector, 0 on the background.
    pub n_dot_h: Option<Vec<f32>>,
}

/// Renders frames of one model, keeping its tessellation, working memory and worker threads
/// between frames.
pub struct Renderer<'a> {
    library: &'a PatchLibrary,
    stages: Stages<'a>,
    pool: Option<(usize, ThreadPool)>,
}

/// What the stages keep from one frame to the next: the mesh, and every buffer whose size
/// depends only on the image and the mesh, so that a frame allocates just the images it returns.
struct Stages<'a> {
    tessellator: Tessellator<'a>,
    /// The mesh's vertices in clip space.
    clip: Vec<Vec4>,
    rasterizer: Rasterizer,
    visibility: VisibilityBuffer,
    gbuffer: GBuffer,
    shading: ShadeBuffers,
    outlining: OutlineBuffers,
}

impl<'a> Renderer<'a> {
    pub fn new(library: &'a PatchLibrary) -> Self {
        Self {
            library,
            stages: Stages {
                tessellator: Tessellator::new(library),
                clip: Vec::new(),
                rasterizer: Rasterizer::new(),
                visibility: VisibilityBuffer::default(),
                gbuffer: GBuffer::default(),
                shading: ShadeBuffers::default(),
                outlining: OutlineBuffers::default(),
            },
            pool: None,
        }
    }

    /// Renders `scene` with `settings`; the scene must show this renderer's model.
    pub fn render(
        &mut self,
        scene: &Scene,
        settings: &Settings,
    ) -> Result<RenderedFrame, RenderError> {
        settings.validate()?;
        scene.camera.validate()?;
        if !std::ptr::eq(scene.library, self.library) {
            return Err(RenderError::Scene(
                "the scene shows another model than this renderer was made for".into(),
            ));
        }
        if scene.looks.len() != self.library.patches.len() {
            return Err(RenderError::Scene(format!(
                "the scene must give one look for each of the model's {} patches, got {}",
                self.library.patches.len(),
                scene.looks.len()
            )));
        }
        let (stages, library) = (&mut self.stages, self.library);
        if settings.threads == 0 {
            return Ok(stages.render(library, scene, settings));
        }
        if self
            .pool
            .as_ref()
            .is_none_or(|(n, _)| *n != settings.threads)
        {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(settings.threads)
                .build()
                .map_err(|e| {
                    RenderError::Settings(format!("cannot start {} threads: {e}", settings.threads))
                })?;
            self.pool = Some((settings.threads, pool));
        }
        let pool = &self.pool.as_ref().expect("the pool was just made").1;
        Ok(pool.install(|| stages.render(library, scene, settings)))
    }
}

impl Stages<'_> {
    fn render(
        &mut self,
        library: &PatchLibrary,
        scene: &Scene,
        settings: &Settings,
    ) -> RenderedFrame {
        let (frame, total) = timed(|| self.stages(library, scene, settings));
        RenderedFrame {
            stats: RenderStats {
                total_seconds: total,
                ..frame.stats
            },
            ..frame
        }
    }

    fn stages(
        &mut self,
        library: &PatchLibrary,
        scene: &Scene,
        settings: &Settings,
    ) -> RenderedFrame {
        let plan = Plan::new(scene, settings);
        let mut stats = RenderStats::default();
        let k = settings.samples_per_side();
        let (width, height) = (settings.width * k, settings.height * k);
        let view_projection = scene
            .camera
            .view_projection(settings.width as f32 / settings.height as f32);

        let ((mesh, rebuilt), seconds) = timed(|| {
            self.tessellator.mesh(
                settings.density,
                view_projection,
                settings.width,
                settings.height,
            )
        });
        stats.tessellation_rebuilt = rebuilt;
        stats.triangles = mesh.triangles.len();
        stats.tessellation.seconds = seconds;

        let (visibility, clip) = (&mut self.visibility, &mut self.clip);
        let rasterizer = &mut self.rasterizer;
        let (raster, seconds) = timed(|| {
            mesh.positions
                .par_iter()
                .with_min_len(PIXELS_PER_JOB)
                .map(|p| view_projection * p.extend(1.0))
                .collect_into_vec(clip);
            let options = RasterOptions {
                threads: 0,
                ..RasterOptions::default()
            };
            let viewport = Viewport { width, height };
            rasterizer.rasterize_into(viewport, clip, &mesh.triangles, &options, visibility)
        });
        let visibility = &*visibility;
        stats.raster = StageStats {
            pixels: raster.pixels_covered,
            seconds,
        };

        let (gbuffer, shading) = (&mut self.gbuffer, &mut self.shading);
        let (mut shaded, seconds) = match plan.surfaces {
            Surfaces::Visibility => timed(|| Shaded {
                colour: shade_visibility(visibility, mesh, scene),
                matte: None,
                n_dot_h: None,
                shaded: raster.pixels_covered,
                highlighted: 0,
                detail: StageStats::default(),
            }),
            Surfaces::Texels => {
                let (exact, seconds) = timed(|| {
                    gbuffer.fill(
                        visibility,
                        mesh,
                        library,
                        &scene.camera,
                        settings.frames,
                        plan.outlines,
                    )
                });
                stats.gbuffer = StageStats {
                    pixels: raster.pixels_covered,
                    seconds,
                };
                stats.exact_frames = exact;
                let analytic = settings.antialias == Antialias::Analytic;
                timed(|| shade(gbuffer, scene, analytic, shading))
            }
        };
        stats.shade = StageStats {
            pixels: shaded.shaded,
            seconds,
        };
        stats.highlight_pixels = shaded.highlighted;
        stats.detail = shaded.detail;
        let gbuffer = &*gbuffer;

        if let (true, Some(outlines)) = (plan.outlines, &scene.outlines) {
            let (_, seconds) = timed(|| {
                let scaled = Outlines {
                    width: outlines.width * k as f32,
                    ..*outlines
                };
                let buffers = &mut self.outlining;
                draw_outlines(gbuffer, &scaled, &mut shaded.colour, buffers);
            });
            stats.outline = StageStats {
                pixels: u64::from(width) * u64::from(height),
                seconds,
            };
        }

        let mut aovs = AovImages::default();
        if plan.aovs {
            let (images, seconds) = timed(|| collect_aovs(scene, gbuffer, &mut shaded, k));
            let count = [
                images.matte.is_some(),
                images.patch_id.is_some(),
                images.depth.is_some(),
                images.normal.is_some(),
                images.uv.is_some(),
                images.n_dot_h.is_some(),
            ]
            .iter()
            .filter(|&&on| on)
            .count() as u64;
            stats.aov = StageStats {
                pixels: count * u64::from(settings.width) * u64::from(settings.height),
                seconds,
            };
            aovs = images;
        }

        let colour = if k == 1 {
            shaded.colour
        } else {
            let (colour, seconds) =
                timed(|| resolve(&shaded.colour, settings.width, settings.height, k));
            stats.resolve = StageStats {
                pixels: u64::from(settings.width) * u64::from(settings.height),
                seconds,
            };
            colour
        };
        RenderedFrame {
            width: settings.width,
            height: settings.height,
            colour,
            aovs,
            stats,
        }
    }
}

/// Resolves `k × k` samples per pixel by averaging premultiplied colour:
/// `α = mean(α_s)`, `rgb = mean(α_s rgb_s) / α`.
fn resolve(samples: &[Vec4], width: u32, height: u32, k: u32) -> Vec<Vec4> {
    let premultiplied: Vec<Vec4> = samples
        .iter()
        .map(|s| (s.truncate() * s.w).extend(s.w))
        .collect();
    box_filter(&premultiplied, width, height, k)
        .into_iter()
        .map(|p| {
            if p.w > 0.0 {
                (p.truncate() / p.w).extend(p.w)
            } else {
                Vec4::ZERO
            }
        })
        .collect()
}

/// The mean of each pixel's `k × k` samples, for an output of `width × height` pixels.
fn box_filter<T>(samples: &[T], width: u32, height: u32, k: u32) -> Vec<T>
where
    T: Copy + Default + Add<Output = T> + Mul<f32, Output = T>,
{
    let (width, k) = (width as usize, k as usize);
    let sample_width = width * k;
    let weight = 1.0 / (k * k) as f32;
    (0..width * height as usize)
        .map(|i| {
            let (x, y) = (i % width, i / width);
            let mut sum = T::default();
            for sy in 0..k {
                for sx in 0..k {
                    sum = sum + samples[(y * k + sy) * sample_width + x * k + sx];
                }
            }
            sum * weight
        })
        .collect()
}

/// The AOVs the scene asked for, at output resolution.
fn collect_aovs(scene: &Scene, gbuffer: &GBuffer, shaded: &mut Shaded, k: u32) -> AovImages {
    let (width, height) = (gbuffer.width / k, gbuffer.height / k);
    let centre = |x: u32, y: u32| gbuffer.at(x * k + k / 2, y * k + k / 2);
    let pixels = || (0..height).flat_map(move |y| (0..width).map(move |x| (x, y)));
    let a = scene.aovs;
    AovImages {
        matte: shaded
            .matte
            .take()
            .map(|samples| box_filter(&samples, width, height, k)),
        n_dot_h: shaded
            .n_dot_h
            .take()
            .map(|samples| box_filter(&samples, width, height, k)),
        patch_id: a.patch_id.then(|| {
            pixels()
                .map(|(x, y)| centre(x, y).map_or(u32::MAX, |t| t.patch))
                .collect()
        }),
        depth: a.depth.then(|| {
            pixels()
                .map(|(x, y)| centre(x, y).map_or(f32::INFINITY, |t| t.depth))
                .collect()
        }),
        normal: a.normal.then(|| {
            pixels()
                .map(|(x, y)| centre(x, y).map_or(Vec3::ZERO, |t| t.frame.n))
                .collect()
        }),
        uv: a.uv.then(|| {
            pixels()
                .map(|(x, y)| centre(x, y).map_or(Vec2::ZERO, |t| t.uv))
                .collect()
        }),
    }
}
