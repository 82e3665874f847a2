//! `glint patches`: the patches and named parts of a model or of a shot's placed instances —
//! what a selector can name.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::anyhow;
use clap::Args;
use serde::Serialize;

use super::{write_stdout, CliError};
use glint::formats::load_patches;
use glint::formats::ron_paths::top_level_name;
use glint::geom::{Edge, PatchLibrary};
use glint::picture::patch_map::number_runs;
use glint::shot::{load_shot, Shot};

/// List the patches and named parts (groups) of a patch file, or of a shot's instances.
///
/// Given a shot, the names are the ones its selectors match: `INSTANCE/PATCH` and
/// `INSTANCE/PART`. For each patch: its index, name, degrees, parameter domain, knot spans, the
/// edges that collapse to a point (where the frame is the limit from inside the patch) and how
/// many trim loops cut it.
/// Each part is listed with the patches it groups. Parts come from a patch library's `groups`,
/// from a `NAME.parts.ron` file beside the model (`teapot.bpt` → `teapot.parts.ron`), and from
/// an instance's `groups` in the shot.
///
/// With --map, also draws the patch map: the model as the shot's camera sees it at --frame (or,
/// for a patch file, from a three-quarter view framing it), each patch in its own flat colour
/// shaded lightly by how it faces the eye, the seams between patches and the silhouette drawn
/// dark, each visible patch labelled with its name, and a legend of the parts and their
/// patches (`lid: 24-27`) in the emptiest corner.
#[derive(Debug, Args)]
#[command(after_help = "Examples:
  glint patches patches/teapot.bpt
  glint patches shots/teapot_turntable.ron
  glint patches patches/car_panels.ron --json
  glint patches patches/teapot.bpt --map out/teapot.map.png
  glint patches shots/teapot_turntable.ron --map out/turntable.map.png --frame 48")]
pub struct PatchesArgs {
    /// A patch file (.ron library or .bpt), or a shot file
    file: PathBuf,
    /// Print JSON instead of a table
    #[arg(long)]
    json: bool,
    /// Also draw the patch map to this PNG (written atomically)
    #[arg(long, value_name = "OUT.png")]
    map: Option<PathBuf>,
    /// The frame of the shot whose camera the map shows (fractional frames allowed)
    /// [default: the shot's first frame]
    #[arg(long, value_name = "F", requires = "map")]
    frame: Option<f64>,
    /// The map's size [default: the shot's resolution, or 800x600 for a patch file]
    #[arg(long, value_name = "WxH", requires = "map", value_parser = super::render::parse_size)]
    size: Option<(u32, u32)>,
}

/// One patch, as listed.
#[derive(Serialize)]
struct PatchRow {
    index: usize,
    name: String,
    degree: [usize; 2],
    domain: [[f64; 2]; 2],
    spans: [usize; 2],
    collapsed: Vec<String>,
    /// The trim loops that cut the patch (0 when it is untrimmed).
    trim_loops: usize,
    parts: Vec<String>,
}

/// One part, as listed.
#[derive(Serialize)]
struct PartRow {
    name: String,
    patches: Vec<usize>,
}

#[derive(Serialize)]
struct Listing {
    patches: Vec<PatchRow>,
    parts: Vec<PartRow>,
}

pub fn run(args: &PatchesArgs) -> Result<(), CliError> {
    let (library, shot) = read(&args.file).map_err(CliError::BadInput)?;
    if let Some(out) = &args.map {
        let view = super::patch_map::MapView {
            file: &args.file,
            shot: shot.as_ref(),
            frame: args.frame,
            size: args.size,
        };
        super::patch_map::write_map(&library, &view, out)?;
    }
    let listing = listing(&library);
    write_stdout("the listing", |out| {
        if args.json {
            serde_json::to_writer_pretty(&mut *out, &listing)?;
            writeln!(out)?;
        } else {
            write_table(out, &args.file, &listing)?;
        }
        Ok(())
    })
}

/// The model of a patch file, or the placed model of a shot (a `.ron` file whose top level is
/// `Shot(…)`) and the shot.
fn read(path: &Path) -> anyhow::Result<(Arc<PatchLibrary>, Option<Shot>)> {
    let is_ron = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("ron"));
    if is_ron {
        let text = std::fs::read_to_string(path)
            .map_err(|e| anyhow!("{}: cannot read the file: {e}", path.display()))?;
        if top_level_name(&text) == Some("Shot") {
            let shot = load_shot(path)?;
            return Ok((Arc::clone(&shot.library), Some(shot)));
        }
    }
    Ok((Arc::new(load_patches(path)?), None))
}

