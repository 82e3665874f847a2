//! `glint probe`: the frame the highlight sees at chosen (u, v) of one patch, as JSON.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::anyhow;
use clap::Args;
use serde::Serialize;

use super::CliError;
use glint::formats::load_patches;
use glint::formats::ron_paths::top_level_name;
use glint::geom::{Frame, PatchLibrary};
use glint::shot::load_shot_text;

/// Print the surface frame at parameters of a patch, as a JSON array.
///
/// For each --uv the output holds the point, the partial derivatives Su and Sv, the unit normal
/// N and the tangents du, dv that the highlight operations move, stretch and split along, and
/// whether the point is degenerate (a collapsed patch edge such as a sphere's pole, where the
/// frame is the limit from inside the patch), and whether the patch's trim cuts it away.
///
/// The file may also be a shot (a `.ron` file whose top level is `Shot(…)`): its patches are
/// named INSTANCE/PATCH, and each is probed where --frame poses it, moved by its instance's
/// and parts' transforms at that frame.
#[derive(Debug, Args)]
#[command(after_help = "Examples:
  glint probe patches/sphere.ron --patch sphere --uv 0.25,0.5
  glint probe patches/teapot.bpt --patch 20 --uv 0,0 --uv 0.5,0.5 --uv 1,1
  glint probe shots/teapot_turntable.ron --patch teapot/20 --frame 48 --uv 0.5,0.5")]
pub struct ProbeArgs {
    /// Patch file: a RON patch library (.ron), Bezier patches (.bpt) or a USD layer (.usda; .usd, .usdc with the usd-binary feature); or a shot
    file: PathBuf,
    /// For a shot, the frame whose pose to probe (fractional frames allowed) [default: the shot's first]
    #[arg(long, value_name = "F")]
    frame: Option<f64>,
    /// Patch name, or its 0-based index in the file
    #[arg(long, value_name = "NAME_OR_INDEX")]
    patch: String,
    /// Parameters to probe, inside the patch's domain (repeat for more points)
    #[arg(long = "uv", value_name = "U,V", required = true, value_parser = parse_uv)]
    uvs: Vec<(f64, f64)>,
}

/// One probed point, as printed.
#[derive(Serialize)]
struct Probe<'a> {
    patch: &'a str,
    u: f64,
    v: f64,
    point: [f64; 3],
    su: [f64; 3],
    sv: [f64; 3],
    normal: [f64; 3],
    du: [f64; 3],
    dv: [f64; 3],
    degenerate: bool,
    /// The patch is trimmed and its trim cuts this point away: it is not drawn.
    trimmed_away: bool,
}

fn parse_uv(text: &str) -> Result<(f64, f64), String> {
    let parsed = text
        .split_once(',')
        .and_then(|(u, v)| Some((u.trim().parse().ok()?, v.trim().parse().ok()?)));
    match parsed {
        Some((u, v)) if f64::is_finite(u) && f64::is_finite(v) => Ok((u, v)),
        _ => Err(format!(
            "expected two numbers U,V such as 0.25,0.5, got '{text}'"
        )),
    }
}

/// The model `path` holds: a patch file's patches, or a shot's model posed at `frame` (the
/// shot's first frame by default). Errors are one line naming the file.
fn read_model(path: &Path, frame: Option<f64>) -> Result<Arc<PatchLibrary>, CliError> {
    let bad = |e: anyhow::Error| CliError::BadInput(e);
    let is_ron = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("ron"));
    // A file that is not UTF-8 text is left to the patch reader, which says where its first
    // bad byte is.
    let text = if is_ron {
        match std::fs::read_to_string(path) {
            Ok(text) => Some(text),
            Err(e) if e.kind() == std::io::ErrorKind::InvalidData => None,
            Err(e) => {
                return Err(bad(anyhow!(
                    "{}: cannot read the file: {e}",
                    path.display()
                )))
            }
        }
    } else {
        None
    };
    if let Some(text) = text.filter(|t| top_level_name(t) == Some("Shot")) {
        let shot = load_shot_text(path, text).map_err(|e| bad(e.into()))?;
        let (first, last) = shot.frames;
        let frame = frame.unwrap_or(first as f64);
        if !(frame >= first as f64 && frame <= last as f64) {
            return Err(bad(anyhow!(
                "{}: --frame {frame} is outside the shot's frame range {first}-{last}",
                path.display()
            )));
        }
        return Ok(shot.library_at(frame));
    }
    if frame.is_some() {
        return Err(bad(anyhow!(
            "{}: --frame poses a shot's model; a patch file has one pose",
            path.display()
        )));
    }
    Ok(Arc::new(
        load_patches(path).map_err(|e| CliError::BadInput(e.into()))?,
    ))
}

pub fn run(args: &ProbeArgs) -> Result<(), CliError> {
    let library = read_model(&args.file, args.frame)?;
    let patch = library
        .find(&args.patch)
        .map_err(|e| CliError::BadInput(anyhow!("{}: {e}", args.file.display())))?;
    let surface = &patch.surface;
    let domain = surface.domain();
    let mut probes = Vec::with_capacity(args.uvs.len());
    for &(u, v) in &args.uvs {
        if !domain.contains(u, v) {
            return Err(CliError::BadInput(anyhow!(
                "(u, v) = ({u}, {v}) is outside the domain of patch '{}': u in [{}, {}], v in [{}, {}]",
                patch.name,
                domain.u.0,
                domain.u.1,
                domain.v.0,
                domain.v.1
            )));
        }
        let d = surface.derivs(u, v, 1);
        let Frame {
            point,
            normal,
            du,
            dv,
            degenerate,
        } = surface.frame(u, v);
        probes.push(Probe {
            patch: &patch.name,
            u,
            v,
            point: point.to_array(),
            su: d.su.to_array(),
            sv: d.sv.to_array(),
            normal: normal.to_array(),
            du: du.to_array(),
            dv: dv.to_array(),
            degenerate,
            trimmed_away: !patch.keeps(u, v),
        });
    }
    let mut out = std::io::stdout().lock();
    serde_json::to_writer_pretty(&mut out, &probes)
        .map_err(anyhow::Error::from)
        .and_then(|()| writeln!(out).map_err(anyhow::Error::from))
        .map_err(|e| CliError::Failed(e.context("writing the probe output")))
}
