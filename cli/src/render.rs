//! `glint render`: the frames of a shot, written atomically, for a person at a terminal or a
//! render farm task.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::Instant;

use clap::Args;
use indicatif::{ProgressBar, ProgressStyle};

use super::stats_report::stats_report;
use super::CliError;
use glint::job::{parse_frames, parse_memory_size, JobError, Overrides, RenderJob, Scrutiny};
use glint::shot::{Aov, Preset};

/// Render the frames of a shot to PNG files.
///
/// Every frame is written atomically (to a hidden temporary file, then renamed), so a frame file
/// that exists is complete. Output is deterministic: the same frame gives the same bytes on any
/// machine and with any number of threads, so a farm task can be retried anywhere. Exit code 0
/// when every requested frame was written (or, with --skip-existing, already there), 2 for bad
/// input (the shot, the options, an output folder that cannot be written), 1 when rendering or
/// writing failed.
#[derive(Debug, Args)]
#[command(after_help = "Examples:
  glint render shots/teapot_turntable.ron
  glint render shots/sphere_ops.ron --frames 1-24 --preset preview --size 320x320
  glint render shots/crescent.ron --frames 1-48x2 --aov matte,patch_id --stats
  glint render shots/line_styles.ron --frames 1 --svg                            # lines as SVG too
  glint render shots/teapot_turntable.ron --frames 49-96 --skip-existing --quiet   # a farm task
  glint render shots/teapot_turntable.ron --frames 12 --preset preview --watch     # tune, save, look

Frame lists: 12 | 1-48 | 1-48x2 (every second frame) | 1,5,9-12.")]
pub struct RenderArgs {
    /// The shot file (RON)
    shot: PathBuf,
    #[command(flatten)]
    target: Target,
    /// Worker threads [default: one per core]
    #[arg(long, value_name = "N")]
    threads: Option<usize>,
    /// The most memory a frame may take, like 512M or 8G: a render whose frames would need
    /// more (estimated from the size, supersampling and mesh before anything is rendered) is
    /// refused [default: three quarters of the machine's memory, or of its control group's
    /// limit]
    #[arg(long, value_name = "SIZE", value_parser = parse_memory_size)]
    max_memory: Option<u64>,
    /// Leave frames already rendered (resume an interrupted render): `current` (the default)
    /// skips a frame only when each of its files is a regular file stamped with the frame's
    /// fingerprint — made from the shot's inputs as they are now — so an edited key renders
    /// again exactly the frames it changes; `any` skips every frame whose colour file exists
    #[arg(long, value_name = "WHICH", num_args = 0..=1, require_equals = true, default_missing_value = "current", value_enum)]
    skip_existing: Option<SkipExisting>,
    /// Append one JSON line per frame written to FILE: frame, path, fingerprint, seconds by
    /// stage, peak memory of the process so far, host
    #[arg(long, value_name = "FILE.jsonl")]
    report: Option<PathBuf>,
    /// Print per-stage statistics (pixels and time) for every frame
    #[arg(long)]
    stats: bool,
    /// Print nothing but errors
    #[arg(long)]
    quiet: bool,
    /// Render, then render again whenever the shot, an include, a patch file or a texture
    /// changes, until Ctrl-C: one line per render, one error line for a broken edit (the next
    /// good save renders). An edit that keeps the camera and settings re-runs only the stages
    /// it touches
    #[arg(long, conflicts_with_all = ["skip_existing", "report"])]
    watch: bool,
}

/// What is rendered: the frames, where they go, their size, preset and AOVs — the options
/// `glint render` and `glint verify` share, so that a check looks at what a render wrote.
#[derive(Debug, Args)]
pub(super) struct Target {
    /// Frames to render [default: the shot's whole range]
    #[arg(long, value_name = "SPEC", value_parser = frame_list_arg, allow_hyphen_values = true)]
    frames: Option<FrameListArg>,
    /// Output path pattern; a run of # becomes the zero-padded frame number. Relative to the
    /// shot file's folder unless absolute [default: the shot's `output`]
    #[arg(long, value_name = "PATTERN")]
    out: Option<PathBuf>,
    /// Image size instead of the shot's resolution
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Accuracy preset instead of the shot's; the shot's explicit settings still refine it
    #[arg(long, value_enum)]
    preset: Option<PresetArg>,
    /// Extra images instead of the shot's list, comma-separated: matte, patch_id, depth,
    /// normal, uv, n_dot_h, n_dot_l (the N·L' each patch's tone reads), outline (the lines alone,
    /// with alpha) (or none). Written as PNGs
    /// beside the frame and as layers of one EXR
    #[arg(long, value_name = "LIST", value_parser = parse_aov_list)]
    aov: Option<AovList>,
    /// Also write each frame's lines as vector strokes, NAME.####.svg beside its PNG: one path
    /// per stroke in pixel coordinates, grouped by kind and by part (docs/lines-for-2d.md)
    #[arg(long)]
    svg: bool,
}

impl Target {
    /// The job's overrides for these options, with `threads` worker threads and a memory
    /// ceiling of `max_memory` bytes.
    pub(super) fn overrides(&self, threads: Option<usize>, max_memory: Option<u64>) -> Overrides {
        Overrides {
            max_memory,
            frames: self.frames.as_ref().map(|f| f.0.clone()),
            size: self.size,
            preset: self.preset.map(Preset::from),
            aovs: self.aov.as_ref().map(|a| a.0.clone()),
            threads,
            output: self.out.clone(),
            svg: self.svg,
        }
    }
}

