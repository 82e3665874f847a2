//! `glint key`: one track of a shot or look file set, keyed or unkeyed in place.

use std::path::{Path, PathBuf};

use anyhow::anyhow;
use clap::{ArgGroup, Args};

use super::CliError;
use glint::formats::replace_text::replace_text;
use glint::formats::ron_location::position_of;
use glint::formats::ron_paths::top_level_name;
use glint::shot::{
    edit_text, load_shot_text, parse_param_path, track_span, track_text, track_texts, TrackEdit,
};

/// Edit one track of a shot or look file in place: set it, key it at a frame, or delete a key.
///
/// Only the track's own text changes; comments, formatting and order stay as written. The
/// edited file is read back and checked to differ in that track alone, and a shot is checked
/// as `glint render` checks it, before the file is replaced (atomically). The track's new text
/// is printed on one line. Parameter paths are described in docs/shot-format.md ("Parameter
/// paths"); `--list` prints every one of a file. A shade entry's numbers are
/// `shade[N].stack[J].alpha` (and every number of an operation, as a highlight layer's), and
/// `shade[N].mask.u[I]`, `….mask.v[I]`, `….mask.feather`, N counting the file's own `shade`
/// entries from 0.
#[derive(Debug, Args)]
#[command(
    group(ArgGroup::new("change").args(["value", "delete", "list"]).required(true)),
    after_help = "Examples:
  glint key shots/teapot_light_orbit.ron --list
  glint key shots/sphere_ops.ron --at 'highlights[0].layers[0].epsilon' --frame 60 --value 0.04
  glint key shots/sphere_ops.ron --at 'highlights[\"ball/*\"].layers[0].colour' --value '(1.0, 0.9, 0.8)'
  glint key shots/sphere_ops.ron --at 'highlights[0].layers[0].stack[0].alpha' --frame 12 --delete
  glint key shots/shade_design.ron --at 'shade[0].stack[0].alpha' --frame 24 --value 0.3
  glint key shots/looks/studio.ron --at 'materials{\"clay\"}.bands[0].threshold' --value 0.1 --dry-run"
)]
pub struct KeyArgs {
    /// The shot or look file (RON); paths name the tracks of this file, not of its includes
    file: PathBuf,
    /// The track, e.g. 'highlights[0].layers[0].stack[1].delta', 'shade[0].stack[0].alpha' or
    /// 'camera.eye'
    #[arg(long, value_name = "PATH", required_unless_present = "list")]
    at: Option<String>,
    /// The frame to key, or whose key to delete (fractional frames allowed). Without it,
    /// --value makes the track a constant
    #[arg(long, value_name = "F", allow_negative_numbers = true)]
    frame: Option<f64>,
    /// The value: a number, or '(x, y, z)' for a point, vector, direction or colour
    #[arg(long, value_name = "V", allow_hyphen_values = true)]
    value: Option<String>,
    /// Delete the key at --frame (the last key leaves the constant it held)
    #[arg(long, requires = "frame")]
    delete: bool,
    /// Print the track before and after, and write nothing
    #[arg(long)]
    dry_run: bool,
    /// Print every parameter path of the file with its track, one a line
    #[arg(long, conflicts_with_all = ["at", "frame", "dry_run"])]
    list: bool,
}

pub fn run(args: &KeyArgs) -> Result<(), CliError> {
    let file = &args.file;
    let text = std::fs::read_to_string(file).map_err(|e| {
        CliError::BadInput(anyhow!("{}: cannot read the file: {e}", file.display()))
    })?;
    let bad = |e: glint::shot::EditError| CliError::BadInput(e.in_file(file).into());
    if args.list {
        let mut out = String::new();
        for (path, track) in track_texts(&text).map_err(bad)? {
            out.push_str(&format!("{path} = {track}\n"));
        }
        print!("{out}");
        return Ok(());
    }
    let written = args.at.as_deref().unwrap_or_default();
    let path = parse_param_path(&text, written).map_err(bad)?;
    let edit = match (&args.value, args.frame) {
        (Some(value), None) => TrackEdit::Set(value.clone()),
        (Some(value), Some(frame)) => TrackEdit::Key {
            frame,
            value: value.clone(),
        },
        (None, Some(frame)) => TrackEdit::Delete { frame },
        (None, None) => {
            return Err(CliError::BadInput(anyhow!(
                "--delete needs --frame F, the frame of the key to delete"
            )))
        }
    };
    let edited = edit_text(&text, &path, &edit).map_err(bad)?;
    // A shot that loads must still load: every value in range at every frame. A look file is
    // checked when a shot that includes it is loaded, and a shot that does not load yet (say,
    // with a value out of range that this edit fixes) is only read back.
    if top_level_name(&text) != Some("Looks") {
        match load_shot_text(file, text.clone()) {
            Ok(_) => {
                load_shot_text(file, edited.clone()).map_err(|e| CliError::BadInput(e.into()))?;
            }
            Err(e) => eprintln!(
                "note: the shot does not load as it was ({e}), so the edited value is not checked against its range"
            ),
        }
    }
    let after = track_text(&edited, &path).map_err(bad)?;
    if args.dry_run {
        let before = track_text(&text, &path).map_err(bad)?;
        let span = track_span(&edited, &path).map_err(bad)?;
        let (line, col) = position_of(&edited, span.map_or(0, |s| s.start));
        println!("{}:{line}:{col}: {path}", file.display());
        println!("- {before}");
        println!("+ {after}");
        return Ok(());
    }
    write_in_place(file, &edited).map_err(CliError::Failed)?;
    println!("{after}");
    Ok(())
}

/// Replaces the file at `file` with `text` ([`replace_text`]).
pub(super) fn write_in_place(file: &Path, text: &str) -> anyhow::Result<()> {
    Ok(replace_text(file, text)?)
}
