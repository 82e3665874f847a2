//! `glint layer`: a structural edit of one highlight layer — an operation inserted, removed or
//! moved, a mask added or removed, a pin removed or made to hold its shape, an outline drawn or
//! keyed, the disc again — written into the file the layer is in.

use std::path::PathBuf;

use anyhow::anyhow;
use clap::{ArgGroup, Args};

use super::key::write_in_place;
use super::{write_stdout, CliError};
use glint::highlight::Op;
use glint::shot::{edit_layer, load_shot, op_text, rounded_number_text, LayerEdit};

/// Change the structure of one highlight layer in its file: insert, remove or move an
/// operation of its stack, add or remove its mask, remove its pin or make it hold the layer's
/// shape, or give it a drawn outline (or the disc back).
///
/// The layer is layer --layer (left to right through the expression's Booleans, from 0) of
/// highlight entry --highlight (from 0, includes first); the edit is written into the file the
/// entry is written in (the shot or an include), atomically, with every other byte as it was,
/// and the file is read back to check that nothing else changed. An inserted operation's
/// numbers are constants (key them with `glint key`); a new mask covers the whole patch
/// (`u: (0, 1), v: (0, 1)`), to narrow with `glint key … --at '…mask.u[0]'`. To add or move a
/// pin, use `glint place --pin`.
///
/// --hold FRAME makes a pinned layer hold the shape it has at FRAME: on every other frame its
/// highlight covers as much of the surface about the pin, as long and as wide, as it does
/// there, while the view and the light change (docs/highlights.md, "Holding the shape").
/// --no-hold lets the shape follow the view again.
///
/// --outline gives the layer a drawn outline of corners in the coordinates
/// t' = ((H', du), (H', dv)) (docs/highlights.md, "Drawn outlines"), written to 4 decimals:
/// `shape: Outline([…])`; with --key-at FRAME it is the outline's key at that frame in
/// `shape: OutlineKeys([…])`, replacing a key there or added in frame order, with as many points
/// as the other keys. The disc or a plain outline keyed becomes the one key at FRAME (as a
/// constant keyed with `glint key` does). --disc takes the shape out: the ε-disc again.
///
/// Exit code 2 for an index out of range, an operation that is not valid, a mask or pin that is
/// not there or already is, a hold on a layer with no pin, an outline that is not a simple closed curve within |t'| ≤ 0.99,
/// a key with another number of points than the other keys.
#[derive(Debug, Args)]
#[command(group(ArgGroup::new("edit").required(true).args(["insert_op", "remove_op", "move_op", "add_mask", "remove_mask", "unpin", "hold", "no_hold", "outline", "disc"])))]
#[command(after_help = "Examples:
  glint layer shots/sphere_ops.ron --highlight 0 --insert-op 'Scale(delta: 0.5, axis: V)'
  glint layer shots/sphere_ops.ron --highlight 0 --insert-op 'Rotate(degrees: 20.0)' --at 0
  glint layer shots/sphere_ops.ron --highlight 0 --move-op 2 --to 0
  glint layer shots/sphere_ops.ron --highlight 0 --remove-op 1
  glint layer shots/crescent.ron --highlight 0 --layer 1 --add-mask
  glint layer shots/teapot_turntable.ron --highlight 1 --hold 1
  glint layer shots/sphere_ops.ron --highlight 0 --outline '(0.0, 0.3), (0.26, -0.15), (-0.26, -0.15)'
  glint layer shots/sphere_ops.ron --highlight 0 --outline '(0.0, 0.2), (0.17, -0.1), (-0.17, -0.1)' --key-at 24
  glint layer shots/sphere_ops.ron --highlight 0 --outline '(0.0, 0.4), (0.35, -0.2), (-0.35, -0.2)' --key-at 48
  glint layer shots/sphere_ops.ron --highlight 0 --disc")]
pub struct LayerArgs {
    /// The shot file (RON)
    shot: PathBuf,
    /// The highlight entry, from 0, includes first (as `glint inspect` lists them)
    #[arg(long, value_name = "N")]
    highlight: usize,
    /// The layer of the entry's expression, left to right from 0
    #[arg(long, value_name = "K", default_value_t = 0)]
    layer: usize,
    /// Insert this operation, written as in a shot, e.g. 'Scale(delta: 0.5, axis: V)'
    #[arg(long, value_name = "OP")]
    insert_op: Option<String>,
    /// Where --insert-op goes in the stack, from 0 [default: at the end]
    #[arg(long, value_name = "I", requires = "insert_op")]
    at: Option<usize>,
    /// Remove the operation at this index of the stack, from 0
    #[arg(long, value_name = "I")]
    remove_op: Option<usize>,
    /// Move the operation at this index of the stack, from 0, to --to
    #[arg(long, value_name = "FROM", requires = "to")]
    move_op: Option<usize>,
    /// Where --move-op puts the operation, from 0
    #[arg(long, value_name = "TO", requires = "move_op")]
    to: Option<usize>,
    /// Add a mask over the whole patch
    #[arg(long)]
    add_mask: bool,
    /// Remove the layer's mask
    #[arg(long)]
    remove_mask: bool,
    /// Remove the layer's pin: its translation is used as written again
    #[arg(long)]
    unpin: bool,
    /// Make the layer's pin hold the shape the layer has at this frame
    #[arg(long, value_name = "FRAME", allow_negative_numbers = true)]
    hold: Option<i64>,
    /// Let the layer's shape follow the view again: its pin's hold taken out
    #[arg(long)]
    no_hold: bool,
    /// Give the layer this drawn outline of corners (x, y) in t', e.g.
    /// '(0.0, 0.3), (0.26, -0.15), (-0.26, -0.15)'
    #[arg(long, value_name = "POINTS")]
    outline: Option<String>,
    /// Write --outline as the outline's key at this frame
    #[arg(long, value_name = "FRAME", requires = "outline")]
    key_at: Option<f64>,
    /// Take the layer's shape out: the ε-disc again
    #[arg(long)]
    disc: bool,
}

