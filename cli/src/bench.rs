//! `glint bench`: measurements run from the command line, with progress bars and printed
//! tables. `glint bench accuracy` sweeps the accuracy ladder (see `glint::accuracy`); `glint
//! bench loop` times an edit to a written frame (`super::bench_loop`).

use std::fs;
use std::path::{Path, PathBuf};

use anyhow::anyhow;
use clap::{Args, Subcommand};
use indicatif::{ProgressBar, ProgressStyle};

use super::CliError;
use crate::{accuracy_csv as csv, accuracy_plot as plot};
use glint::accuracy::geometry::{frame_costs, mesh_errors, FrameCost, MeshError};
use glint::accuracy::scaling::{growth, Scaling, ScalingPoint, Series};
use glint::accuracy::sweep::{compare_presets, summarize, Summary, Sweep};
use glint::formats::atomic::write_atomically;
use glint::formats::load_patches;

/// Measure what accuracy costs in time, and how long an edit takes to reach a frame.
#[derive(Debug, Args)]
pub struct BenchArgs {
    #[command(subcommand)]
    bench: Bench,
}

#[derive(Debug, Subcommand)]
enum Bench {
    Accuracy(AccuracyArgs),
    Loop(super::bench_loop::LoopArgs),
}

/// Sweep the accuracy ladder on the analytic sphere and time frames as they scale.
///
/// Every combination of tessellation density (segments per knot span, or a screen tolerance),
/// frame mode (interpolated, exact, refined) and anti-aliasing (none, analytic, 2×2 to 4×4
/// supersampling, adaptive 4×4), plus the preview and final presets, renders the exact NURBS unit sphere in
/// sixteen views at each --resolution: five highlight stacks near the centre (identity,
/// translate+scale, split, square, a Boolean crescent) and eleven hard ones (highlights 30°, 50°
/// and 70° off centre, at and near the pole, near the border of a 75° wide-angle view, a thin
/// crescent, ε = 0.001, a split into four, a keyed translation at fractional frames). Then the
/// presets run side by side at --target-resolution. Each render is compared with the analytic
/// sphere ray-cast through 8×8 samples per pixel, 32×32 on edges: 1 − IoU and mean boundary
/// displacement in pixels of the highlight matte and of the silhouette (the frame's alpha), and
/// the largest normal error in degrees; its time is the median of --repeats frames. The tables
/// give the worst view of each rung beside the mean, and the Pareto front is drawn on the worst.
///
/// Then the geometry alone (tessellation density against position and normal error and
/// tessellation time; the G-buffer cost of exact and refined frames) and the scaling of frame
/// time with resolution, with copies of the teapot, and with 1 and 2 threads (the fitted
/// log-log growth).
///
/// Prints the tables and writes to --out: accuracy.csv (every view), accuracy_summary.csv
/// (over views, Pareto front marked), accuracy.svg (error against time), geometry.csv,
/// frame_cost.csv and scaling.csv.
#[derive(Debug, Args)]
#[command(after_help = "Examples:
  glint bench accuracy --quick
  glint bench accuracy --presets-only --target-resolution 256
  glint bench accuracy --out docs/accuracy --resolution 256,512 --target-resolution 1024")]
pub struct AccuracyArgs {
    /// Directory for the CSV files and the plot (created if missing; files replaced atomically)
    #[arg(long, value_name = "DIR", default_value = "out/accuracy")]
    out: PathBuf,
    /// A reduced sweep: 2 densities, 2 frame modes, 2 edge modes, 3 views, the presets, and
    /// smaller scaling runs (default resolutions 128 and 256)
    #[arg(long)]
    quick: bool,
    /// Only the presets side by side with their candidates at --target-resolution, every view
    /// listed; writes presets.csv
    #[arg(long)]
    presets_only: bool,
    /// Image sides for the whole ladder, square (comma-separated or repeated) [default: 256,512;
    /// with --quick 128,256]
    #[arg(
        long = "resolution",
        value_name = "SIDE",
        value_delimiter = ',',
        value_parser = clap::value_parser!(u32).range(16..=4096)
    )]
    resolutions: Vec<u32>,
    /// Image side for the presets side by side on every view (with the candidates they were
    /// chosen from) [default: 1024; with --quick 256]
    #[arg(long, value_name = "SIDE", value_parser = clap::value_parser!(u32).range(16..=4096))]
    target_resolution: Option<u32>,
    /// Timed frames per setting; the median is reported
    #[arg(long, value_name = "N", default_value_t = 3,
          value_parser = clap::value_parser!(u32).range(1..=1000))]
    repeats: u32,
    /// Worker threads per frame (0: one per core); the thread series always runs 1 and 2
    #[arg(long, value_name = "N", default_value_t = 0,
          value_parser = clap::value_parser!(u32).range(0..=256))]
    threads: u32,
    /// The model copied for the scaling series
    #[arg(long, value_name = "FILE", default_value = "patches/teapot.bpt")]
    teapot: PathBuf,
}

pub fn run(args: &BenchArgs) -> Result<(), CliError> {
    match &args.bench {
        Bench::Accuracy(args) => accuracy(args),
        Bench::Loop(args) => super::bench_loop::run(args),
    }
}

