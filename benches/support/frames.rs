//! Whole frames measured side by side, for the benchmarks that render them.
//!
//! The variants take turns: each round gives every variant a turn, starting with a different
//! one each round, so a slow spell of this shared machine falls on all of them alike. A turn
//! renders two frames and times the second, which finds the caches and memory as the frame
//! before it left them, as in a frame loop. A ratio is the median over rounds of
//! `numerator frame / denominator frame` from the same round, given with its quartiles. A frame
//! is timed from the call to the drop of what it returned, as a frame loop pays for it.
//!
//! For a profiler, `GLINT_BENCH_PROFILE=NAME` renders only variant `NAME`, 4 frames (or
//! `GLINT_BENCH_PROFILE_FRAMES`), and exits without measuring:
//!
//! ```sh
//! GLINT_BENCH_PROFILE=moving valgrind --tool=callgrind target/release/deps/render-*
//! ```

use std::sync::Arc;
use std::time::Instant;

use glint::geom::PatchLibrary;
use glint::render::{RenderStats, Renderer, Scene, Settings, Stage};

/// One thing to render, frame after frame.
pub struct Variant<'a> {
    pub name: &'static str,
    frame: Box<dyn FnMut() -> Option<RenderStats> + 'a>,
}

impl<'a> Variant<'a> {
    /// A variant rendered by `frame`, which gives the frame's statistics when the renderer
    /// made it (`None` for a baseline built from the stages).
    pub fn new(name: &'static str, frame: impl FnMut() -> Option<RenderStats> + 'a) -> Self {
        Self {
            name,
            frame: Box::new(frame),
        }
    }

    /// `scene`, which shows `library`, rendered with `settings` by a renderer of its own.
    pub fn render(
        name: &'static str,
        library: &Arc<PatchLibrary>,
        scene: &'a Scene<'a>,
        settings: &'a Settings,
    ) -> Self {
        let mut renderer = Renderer::new(Arc::clone(library));
        Self::new(name, move || {
            Some(renderer.render(scene, settings).unwrap().stats)
        })
    }
}

/// Rounds rendered before measuring: the tessellation is cached and the buffers sized.
const WARM_UP_ROUNDS: usize = 5;

/// What [`measure`] recorded: per variant, per round, the frame's seconds and statistics.
pub struct Measured {
    names: Vec<&'static str>,
    seconds: Vec<Vec<f64>>,
    stats: Vec<Vec<Option<RenderStats>>>,
}

/// Renders `rounds` rounds of `variants` after a warm-up.
pub fn measure(variants: &mut [Variant], rounds: usize) -> Measured {
    if let Ok(name) = std::env::var("GLINT_BENCH_PROFILE") {
        profile(variants, &name);
    }
    let n = variants.len();
    let mut measured = Measured {
        names: variants.iter().map(|v| v.name).collect(),
        seconds: vec![Vec::with_capacity(rounds); n],
        stats: vec![Vec::with_capacity(rounds); n],
    };
    for round in 0..WARM_UP_ROUNDS + rounds {
        for k in (0..n).map(|k| (k + round) % n) {
            // Untimed: leaves the memory as this variant's frames do.
            (variants[k].frame)();
            let start = Instant::now();
            let stats = (variants[k].frame)();
            let seconds = start.elapsed().as_secs_f64();
            if round >= WARM_UP_ROUNDS {
                measured.seconds[k].push(seconds);
                measured.stats[k].push(stats);
            }
        }
    }
    measured
}

/// Renders only variant `name`, `GLINT_BENCH_PROFILE_FRAMES` frames (4 if unset), and exits:
/// what a profiler counts is then that variant's frames (and the setup before them).
fn profile(variants: &mut [Variant], name: &str) -> ! {
    let frames = std::env::var("GLINT_BENCH_PROFILE_FRAMES")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(4);
    let Some(variant) = variants.iter_mut().find(|v| v.name == name) else {
        let names: Vec<&str> = variants.iter().map(|v| v.name).collect();
        eprintln!("no variant {name}: this benchmark has {}", names.join(", "));
        std::process::exit(2);
    };
    for _ in 0..frames {
        (variant.frame)();
    }
    std::process::exit(0);
}

