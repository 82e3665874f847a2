//! Scaling: frame time against resolution, against the number of patches (copies of a model,
//! such as the teapot) and against the number of threads, with the fitted growth.

use std::sync::Arc;

use glam::{DVec3, Vec3};

use crate::geom::{NamedPatch, PatchLibrary};
use crate::highlight::{Expr, Layer, Light, Op};
use crate::render::tessellate::Density;
use crate::render::{
    Aovs, Camera, PatchLook, Projection, RenderError, Renderer, Scene, Settings, Tone,
};
use crate::toon::CelRamp;

use super::timing::{log_log_slope, median};

/// What a scaling series varies.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Series {
    /// Square images of this side; x is the pixel count.
    Resolution,
    /// Copies of the model side by side at 512 × 512, 8 segments per span; x is the patch count.
    Patches,
    /// Worker threads at 1024 × 1024; x is the thread count.
    Threads,
}

impl Series {
    pub fn name(self) -> &'static str {
        match self {
            Series::Resolution => "resolution",
            Series::Patches => "patches",
            Series::Threads => "threads",
        }
    }
}

/// One timed configuration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScalingPoint {
    pub series: Series,
    /// `preview` or `final`.
    pub preset: &'static str,
    /// Pixels, patches or threads.
    pub x: f64,
    pub triangles: usize,
    /// The median frame time, in seconds.
    pub frame_seconds: f64,
}

/// `count` copies of `model`, in rows of ⌈√count⌉, each moved by `spacing` along x (within a
/// row) and along y (between rows).
pub fn copies(model: &PatchLibrary, count: usize, spacing: f64) -> PatchLibrary {
    let columns = (count as f64).sqrt().ceil().max(1.0) as usize;
    let patches = (0..count)
        .flat_map(|copy| {
            let offset =
                spacing * DVec3::new((copy % columns) as f64, (copy / columns) as f64, 0.0);
            model.patches.iter().map(move |p| NamedPatch {
                name: format!("{}#{copy}", p.name),
                trim: p.trim.clone(),
                surface: p.surface.map_points(|q| q + offset),
            })
        })
        .collect();
    PatchLibrary::new(patches)
}

/// The centre and radius of a sphere around every control point of `library` (the surfaces lie
/// in the hull of their control points).
fn bounds(library: &PatchLibrary) -> (DVec3, f64) {
    let points: Vec<DVec3> = library.control_points().collect();
    let (low, high) = points.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let centre = 0.5 * (low + high);
    let radius = points
        .iter()
        .map(|p| (*p - centre).length())
        .fold(1e-6, f64::max);
    (centre, radius)
}

/// `library` seen whole from the front, above and to the side, with a stretched highlight and
/// two-tone cel on every patch.
fn scene(library: &PatchLibrary) -> Scene<'_> {
    let (centre, radius) = bounds(library);
    let fov = 35.0f32;
    let distance = radius / f64::from(fov.to_radians() * 0.5).sin();
    let eye = centre + distance * DVec3::new(0.55, -0.7, 0.45).normalize();
    let highlight = Expr::Layer(Layer::new(
        vec![Op::Scale {
            delta: 0.5,
            axis: Default::default(),
        }],
        0.05,
        [1.0, 1.0, 1.0],
    ))
    .prepare()
    .expect("the highlight parameters are in range");
    Scene {
        library,
        looks: library
            .patches
            .iter()
            .map(|_| PatchLook {
                designed_light: None,
                lines: None,
                tone: Tone::Cel(CelRamp::two_tone(Vec3::splat(0.2), Vec3::splat(0.7), 0.0)),
                highlight: Some(highlight.clone()),
            })
            .collect(),
        camera: Camera {
            eye: eye.as_vec3(),
            target: centre.as_vec3(),
            up: Vec3::Z,
            projection: Projection::Perspective { fov_y_degrees: fov },
            near: (0.1 * distance) as f32,
            far: (3.0 * distance) as f32,
        },
        light: Light::Directional {
            towards: Vec3::new(0.4, -0.5, 0.8).normalize(),
        },
        outlines: None,
        aovs: Aovs::default(),
        materials: Vec::new(),
    }
}

/// The median time of `repeats` frames after one untimed frame, and the triangle count.
fn time_frames(
    library: &Arc<PatchLibrary>,
    settings: &Settings,
    repeats: usize,
) -> Result<(f64, usize), RenderError> {
    let scene = scene(library);
    let mut renderer = Renderer::new(Arc::clone(library));
    let triangles = renderer.render(&scene, settings)?.stats.triangles;
    let mut times = Vec::with_capacity(repeats);
    for _ in 0..repeats.max(1) {
        times.push(renderer.render(&scene, settings)?.stats.total_seconds);
    }
    Ok((median(&mut times), triangles))
}

