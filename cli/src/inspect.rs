//! `glint inspect`: every track of a shot read at one frame, as the animator wrote it.

use std::fmt::Write as _;
use std::path::PathBuf;

use anyhow::anyhow;
use clap::Args;
use glam::Vec3;

use super::CliError;
use glint::highlight::{Expr, Layer, Light, Outline, Segment, Shape};
use glint::render::Projection;
use glint::shot::{
    frame_text, load_shot, mask_text, op_text, rounded_number_text, MaterialState, Shot,
};
use glint::toon::{Abstraction, DetailMap, HighlightFrame, ShapeDetail, XToon};

/// Print the value of every track of a shot at one frame.
///
/// Camera, light, materials and each parameter of each highlight layer, in the shot file's own
/// syntax: numbers to 6 significant digits, vectors as (x, y, z), so that a value can be pasted
/// into the file (or given to `glint key --value`). Fractional frames show what the
/// interpolation gives between keys.
#[derive(Debug, Args)]
#[command(after_help = "Examples:
  glint inspect shots/sphere_ops.ron --frame 12
  glint inspect shots/teapot_turntable.ron --frame 30.5 --patch 'teapot/2*'")]
pub struct InspectArgs {
    /// The shot file (RON)
    shot: PathBuf,
    /// The frame (fractional frames allowed)
    #[arg(long, allow_negative_numbers = true)]
    frame: f64,
    /// Show only the patches this name or glob pattern picks (INSTANCE/PATCH)
    #[arg(long, value_name = "NAME")]
    patch: Option<String>,
}

pub fn run(args: &InspectArgs) -> Result<(), CliError> {
    let shot = load_shot(&args.shot).map_err(|e| CliError::BadInput(e.into()))?;
    if !args.frame.is_finite() {
        return Err(CliError::BadInput(anyhow!(
            "the frame must be a finite number"
        )));
    }
    let report = inspect(&shot, args.frame, args.patch.as_deref()).map_err(CliError::BadInput)?;
    print!("{report}");
    Ok(())
}

/// The report `glint inspect` prints.
fn inspect(shot: &Shot, frame: f64, patch: Option<&str>) -> anyhow::Result<String> {
    let state = shot.at(frame);
    let patches: Vec<usize> = (0..shot.library.patches.len())
        .filter(|&i| {
            patch.is_none_or(|p| glint::shot::matches_patch(p, &shot.library.patches[i].name))
        })
        .collect();
    if let (Some(pattern), true) = (patch, patches.is_empty()) {
        let example = match shot.library.patches.first() {
            Some(first) => format!("patches are named INSTANCE/PATCH, e.g. \"{}\"", first.name),
            None => "the shot has no patches".to_string(),
        };
        return Err(anyhow!(
            "--patch {pattern} picks no patch of {}; {example}",
            shot.path.display()
        ));
    }
    let mut out = String::new();
    let (first, last) = shot.frames;
    let _ = writeln!(
        out,
        "{} at frame {frame} (range {first}-{last})",
        shot.path.display()
    );
    let c = &state.camera;
    let _ = writeln!(out, "camera:");
    let _ = writeln!(out, "  eye: {}", triple(c.eye));
    let _ = writeln!(out, "  target: {}", triple(c.target));
    let _ = writeln!(out, "  up: {}", triple(c.up));
    let _ = match c.projection {
        Projection::Perspective { fov_y_degrees } => writeln!(
            out,
            "  projection: Perspective(fov_y_degrees: {})",
            number(fov_y_degrees)
        ),
        Projection::Orthographic { height } => {
            writeln!(
                out,
                "  projection: Orthographic(height: {})",
                number(height)
            )
        }
    };
    let _ = match state.light {
        Light::Directional { towards } => {
            writeln!(out, "light: Directional(towards: {})", triple(towards))
        }
        Light::Point { position } => writeln!(out, "light: Point(position: {})", triple(position)),
    };
    let names: Vec<&str> = shot.material_names().collect();
    for (index, material) in state.materials.iter().enumerate() {
        if !patches.iter().any(|&p| shot.material_of(p) == index) {
            continue;
        }
        let _ = match material {
            MaterialState::Cel(ramp) => {
                let bands: Vec<String> = ramp
                    .bands
                    .iter()
                    .map(|(t, c)| format!("({}, {})", number(*t), triple(*c)))
                    .collect();
                writeln!(
                    out,
                    "material \"{}\": Cel(base: {}, bands: [{}])",
                    names[index],
                    triple(ramp.base),
                    bands.join(", ")
                )
            }
            MaterialState::XToon(tone) => {
                writeln!(out, "material \"{}\": {}", names[index], xtoon(tone))
            }
        };
    }
    for (index, (expr, selector)) in state
        .highlights
        .iter()
        .zip(shot.highlight_selectors())
        .enumerate()
    {
        let on: Vec<&str> = patches
            .iter()
            .filter(|&&p| shot.highlight_of(p) == Some(index))
            .map(|&p| shot.library.patches[p].name.as_str())
            .collect();
        if on.is_empty() {
            continue;
        }
        // Numbered as parameter paths number them.
        let _ = writeln!(
            out,
            "highlights[{index}] ({}) on {}:",
            selector.join(", "),
            on.join(", ")
        );
        describe(expr, 1, &mut 0, &mut out);
    }
    let bare: Vec<&str> = patches
        .iter()
        .filter(|&&p| shot.highlight_of(p).is_none())
        .map(|&p| shot.library.patches[p].name.as_str())
        .collect();
    if !bare.is_empty() {
        let _ = writeln!(out, "no highlight on {}", bare.join(", "));
    }
    Ok(out)
}

/// A number as the shot file writes it, to 6 significant digits.
fn number(x: f32) -> String {
    rounded_number_text(x)
}