/// The median and quartiles of `values`.
fn quartiles(mut values: Vec<f64>) -> [f64; 3] {
    values.sort_by(f64::total_cmp);
    let at = |q: f64| values[((values.len() - 1) as f64 * q).round() as usize];
    [at(0.25), at(0.5), at(0.75)]
}

impl Measured {
    fn index(&self, name: &str) -> usize {
        self.names
            .iter()
            .position(|&n| n == name)
            .unwrap_or_else(|| panic!("no variant {name}"))
    }

    /// Prints each variant's median frame time, and for the renderer's frames the median of
    /// each stage and the samples covered.
    pub fn print_frames(&self, title: &str) {
        let rounds = self.seconds[0].len();
        println!("\n{title} (median of {rounds} rounds, ms)");
        // Each column as wide as its variant's name, and at least 15.
        let widths: Vec<usize> = self.names.iter().map(|n| n.len().max(15)).collect();
        print!("{:<14}", "stage");
        for (name, w) in self.names.iter().zip(&widths) {
            print!(" {name:>w$}");
        }
        println!();
        for stage in Stage::ALL {
            print!("{:<14}", stage.name());
            for (frames, w) in self.stats.iter().zip(&widths) {
                let seconds = |s: &RenderStats| s[stage].seconds;
                match frames.iter().map(|s| s.as_ref().map(seconds)).collect() {
                    Some(seconds) => print!(" {:>w$.3}", quartiles(seconds)[1] * 1e3),
                    None => print!(" {:>w$}", "-"),
                }
            }
            println!();
        }
        print!("{:<14}", "frame");
        for (seconds, w) in self.seconds.iter().zip(&widths) {
            print!(" {:>w$.3}", quartiles(seconds.clone())[1] * 1e3);
        }
        println!();
        for (label, stage) in [
            ("covered", Stage::Rasterize),
            ("supersampled", Stage::Supersample),
        ] {
            print!("{label:<14}");
            for (frames, w) in self.stats.iter().zip(&widths) {
                match &frames[0] {
                    Some(s) => print!(" {:>w$}", s[stage].pixels),
                    None => print!(" {:>w$}", "-"),
                }
            }
            println!();
        }
    }

    /// Prints, for each `(numerator, denominator)`, the median over rounds of the ratio of
    /// their frame times in the same round, with its quartiles.
    pub fn print_ratios(&self, title: &str, pairs: &[(&str, &str)]) {
        println!("\n{title} (per round, median and quartiles)");
        for &(numerator, denominator) in pairs {
            let (a, b) = (
                &self.seconds[self.index(numerator)],
                &self.seconds[self.index(denominator)],
            );
            let ratios = a.iter().zip(b).map(|(a, b)| a / b).collect();
            print_ratio(&format!("{numerator} / {denominator}"), ratios);
        }
    }

    /// Prints, for each `(numerator, denominator)`, the median over rounds of
    /// `(numerator frame − its stage) / denominator frame` from the same round, with its
    /// quartiles: the ratio were `stage` to take no time.
    // Only the trim benchmark leaves a stage out.
    #[allow(dead_code)]
    pub fn print_ratios_without(&self, stage: Stage, pairs: &[(&str, &str)]) {
        for &(numerator, denominator) in pairs {
            let k = self.index(numerator);
            let (a, b) = (&self.seconds[k], &self.seconds[self.index(denominator)]);
            let ratios = a.iter().zip(&self.stats[k]).zip(b).map(|((a, s), b)| {
                let spent = s.as_ref().map_or(0.0, |s| s[stage].seconds);
                (a - spent) / b
            });
            let label = format!("{numerator} − {stage} / {denominator}");
            print_ratio(&label, ratios.collect());
        }
    }
}

/// Prints `label` with the median and quartiles of the per-round `ratios`.
fn print_ratio(label: &str, ratios: Vec<f64>) {
    let [q1, median, q3] = quartiles(ratios);
    println!("{label:<40} {median:>6.3}   [{q1:.3}, {q3:.3}]");
}