/// `(x, y), (x, y), …` read as the corners of an outline.
fn outline_points(written: &str) -> Result<Vec<[f32; 2]>, anyhow::Error> {
    let corners: Vec<(f32, f32)> = ron::from_str(&format!("[{written}]")).map_err(|e| {
        anyhow!(
            "--outline '{written}' is not a list of corners (x, y), (x, y), …: {}",
            e.code
        )
    })?;
    Ok(corners.into_iter().map(|(x, y)| [x, y]).collect())
}

pub fn run(args: &LayerArgs) -> Result<(), CliError> {
    let bad = |e: anyhow::Error| CliError::BadInput(e);
    let shown = args.shot.display();
    let shot = load_shot(&args.shot).map_err(|e| bad(e.into()))?;
    let state = shot.at(shot.frames.0 as f64);
    let Some((file, index)) = shot.highlight_written(args.highlight) else {
        let count = state.highlights.len();
        return Err(bad(anyhow!(
            "{shown}: the shot has {count} highlight entr{}, numbered from 0, so there is no \
             highlight {}",
            if count == 1 { "y" } else { "ies" },
            args.highlight
        )));
    };
    let file = file.to_path_buf();
    let text = std::fs::read_to_string(&file)
        .map_err(|e| CliError::Failed(anyhow!("{}: cannot read the file: {e}", file.display())))?;
    let stack_len = state
        .highlights
        .get(args.highlight)
        .and_then(|expr| expr.layers().get(args.layer).map(|layer| layer.stack.len()))
        .unwrap_or(0);
    let (edit, done) = if let Some(written) = &args.insert_op {
        let op: Op<f32> = ron::from_str(written).map_err(|e| {
            bad(anyhow!(
                "--insert-op '{written}' is not an operation as a shot writes one: {e}"
            ))
        })?;
        let at = args.at.unwrap_or(stack_len);
        let shown_op = op_text(&op, rounded_number_text);
        (
            LayerEdit::InsertOp { index: at, op },
            format!("inserted {shown_op} at stack[{at}]"),
        )
    } else if let Some(index) = args.remove_op {
        (
            LayerEdit::RemoveOp { index },
            format!("removed stack[{index}]"),
        )
    } else if let (Some(from), Some(to)) = (args.move_op, args.to) {
        (
            LayerEdit::MoveOp { from, to },
            format!("moved stack[{from}] to stack[{to}]"),
        )
    } else if args.add_mask {
        (
            LayerEdit::AddMask,
            "added a mask over the whole patch".into(),
        )
    } else if args.remove_mask {
        (LayerEdit::RemoveMask, "removed the mask".into())
    } else if let Some(written) = &args.outline {
        let points = outline_points(written).map_err(bad)?;
        let done = match args.key_at {
            Some(frame) => format!(
                "keyed the outline at frame {} ({} points)",
                glint::shot::frame_text(frame),
                points.len()
            ),
            None => format!("drew an outline of {} points", points.len()),
        };
        (
            LayerEdit::Outline {
                key: args.key_at,
                points,
            },
            done,
        )
    } else if args.disc {
        (LayerEdit::Disc, "made the shape the disc again".into())
    } else if let Some(frame) = args.hold {
        (
            LayerEdit::Hold { frame: Some(frame) },
            format!("the pin holds the shape of frame {frame}"),
        )
    } else if args.no_hold {
        (
            LayerEdit::Hold { frame: None },
            "the shape follows the view again".into(),
        )
    } else {
        (LayerEdit::Unpin, "removed the pin".into())
    };
    let edited =
        edit_layer(&text, index, args.layer, &edit).map_err(|e| bad(e.in_file(&file).into()))?;
    write_in_place(&file, &edited).map_err(CliError::Failed)?;
    write_stdout("the edit", |out| {
        writeln!(
            out,
            "highlights[{index}].layers[{}] in {}: {done}",
            args.layer,
            file.display()
        )?;
        Ok(())
    })
}
