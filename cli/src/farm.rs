//! `glint farm slurm`: a shot's frames as a Slurm job array — each task renders its chunk and
//! is requeued when it fails — and a task after it that verifies the whole shot.

use std::path::{Path, PathBuf};
use std::process::Command;

use anyhow::{anyhow, Context};
use clap::{Args, Subcommand};

use super::render::{frame_list_arg, parse_size, FrameListArg, PresetArg};
use super::{write_stdout, CliError};
use glint::job::{frame_spec, Overrides, RenderJob};
use glint::shot::Preset;

/// Render a shot on a render farm.
#[derive(Debug, Args)]
pub struct FarmArgs {
    #[command(subcommand)]
    manager: Manager,
}

#[derive(Debug, Subcommand)]
enum Manager {
    Slurm(SlurmArgs),
}

/// Write (or submit) the Slurm job array that renders a shot, and its verification.
///
/// The frames are cut into chunks of --chunk frames, one array task each. A task renders its
/// chunk with `glint render --frames CHUNK --threads $SLURM_CPUS_PER_TASK --skip-existing`, so a
/// retry renders only what is missing or stale, and logs one line per frame; when it fails it
/// requeues itself, up to --retries times. The memory each task asks for is glint's estimate
/// for the shot's size and preset (with a margin) unless --mem is given. A last job, which
/// starts when every task has ended, runs `glint verify` on the whole shot and fails when a
/// frame is missing, broken or stale, printing the frames to render again.
///
/// --print (the default) prints the array's script; --submit submits it and the verification
/// with sbatch and prints their job ids. Paths in the script are absolute, so it can be run
/// from anywhere on the farm's shared disk.
#[derive(Debug, Args)]
#[command(after_help = "Examples:
  glint farm slurm shots/teapot_turntable.ron --chunk 24 --cpus 8
  glint farm slurm shots/teapot_turntable.ron --chunk 12 --cpus 4 --partition render --submit
  glint farm slurm shots/sphere_ops.ron --frames 1-48 --size 1920x1080 --mem 6G --retries 3 --submit

Other managers take the same contract: give each task a frame list (OpenCue's #FRAME_START#-#FRAME_END# or Deadline's <STARTFRAME>-<ENDFRAME>), run glint render with --skip-existing, and glint verify at the end.")]
struct SlurmArgs {
    /// The shot file (RON)
    shot: PathBuf,
    /// Frames to render [default: the shot's whole range]
    #[arg(long, value_name = "SPEC", value_parser = frame_list_arg, allow_hyphen_values = true)]
    frames: Option<FrameListArg>,
    /// Frames per array task
    #[arg(long, value_name = "N", default_value_t = 8, value_parser = clap::value_parser!(u32).range(1..))]
    chunk: u32,
    /// CPUs per task (the render's threads)
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u32).range(1..=1024))]
    cpus: u32,
    /// Memory per task as Slurm writes it (4G, 800M) [default: glint's estimate]
    #[arg(long, value_name = "SIZE", value_parser = parse_memory)]
    mem: Option<String>,
    /// The partition to run in [default: the cluster's]
    #[arg(long, value_name = "P")]
    partition: Option<String>,
    /// How many times a failed task is requeued
    #[arg(long, value_name = "K", default_value_t = 2, value_parser = clap::value_parser!(u32).range(0..=100))]
    retries: u32,
    /// Image size instead of the shot's resolution
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Accuracy preset instead of the shot's
    #[arg(long, value_enum)]
    preset: Option<PresetArg>,
    /// Also write each frame's lines as SVG (as `glint render --svg`); the verification job
    /// checks the SVGs too
    #[arg(long)]
    svg: bool,
    /// Where the tasks' logs go [default: a folder `slurm-logs` beside the shot]
    #[arg(long, value_name = "DIR")]
    logs: Option<PathBuf>,
    /// Print the script (the default)
    #[arg(long, conflicts_with = "submit")]
    print: bool,
    /// Submit the array and its verification with sbatch
    #[arg(long)]
    submit: bool,
}

/// Slurm's memory sizes: a whole number with an optional K, M, G or T.
fn parse_memory(text: &str) -> Result<String, String> {
    let digits = text.trim_end_matches(['K', 'M', 'G', 'T', 'k', 'm', 'g', 't']);
    let unit = &text[digits.len()..];
    if digits.is_empty() || !digits.chars().all(|c| c.is_ascii_digit()) || unit.len() > 1 {
        return Err(format!(
            "expected a memory size such as 4G or 800M, got '{text}'"
        ));
    }
    Ok(text.to_uppercase())
}

