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
use glint::job::{Overrides, RenderJob};
use glint::shot::{load_shot_text, Preset};

use super::render::{parse_size, PresetArg};

/// Print the surface frame at parameters of a patch, as a JSON array.
///
/// For each --uv the output holds the point, the partial derivatives Su and Sv, the unit normal
/// N and the tangents du, dv that the highlight operations move, stretch and split along, and
/// whether the point is degenerate (a collapsed patch edge such as a sphere's pole, where the
/// frame is the limit from inside the patch), and whether the patch's trim cuts it away.
///
/// The file may also be a shot (a `.ron` file whose top level is `Shot(…)`): its patches are
/// named INSTANCE/PATCH, and each is probed where --frame poses it, moved by its instance's
/// and parts' transforms at that frame. For a shot, each point also says where it lands in
/// that frame's image (`image.pixel`, in pixels from the top left with a pixel's centre at its
/// integer coordinates, as `glint place --pixel` reads them), whether it is in front of the
/// camera and inside the image, and whether the frame shows it (`visible`: the frame, rendered
/// at --size and --preset, draws the point's patch at its depth there; false when another
/// surface hides it or it faces away).
#[derive(Debug, Args)]
#[command(after_help = "Examples:
  glint probe patches/sphere.ron --patch sphere --uv 0.25,0.5
  glint probe patches/teapot.bpt --patch 20 --uv 0,0 --uv 0.5,0.5 --uv 1,1
  glint probe shots/teapot_turntable.ron --patch teapot/20 --frame 48 --uv 0.5,0.5
  glint probe shots/teapot_lid_opens.ron --patch teapot/25 --uv 0.1,0.5 --frame 24 --size 1280x720")]
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
    /// For a shot, the image size the pixels refer to, instead of the shot's resolution
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// For a shot, the accuracy preset of the frame that decides what is visible [default: the shot's]
    #[arg(long, value_enum)]
    preset: Option<PresetArg>,
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
    /// For a shot: where the point lands in the frame's image.
    #[serde(skip_serializing_if = "Option::is_none")]
    image: Option<InImage>,
}

/// Where a probed point of a shot lands in its frame's image.
#[derive(Serialize)]
struct InImage {
    /// Pixels from the top left, a pixel's centre at integer coordinates.
    pixel: [f64; 2],
    /// The image's size, `[width, height]`.
    size: [u32; 2],
    in_front: bool,
    in_image: bool,
    visible: bool,
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

/// A shot probed at a frame: its job (rendering at the size and preset asked for) and the frame.
struct ShotAt {
    job: RenderJob,
    frame: f64,
}

/// The model `path` holds: a patch file's patches, or a shot's model posed at `args.frame`
/// (the shot's first frame by default) with the shot's job. Errors are one line naming the
/// file.
fn read_model(
    path: &Path,
    args: &ProbeArgs,
) -> Result<(Arc<PatchLibrary>, Option<ShotAt>), CliError> {
    let frame = args.frame;
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
        let library = shot.library_at(frame);
        let overrides = Overrides {
            size: args.size,
            preset: args.preset.map(Preset::from),
            ..Overrides::default()
        };
        let job = RenderJob::new(shot, &overrides).map_err(|e| bad(e.into()))?;
        return Ok((library, Some(ShotAt { job, frame })));
    }
    let for_a_shot = [
        (
            frame.is_some(),
            "--frame poses a shot's model; a patch file has one pose",
        ),
        (
            args.size.is_some() || args.preset.is_some(),
            "--size and --preset say how a shot's frame is rendered; a patch file has no frame",
        ),
    ];
    if let Some((_, message)) = for_a_shot.iter().find(|(given, _)| *given) {
        return Err(bad(anyhow!("{}: {message}", path.display())));
    }
    let library = load_patches(path).map_err(|e| CliError::BadInput(e.into()))?;
    Ok((Arc::new(library), None))
}

pub fn run(args: &ProbeArgs) -> Result<(), CliError> {
    let (library, mut shot) = read_model(&args.file, args)?;
    let patch = library
        .find(&args.patch)
        .map_err(|e| CliError::BadInput(anyhow!("{}: {e}", args.file.display())))?;
    let index = library
        .patches
        .iter()
        .position(|p| std::ptr::eq(p, patch))
        .unwrap_or_default();
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
            image: match shot.as_mut() {
                Some(ShotAt { job, frame }) => Some(in_image(job, *frame, index, (u, v))?),
                None => None,
            },
        });
    }
    let mut out = std::io::stdout().lock();
    serde_json::to_writer_pretty(&mut out, &probes)
        .map_err(anyhow::Error::from)
        .and_then(|()| writeln!(out).map_err(anyhow::Error::from))
        .map_err(|e| CliError::Failed(e.context("writing the probe output")))
}

/// Where `(u, v)` of patch `patch` lands in `job`'s image at `frame`.
fn in_image(
    job: &mut RenderJob,
    frame: f64,
    patch: usize,
    uv: (f64, f64),
) -> Result<InImage, CliError> {
    let seen = job.pixel_of(frame, patch, uv).map_err(|e| {
        let shot = job.shot().path.display().to_string();
        if e.is_bad_input() {
            CliError::BadInput(anyhow!("{shot}: {e}"))
        } else {
            CliError::Failed(anyhow!("{shot}: {e}"))
        }
    })?;
    let settings = job.settings();
    Ok(InImage {
        pixel: [seen.pixel.0, seen.pixel.1],
        size: [settings.width, settings.height],
        in_front: seen.in_front,
        in_image: seen.in_image,
        visible: seen.visible,
    })
}
