//! `glint place`: the translation that puts a highlight's centre, or with --shade a cel band's
//! edge, on the surface point under a pixel.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::anyhow;
use clap::Args;
use serde::Serialize;

use super::key::write_in_place;
use super::render::{parse_size, PresetArg};
use super::{write_stdout, CliError};
use glint::job::shade_place::{ShadeChoice, ShadePlacement};
use glint::job::{LayerChoice, LayerUnder, Overrides, PlaceError, Placement, RenderJob};
use glint::shot::{
    apply_edits, edit_layer, frame_text, parse_param_path, rounded_number_text, LayerEdit, Preset,
    TrackEdit,
};

/// Solve a highlight's translation so that its centre lands on the point under a pixel.
///
/// Finds the patch and (u, v) under the pixel (the patch the frame draws there, then (u, v)
/// refined onto the pixel's ray) and solves the layer's translation (α, β) in closed form so
/// that the highlight's centre — where the transformed H equals N — is on that point under
/// that frame's camera and light, with the operations before the translation taken into
/// account and those after it shaping the highlight around the centre. The translation solved
/// is the layer's last Translate. Prints the key in the shot's syntax and the `glint key`
/// commands that write it; --write writes both keys into the file the highlight is written in.
///
/// One (α, β) serves every patch the layer is drawn on, each in its own frame; the report
/// shows, for each, how near its highlight comes to a centre there (0 at a centre, below ε
/// where the highlight shows). Where the layer shows more than once — on several patches, or
/// twice on one whose normals turn back (an S-bend, a lid) — it warns and lists every centre,
/// each with the pixel it lands on and whether the frame shows it (docs/tutorial.md).
///
/// With --at PATCH:U,V instead of --pixel the point is named, not pointed at: (u, v) of the
/// patch as the model is posed at the frame, whether the frame shows it or not (it warns when
/// not) — so that a translation keyed at one frame can be keyed on the same surface point at
/// another, with no pixel to find (`glint probe --patch P --uv U,V --frame F` says where it
/// lands).
///
/// With --pin the layer is pinned instead: its pin, added or replaced, names the patch and
/// (u, v) under the pixel, and its translation is solved there on every frame from then on
/// (--write writes the pin; a pinned layer is moved this way). A layer without a translation
/// gets one when it is drawn.
///
/// With --shade a cel band's edge is placed instead (docs/highlights.md, "Placing the
/// shadow"): the translation solved is the last Translate of a shade entry picking the patch
/// (--entry, default the last one), moved along the tangential direction of the light at the
/// point until band K's edge (--band; default, of the bands a translation can move there, the
/// one whose edge is nearest the point now) — N·L' equal to its threshold — passes through the
/// point, with the patch's whole designed light at that frame (every entry, the other
/// operations, the mask). Every operation keeps the sign of N·L, so an edge at threshold 0, or
/// one on the other side of the terminator from the point, cannot be moved there: a band edge
/// is placed above 0, on the light's side. --write keys α and β at the frame where they are
/// keyed, and sets the constant where they are not.
///
/// Pixels are counted from the top left, in the shot's resolution (or --size); a pixel's
/// centre is at its integer coordinates, and fractions are allowed. Exit code 2 for a pixel
/// off the model or outside the image, a patch without a highlight, a layer without a
/// translation or one that is pinned (its translation is solved on every frame: move its pin
/// with --pin instead); with --shade, for a patch without a shade entry or a cel band, an entry
/// without a translation, or an edge no translation in range puts on the point.
#[derive(Debug, Args)]
#[command(after_help = "Examples:
  glint place shots/sphere_ops.ron --frame 1 --pixel 320,180
  glint place shots/crescent.ron --frame 12 --pixel 330,170 --layer 1
  glint place shots/sphere_ops.ron --frame 30 --pixel 200,150 --size 240x240 --json
  glint place shots/sphere_ops.ron --frame 12 --pixel 300,200 --write
  glint place shots/sphere_ops.ron --frame 48 --at ball/sphere:0.83,0.62 --write
  glint place shots/teapot_lid_opens.ron --frame 24 --pixel 322,118 --pin --write
  glint place shots/shade_design.ron --frame 48 --pixel 300,200 --shade --band 0 --write")]
