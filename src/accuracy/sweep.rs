//! The accuracy sweep: every rung of the ladder (tessellation density × frame mode ×
//! anti-aliasing) on the analytic sphere, for several views ([`Case`]) and resolutions, with its
//! error against the analytic reference and its time per frame.

use std::sync::Arc;

use std::fmt;

use crate::render::tessellate::Density;
use crate::render::{Antialias, Aovs, FrameMode, RenderError, Renderer, Settings};

use super::case::{Case, Pose};
use super::metrics::{boundary_displacement, iou};
use super::reference::{AnalyticSphere, NormalErrors};
pub use super::stack::Stack;
use super::timing::median;

/// Sub-pixel samples per side of the reference coverage: 64 per pixel.
pub const REFERENCE_SAMPLES: u32 = 8;

/// Sub-pixel samples per side of the reference coverage where a pixel is on an edge:
/// 1024 per pixel ([`AnalyticSphere::mattes`]).
pub const REFERENCE_EDGE_SAMPLES: u32 = 32;

/// One rung of the ladder: how the sweep renders.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rung {
    pub density: Density,
    pub frames: FrameMode,
    pub antialias: Antialias,
}

impl Rung {
    /// The rung a preset stands on.
    pub fn of(settings: &Settings) -> Self {
        Self {
            density: settings.density,
            frames: settings.frames,
            antialias: settings.antialias,
        }
    }

    /// The settings of this rung on a `size × size` image with `threads` workers.
    pub fn settings(&self, size: u32, threads: usize) -> Settings {
        Settings {
            width: size,
            height: size,
            density: self.density,
            frames: self.frames,
            antialias: self.antialias,
            threads,
        }
    }

    /// `preview` or `final` when this rung is that preset's.
    pub fn preset(&self) -> Option<&'static str> {
        if *self == Rung::of(&Settings::preview(1, 1)) {
            Some("preview")
        } else if *self == Rung::of(&Settings::final_quality(1, 1)) {
            Some("final")
        } else {
            None
        }
    }
}

impl fmt::Display for Rung {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} / {} / {}", self.density, self.frames, self.antialias)
    }
}

/// How far one render is from the analytic reference.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Errors {
    /// 1 − IoU of the highlight matte against the reference coverage ([`iou`]).
    pub one_minus_iou: f64,
    /// Mean boundary displacement of the highlight in pixels ([`boundary_displacement`]).
    pub boundary_pixels: f64,
    /// 1 − IoU of the frame's alpha against the sphere's coverage.
    pub silhouette_one_minus_iou: f64,
    /// Mean boundary displacement of the silhouette in pixels.
    pub silhouette_pixels: f64,
    /// The largest angle between the normal AOV and the sphere's normal, in degrees.
    pub max_normal_degrees: f64,
    /// The mean of that angle over the pixels both cover, in degrees.
    pub mean_normal_degrees: f64,
}

/// One setting on one view at one resolution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Measurement {
    pub size: u32,
    pub case: Case,
    pub rung: Rung,
    pub triangles: usize,
    pub errors: Errors,
    /// The median time of a frame (without AOVs), in seconds.
    pub frame_seconds: f64,
}

/// What to measure.
#[derive(Clone, Debug, PartialEq)]
pub struct Sweep {
    /// Image sides (square images).
    pub sizes: Vec<u32>,
    /// The views, each measured on every rung.
    pub cases: Vec<Case>,
    pub rungs: Vec<Rung>,
    /// Timed frames per measurement, after one untimed frame that also gives the errors.
    pub repeats: usize,
    /// Worker threads per frame (0: one per core).
    pub threads: usize,
}

impl Sweep {
    /// Every combination of `densities`, `frames` and `antialias`, plus the presets' rungs if
    /// they are not among them.
    pub fn ladder(
        densities: &[Density],
        frames: &[FrameMode],
        antialias: &[Antialias],
    ) -> Vec<Rung> {
        let mut rungs: Vec<Rung> = densities
            .iter()
            .flat_map(|&density| {
                frames.iter().flat_map(move |&frames| {
                    antialias.iter().map(move |&antialias| Rung {
                        density,
                        frames,
                        antialias,
                    })
                })
            })
            .collect();
        for preset in [Settings::preview(1, 1), Settings::final_quality(1, 1)] {
            if !rungs.contains(&Rung::of(&preset)) {
                rungs.push(Rung::of(&preset));
            }
        }
        rungs
    }