pub fn run(args: &FarmArgs) -> Result<(), CliError> {
    match &args.manager {
        Manager::Slurm(slurm) => run_slurm(slurm),
    }
}

/// `text` quoted for the shell: in single quotes, each single quote written `'\''`.
fn quoted(text: &str) -> String {
    format!("'{}'", text.replace('\'', r"'\''"))
}

fn absolute(path: &Path) -> Result<PathBuf, CliError> {
    std::path::absolute(path).map_err(|e| CliError::BadInput(anyhow!("{}: {e}", path.display())))
}

fn run_slurm(args: &SlurmArgs) -> Result<(), CliError> {
    let overrides = Overrides {
        frames: args.frames.as_ref().map(|f| f.0.clone()),
        size: args.size,
        preset: args.preset.map(Preset::from),
        // The ceiling is the task's own, set below from what it requests.
        max_memory: Some(u64::MAX),
        ..Overrides::default()
    };
    let job = RenderJob::load(&args.shot, &overrides).map_err(|e| CliError::BadInput(e.into()))?;
    let shot = absolute(&args.shot)?;
    let glint = std::env::current_exe()
        .map_err(|e| CliError::Failed(anyhow!("cannot find the glint binary: {e}")))?;
    let logs = match &args.logs {
        Some(logs) => absolute(logs)?,
        None => shot.parent().unwrap_or(Path::new("/")).join("slurm-logs"),
    };
    let chunks: Vec<String> = job
        .frames()
        .chunks(args.chunk as usize)
        .map(frame_spec)
        .collect();
    let mem = args.mem.clone().unwrap_or_else(|| {
        // The estimate and a quarter more, in MiB.
        let bytes = job.peak_bytes();
        format!("{}M", (bytes + bytes / 4).div_ceil(1 << 20))
    });
    // Each task may use what it requests (Slurm reads a bare number as megabytes).
    let ceiling = if mem.bytes().all(|b| b.is_ascii_digit()) {
        format!("{mem}M")
    } else {
        mem.clone()
    };
    let mut options = String::new();
    if let Some((w, h)) = args.size {
        options.push_str(&format!(" --size {w}x{h}"));
    }
    if let Some(preset) = args.preset {
        options.push_str(match preset {
            PresetArg::Preview => " --preset preview",
            PresetArg::Final => " --preset final",
        });
    }
    if args.svg {
        options.push_str(" --svg");
    }
    let name = shot
        .file_stem()
        .map_or_else(|| "shot".to_string(), |s| s.to_string_lossy().into_owned());
    let script = array_script(&ArrayScript {
        name: &name,
        glint: &glint,
        shot: &shot,
        logs: &logs,
        chunks: &chunks,
        cpus: args.cpus,
        mem: &mem,
        partition: args.partition.as_deref(),
        retries: args.retries,
        options: &format!("{options} --max-memory {}", quoted(&ceiling)),
    });
    let verify = format!(
        "{} verify {} --frames {}{options}",
        quoted(&glint.display().to_string()),
        quoted(&shot.display().to_string()),
        frame_spec(job.frames()),
    );
    if !args.submit {
        return write_stdout("the script", |out| {
            out.write_all(script.as_bytes())?;
            writeln!(
                out,
                "# Then verify, once every task has ended:\n#   sbatch --dependency=afterany:JOB_ID --wrap {}",
                quoted(&verify)
            )?;
            Ok(())
        });
    }
    std::fs::create_dir_all(&logs)
        .map_err(|e| CliError::Failed(anyhow!("cannot create {}: {e}", logs.display())))?;
    let array = sbatch(&[], Some(&script)).map_err(CliError::Failed)?;
    let mut verify_options = vec![
        format!("--dependency=afterany:{array}"),
        format!("--job-name=glint-verify-{name}"),
        format!("--output={}/verify-%j.log", logs.display()),
        "--mem=1G".to_string(),
    ];
    if let Some(partition) = &args.partition {
        verify_options.push(format!("--partition={partition}"));
    }
    verify_options.push("--wrap".to_string());
    verify_options.push(verify);
    let check = sbatch(&verify_options, None).map_err(CliError::Failed)?;
    write_stdout("the job ids", |out| {
        writeln!(
            out,
            "array job {array}: {} tasks, logs in {}",
            chunks.len(),
            logs.display()
        )?;
        writeln!(out, "verify job {check}: runs when every task has ended")?;
        Ok(())
    })
}