fn bar(length: usize, what: &str) -> ProgressBar {
    let bar = ProgressBar::new(length as u64);
    bar.set_style(
        ProgressStyle::with_template("{prefix:>9} [{bar:30}] {pos}/{len} {elapsed} {msg}")
            .expect("the template is valid")
            .progress_chars("=> "),
    );
    bar.set_prefix(what.to_string());
    bar
}

fn accuracy(args: &AccuracyArgs) -> Result<(), CliError> {
    let model =
        std::sync::Arc::new(load_patches(&args.teapot).map_err(|e| CliError::BadInput(e.into()))?);
    // Before the long measurements: an output directory that cannot be made fails at once.
    fs::create_dir_all(&args.out)
        .map_err(|e| CliError::BadInput(anyhow!("cannot create {}: {e}", args.out.display())))?;
    let (repeats, threads) = (args.repeats as usize, args.threads as usize);
    let sizes = match (args.resolutions.is_empty(), args.quick) {
        (false, _) => args.resolutions.clone(),
        (true, false) => vec![256, 512],
        (true, true) => vec![128, 256],
    };
    let sweep = if args.quick {
        Sweep::quick(sizes, repeats, threads)
    } else {
        Sweep::full(sizes, repeats, threads)
    };
    let target_size = args
        .target_resolution
        .unwrap_or(if args.quick { 256 } else { 1024 });
    let presets = Sweep::presets(target_size, repeats, threads);
    let failed = |e: glint::render::RenderError| CliError::Failed(e.into());
    if args.presets_only {
        return presets_only(&presets, &args.out);
    }

    let progress = bar(sweep.len() + presets.len(), "sweep");
    let mut measurements = Vec::with_capacity(sweep.len() + presets.len());
    for sweep in [&sweep, &presets] {
        measurements.extend(
            sweep
                .run(|m| {
                    progress.set_message(format!("{} {} {}", m.size, m.case, m.rung));
                    progress.inc(1);
                })
                .map_err(failed)?,
        );
    }
    progress.finish_with_message("done");
    let summaries = summarize(&measurements);

    let (segments, cost_size): (&[u32], u32) = if args.quick {
        (&[2, 4, 8, 16], 256)
    } else {
        (&[1, 2, 4, 8, 16, 32, 64], 1024)
    };
    let progress = bar(2, "geometry");
    let meshes = mesh_errors(segments, repeats);
    progress.inc(1);
    let costs = frame_costs(cost_size, repeats, threads).map_err(failed)?;
    progress.finish_with_message("done");

    let scaling = if args.quick {
        Scaling {
            sizes: vec![128, 256, 512, 1024],
            copies: vec![1, 2, 4],
            threads: vec![1, 2],
            repeats,
            workers: threads,
        }
    } else {
        Scaling {
            sizes: vec![256, 512, 1024, 2048],
            copies: vec![1, 2, 4, 8],
            threads: vec![1, 2],
            repeats,
            workers: threads,
        }
    };
    let progress = bar(scaling.len(), "scaling");
    let points = scaling
        .run(&model, |p| {
            progress.set_message(format!("{} {} {}", p.series.name(), p.preset, p.x));
            progress.inc(1);
        })
        .map_err(failed)?;
    progress.finish_with_message("done");

    print_sweep(&summaries);
    print_geometry(&meshes, &costs);
    print_scaling(&points);

    let files = [
        ("accuracy.csv", csv::sweep(&measurements)),
        ("accuracy_summary.csv", csv::summary(&summaries)),
        (
            "accuracy.svg",
            plot::error_against_time(&summaries).map_err(|e| CliError::Failed(anyhow!(e)))?,
        ),
        ("geometry.csv", csv::mesh_errors(&meshes)),
        ("frame_cost.csv", csv::frame_costs(&costs)),
        ("scaling.csv", csv::scaling(&points)),
    ];
    write_all(&args.out, &files).map_err(CliError::Failed)?;
    println!("\nwrote {} files to {}", files.len(), args.out.display());
    Ok(())
}

/// `--presets-only`: the presets and their candidates on every view, one table row per view.
fn presets_only(presets: &Sweep, out: &Path) -> Result<(), CliError> {
    let progress = bar(presets.len(), "presets");
    let measurements = presets
        .run(|m| {
            progress.set_message(format!("{} {}", m.case, m.rung));
            progress.inc(1);
        })
        .map_err(|e| CliError::Failed(e.into()))?;
    progress.finish_with_message("done");
    println!(
        "\n{:<34} {:<36} {:>9} {:>8} {:>9} {:>8} {:>9}",
        "view", "rung", "1-IoU", "bound px", "sil 1-IoU", "sil px", "ms/frame"
    );
    for m in &measurements {
        println!(
            "{:<34} {:<36} {:>9.2e} {:>8.3} {:>9.2e} {:>8.3} {:>9.2}",
            m.case.to_string(),
            format!("{} {}", m.rung.preset().unwrap_or(""), m.rung),
            m.errors.one_minus_iou,
            m.errors.boundary_pixels,
            m.errors.silhouette_one_minus_iou,
            m.errors.silhouette_pixels,
            1e3 * m.frame_seconds
        );
    }
    print_sweep(&summarize(&measurements));
    let files = [("presets.csv", csv::sweep(&measurements))];
    write_all(out, &files).map_err(CliError::Failed)?;
    println!("\nwrote {} to {}", files[0].0, out.display());
    Ok(())
}