    /// The full ladder: fixed densities of 2 to 32 segments per span and screen tolerances of
    /// 1 and 0.25 pixels; the three frame modes; no, analytic, 2 × 2, 3 × 3 and 4 × 4 edges;
    /// every view ([`Case::all`]).
    pub fn full(sizes: Vec<u32>, repeats: usize, threads: usize) -> Self {
        let span = |n: u32| Density::PerSpan { u: n, v: n };
        let tolerance = |pixels: f32| Density::ScreenTolerance { pixels };
        Self {
            sizes,
            cases: Case::all(),
            rungs: Self::ladder(
                &[
                    span(2),
                    span(4),
                    span(8),
                    span(16),
                    span(32),
                    tolerance(1.0),
                    tolerance(0.25),
                ],
                &[
                    FrameMode::Interpolated,
                    FrameMode::Exact,
                    FrameMode::Refined,
                ],
                &[
                    Antialias::None,
                    Antialias::Analytic,
                    Antialias::Supersample(2),
                    Antialias::Supersample(3),
                    Antialias::Supersample(4),
                    Antialias::Adaptive(4),
                ],
            ),
            repeats,
            threads,
        }
    }

    /// A reduced ladder for a quick look: 4 and 16 segments per span, interpolated and exact
    /// frames, no and 3 × 3 edges, the presets; the identity and crescent stacks in front, and
    /// the identity 70° off centre.
    pub fn quick(sizes: Vec<u32>, repeats: usize, threads: usize) -> Self {
        let span = |n: u32| Density::PerSpan { u: n, v: n };
        Self {
            sizes,
            cases: vec![
                Case {
                    pose: Pose::Front,
                    stack: Stack::Identity,
                },
                Case {
                    pose: Pose::Front,
                    stack: Stack::Crescent,
                },
                Case {
                    pose: Pose::OffCentre { degrees: 70 },
                    stack: Stack::Identity,
                },
            ],
            rungs: Self::ladder(
                &[span(4), span(16)],
                &[FrameMode::Interpolated, FrameMode::Exact],
                &[Antialias::None, Antialias::Supersample(3)],
            ),
            repeats,
            threads,
        }
    }

    /// The presets side by side on every view at one size, with the candidates they were
    /// chosen from: at a 0.25 px tolerance exact frames with analytic, 3 × 3 and 4 × 4 edges
    /// and refined frames with 3 × 3 edges; at 0.5 px refined frames with analytic edges.
    pub fn presets(size: u32, repeats: usize, threads: usize) -> Self {
        let rung = |pixels: f32, frames: FrameMode, antialias: Antialias| Rung {
            density: Density::ScreenTolerance { pixels },
            frames,
            antialias,
        };
        let candidates = [
            rung(0.25, FrameMode::Exact, Antialias::Supersample(4)),
            rung(0.25, FrameMode::Refined, Antialias::Adaptive(4)),
            rung(0.05, FrameMode::Refined, Antialias::Adaptive(3)),
            rung(0.05, FrameMode::Exact, Antialias::Adaptive(4)),
            rung(0.5, FrameMode::Refined, Antialias::Analytic),
        ];
        let mut rungs = Self::ladder(&[], &[], &[]);
        rungs.extend(candidates.iter().filter(|c| c.preset().is_none()));
        Self {
            sizes: vec![size],
            cases: Case::all(),
            rungs,
            repeats,
            threads,
        }
    }