#[command(group(clap::ArgGroup::new("point").required(true).args(["pixel", "at"])))]
pub struct PlaceArgs {
    /// The shot file (RON)
    shot: PathBuf,
    /// The frame whose camera, light and parameters to solve with [default: the shot's first]
    #[arg(long, value_name = "F")]
    frame: Option<f64>,
    /// The image position: pixel column and row from the top left
    #[arg(long, value_name = "X,Y", value_parser = parse_pixel)]
    pixel: Option<(f64, f64)>,
    /// The surface point instead of a pixel: a patch name and (u, v), e.g. teapot/5:0.3,0.6 —
    /// the same point at any frame, seen or not
    #[arg(long, value_name = "PATCH:U,V", value_parser = parse_point, conflicts_with = "shade")]
    at: Option<(String, (f64, f64))>,
    /// The highlight entry, from 0, includes first [default: the one drawn on the patch]
    #[arg(long, value_name = "N", conflicts_with = "shade")]
    highlight: Option<usize>,
    /// The layer of the highlight's expression, left to right from 0 [default: the first
    /// with a translation]
    #[arg(long, value_name = "K", conflicts_with = "shade")]
    layer: Option<usize>,
    /// Place a cel band's edge by a shade entry's translation instead of a highlight
    #[arg(long, conflicts_with = "pin")]
    shade: bool,
    /// With --shade: the shade entry, from 0, includes first [default: the last that picks the
    /// patch]
    #[arg(long, value_name = "N", requires = "shade")]
    entry: Option<usize>,
    /// With --shade: the band of the patch's cel material whose edge to place, from 0
    /// [default: the one whose edge is nearest the point]
    #[arg(long, value_name = "K", requires = "shade")]
    band: Option<usize>,
    /// Image size the pixel refers to, instead of the shot's resolution
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<(u32, u32)>,
    /// Accuracy preset of the frame the patch is looked up in [default: the shot's]
    #[arg(long, value_enum)]
    preset: Option<PresetArg>,
    /// Print the placement as JSON
    #[arg(long)]
    json: bool,
    /// Write the keys into the file the highlight is written in (the shot or an include),
    /// atomically, leaving every other byte as it was
    #[arg(long)]
    write: bool,
    /// Pin the layer to the surface point under the pixel instead of keying its translation
    #[arg(long)]
    pin: bool,
}

/// `PATCH:U,V` read as a patch name and its (u, v); the name is what comes before the last
/// colon.
fn parse_point(text: &str) -> Result<(String, (f64, f64)), String> {
    let expected = || format!("expected PATCH:U,V such as teapot/5:0.3,0.6, got '{text}'");
    let (patch, uv) = text.rsplit_once(':').ok_or_else(expected)?;
    let (u, v) = uv.split_once(',').ok_or_else(expected)?;
    let (u, v) = (
        u.trim().parse::<f64>().map_err(|_| expected())?,
        v.trim().parse::<f64>().map_err(|_| expected())?,
    );
    if patch.is_empty() || !(u.is_finite() && v.is_finite()) {
        return Err(expected());
    }
    Ok((patch.to_string(), (u, v)))
}

/// The patch of the shot's model named `name`, or why there is none (with the nearest name).
fn named_patch(job: &RenderJob, name: &str) -> Result<usize, CliError> {
    let patches = &job.shot().library.patches;
    if let Some(index) = patches.iter().position(|p| p.name == name) {
        return Ok(index);
    }
    let names: Vec<&str> = patches.iter().map(|p| p.name.as_str()).collect();
    let mut message = format!(
        "{}: --at names the patch \"{name}\", which the shot's model has not",
        job.shot().path.display()
    );
    if let Some(close) = glint::formats::ron_location::closest_name(name, &names) {
        message.push_str(&format!("; did you mean \"{close}\"?"));
    }
    Err(CliError::BadInput(anyhow!(message)))
}

fn parse_pixel(text: &str) -> Result<(f64, f64), String> {
    text.split_once(',')
        .and_then(|(x, y)| Some((x.trim().parse().ok()?, y.trim().parse().ok()?)))
        .filter(|&(x, y): &(f64, f64)| x.is_finite() && y.is_finite())
        .ok_or_else(|| format!("expected a pixel X,Y such as 320,180, got '{text}'"))
}

/// A placement as printed with --json.
#[derive(Serialize)]
struct Report<'a> {
    frame: f64,
    pixel: [f64; 2],
    patch: &'a str,
    parts: Vec<&'a str>,
    u: f64,
    v: f64,
    highlight: usize,
    file: String,
    path: String,
    alpha: f32,
    beta: f32,
    residuals: Vec<ResidualReport<'a>>,
    centres: Vec<CentreReport<'a>>,
}

