//! The accuracy sweep: every rung of the ladder (tessellation density × frame mode ×
//! anti-aliasing) on the analytic sphere, for several highlight stacks and resolutions, with its
//! error against the analytic reference and its time per frame.

use std::sync::Arc;

use std::fmt;

use crate::highlight::{Expr, Layer, Op, PreparedExpr, SquareStyle};
use crate::render::tessellate::Density;
use crate::render::{Antialias, Aovs, FrameMode, Projection, RenderError, Renderer, Settings};

use super::metrics::{boundary_displacement, iou};
use super::reference::{AnalyticSphere, NormalErrors};
use super::timing::median;

/// Sub-pixel samples per side of the reference coverage: 64 per pixel.
pub const REFERENCE_SAMPLES: u32 = 8;

/// The highlight stacks the sweep renders.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stack {
    /// The plain Blinn highlight.
    Identity,
    /// Moved toward du and −dv, then stretched along du.
    TranslateScale,
    /// Cut in two along dv.
    Split,
    /// Squared (tangent style).
    Square,
    /// A Boolean crescent: a plain highlight minus a moved one.
    Crescent,
}

impl Stack {
    pub const ALL: [Stack; 5] = [
        Stack::Identity,
        Stack::TranslateScale,
        Stack::Split,
        Stack::Square,
        Stack::Crescent,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Stack::Identity => "identity",
            Stack::TranslateScale => "translate+scale",
            Stack::Split => "split",
            Stack::Square => "square",
            Stack::Crescent => "crescent",
        }
    }

    /// The highlight expression, ε = 0.04 (0.06 for the crescent's outer layer).
    pub fn expression(self) -> PreparedExpr {
        let layer = |stack: Vec<Op>, epsilon: f32| {
            Box::new(Expr::Layer(Layer::new(stack, epsilon, [1.0, 1.0, 1.0])))
        };
        let expr = match self {
            Stack::Identity => *layer(vec![], 0.04),
            Stack::TranslateScale => *layer(
                vec![
                    Op::Translate {
                        alpha: 0.15,
                        beta: -0.1,
                    },
                    Op::Scale {
                        delta: 0.6,
                        axis: Default::default(),
                    },
                ],
                0.04,
            ),
            Stack::Split => *layer(
                vec![Op::Split {
                    gamma_u: 0.08,
                    gamma_v: 0.0,
                }],
                0.04,
            ),
            Stack::Square => *layer(
                vec![Op::Square {
                    sigma: 0.2,
                    n: 2.0,
                    style: SquareStyle::Tangent,
                }],
                0.04,
            ),
            Stack::Crescent => Expr::Subtract(
                layer(vec![], 0.06),
                layer(
                    vec![Op::Translate {
                        alpha: 0.12,
                        beta: 0.05,
                    }],
                    0.05,
                ),
            ),
        };
        expr.prepare()
            .expect("the sweep's highlight parameters are in range")
    }
}

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
    /// Mean boundary displacement in pixels ([`boundary_displacement`]).
    pub boundary_pixels: f64,
    /// The largest angle between the normal AOV and the sphere's normal, in degrees.
    pub max_normal_degrees: f64,
    /// The mean of that angle over the pixels both cover, in degrees.
    pub mean_normal_degrees: f64,
}