    /// The number of measurements [`Sweep::run`] makes.
    pub fn len(&self) -> usize {
        self.sizes.len() * self.cases.len() * self.rungs.len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Measures every rung on every view and size, calling `done` after each measurement.
    pub fn run(&self, mut done: impl FnMut(&Measurement)) -> Result<Vec<Measurement>, RenderError> {
        let library = AnalyticSphere::library();
        let mut renderer = Renderer::new(Arc::clone(&library));
        let mut measurements = Vec::with_capacity(self.len());
        for &size in &self.sizes {
            for &case in &self.cases {
                let sphere = case.pose.sphere();
                let highlight = case.stack.expression();
                let reference = sphere.mattes(
                    &case.stack.reference_expression(),
                    size,
                    REFERENCE_SAMPLES,
                    REFERENCE_EDGE_SAMPLES,
                );
                for &rung in &self.rungs {
                    let settings = rung.settings(size, self.threads);
                    let with = |aovs| sphere.scene(&library, &highlight, aovs);
                    let matte_only = Aovs {
                        matte: true,
                        ..Aovs::default()
                    };
                    let frame = renderer.render(&with(matte_only), &settings)?;
                    let alpha: Vec<f32> = frame.colour.iter().map(|c| c.w).collect();
                    let matte = frame.aovs.matte.unwrap_or_default();
                    // The normals from a frame of their own: the normal AOV reads every
                    // pixel's frame, which an adaptive frame's one-sample pass otherwise
                    // interpolates (`Plan::first_frames`), so that the mattes above are those
                    // of a frame without it.
                    let normal_only = Aovs {
                        normal: true,
                        ..Aovs::default()
                    };
                    let normals = renderer
                        .render(&with(normal_only), &settings)?
                        .aovs
                        .normal
                        .unwrap_or_default();
                    let normal = sphere
                        .normal_errors(&normals, size, settings.samples_per_side())
                        .unwrap_or(NormalErrors {
                            max_degrees: 180.0,
                            mean_degrees: 180.0,
                        });
                    let width = size as usize;
                    let errors = Errors {
                        one_minus_iou: 1.0 - iou(&matte, &reference.highlight).unwrap_or(0.0),
                        boundary_pixels: boundary_displacement(&matte, &reference.highlight, width)
                            .unwrap_or(f64::INFINITY),
                        silhouette_one_minus_iou: 1.0
                            - iou(&alpha, &reference.silhouette).unwrap_or(0.0),
                        silhouette_pixels: boundary_displacement(
                            &alpha,
                            &reference.silhouette,
                            width,
                        )
                        .unwrap_or(f64::INFINITY),
                        max_normal_degrees: normal.max_degrees,
                        mean_normal_degrees: normal.mean_degrees,
                    };
                    let plain = sphere.scene(&library, &highlight, Aovs::default());
                    let mut times = Vec::with_capacity(self.repeats);
                    for _ in 0..self.repeats.max(1) {
                        times.push(renderer.render(&plain, &settings)?.stats.total_seconds);
                    }
                    let measurement = Measurement {
                        size,
                        case,
                        rung,
                        triangles: frame.stats.triangles,
                        errors,
                        frame_seconds: median(&mut times),
                    };
                    done(&measurement);
                    measurements.push(measurement);
                }
            }
        }
        Ok(measurements)
    }
}

/// One rung at one size, over all views.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summary {
    pub size: u32,
    pub rung: Rung,
    pub triangles: usize,
    /// The mean over views of the highlight's 1 − IoU.
    pub mean_one_minus_iou: f64,
    /// The worst view's highlight 1 − IoU.
    pub worst_one_minus_iou: f64,
    /// The mean over views of the highlight's boundary displacement, in pixels.
    pub mean_boundary_pixels: f64,
    /// The worst view's highlight boundary displacement, in pixels.
    pub worst_boundary_pixels: f64,
    /// The worst view's silhouette 1 − IoU.
    pub worst_silhouette_one_minus_iou: f64,
    /// The worst view's silhouette boundary displacement, in pixels.
    pub worst_silhouette_pixels: f64,
    /// The largest normal error over views, in degrees.
    pub max_normal_degrees: f64,
    /// The mean over views of the mean normal error, in degrees.
    pub mean_normal_degrees: f64,
    /// The mean over views of the median frame time, in seconds.
    pub frame_seconds: f64,
    /// No other rung at this size is at least as fast and at least as accurate (worst
    /// highlight 1 − IoU), and better in one.
    pub pareto: bool,
}