/// One centre of the placed layer, where it lands and whether the frame shows it there.
#[derive(Serialize)]
struct CentreReport<'a> {
    patch: &'a str,
    u: f64,
    v: f64,
    nearest: f32,
    pixel: [f64; 2],
    visible: bool,
}

#[derive(Serialize)]
struct ResidualReport<'a> {
    patch: &'a str,
    nearest: f32,
    u: f64,
    v: f64,
    covered: bool,
}

pub fn run(args: &PlaceArgs) -> Result<(), CliError> {
    let overrides = Overrides {
        size: args.size,
        preset: args.preset.map(Preset::from),
        threads: None,
        ..Overrides::default()
    };
    let mut job = RenderJob::load(&args.shot, &overrides).map_err(|e| {
        if e.is_bad_input() {
            CliError::BadInput(e.into())
        } else {
            CliError::Failed(e.into())
        }
    })?;
    let frame = args.frame.unwrap_or(job.shot().frames.0 as f64);
    let (first, last) = job.shot().frames;
    if !(frame >= first as f64 && frame <= last as f64) {
        return Err(CliError::BadInput(anyhow!(
            "{}: frame {frame} is outside the shot's frame range {first}-{last}",
            args.shot.display()
        )));
    }
    let choice = LayerChoice {
        highlight: args.highlight,
        layer: args.layer,
    };
    if args.pin {
        return pin(args, &mut job, frame, choice);
    }
    if args.shade {
        return shade(args, &mut job, frame);
    }
    let placed = match (&args.at, args.pixel) {
        (Some((name, uv)), _) => {
            let patch = named_patch(&job, name)?;
            let placed = job.place_at(frame, (patch, *uv), choice);
            // Solved all the same, but shading turns the surface toward the eye: seen from
            // behind, a point's highlight shows where the surface faces the other way.
            if let Ok(p) = job.pixel_of(frame, patch, *uv) {
                if !p.visible {
                    eprintln!(
                        "warning: frame {} does not show {name} at (u, v) = ({}, {}); a highlight \
                         centred there shows only where the frame sees that point",
                        frame_text(frame),
                        number(uv.0),
                        number(uv.1)
                    );
                }
            }
            placed
        }
        (None, Some(pixel)) => job.place(frame, pixel, choice),
        (None, None) => return Err(CliError::BadInput(anyhow!("give --pixel or --at"))),
    };
    let placement = placed.map_err(|e| {
        let bad = e.is_bad_input();
        let e = anyhow!("{}: {e}", args.shot.display());
        if bad {
            CliError::BadInput(e)
        } else {
            CliError::Failed(e)
        }
    })?;
    let report = report(&job, &placement);
    if args.write {
        write_keys(&report, &placement)?;
    }
    write_stdout("the placement", |out| {
        if args.json {
            serde_json::to_writer_pretty(&mut *out, &report)?;
            writeln!(out)?;
        } else {
            write_report(out, &report, &placement)?;
            if args.write {
                writeln!(out, "wrote both keys into {}", report.file)?;
            }
        }
        Ok(())
    })
}

/// Keys the placed translation's α and β at the placement's frame in the file its highlight
/// is written in ([`write_translation`]).
fn write_keys(r: &Report, p: &Placement) -> Result<(), CliError> {
    let key = |value: f32| TrackEdit::Key {
        frame: p.frame,
        value: rounded_number_text(value),
    };
    write_translation(
        &r.file,
        &r.path,
        [("alpha", key(r.alpha)), ("beta", key(r.beta))],
    )
}

/// Writes `edits` of the α and β of the translation at parameter path `path` into `file`
/// ([`apply_edits`]: only those two tracks change, checked by reading the file back), in
/// place.
fn write_translation(
    file: &str,
    path: &str,
    edits: [(&str, TrackEdit); 2],
) -> Result<(), CliError> {
    let file = Path::new(file);
    let text = std::fs::read_to_string(file)
        .map_err(|e| CliError::Failed(anyhow!("{}: cannot read the file: {e}", file.display())))?;
    let bad = |e: glint::shot::EditError| CliError::BadInput(e.in_file(file).into());
    let mut parsed = Vec::with_capacity(2);
    for (name, edit) in edits {
        let at = parse_param_path(&text, &format!("{path}.{name}")).map_err(bad)?;
        parsed.push((at, edit));
    }
    let edited = apply_edits(&text, &parsed).map_err(bad)?;
    write_in_place(file, &edited).map_err(CliError::Failed)
}