/// One setting on one stack at one resolution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Measurement {
    pub size: u32,
    pub stack: Stack,
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
    pub stacks: Vec<Stack>,
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
    /// all five stacks.
    pub fn full(sizes: Vec<u32>, repeats: usize, threads: usize) -> Self {
        let span = |n: u32| Density::PerSpan { u: n, v: n };
        let tolerance = |pixels: f32| Density::ScreenTolerance { pixels };
        Self {
            sizes,
            stacks: Stack::ALL.to_vec(),
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
                ],
            ),
            repeats,
            threads,
        }
    }

    /// A reduced ladder for a quick look: 4 and 16 segments per span, interpolated and exact
    /// frames, no and 3 × 3 edges, the presets; the identity and crescent stacks.
    pub fn quick(sizes: Vec<u32>, repeats: usize, threads: usize) -> Self {
        let span = |n: u32| Density::PerSpan { u: n, v: n };
        Self {
            sizes,
            stacks: vec![Stack::Identity, Stack::Crescent],
            rungs: Self::ladder(
                &[span(4), span(16)],
                &[FrameMode::Interpolated, FrameMode::Exact],
                &[Antialias::None, Antialias::Supersample(3)],
            ),
            repeats,
            threads,
        }
    }

    /// The presets side by side on all five stacks at one size, with the candidates they were
    /// chosen from: at a 0.25 px tolerance exact frames with analytic, 3 × 3 and 4 × 4 edges
    /// and refined frames with 3 × 3 edges; at 0.5 px refined frames with analytic edges.
    pub fn presets(size: u32, repeats: usize, threads: usize) -> Self {
        let rung = |pixels: f32, frames: FrameMode, antialias: Antialias| Rung {
            density: Density::ScreenTolerance { pixels },
            frames,
            antialias,
        };
        let candidates = [
            rung(0.25, FrameMode::Exact, Antialias::Analytic),
            rung(0.25, FrameMode::Exact, Antialias::Supersample(3)),
            rung(0.25, FrameMode::Exact, Antialias::Supersample(4)),
            rung(0.25, FrameMode::Refined, Antialias::Supersample(3)),
            rung(0.5, FrameMode::Refined, Antialias::Analytic),
        ];
        let mut rungs = Self::ladder(&[], &[], &[]);
        rungs.extend(candidates.iter().filter(|c| c.preset().is_none()));
        Self {
            sizes: vec![size],
            stacks: Stack::ALL.to_vec(),
            rungs,
            repeats,
            threads,
        }
    }

    /// The number of measurements [`Sweep::run`] makes.
    pub fn len(&self) -> usize {
        self.sizes.len() * self.stacks.len() * self.rungs.len()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Measures every rung on every stack and size, in a perspective view of the sphere
    /// (30° field of view), calling `done` after each measurement.
    pub fn run(&self, mut done: impl FnMut(&Measurement)) -> Result<Vec<Measurement>, RenderError> {
        let sphere = AnalyticSphere::new(Projection::Perspective {
            fov_y_degrees: 30.0,
        });
        let library = AnalyticSphere::library();
        let mut renderer = Renderer::new(Arc::clone(&library));
        let mut measurements = Vec::with_capacity(self.len());
        for &size in &self.sizes {
            for &stack in &self.stacks {
                let highlight = stack.expression();
                let reference = sphere.coverage(&highlight, size, REFERENCE_SAMPLES);
                for &rung in &self.rungs {
                    let settings = rung.settings(size, self.threads);
                    let with_aovs = sphere.scene(
                        &library,
                        &highlight,
                        Aovs {
                            matte: true,
                            normal: true,
                            ..Aovs::default()
                        },
                    );
                    let frame = renderer.render(&with_aovs, &settings)?;
                    let (matte, normals) = (
                        frame.aovs.matte.unwrap_or_default(),
                        frame.aovs.normal.unwrap_or_default(),
                    );
                    let normal = sphere
                        .normal_errors(&normals, size, settings.samples_per_side())
                        .unwrap_or(NormalErrors {
                            max_degrees: 180.0,
                            mean_degrees: 180.0,
                        });
                    let errors = Errors {
                        one_minus_iou: 1.0 - iou(&matte, &reference).unwrap_or(0.0),
                        boundary_pixels: boundary_displacement(&matte, &reference, size as usize)
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
                        stack,
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

/// One rung at one size, over all stacks.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Summary {
    pub size: u32,
    pub rung: Rung,
    pub triangles: usize,
    /// The mean over stacks of 1 − IoU.
    pub mean_one_minus_iou: f64,
    /// The worst stack's 1 − IoU.
    pub worst_one_minus_iou: f64,
    /// The mean over stacks of the boundary displacement, in pixels.
    pub mean_boundary_pixels: f64,
    /// The largest normal error over stacks, in degrees.
    pub max_normal_degrees: f64,
    /// The mean over stacks of the mean normal error, in degrees.
    pub mean_normal_degrees: f64,
    /// The mean over stacks of the median frame time, in seconds.
    pub frame_seconds: f64,
    /// No other rung at this size is at least as fast and at least as accurate (mean 1 − IoU),
    /// and better in one.
    pub pareto: bool,
}

/// The measurements summarized per size and rung (in the order they were measured), with the
/// Pareto front of mean 1 − IoU against time marked per size.
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
            max_normal_degrees: max(|o| o.errors.max_normal_degrees),
            mean_normal_degrees: mean(|o| o.errors.mean_normal_degrees),
            frame_seconds: mean(|o| o.frame_seconds),
            pareto: false,
        });
    }
    let points: Vec<(f64, f64)> = summaries
        .iter()
        .map(|s| (s.frame_seconds, s.mean_one_minus_iou))
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
    /// The worst stack's IoU under `final`.
    pub final_worst_iou: f64,
    /// The mean IoU over stacks under `final`.
    pub final_mean_iou: f64,
    /// Mean frame times over stacks, in seconds.
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
                preview_seconds: preview.frame_seconds,
                final_seconds: last.frame_seconds,
            })
        })
        .collect()
}
