//! `glint verify`: whether every frame of a shot is on disk, whole and current, and the frame
//! list to render again when not.

use std::path::PathBuf;

use clap::Args;

use super::render::Target;
use super::{write_stdout, CliError};
use glint::job::{frame_spec, JobError, RenderJob, Scrutiny};

/// Check that every frame of a shot was rendered, whole, from the shot's inputs as they are now.
///
/// For each frame, each file `glint render` writes (the colour PNG, the AOV PNGs and the EXR)
/// must be a regular file that decodes, of the shot's size, and carry the fingerprint of the
/// frame's inputs — the shot's values at that frame, the model, the textures, the settings and
/// glint's version — so that a frame made before an edit of a key it depends on is reported.
/// Give the same --out, --size, --preset and --aov as the render.
///
/// Prints one line per problem, a summary, and the frames to render again as a list for
/// --frames. Exit code 0 only when every frame is complete, 1 when some must be rendered again,
/// 2 for bad input.
#[derive(Debug, Args)]
#[command(after_help = "Examples:
  glint verify shots/teapot_turntable.ron
  glint verify shots/teapot_turntable.ron --frames 49-96 --size 1280x720
  glint render shots/teapot_turntable.ron --frames \"$(glint verify shots/teapot_turntable.ron --spec-only)\"")]
pub struct VerifyArgs {
    /// The shot file (RON)
    shot: PathBuf,
    /// The frames, output pattern, size, preset and AOVs, as given to the render
    #[command(flatten)]
    target: Target,
    /// Print only the frame list to render again (empty when complete)
    #[arg(long)]
    spec_only: bool,
}

pub fn run(args: &VerifyArgs) -> Result<(), CliError> {
    // Checking renders nothing: no memory ceiling.
    let overrides = args.target.overrides(None, Some(u64::MAX));
    let job = RenderJob::load(&args.shot, &overrides).map_err(|e: JobError| {
        if e.is_bad_input() {
            CliError::BadInput(e.into())
        } else {
            CliError::Failed(e.into())
        }
    })?;
    let size = (job.settings().width, job.settings().height);
    let frames = job.frames().to_vec();
    let mut again = Vec::new();
    let mut lines = Vec::new();
    for &frame in &frames {
        let problems = job.frame_problems(frame, Scrutiny::Decode);
        if problems.is_empty() {
            continue;
        }
        again.push(frame);
        for (file, problem) in problems {
            lines.push(format!(
                "frame {frame}: {}: {}",
                file.display(),
                problem.describe(size)
            ));
        }
    }
    let spec = frame_spec(&again);
    write_stdout("the report", |out| {
        if args.spec_only {
            writeln!(out, "{spec}")?;
            return Ok(());
        }
        for line in &lines {
            writeln!(out, "{line}")?;
        }
        writeln!(
            out,
            "{} frames checked: {} complete, {} to render again",
            frames.len(),
            frames.len() - again.len(),
            again.len()
        )?;
        if !again.is_empty() {
            writeln!(out, "render again: --frames {spec}")?;
        }
        Ok(())
    })?;
    if again.is_empty() {
        Ok(())
    } else {
        Err(CliError::Failed(anyhow::anyhow!(
            "{} of {} frames must be rendered again",
            again.len(),
            frames.len()
        )))
    }
}