/// The placement with names and the parameter path of its translation.
fn report<'a>(job: &'a RenderJob, p: &Placement) -> Report<'a> {
    let shot = job.shot();
    let library = &shot.library;
    let (file, index) = shot
        .highlight_written(p.highlight)
        .map_or((shot.path.as_path(), p.highlight), |(f, i)| (f, i));
    Report {
        frame: p.frame,
        pixel: [p.pixel.0, p.pixel.1],
        patch: &library.patches[p.patch].name,
        parts: library
            .groups_of(p.patch)
            .map(|g| g.name.as_str())
            .collect(),
        u: p.uv.0,
        v: p.uv.1,
        highlight: p.highlight,
        file: file.display().to_string(),
        path: format!("highlights[{index}].layers[{}].stack[{}]", p.layer, p.op),
        alpha: p.translation.x,
        beta: p.translation.y,
        residuals: p
            .residuals
            .iter()
            .map(|r| ResidualReport {
                patch: &library.patches[r.patch].name,
                nearest: r.nearest,
                u: r.uv.0,
                v: r.uv.1,
                covered: r.covered,
            })
            .collect(),
        centres: p
            .centres
            .iter()
            .map(|c| {
                let (pixel, visible) = c.pixel.map_or(([f64::NAN; 2], false), |i| {
                    ([i.pixel.0, i.pixel.1], i.visible)
                });
                CentreReport {
                    patch: &library.patches[c.patch].name,
                    u: c.uv.0,
                    v: c.uv.1,
                    nearest: c.nearest,
                    pixel,
                    visible,
                }
            })
            .collect(),
    }
}

/// The first two lines of a placement: the pixel, the frame and the surface point under it,
/// then the translation placed, `PATH in FILE: Translate(alpha: A, beta: B)`.
#[allow(clippy::too_many_arguments)]
fn write_point_and_translation(
    out: &mut dyn Write,
    frame: &str,
    pixel: [f64; 2],
    patch: &str,
    parts: &[&str],
    (u, v): (f64, f64),
    (path, file): (&str, &str),
    (alpha, beta): (f32, f32),
) -> std::io::Result<()> {
    let parts = if parts.is_empty() {
        String::new()
    } else {
        format!(" ({})", parts.join(", "))
    };
    writeln!(
        out,
        "pixel ({}, {}) at frame {frame}: {patch}{parts}, u = {}, v = {}",
        number(pixel[0]),
        number(pixel[1]),
        number(u),
        number(v)
    )?;
    writeln!(
        out,
        "{path} in {file}: Translate(alpha: {}, beta: {})",
        number(f64::from(alpha)),
        number(f64::from(beta))
    )
}

fn write_report(out: &mut dyn Write, r: &Report, p: &Placement) -> std::io::Result<()> {
    write_point_and_translation(
        out,
        &r.frame.to_string(),
        r.pixel,
        r.patch,
        &r.parts,
        (r.u, r.v),
        (&r.path, &r.file),
        (r.alpha, r.beta),
    )?;
    let frame = frame_text(p.frame);
    writeln!(
        out,
        "keys at frame {frame}: alpha: ({frame}, {}), beta: ({frame}, {})",
        number(f64::from(r.alpha)),
        number(f64::from(r.beta))
    )?;
    if r.centres.len() > 1 {
        writeln!(
            out,
            "warning: the layer shows {} times: it has a centre (a least ‖N − H'‖) at each of",
            r.centres.len()
        )?;
        for c in &r.centres {
            let seen = if c.visible {
                "in view"
            } else {
                "out of view or hidden"
            };
            writeln!(
                out,
                "  {:<16} u = {}, v = {}: pixel ({}, {}), {seen}",
                c.patch,
                number(c.u),
                number(c.v),
                number(c.pixel[0]),
                number(c.pixel[1])
            )?;
        }
        writeln!(
            out,
            "  a mask on the layer keeps one (tune's mask mode draws it; docs/highlights.md)"
        )?;
    }
    if r.residuals.len() > 1 {
        writeln!(
            out,
            "the layer on each of its patches (least ‖N − H'‖²/2; 0 is a centre):"
        )?;
        for res in &r.residuals {
            let shows = if res.covered {
                "shows"
            } else {
                "does not show"
            };
            writeln!(
                out,
                "  {:<16} {:<10} at u = {}, v = {}: the highlight {shows}",
                res.patch,
                format!("{:.5}", res.nearest),
                number(res.u),
                number(res.v)
            )?;
        }
    }
    Ok(())
}

