//! `glint bench loop`: the animator's loop timed — from a saved edit of a shot to its frame
//! written — for an edit of a highlight against an edit of the camera, side by side.

use std::fs;
use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::anyhow;
use clap::Args;

use super::CliError;
use glint::formats::atomic::Durability;
use glint::job::{JobError, Overrides, RenderJob};
use glint::render::{RenderStats, Stage};

/// Time the animator's loop: from an edit saved to a shot file to its frame written.
///
/// Two copies of a one-frame shot of the teapot (the turntable's look: a highlight on every
/// patch and a squared one on the body, outlines, the preview preset at 640×360) are written
/// to --out as highlight.ron and camera.ron, their frames beside them. Round after round, one copy gets a highlight-only edit (the body highlight's ε)
/// and the other a camera edit (the eye moves), in turns, each round starting with the other
/// edit; each edit is saved, the shot loaded again (the model kept, as `glint render --watch`
/// does), its frame rendered and written (PNG, atomically). The highlight edit re-runs only the
/// stages it touches on the kept G-buffer; the camera edit runs every stage.
///
/// Prints, for each edit, the median and quartiles over rounds of each step — loading the
/// shot again, rendering, writing — and of the whole, the stages that ran and were reused, and
/// the per-round ratio of the camera edit's time to the highlight edit's.
#[derive(Debug, Args)]
#[command(after_help = "Examples:
  glint bench loop
  glint bench loop --rounds 20 --threads 1")]
pub struct LoopArgs {
    /// Rounds measured, after 5 that warm up
    #[arg(long, value_name = "N", default_value_t = 100,
          value_parser = clap::value_parser!(u32).range(1..=100_000))]
    rounds: u32,
    /// Worker threads per frame (0: one per core)
    #[arg(long, value_name = "N", default_value_t = 0,
          value_parser = clap::value_parser!(u32).range(0..=256))]
    threads: u32,
    /// Directory for the two shots and their frames (created if missing)
    #[arg(long, value_name = "DIR", default_value = "out/bench_loop")]
    out: PathBuf,
    /// The model
    #[arg(long, value_name = "FILE", default_value = "patches/teapot.bpt")]
    teapot: PathBuf,
}

/// Rounds run before measuring: the thread pool started, the buffers sized.
const WARM_UP_ROUNDS: usize = 5;

/// The two edits, in the order of the printed tables.
const EDITS: [Edit; 2] = [Edit::Highlight, Edit::Camera];

/// What an edit changes in the shot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Edit {
    /// The body highlight's ε: 0.025 and 0.03 in turn.
    Highlight,
    /// The eye: two points 2° apart on the orbit in turn.
    Camera,
}

impl Edit {
    fn name(self) -> &'static str {
        match self {
            Edit::Highlight => "highlight",
            Edit::Camera => "camera",
        }
    }

    /// The shot's text after the `n`-th edit of this kind.
    fn shot(self, n: usize, model: &Path) -> String {
        let flip = n % 2 == 1;
        let epsilon = match (self, flip) {
            (Edit::Highlight, true) => 0.03,
            _ => 0.025,
        };
        let eye = match (self, flip) {
            (Edit::Camera, true) => (-1.252, -8.911),
            _ => (-1.563, -8.863),
        };
        shot_text(self.name(), model, epsilon, eye)
    }
}

/// A one-frame shot of the teapot with the turntable's look, its body highlight's ε and the
/// eye's (x, y) given, written to `NAME.1.png`.
fn shot_text(name: &str, model: &Path, epsilon: f64, (x, y): (f64, f64)) -> String {
    format!(
        r#"Shot(
    resolution: (640, 360),
    frames: (1, 1),
    fps: 24,
    output: "{name}.#.png",
    instances: [(name: "teapot", file: {model:?}, material: "porcelain")],
    materials: {{
        "porcelain": Cel(
            base: (0.10, 0.16, 0.32),
            bands: [(0.0, (0.30, 0.45, 0.80)), (0.55, (0.45, 0.62, 0.95))],
        ),
    }},
    camera: (eye: ({x}, {y}, 4.5), target: (0.0, 0.0, 1.4), projection: Perspective(fov_y_degrees: 32.0)),
    light: Directional(towards: (-0.352, -0.553, 0.755)),
    highlights: [
        (patches: "teapot/*", expr: Layer((stack: [], epsilon: 0.01, colour: (1.0, 1.0, 1.0)))),
        (
            patches: ["teapot/[4-9]", "teapot/1[01]"],
            expr: Layer((
                stack: [
                    Translate(alpha: 0.341, beta: 0.302),
                    Scale(delta: 0.5, axis: V),
                    Square(sigma: 0.2, n: 2.0),
                ],
                epsilon: {epsilon},
                colour: (1.0, 0.98, 0.9),
            )),
        ),
    ],
    render: (
        preset: Preview,
        outlines: (width: 2.0, colour: (0.05, 0.04, 0.1), crease_degrees: 70.0),
    ),
)
"#
    )
}

/// The seconds of one step of the loop.
#[derive(Clone, Copy, Debug, Default)]
struct Steps {
    reload: f64,
    render: f64,
    write: f64,
}

impl Steps {
    fn total(&self) -> f64 {
        self.reload + self.render + self.write
    }
}

/// One edit's shot and job.
struct Subject {
    edit: Edit,
    path: PathBuf,
    job: RenderJob,
    edits: usize,
    last: Option<RenderStats>,
}