/// A point, vector or colour as the shot file writes it: `(x, y, z)`.
fn triple(v: Vec3) -> String {
    format!("({}, {}, {})", number(v.x), number(v.y), number(v.z))
}

/// The expression as an indented tree: Booleans with their operands, each layer's parameters
/// and then its ops one per line, in the shot file's syntax.
fn describe(expr: &Expr, depth: usize, layers: &mut usize, out: &mut String) {
    let pad = "  ".repeat(depth);
    let (name, a, b) = match expr {
        Expr::Layer(layer) => {
            let _ = writeln!(out, "{pad}layers[{layers}]: {}", layer_fields(layer));
            *layers += 1;
            for (i, op) in layer.stack.iter().enumerate() {
                let _ = writeln!(out, "{pad}  stack[{i}]: {}", op_text(op, number));
            }
            return;
        }
        Expr::Union(a, b) => ("union", a, b),
        Expr::Subtract(a, b) => ("subtract (first minus second)", a, b),
        Expr::Intersect(a, b) => ("intersect", a, b),
    };
    let _ = writeln!(out, "{pad}{name}:");
    describe(a, depth + 1, layers, out);
    describe(b, depth + 1, layers, out);
}

/// A layer's fields but its stack, as written in `Layer((…))`: a feather or mask only when it
/// has one.
fn layer_fields(layer: &Layer) -> String {
    let Layer {
        stack: _,
        epsilon,
        colour,
        opacity,
        feather,
        mask,
        // At a frame a pin is already solved into the stack's translation.
        pin: _,
        frame: _,
        shape,
        shape_map,
    } = layer;
    let mut fields = format!(
        "epsilon: {}, colour: {}, opacity: {}",
        number(*epsilon),
        triple(Vec3::from_array(*colour)),
        number(*opacity)
    );
    if let Some(feather) = feather {
        fields.push_str(&format!(", feather: {}", number(*feather)));
    }
    if let Some(m) = mask {
        fields.push_str(&format!(", {}", mask_text(m, number)));
    }
    if let Some(shape) = shape_text(shape) {
        fields.push_str(&format!(", {shape}"));
    }
    if let Some(map) = shape_map {
        // Solved at the frame for a pin that holds its shape: rows of the map.
        let m = map.matrix;
        fields.push_str(&format!(
            ", holding its shape by the map (({}, {}), ({}, {}))",
            number(m.x_axis.x),
            number(m.y_axis.x),
            number(m.x_axis.y),
            number(m.y_axis.y)
        ));
    }
    fields
}

/// A drawn shape at the frame as a shot writes it, `shape: Outline([(x, y), Bezier(…), …])`:
/// keyed outlines as the outline of their points there, with the keys it lies between and how
/// far. None for the disc.
fn shape_text(shape: &Shape) -> Option<String> {
    match shape {
        Shape::Disc => None,
        Shape::Outline(o) => Some(format!("shape: {}", outline_text(o))),
        Shape::Morph(m) => {
            let at = format!("shape: {}", outline_text(&m.lerped()));
            Some(match m.try_between_keys() {
                Some((a, b, s)) => format!(
                    "{at} (morphing from the key at frame {} to the key at frame {}, {} of the way)",
                    frame_text(a),
                    frame_text(b),
                    number(s)
                ),
                None => at,
            })
        }
    }
}

/// `Outline([…])`: each corner `(x, y)`, each Bézier `Bezier((x1, y1), (x2, y2), (x, y))`.
fn outline_text(outline: &Outline) -> String {
    let pair = |p: &[f32; 2]| format!("({}, {})", number(p[0]), number(p[1]));
    let pieces: Vec<String> = outline
        .segments
        .iter()
        .map(|segment| match segment {
            Segment::Corner(p) => pair(p),
            Segment::Bezier([c1, c2, end]) => {
                format!("Bezier({}, {}, {})", pair(c1), pair(c2), pair(end))
            }
        })
        .collect();
    format!("Outline([{}])", pieces.join(", "))
}

/// An X-Toon material without its texture, e.g.
/// `XToon(detail: Depth(z_min: 9.0, r: 3.5), invert: false)`; its shape detail when it has one.
fn xtoon(tone: &XToon) -> String {
    let XToon {
        detail,
        invert,
        shape,
    } = tone;
    let detail = match detail {
        DetailMap::Depth { z_min, r } => {
            format!("Depth(z_min: {}, r: {})", number(*z_min), number(*r))
        }
        DetailMap::DepthOfField { focus, z_min, r } => format!(
            "DepthOfField(focus: {}, z_min: {}, r: {})",
            triple(Vec3::from_array(*focus)),
            number(*z_min),
            number(*r)
        ),
        DetailMap::NearSilhouette { r } => format!("NearSilhouette(r: {})", number(*r)),
        DetailMap::Highlight { s } => format!("Highlight(s: {})", number(*s)),
    };
    let shape = match shape {
        None => String::new(),
        Some(ShapeDetail {
            abstraction,
            weight,
            highlight_frame,
        }) => {
            let abstraction = match abstraction {
                Abstraction::Sphere => "Sphere".to_string(),
                Abstraction::Ellipsoid => "Ellipsoid".to_string(),
                Abstraction::Cylinder => "Cylinder".to_string(),
                Abstraction::Smoothed { iterations } => {
                    format!("Smoothed(iterations: {iterations})")
                }
            };
            let frame = match highlight_frame {
                HighlightFrame::Abstracted => "Abstracted",
                HighlightFrame::True => "True",
            };
            format!(
                ", shape: (abstraction: {abstraction}, weight: {}, highlight_frame: {frame})",
                number(*weight)
            )
        }
    };
    format!("XToon(detail: {detail}, invert: {invert}{shape})")
}