/// A number as the report and the keys write it: six significant digits.
fn number(x: f64) -> String {
    rounded_number_text(x as f32)
}

/// A pin as printed with --pin --json.
#[derive(Serialize)]
struct PinReport<'a> {
    frame: f64,
    pixel: [f64; 2],
    patch: &'a str,
    u: f32,
    v: f32,
    highlight: usize,
    file: String,
    path: String,
    pin: String,
}

/// `glint place --pin`: the layer drawn on the patch under the pixel pinned there.
fn pin(
    args: &PlaceArgs,
    job: &mut RenderJob,
    frame: f64,
    choice: LayerChoice,
) -> Result<(), CliError> {
    let shown = args.shot.display();
    let failed = |e: PlaceError| {
        let bad = e.is_bad_input();
        let e = anyhow!("{shown}: {e}");
        if bad {
            CliError::BadInput(e)
        } else {
            CliError::Failed(e)
        }
    };
    let (under, pixel) = match (&args.at, args.pixel) {
        (Some((name, uv)), _) => {
            let patch = named_patch(job, name)?;
            let under = job.layer_at(frame, (patch, *uv), choice).map_err(failed)?;
            let pixel = job.pixel_of(frame, patch, under.uv).map_err(failed)?.pixel;
            (under, pixel)
        }
        (None, Some(pixel)) => (
            job.layer_under(frame, pixel, choice).map_err(failed)?,
            pixel,
        ),
        (None, None) => return Err(CliError::BadInput(anyhow!("give --pixel or --at"))),
    };
    let LayerUnder {
        patch,
        uv,
        highlight: drawn,
        layer,
    } = under;
    let shot = job.shot();
    let name = &shot.library.patches[patch].name;
    let (file, index) = shot
        .highlight_written(drawn)
        .map_or((shot.path.as_path(), drawn), |(f, i)| (f, i));
    let rounded = |x: f64| {
        rounded_number_text(x as f32)
            .parse::<f32>()
            .unwrap_or(x as f32)
    };
    let (u, v) = (rounded(uv.0), rounded(uv.1));
    let edit = LayerEdit::Pin {
        patch: name.clone(),
        u,
        v,
    };
    let text = std::fs::read_to_string(file)
        .map_err(|e| CliError::Failed(anyhow!("{}: cannot read the file: {e}", file.display())))?;
    let edited = edit_layer(&text, index, layer, &edit)
        .map_err(|e| CliError::BadInput(e.in_file(file).into()))?;
    let report = PinReport {
        frame,
        pixel: [pixel.0, pixel.1],
        patch: name,
        u,
        v,
        highlight: drawn,
        file: file.display().to_string(),
        path: format!("highlights[{index}].layers[{layer}]"),
        pin: format!(
            "pin: (patch: {}, u: {}, v: {})",
            serde_json::to_string(name).unwrap_or_default(),
            rounded_number_text(u),
            rounded_number_text(v)
        ),
    };
    if args.write {
        write_in_place(file, &edited).map_err(CliError::Failed)?;
    }
    write_stdout("the pin", |out| {
        if args.json {
            serde_json::to_writer_pretty(&mut *out, &report)?;
            writeln!(out)?;
        } else {
            writeln!(
                out,
                "pixel ({}, {}) at frame {}: {}, u = {}, v = {}",
                number(report.pixel[0]),
                number(report.pixel[1]),
                frame_text(frame),
                report.patch,
                rounded_number_text(u),
                rounded_number_text(v)
            )?;
            writeln!(out, "{} in {}: {}", report.path, report.file, report.pin)?;
            if args.write {
                writeln!(out, "wrote the pin into {}", report.file)?;
            }
        }
        Ok(())
    })
}

/// A shade placement as printed with --shade --json.
#[derive(Serialize)]
struct ShadeReport<'a> {
    frame: f64,
    pixel: [f64; 2],
    patch: &'a str,
    parts: Vec<&'a str>,
    u: f64,
    v: f64,
    entry: usize,
    file: String,
    path: String,
    band: usize,
    threshold: f32,
    n_dot_l_before: f32,
    alpha: f32,
    beta: f32,
    alpha_keyed: bool,
    beta_keyed: bool,
}

