//! The command line: argument parsing, terminal output and exit codes (0 success, 2 bad input or
//! usage, 1 a failure while working).

mod accuracy_csv;
mod accuracy_plot;
mod bench;
mod bench_loop;
mod error;
mod farm;
mod inspect;
mod key;
mod layer;
mod patch_map;
mod patches;
mod place;
mod probe;
mod render;
mod report;
mod sheet;
mod stats_report;
mod stdout;
pub mod tune;
mod vary;
mod verify;
mod watch;
mod watched;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

pub use error::CliError;
pub(crate) use stdout::write_stdout;

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
    Key(key::KeyArgs),
    Layer(layer::LayerArgs),
    Probe(probe::ProbeArgs),
    Patches(patches::PatchesArgs),
    Place(place::PlaceArgs),
    Sheet(sheet::SheetArgs),
    Tune(tune::command::TuneArgs),
    Verify(verify::VerifyArgs),
    Bench(bench::BenchArgs),
    Farm(farm::FarmArgs),
}

/// Parses the process arguments, runs the command and returns its exit code.
pub fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return usage_error(&e),
    };
    let result = match cli.command {
        Command::Render(args) => render::run(&args),
        Command::Inspect(args) => inspect::run(&args),
        Command::Key(args) => key::run(&args),
        Command::Layer(args) => layer::run(&args),
        Command::Probe(args) => probe::run(&args),
        Command::Patches(args) => patches::run(&args),
        Command::Place(args) => place::run(&args),
        Command::Sheet(args) => sheet::run(&args),
        Command::Tune(args) => tune::command::run(&args),
        Command::Verify(args) => verify::run(&args),
        Command::Bench(args) => bench::run(&args),
        Command::Farm(args) => farm::run(&args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            let code = match error {
                CliError::BadInput(_) => 2,
                CliError::Failed(_) => 1,
            };
            eprintln!("error: {}", one_line(&format!("{error:#}")));
            ExitCode::from(code)
        }
    }
}

/// Answers a command line that does not parse: help and the version as clap prints them
/// (exit 0, or 2 for help shown because nothing was asked), anything else as one line — the
/// problem, clap's tip if it has one, and where to look — with exit code 2.
fn usage_error(e: &clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp
        | ErrorKind::DisplayVersion
        | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            let _ = e.print();
            ExitCode::from(u8::try_from(e.exit_code()).unwrap_or(2))
        }
        _ => {
            let text = e.render().to_string();
            let mut problem: Vec<&str> = Vec::new();
            let mut tips: Vec<&str> = Vec::new();
            for line in text.lines().map(str::trim).filter(|l| !l.is_empty()) {
                if line.starts_with("Usage:") || line.starts_with("For more information") {
                    break;
                }
                match line.strip_prefix("tip: ") {
                    Some(tip) => tips.push(tip),
                    None => problem.push(line.trim_start_matches("error: ")),
                }
            }
            let problem = problem.join(" ");
            let tip = if tips.is_empty() {
                String::new()
            } else {
                format!(" ({})", tips.join("; "))
            };
            eprintln!(
                "error: {}{}; see --help",
                one_line(&problem),
                one_line(&tip)
            );
            ExitCode::from(2)
        }
    }
}

/// `text` on one line: line breaks and other control characters written as escapes (`\n`,
/// `\u{0}`), so that a name holding them cannot split an error line or reach the terminal raw.
#[must_use]
pub fn one_line(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_characters_are_escaped_onto_one_line() {
        assert_eq!(one_line("a\nb\u{0}c\td é"), "a\\nb\\u{0}c\\td é");
    }
}