impl Subject {
    fn new(edit: Edit, dir: &Path, model: &Path, threads: usize) -> Result<Self, CliError> {
        let path = dir.join(format!("{}.ron", edit.name()));
        write(&path, &edit.shot(0, model))?;
        let overrides = Overrides {
            threads: Some(threads),
            ..Overrides::default()
        };
        let mut job = RenderJob::load(&path, &overrides).map_err(bad)?;
        // Frames written as `glint render --watch` writes them.
        job.set_durability(Durability::Unsynced);
        job.check_writable().map_err(bad)?;
        let image = job.render_frame(1.0).map_err(failed)?;
        job.write_frame(1, &image).map_err(failed)?;
        Ok(Self {
            edit,
            path,
            job,
            edits: 0,
            last: None,
        })
    }

    /// Saves the next edit, then times loading the shot again, rendering and writing.
    fn step(&mut self, model: &Path) -> Result<Steps, CliError> {
        self.edits += 1;
        write(&self.path, &self.edit.shot(self.edits, model))?;
        let start = Instant::now();
        self.job.reload().map_err(bad)?;
        let loaded = Instant::now();
        let image = self.job.render_frame(1.0).map_err(failed)?;
        let rendered = Instant::now();
        self.job.write_frame(1, &image).map_err(failed)?;
        let written = Instant::now();
        self.last = Some(image.stats);
        Ok(Steps {
            reload: (loaded - start).as_secs_f64(),
            render: (rendered - loaded).as_secs_f64(),
            write: (written - rendered).as_secs_f64(),
        })
    }
}

pub(super) fn run(args: &LoopArgs) -> Result<(), CliError> {
    fs::create_dir_all(&args.out)
        .map_err(|e| CliError::BadInput(anyhow!("cannot create {}: {e}", args.out.display())))?;
    let model = std::path::absolute(&args.teapot)
        .map_err(|e| CliError::BadInput(anyhow!("{}: {e}", args.teapot.display())))?;
    let threads = args.threads as usize;
    let mut subjects = [
        Subject::new(EDITS[0], &args.out, &model, threads)?,
        Subject::new(EDITS[1], &args.out, &model, threads)?,
    ];
    let rounds = args.rounds as usize;
    let mut measured: [Vec<Steps>; 2] = [Vec::with_capacity(rounds), Vec::with_capacity(rounds)];
    for round in 0..WARM_UP_ROUNDS + rounds {
        for k in [round % 2, (round + 1) % 2] {
            let steps = subjects[k].step(&model)?;
            if round >= WARM_UP_ROUNDS {
                measured[k].push(steps);
            }
        }
    }
    print_report(&subjects, &measured, rounds);
    Ok(())
}

fn print_report(subjects: &[Subject; 2], measured: &[Vec<Steps>; 2], rounds: usize) {
    println!(
        "\nFrom a saved edit to a written frame: the teapot, 640×360, preview \
         (median [quartiles] of {rounds} rounds, ms)"
    );
    println!(
        "{:<10} {:>22} {:>22} {:>22} {:>22}",
        "edit", "load shot", "render", "write PNG", "total"
    );
    for (subject, steps) in subjects.iter().zip(measured) {
        let column = |f: fn(&Steps) -> f64| {
            let [q1, median, q3] = quartiles(steps.iter().map(f).collect());
            format!("{:.2} [{:.2}, {:.2}]", median * 1e3, q1 * 1e3, q3 * 1e3)
        };
        println!(
            "{:<10} {:>22} {:>22} {:>22} {:>22}",
            subject.edit.name(),
            column(|s| s.reload),
            column(|s| s.render),
            column(|s| s.write),
            column(Steps::total),
        );
    }
    println!("\nStages of the last frame of each edit");
    for subject in subjects {
        if let Some(stats) = &subject.last {
            let names = |pick: fn(&RenderStats, Stage) -> bool| {
                let names: Vec<&str> = Stage::ALL
                    .into_iter()
                    .filter(|&s| pick(stats, s))
                    .map(Stage::name)
                    .collect();
                if names.is_empty() {
                    "none".to_string()
                } else {
                    names.join(", ")
                }
            };
            println!(
                "{:<10} ran {}; reused {}",
                subject.edit.name(),
                names(RenderStats::ran),
                names(RenderStats::reused)
            );
        }
    }
    println!("\nRatios per round (median [quartiles])");
    for (what, f) in [
        ("total", Steps::total as fn(&Steps) -> f64),
        ("render", |s: &Steps| s.render),
    ] {
        let [q1, median, q3] = quartiles(
            measured[1]
                .iter()
                .zip(&measured[0])
                .map(|(camera, highlight)| f(camera) / f(highlight))
                .collect(),
        );
        println!("camera / highlight, {what:<7} {median:>7.2}   [{q1:.2}, {q3:.2}]");
    }
}

/// The median and quartiles of `values`.
fn quartiles(mut values: Vec<f64>) -> [f64; 3] {
    values.sort_by(f64::total_cmp);
    let at = |q: f64| values[((values.len() - 1) as f64 * q).round() as usize];
    [at(0.25), at(0.5), at(0.75)]
}

/// Saves `text` at `path` as an editor does: a new file renamed over the old one.
fn write(path: &Path, text: &str) -> Result<(), CliError> {
    let temporary = path.with_extension("ron.tmp");
    fs::write(&temporary, text)
        .and_then(|()| fs::rename(&temporary, path))
        .map_err(|e| CliError::Failed(anyhow!("cannot write {}: {e}", path.display())))
}

fn bad(e: JobError) -> CliError {
    CliError::BadInput(e.into())
}

fn failed(e: JobError) -> CliError {
    CliError::Failed(e.into())
}