/// What the scaling measurements cover.
#[derive(Clone, Debug, PartialEq)]
pub struct Scaling {
    /// Image sides for the resolution series.
    pub sizes: Vec<u32>,
    /// Copies of the model for the patch series.
    pub copies: Vec<usize>,
    /// Thread counts for the thread series.
    pub threads: Vec<usize>,
    pub repeats: usize,
    /// Workers for the resolution and patch series (0: one per core).
    pub workers: usize,
}

impl Scaling {
    /// The number of configurations [`Scaling::run`] times.
    pub fn len(&self) -> usize {
        2 * (self.sizes.len() + self.threads.len()) + self.copies.len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Times `model` under the `preview` and `final` presets at every size and thread count,
    /// and copies of it under `preview` with a fixed density; calls `done` after each point.
    pub fn run(
        &self,
        model: &Arc<PatchLibrary>,
        mut done: impl FnMut(&ScalingPoint),
    ) -> Result<Vec<ScalingPoint>, RenderError> {
        type Preset = fn(u32, u32) -> Settings;
        let presets: [(&'static str, Preset); 2] = [
            ("preview", Settings::preview),
            ("final", Settings::final_quality),
        ];
        let mut points = Vec::with_capacity(self.len());
        let mut record = |point: ScalingPoint| {
            done(&point);
            points.push(point);
        };
        for &(preset, make) in &presets {
            for &size in &self.sizes {
                let settings = Settings {
                    threads: self.workers,
                    ..make(size, size)
                };
                let (seconds, triangles) = time_frames(model, &settings, self.repeats)?;
                record(ScalingPoint {
                    series: Series::Resolution,
                    preset,
                    x: f64::from(size) * f64::from(size),
                    triangles,
                    frame_seconds: seconds,
                });
            }
        }
        for &count in &self.copies {
            let library = Arc::new(copies(model, count, 7.0));
            let settings = Settings {
                density: Density::PerSpan { u: 8, v: 8 },
                threads: self.workers,
                ..Settings::preview(512, 512)
            };
            let (seconds, triangles) = time_frames(&library, &settings, self.repeats)?;
            record(ScalingPoint {
                series: Series::Patches,
                preset: "preview",
                x: library.patches.len() as f64,
                triangles,
                frame_seconds: seconds,
            });
        }
        for &(preset, make) in &presets {
            for &threads in &self.threads {
                let settings = Settings {
                    threads,
                    ..make(1024, 1024)
                };
                let (seconds, triangles) = time_frames(model, &settings, self.repeats)?;
                record(ScalingPoint {
                    series: Series::Threads,
                    preset,
                    x: threads as f64,
                    triangles,
                    frame_seconds: seconds,
                });
            }
        }
        Ok(points)
    }
}

/// The fitted growth exponent of frame time in x for one series and preset: the least-squares
/// slope in log-log ([`log_log_slope`]).
pub fn growth(points: &[ScalingPoint], series: Series, preset: &str) -> Option<f64> {
    let xy: Vec<(f64, f64)> = points
        .iter()
        .filter(|p| p.series == series && p.preset == preset)
        .map(|p| (p.x, p.frame_seconds))
        .collect();
    log_log_slope(&xy)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::shapes;

    #[test]
    fn copies_are_moved_apart_and_keep_their_shape() {
        let model = PatchLibrary {
            patches: vec![NamedPatch {
                name: "ball".into(),
                trim: None,
                surface: shapes::sphere(DVec3::ZERO, 1.0).unwrap(),
            }],
            groups: Vec::new(),
        };
        let four = copies(&model, 4, 3.0);
        assert_eq!(four.patches.len(), 4);
        let centre = |i: usize| four.patches[i].surface.point(0.0, 0.5) - DVec3::X;
        assert!((centre(1) - DVec3::new(3.0, 0.0, 0.0)).length() < 1e-12);
        assert!((centre(3) - DVec3::new(3.0, 3.0, 0.0)).length() < 1e-12);
        let (c, r) = bounds(&four);
        assert!(
            (c - DVec3::new(1.5, 1.5, 0.0)).length() < 1e-9 && r > 3.0,
            "{c} {r}"
        );
    }
}