/// Which frames `--skip-existing` leaves.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum SkipExisting {
    /// Frames whose files are all there, whole, and made from the current inputs
    Current,
    /// Frames whose colour file exists, whatever made it
    Any,
}

#[derive(Clone, Copy, Debug, clap::ValueEnum)]
pub(super) enum PresetArg {
    /// Fast feedback: coarse tessellation, interpolated frames, no anti-aliasing
    Preview,
    /// Finished frames: fine tessellation, refined frames, adaptive anti-aliasing
    Final,
}

impl From<PresetArg> for Preset {
    fn from(preset: PresetArg) -> Self {
        match preset {
            PresetArg::Preview => Preset::Preview,
            PresetArg::Final => Preset::Final,
        }
    }
}

pub(super) fn parse_size(text: &str) -> Result<(u32, u32), String> {
    text.split_once(['x', 'X'])
        .and_then(|(w, h)| Some((w.trim().parse().ok()?, h.trim().parse().ok()?)))
        .filter(|&(w, h): &(u32, u32)| w > 0 && h > 0)
        .ok_or_else(|| format!("expected a size WxH such as 1280x720, got '{text}'"))
}

/// Frames as `--frames` lists them.
#[derive(Clone, Debug)]
pub(super) struct FrameListArg(pub Vec<i64>);

pub(super) fn frame_list_arg(text: &str) -> Result<FrameListArg, String> {
    parse_frames(text).map(FrameListArg)
}

/// AOVs as `--aov` lists them.
#[derive(Clone, Debug)]
pub(super) struct AovList(pub Vec<Aov>);

pub(super) fn parse_aov_list(text: &str) -> Result<AovList, String> {
    if text.trim() == "none" {
        return Ok(AovList(Vec::new()));
    }
    text.split(',')
        .map(|name| name.trim().parse())
        .collect::<Result<_, _>>()
        .map(AovList)
}

pub fn run(args: &RenderArgs) -> Result<(), CliError> {
    let overrides = args.target.overrides(args.threads, args.max_memory);
    if args.watch {
        let printing = super::watch::Printing {
            stats: args.stats,
            quiet: args.quiet,
        };
        return super::watch::run(&args.shot, &overrides, printing);
    }
    let failed = |e: JobError| {
        if e.is_bad_input() {
            CliError::BadInput(e.into())
        } else {
            CliError::Failed(e.into())
        }
    };
    let mut job = RenderJob::load(&args.shot, &overrides).map_err(failed)?;
    job.check_writable().map_err(failed)?;

    let frames = job.frames().to_vec();
    let log = Log::new(args.quiet, frames.len());
    let (mut written, mut skipped) = (0usize, 0usize);
    let started = Instant::now();
    for frame in frames {
        let path = job.frame_path(frame);
        let done = match args.skip_existing {
            None => false,
            Some(SkipExisting::Any) => path.exists(),
            Some(SkipExisting::Current) => job.frame_problems(frame, Scrutiny::Stamp).is_empty(),
        };
        if done {
            job.clear_stale_temporaries(frame).map_err(failed)?;
            skipped += 1;
            log.frame(format!("frame {frame}: {} exists, skipped", path.display()));
            continue;
        }
        let frame_started = Instant::now();
        let image = job.render_frame(frame as f64).map_err(failed)?;
        job.write_frame(frame, &image).map_err(failed)?;
        written += 1;
        if let Some(report) = &args.report {
            super::report::append(report, &job, frame, &image.stats, frame_started.elapsed())
                .map_err(CliError::Failed)?;
        }
        let seconds = frame_started.elapsed().as_secs_f64();
        log.frame(format!(
            "frame {frame}: {} ({:.0} ms)",
            path.display(),
            seconds * 1e3
        ));
        if args.stats {
            log.always(stats_report(frame, &image.stats));
        }
    }
    let frames = |n: usize| {
        if n == 1 {
            "1 frame".to_string()
        } else {
            format!("{n} frames")
        }
    };
    log.finish(format!(
        "{} written, {skipped} skipped, in {:.1} s",
        frames(written),
        started.elapsed().as_secs_f64()
    ));
    Ok(())
}

/// Progress: a bar on a terminal, one line per frame otherwise (farm logs), nothing when quiet.
struct Log {
    bar: Option<ProgressBar>,
    quiet: bool,
}

impl Log {
    fn new(quiet: bool, frames: usize) -> Self {
        let bar = (!quiet && std::io::stderr().is_terminal()).then(|| {
            let bar = ProgressBar::new(frames as u64);
            bar.set_style(
                ProgressStyle::with_template("{bar:40} {pos}/{len} frames, {eta} left  {msg}")
                    .unwrap_or_else(|_| ProgressStyle::default_bar()),
            );
            bar
        });
        Self { bar, quiet }
    }

    /// A finished (or skipped) frame.
    fn frame(&self, line: String) {
        match &self.bar {
            Some(bar) => {
                bar.set_message(line);
                bar.inc(1);
            }
            None if !self.quiet => println!("{line}"),
            None => {}
        }
    }

    /// A report asked for explicitly, printed even when quiet.
    fn always(&self, text: String) {
        match &self.bar {
            Some(bar) => bar.println(text),
            None => println!("{text}"),
        }
    }

    fn finish(self, line: String) {
        if let Some(bar) = self.bar {
            bar.finish_and_clear();
        }
        if !self.quiet {
            println!("{line}");
        }
    }
}