fn listing(library: &PatchLibrary) -> Listing {
    let patches = library
        .patches
        .iter()
        .enumerate()
        .map(|(index, patch)| {
            let s = &patch.surface;
            let domain = s.domain();
            PatchRow {
                index,
                name: patch.name.clone(),
                degree: [s.knots_u().degree(), s.knots_v().degree()],
                domain: [[domain.u.0, domain.u.1], [domain.v.0, domain.v.1]],
                spans: [
                    spans(s.knots_u().knots(), s.knots_u().degree(), s.count_u()),
                    spans(s.knots_v().knots(), s.knots_v().degree(), s.count_v()),
                ],
                collapsed: s.collapsed_edges().iter().map(Edge::to_string).collect(),
                trim_loops: patch.trim.as_ref().map_or(0, |t| t.loops().len()),
                parts: library.groups_of(index).map(|g| g.name.clone()).collect(),
            }
        })
        .collect();
    let parts = library
        .groups
        .iter()
        .map(|g| PartRow {
            name: g.name.clone(),
            patches: g.patches.clone(),
        })
        .collect();
    Listing { patches, parts }
}

/// The knot spans of non-zero length inside the domain `[t_p, t_n]`.
fn spans(knots: &[f64], degree: usize, count: usize) -> usize {
    knots[degree..=count]
        .windows(2)
        .filter(|w| w[1] > w[0])
        .count()
}

fn write_table(out: &mut dyn Write, file: &Path, listing: &Listing) -> std::io::Result<()> {
    writeln!(
        out,
        "{}: {} patches, {} parts",
        file.display(),
        listing.patches.len(),
        listing.parts.len()
    )?;
    let width = listing
        .patches
        .iter()
        .map(|p| p.name.chars().count())
        .chain(listing.parts.iter().map(|p| p.name.chars().count()))
        .max()
        .unwrap_or(4)
        .max(4);
    writeln!(
        out,
        "{:>5}  {:<width$}  {:<6}  {:<27}  {:<5}  {:<15}  {:<8}  parts",
        "index", "name", "degree", "domain (u × v)", "spans", "collapsed", "trim"
    )?;
    for p in &listing.patches {
        let domain = format!(
            "[{}, {}] × [{}, {}]",
            p.domain[0][0], p.domain[0][1], p.domain[1][0], p.domain[1][1]
        );
        let collapsed = if p.collapsed.is_empty() {
            "-".to_string()
        } else {
            p.collapsed.join(" ")
        };
        let trim = match p.trim_loops {
            0 => "-".to_string(),
            1 => "1 loop".to_string(),
            n => format!("{n} loops"),
        };
        writeln!(
            out,
            "{:>5}  {:<width$}  {:<6}  {:<27}  {:<5}  {:<15}  {:<8}  {}",
            p.index,
            p.name,
            format!("{}×{}", p.degree[0], p.degree[1]),
            domain,
            format!("{}×{}", p.spans[0], p.spans[1]),
            collapsed,
            trim,
            p.parts.join(" ")
        )?;
    }
    if !listing.parts.is_empty() {
        writeln!(out)?;
        writeln!(out, "{:<width$}  patches", "part")?;
        for part in &listing.parts {
            writeln!(
                out,
                "{:<width$}  {}",
                part.name,
                index_ranges(&part.patches)
            )?;
        }
    }
    Ok(())
}

/// Increasing indices written with runs shortened: `0-3 8 10-11`.
fn index_ranges(indices: &[usize]) -> String {
    number_runs(&indices.iter().map(|&i| i as u64).collect::<Vec<_>>())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn runs_of_indices_are_shortened() {
        assert_eq!(index_ranges(&[0, 1, 2, 3, 8, 10, 11]), "0-3 8 10-11");
        assert_eq!(index_ranges(&[]), "");
    }

    #[test]
    fn spans_count_intervals_of_nonzero_length_inside_the_domain() {
        // Degree 2, 5 control points, one double interior knot.
        assert_eq!(spans(&[0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0], 2, 5), 2);
        assert_eq!(spans(&[0.0, 0.0, 1.0, 1.0], 1, 2), 1);
    }
}