/// The measurements summarized per size and rung (in the order they were measured), with the
/// Pareto front of the worst view's 1 − IoU against time marked per size.
pub fn summarize(measurements: &[Measurement]) -> Vec<Summary> {
    let mut summaries: Vec<Summary> = Vec::new();
    for m in measurements {
        if summaries
            .iter()
            .any(|s| s.size == m.size && s.rung == m.rung)
        {
            continue;
        }
        let same: Vec<&Measurement> = measurements
            .iter()
            .filter(|o| o.size == m.size && o.rung == m.rung)
            .collect();
        let n = same.len() as f64;
        let mean = |f: fn(&Measurement) -> f64| same.iter().map(|o| f(o)).sum::<f64>() / n;
        let max = |f: fn(&Measurement) -> f64| same.iter().map(|o| f(o)).fold(0.0, f64::max);
        summaries.push(Summary {
            size: m.size,
            rung: m.rung,
            triangles: m.triangles,
            mean_one_minus_iou: mean(|o| o.errors.one_minus_iou),
            worst_one_minus_iou: max(|o| o.errors.one_minus_iou),
            mean_boundary_pixels: mean(|o| o.errors.boundary_pixels),
            worst_boundary_pixels: max(|o| o.errors.boundary_pixels),
            worst_silhouette_one_minus_iou: max(|o| o.errors.silhouette_one_minus_iou),
            worst_silhouette_pixels: max(|o| o.errors.silhouette_pixels),
            max_normal_degrees: max(|o| o.errors.max_normal_degrees),
            mean_normal_degrees: mean(|o| o.errors.mean_normal_degrees),
            frame_seconds: mean(|o| o.frame_seconds),
            pareto: false,
        });
    }
    let points: Vec<(f64, f64)> = summaries
        .iter()
        .map(|s| (s.frame_seconds, s.worst_one_minus_iou))
        .collect();
    let sizes: Vec<u32> = summaries.iter().map(|s| s.size).collect();
    for (i, summary) in summaries.iter_mut().enumerate() {
        let (time, error) = points[i];
        summary.pareto = !points.iter().zip(&sizes).any(|(&(t, e), &size)| {
            size == summary.size && t <= time && e <= error && (t < time || e < error)
        });
    }
    summaries
}

/// The presets side by side at one size.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PresetComparison {
    pub size: u32,
    /// The worst view's highlight IoU under `final`.
    pub final_worst_iou: f64,
    /// The mean highlight IoU over views under `final`.
    pub final_mean_iou: f64,
    /// The worst view's silhouette IoU under `final`.
    pub final_worst_silhouette_iou: f64,
    /// Mean frame times over views, in seconds.
    pub preview_seconds: f64,
    pub final_seconds: f64,
}

impl PresetComparison {
    /// How many times faster `preview` is than `final`.
    pub fn speedup(&self) -> f64 {
        self.final_seconds / self.preview_seconds
    }
}

/// The presets compared at every size where both were measured.
pub fn compare_presets(summaries: &[Summary]) -> Vec<PresetComparison> {
    let find = |size: u32, preset: &str| {
        summaries
            .iter()
            .find(|s| s.size == size && s.rung.preset() == Some(preset))
    };
    let mut sizes: Vec<u32> = summaries.iter().map(|s| s.size).collect();
    sizes.dedup();
    sizes
        .into_iter()
        .filter_map(|size| {
            let (preview, last) = (find(size, "preview")?, find(size, "final")?);
            Some(PresetComparison {
                size,
                final_worst_iou: 1.0 - last.worst_one_minus_iou,
                final_mean_iou: 1.0 - last.mean_one_minus_iou,
                final_worst_silhouette_iou: 1.0 - last.worst_silhouette_one_minus_iou,
                preview_seconds: preview.frame_seconds,
                final_seconds: last.frame_seconds,
            })
        })
        .collect()
}