/// `glint place --shade`: the translation of a shade entry that puts a band edge on the point
/// under the pixel.
fn shade(args: &PlaceArgs, job: &mut RenderJob, frame: f64) -> Result<(), CliError> {
    let shown = args.shot.display();
    let choice = ShadeChoice {
        entry: args.entry,
        band: args.band,
    };
    let Some(pixel) = args.pixel else {
        return Err(CliError::BadInput(anyhow!(
            "--shade places an edge under --pixel"
        )));
    };
    let p = job.place_shade(frame, pixel, choice).map_err(|e| {
        let bad = e.is_bad_input();
        let e = anyhow!("{shown}: {e}");
        if bad {
            CliError::BadInput(e)
        } else {
            CliError::Failed(e)
        }
    })?;
    let report = shade_report(job, &p);
    if args.write {
        write_shade(&report, &p)?;
    }
    write_stdout("the placement", |out| {
        if args.json {
            serde_json::to_writer_pretty(&mut *out, &report)?;
            writeln!(out)?;
        } else {
            write_shade_report(out, &report)?;
            if args.write {
                writeln!(out, "wrote alpha and beta into {}", report.file)?;
            }
        }
        Ok(())
    })
}

/// The shade placement with names, the parameter path of its translation and whether each of
/// α and β is keyed.
fn shade_report<'a>(job: &'a RenderJob, p: &ShadePlacement) -> ShadeReport<'a> {
    let shot = job.shot();
    let library = &shot.library;
    let (file, index) = shot
        .shade_written(p.entry)
        .map_or((shot.path.as_path(), p.entry), |(f, i)| (f, i));
    let keyed = |track: &glint::anim::Track<f32>| matches!(track, glint::anim::Track::Keys(_));
    let (alpha_keyed, beta_keyed) = match shot
        .shade_stack(p.entry)
        .and_then(|s| s.stack.get(p.op).cloned())
    {
        Some(glint::highlight::Op::Translate { alpha, beta }) => (keyed(&alpha), keyed(&beta)),
        _ => (false, false),
    };
    ShadeReport {
        frame: p.frame,
        pixel: [p.pixel.0, p.pixel.1],
        patch: &library.patches[p.patch].name,
        parts: library
            .groups_of(p.patch)
            .map(|g| g.name.as_str())
            .collect(),
        u: p.uv.0,
        v: p.uv.1,
        entry: p.entry,
        file: file.display().to_string(),
        path: format!("shade[{index}].stack[{}]", p.op),
        band: p.band,
        threshold: p.threshold,
        n_dot_l_before: p.n_dot_l_before,
        alpha: p.translation.x,
        beta: p.translation.y,
        alpha_keyed,
        beta_keyed,
    }
}

/// What --write does to one of α and β: its key at the frame where the track is keyed, its
/// constant where it is not.
fn shade_edit(keyed: bool, frame: f64, value: f32) -> TrackEdit {
    let value = rounded_number_text(value);
    if keyed {
        TrackEdit::Key { frame, value }
    } else {
        TrackEdit::Set(value)
    }
}

/// Writes the placed translation's α and β ([`shade_edit`]) into the file the shade entry is
/// written in ([`write_translation`]).
fn write_shade(r: &ShadeReport, p: &ShadePlacement) -> Result<(), CliError> {
    write_translation(
        &r.file,
        &r.path,
        [
            ("alpha", shade_edit(r.alpha_keyed, p.frame, r.alpha)),
            ("beta", shade_edit(r.beta_keyed, p.frame, r.beta)),
        ],
    )
}

fn write_shade_report(out: &mut dyn Write, r: &ShadeReport) -> std::io::Result<()> {
    write_point_and_translation(
        out,
        &frame_text(r.frame),
        r.pixel,
        r.patch,
        &r.parts,
        (r.u, r.v),
        (&r.path, &r.file),
        (r.alpha, r.beta),
    )?;
    writeln!(
        out,
        "band {}'s edge (N·L' = {}) through the point, where N·L' was {}",
        r.band,
        number(f64::from(r.threshold)),
        number(f64::from(r.n_dot_l_before))
    )?;
    let frame = frame_text(r.frame);
    let written = |name: &str, value: f32, keyed: bool| {
        if keyed {
            format!("{name}: key ({frame}, {})", number(f64::from(value)))
        } else {
            format!("{name}: constant {}", number(f64::from(value)))
        }
    };
    writeln!(
        out,
        "writes {}, {}",
        written("alpha", r.alpha, r.alpha_keyed),
        written("beta", r.beta, r.beta_keyed)
    )
}