/// What the array's script is made of.
struct ArrayScript<'a> {
    name: &'a str,
    glint: &'a Path,
    shot: &'a Path,
    logs: &'a Path,
    chunks: &'a [String],
    cpus: u32,
    mem: &'a str,
    partition: Option<&'a str>,
    retries: u32,
    options: &'a str,
}

/// The job array's script: one task per chunk of frames.
fn array_script(s: &ArrayScript) -> String {
    let mut out = String::from("#!/bin/bash\n");
    out.push_str(&format!("#SBATCH --job-name=glint-{}\n", s.name));
    out.push_str(&format!(
        "#SBATCH --array=0-{}\n",
        s.chunks.len().saturating_sub(1)
    ));
    out.push_str(&format!("#SBATCH --cpus-per-task={}\n", s.cpus));
    out.push_str(&format!("#SBATCH --mem={}\n", s.mem));
    out.push_str("#SBATCH --requeue\n");
    // A requeued task writes to the same log: keep what its earlier tries wrote.
    out.push_str("#SBATCH --open-mode=append\n");
    out.push_str(&format!(
        "#SBATCH --output={}/glint-%A_%a.log\n",
        s.logs.display()
    ));
    if let Some(partition) = s.partition {
        out.push_str(&format!("#SBATCH --partition={partition}\n"));
    }
    out.push_str("# Each task renders its chunk; a retry renders only what is missing or stale.\n");
    out.push_str("chunks=(");
    out.push_str(
        &s.chunks
            .iter()
            .map(|c| quoted(c))
            .collect::<Vec<_>>()
            .join(" "),
    );
    out.push_str(")\n");
    out.push_str(&format!(
        "{} render {} --frames \"${{chunks[$SLURM_ARRAY_TASK_ID]}}\" --threads \"$SLURM_CPUS_PER_TASK\" --skip-existing{}\n",
        quoted(&s.glint.display().to_string()),
        quoted(&s.shot.display().to_string()),
        s.options
    ));
    out.push_str("status=$?\n");
    out.push_str(&format!(
        "if [ \"$status\" -ne 0 ] && [ \"${{SLURM_RESTART_COUNT:-0}}\" -lt {} ]; then\n",
        s.retries
    ));
    // The requeue ends this try by stopping it: waiting for that, rather than exiting first,
    // keeps Slurm from taking the failed exit for the task's end and dropping the requeue. A
    // requeue refused ends the task at once with the render's failure.
    out.push_str("    echo \"task $SLURM_ARRAY_TASK_ID failed ($status): requeued\"\n");
    out.push_str(
        "    if scontrol requeue \"${SLURM_ARRAY_JOB_ID}_${SLURM_ARRAY_TASK_ID}\"; then\n",
    );
    out.push_str("        sleep 300\n");
    out.push_str("    fi\n");
    out.push_str(
        "    echo \"task $SLURM_ARRAY_TASK_ID failed ($status): Slurm did not requeue it\" >&2\n",
    );
    out.push_str("fi\n");
    out.push_str("exit \"$status\"\n");
    out
}

/// Runs `sbatch --parsable` with `options` (and `script` on its standard input); the job id.
fn sbatch(options: &[String], script: Option<&str>) -> anyhow::Result<String> {
    use std::io::Write as _;
    let mut command = Command::new("sbatch");
    command.arg("--parsable").args(options);
    command
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped());
    let mut child = command
        .spawn()
        .context("cannot run sbatch (is Slurm installed?)")?;
    if let Some(mut stdin) = child.stdin.take() {
        stdin.write_all(script.unwrap_or_default().as_bytes())?;
    }
    let out = child.wait_with_output()?;
    if !out.status.success() {
        return Err(anyhow!(
            "sbatch failed: {}",
            String::from_utf8_lossy(&out.stderr).trim()
        ));
    }
    let id = String::from_utf8_lossy(&out.stdout);
    Ok(id.trim().split(';').next().unwrap_or_default().to_string())
}