fn write_all(dir: &Path, files: &[(&str, String)]) -> anyhow::Result<()> {
    for (name, text) in files {
        write_atomically(&dir.join(name), |out| {
            use std::io::Write;
            out.write_all(text.as_bytes()).map_err(|e| e.to_string())
        })?;
    }
    Ok(())
}

fn print_sweep(summaries: &[Summary]) {
    println!(
        "\nAccuracy ladder on the analytic sphere (mean and worst over views; * Pareto front of the worst)"
    );
    println!(
        "{:>5} {:<8} {:<12} {:<13} {:<9} {:>7} {:>9} {:>9} {:>8} {:>8} {:>9} {:>8} {:>8} {:>8} {:>9}",
        "size",
        "preset",
        "density",
        "frames",
        "antialias",
        "tris",
        "1-IoU",
        "worst",
        "bound px",
        "worst px",
        "sil worst",
        "sil px",
        "max N°",
        "mean N°",
        "ms/frame"
    );
    for s in summaries {
        println!(
            "{:>5} {:<8} {:<12} {:<13} {:<9} {:>7} {:>9.2e} {:>9.2e} {:>8.3} {:>8.3} {:>9.2e} {:>8.3} {:>8.2} {:>8.3} {:>9.2} {}",
            s.size,
            s.rung.preset().unwrap_or(""),
            s.rung.density.to_string(),
            s.rung.frames.to_string(),
            s.rung.antialias.to_string(),
            s.triangles,
            s.mean_one_minus_iou,
            s.worst_one_minus_iou,
            s.mean_boundary_pixels,
            s.worst_boundary_pixels,
            s.worst_silhouette_one_minus_iou,
            s.worst_silhouette_pixels,
            s.max_normal_degrees,
            s.mean_normal_degrees,
            1e3 * s.frame_seconds,
            if s.pareto { "*" } else { "" }
        );
    }
    println!("\nPresets side by side (same run)");
    println!(
        "{:>5} {:>15} {:>16} {:>16} {:>12} {:>12} {:>9}",
        "size",
        "final mean IoU",
        "final worst IoU",
        "worst silhouette",
        "preview ms",
        "final ms",
        "final/preview"
    );
    for c in compare_presets(summaries) {
        println!(
            "{:>5} {:>15.5} {:>16.5} {:>16.5} {:>12.2} {:>12.2} {:>8.2}x",
            c.size,
            c.final_mean_iou,
            c.final_worst_iou,
            c.final_worst_silhouette_iou,
            1e3 * c.preview_seconds,
            1e3 * c.final_seconds,
            c.speedup()
        );
    }
}

fn print_geometry(meshes: &[MeshError], costs: &[FrameCost]) {
    println!("\nTessellated unit sphere against the analytic one");
    println!(
        "{:>9} {:>9} {:>14} {:>11} {:>14}",
        "seg/span", "tris", "max position", "max normal°", "tessellate ms"
    );
    for m in meshes {
        println!(
            "{:>9} {:>9} {:>14.3e} {:>11.4} {:>14.3}",
            m.segments,
            m.triangles,
            m.max_position_error,
            m.max_normal_degrees,
            1e3 * m.tessellate_seconds
        );
    }
    println!("\nWhat frames cost (16 segments per span, no anti-aliasing)");
    println!(
        "{:<13} {:>12} {:>14} {:>10} {:>15}",
        "frames", "NURBS evals", "G-buffer ns/px", "ms/frame", "vs interpolated"
    );
    let base = costs.first().map_or(1.0, |c| c.frame_seconds);
    for c in costs {
        println!(
            "{:<13} {:>12} {:>14.1} {:>10.2} {:>14.2}x",
            c.frames.to_string(),
            c.exact_frames,
            c.gbuffer_ns_per_pixel,
            1e3 * c.frame_seconds,
            c.frame_seconds / base
        );
    }
}

fn print_scaling(points: &[ScalingPoint]) {
    println!("\nScaling (teapot)");
    println!(
        "{:<11} {:<8} {:>10} {:>9} {:>10}",
        "series", "preset", "x", "tris", "ms/frame"
    );
    for p in points {
        println!(
            "{:<11} {:<8} {:>10} {:>9} {:>10.2}",
            p.series.name(),
            p.preset,
            p.x,
            p.triangles,
            1e3 * p.frame_seconds
        );
    }
    println!("\nFitted growth (least-squares slope in log-log: time ∝ x^slope)");
    for (series, what) in [
        (Series::Resolution, "pixels"),
        (Series::Patches, "patches"),
        (Series::Threads, "threads"),
    ] {
        for preset in ["preview", "final"] {
            if let Some(slope) = growth(points, series, preset) {
                println!("  {preset:<8} time against {what:<8} slope {slope:.2}");
            }
        }
    }
}
