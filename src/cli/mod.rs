//! The command line: argument parsing, terminal output and exit codes (0 success, 2 bad input or
//! usage, 1 a failure while working).

mod bench;
mod inspect;
mod patch_map;
mod patches;
mod probe;
mod render;
mod sheet;
mod vary;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// glint renders cel-animation frames of NURBS patch models with designed, keyframed stylized
/// highlights.
#[derive(Debug, Parser)]
#[command(name = "glint", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    Render(render::RenderArgs),
    Inspect(inspect::InspectArgs),
    Probe(probe::ProbeArgs),
    Patches(patches::PatchesArgs),
    Sheet(sheet::SheetArgs),
    Bench(bench::BenchArgs),
}

/// Why a command stopped.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// The input cannot be used (a malformed file, an unknown patch, a value out of range): exit 2.
    #[error(transparent)]
    BadInput(anyhow::Error),
    /// The input was fine but the work failed (an output could not be written): exit 1.
    #[error(transparent)]
    Failed(anyhow::Error),
}

/// Parses the process arguments, runs the command and returns its exit code.
pub fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Render(args) => render::run(&args),
        Command::Inspect(args) => inspect::run(&args),
        Command::Probe(args) => probe::run(&args),
        Command::Patches(args) => patches::run(&args),
        Command::Sheet(args) => sheet::run(&args),
        Command::Bench(args) => bench::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            let code = match error {
                CliError::BadInput(_) => 2,
                CliError::Failed(_) => 1,
            };
            eprintln!("error: {error:#}");
            ExitCode::from(code)
        }
    }
}
