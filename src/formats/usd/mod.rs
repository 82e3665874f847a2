//! USD text layers (`.usda`): the `NurbsPatch` prims of one flattened layer, placed by their
//! `Xform` ancestors, named by their prim paths and grouped by their parents.
//!
//! What is read: `def` prims; `Xform`, `Scope` and untyped prims as groups (an `Xform`'s ops
//! transform everything under it); `NurbsPatch` prims ([`nurbs_patch`]) and their trim curves
//! ([`trim_curves`]); the layer's `upAxis`
//! (a `"Y"`-up layer is turned to glint's z up: `(x, y, z) ↦ (x, −z, y)`). Prims that are
//! inactive or invisible are left out, with everything under them, and so are prims of types
//! that draw nothing (materials, shaders, cameras, lights). Time-sampled `points` and xformOps
//! animate the patches ([`motion`]). What is refused, where it is written: composition (`over`,
//! `class`, references, payloads, inherits, specializes, variants, sublayers), splines, other
//! attributes glint reads whose time samples differ, connected attributes glint reads, trim
//! loops that are not closed or run the wrong way, and geometry glint does not draw (meshes,
//! curves, points, implicit shapes). A binary layer (`.usdc`, with the `usd-binary` feature) is
//! read into the same [`Layer`](layer::Layer) and from there the same way.

#[cfg(feature = "usd-binary")]
mod binary;
mod layer;
mod lexer;
mod motion;
mod nurbs_patch;
mod text;
mod track;
mod trim_curves;
mod xform;

use glam::{DMat4, DVec3};

use super::FormatError;
use crate::geom::{NamedPatch, PatchGroup, PatchLibrary};
use layer::{Prim, Value};
use motion::{compose_reach, reach_of, Node, PatchMotion};
pub use motion::{TimeCodes, UsdMotion, DEFAULT_TIME_CODES_PER_SECOND};
pub use text::MAX_SAMPLES;

/// Prim types that are geometry glint does not draw: a file with one is refused rather than
/// drawn without it.
const UNDRAWN_GEOMETRY: [&str; 14] = [
    "Mesh",
    "Points",
    "BasisCurves",
    "NurbsCurves",
    "HermiteCurves",
    "TetMesh",
    "Sphere",
    "Cube",
    "Cone",
    "Cylinder",
    "Cylinder_1",
    "Capsule",
    "Plane",
    "PointInstancer",
];

/// The most patches one file may hold.
pub const MAX_PATCHES: usize = 100_000;

/// Reads the USDA layer `text` (shown in errors as `shown`) into a library: one patch per
/// `NurbsPatch` prim, named by its path without the leading `/` (`/car/hood` → `car/hood`),
/// and one part per prim above patches (`car`), holding every patch under it. A time-sampled
/// value is read at its earliest sample.
pub fn parse_usda(text: &str, shown: &str) -> Result<PatchLibrary, FormatError> {
    Ok(parse_usda_motion(text, shown)?.0)
}

/// Reads the USDA layer `text` as [`parse_usda`] does, with how its patches move: None when
/// no patch's control points change over time.
pub fn parse_usda_motion(
    text: &str,
    shown: &str,
) -> Result<(PatchLibrary, Option<UsdMotion>), FormatError> {
    let at = |offset: usize, message: String| located(text, shown, offset, message);
    let header = text.lines().next().unwrap_or("");
    if !header.starts_with("#usda ") {
        return Err(at(
            0,
            "not a USD text layer: the first line must be `#usda 1.0` (for a binary .usdc or .usd, convert it: usdcat model.usdc -o model.usda)".to_string(),
        ));
    }
    let tokens = lexer::tokens(text).map_err(|e| at(e.at, e.message))?;
    let layer = text::parse(&tokens, text.len()).map_err(|e| at(e.at, e.message))?;
    library_of(&layer, &at)
}

/// The time codes of `layer`'s metadata, a rate that is not positive refused.
fn time_codes_of(
    times: &layer::LayerTimes,
    at: &dyn Fn(usize, String) -> FormatError,
) -> Result<TimeCodes, FormatError> {
    for (name, rate) in [
        ("timeCodesPerSecond", times.time_codes_per_second),
        ("framesPerSecond", times.frames_per_second),
    ] {
        if let Some((x, offset)) = rate {
            if x <= 0.0 {
                return Err(at(
                    offset,
                    format!("`{name}` is {x}; it must be more than 0"),
                ));
            }
        }
    }
    Ok(TimeCodes {
        per_second: times
            .time_codes_per_second
            .map_or(DEFAULT_TIME_CODES_PER_SECOND, |(x, _)| x),
        frames_per_second: times.frames_per_second.map(|(x, _)| x),
        start: times.start_time_code.map(|(x, _)| x),
        end: times.end_time_code.map(|(x, _)| x),
    })
}

/// Whether a property of `prims` or a prim under them has time samples holding more than one
/// value.
fn animates(prims: &[Prim]) -> bool {
    prims
        .iter()
        .any(|p| p.properties.iter().any(layer::Property::varies) || animates(&p.children))
}

/// Reads the binary USD layer at `path` (shown in errors as `shown`) as [`parse_usda_motion`]
/// reads a text one, with how its patches move: the same time samples and time codes give the
/// same motion. Its errors name the prim, having no line and column.
#[cfg(feature = "usd-binary")]
pub fn read_usdc_motion(
    path: &std::path::Path,
    shown: &str,
) -> Result<(PatchLibrary, Option<UsdMotion>), FormatError> {
    let at = |_: usize, message: String| FormatError::File {
        path: shown.to_string(),
        message,
    };
    let layer = binary::read(path).map_err(|m| at(layer::NOWHERE, m))?;
    library_of(&layer, &at)
}

/// The error `message` at byte `offset` of `text`, a file shown as `shown`.
fn located(text: &str, shown: &str, offset: usize, message: String) -> FormatError {
    let (line, col) = super::ron_location::position_of(text, offset.min(text.len()));
    FormatError::Usd {
        path: shown.to_string(),
        line,
        col,
        message,
    }
}

/// The library of `layer`, `at` placing an error at what it is about.
fn library_of(
    layer: &layer::Layer,
    at: &dyn Fn(usize, String) -> FormatError,
) -> Result<(PatchLibrary, Option<UsdMotion>), FormatError> {
    let up = match &layer.up_axis {
        None => DMat4::IDENTITY,
        Some((axis, _)) if axis == "Z" => DMat4::IDENTITY,
        Some((axis, _)) if axis == "Y" => DMat4::from_cols(
            glam::DVec4::X,
            glam::DVec4::Z,
            -glam::DVec4::Y,
            glam::DVec4::W,
        ),
        Some((axis, offset)) => {
            return Err(at(
                *offset,
                format!("upAxis \"{axis}\" is neither \"Y\" nor \"Z\""),
            ))
        }
    };
    let time_codes = time_codes_of(&layer.times, at)?;
    let mut library = PatchLibrary::default();
    let mut walker = Walker {
        library: &mut library,
        at,
        animated: animates(&layer.prims),
        nodes: Vec::new(),
        motions: Vec::new(),
    };
    let root = Placement {
        world: up,
        node: None,
        since: up,
    };
    for prim in &layer.prims {
        walker.prim(prim, "", &root)?;
    }
    let (nodes, motions) = (walker.nodes, walker.motions);
    if library.patches.is_empty() {
        return Err(at(
            0,
            "the layer has no NurbsPatch prim to draw".to_string(),
        ));
    }
    let motion = if motions.len() == library.patches.len() {
        UsdMotion::try_new(time_codes, nodes, motions)
    } else {
        None
    };
    Ok((library, motion))
}

/// Where a prim is placed: its world transform with every value at its earliest sample, and
/// its world transform over time, `N(t) · since` ([`motion`]).
#[derive(Clone, Copy)]
struct Placement {
    world: DMat4,
    node: Option<usize>,
    since: DMat4,
}

struct Walker<'a> {
    library: &'a mut PatchLibrary,
    at: &'a dyn Fn(usize, String) -> FormatError,
    /// Whether the layer has values that change over time: only then is motion kept.
    animated: bool,
    nodes: Vec<Node>,
    /// One per patch, when `animated`.
    motions: Vec<PatchMotion>,
}

impl Walker<'_> {
    fn error(&self, offset: usize, message: String) -> FormatError {
        (self.at)(offset, message)
    }

    /// Reads `prim`, under the prim at `parent` (`""` at the root) placed at `placement`.
    fn prim(
        &mut self,
        prim: &Prim,
        parent: &str,
        placement: &Placement,
    ) -> Result<(), FormatError> {
        let path = if parent.is_empty() {
            prim.name.clone()
        } else {
            format!("{parent}/{}", prim.name)
        };
        let shown_path = format!("/{path}");
        let visibility = match prim.property("visibility") {
            None => None,
            Some(p) => p.held_value().map_err(|e| {
                self.error(e.at, format!("{shown_path}: `visibility` {}", e.message))
            })?,
        };
        let invisible = matches!(visibility, Some(Value::Str(s)) if s == "invisible");
        if prim.inactive || invisible {
            return Ok(());
        }
        let type_name = prim.type_name.as_deref().unwrap_or("");
        if UNDRAWN_GEOMETRY.contains(&type_name) {
            return Err(self.error(
                prim.at,
                format!("{shown_path} is a {type_name}; glint draws NurbsPatch prims only — convert it to NURBS, or deactivate it (active = false)"),
            ));
        }
        let placed = matches!(type_name, "Xform" | "NurbsPatch" | "" | "Scope");
        if !placed {
            // Materials, shaders, cameras, lights: nothing to draw under them.
            return Ok(());
        }
        let placement = if type_name == "Scope" {
            *placement
        } else {
            let local = xform::read(prim, &shown_path).map_err(|e| self.error(e.at, e.message))?;
            self.placement_under(placement, local)
        };
        let world = placement.world;
        let first = self.library.patches.len();
        if type_name == "NurbsPatch" {
            if self.library.patches.len() >= MAX_PATCHES {
                return Err(self.error(
                    prim.at,
                    format!("the file has more than {MAX_PATCHES} patches"),
                ));
            }
            let read =
                nurbs_patch::surface(prim, &shown_path).map_err(|e| self.error(e.at, e.message))?;
            let surface = &read.surface;
            let trim = trim_curves::trim(prim, &shown_path, surface.domain(), read.mirrored)
                .map_err(|e| self.error(e.at, e.message))?;
            let placed = place(surface, world)
                .map_err(|m| self.error(prim.at, format!("{shown_path}: {m}")))?;
            if self.animated {
                let motion = self.patch_motion(read, &placement);
                if motion.moves() {
                    self.check_reach(&motion, prim.at, &shown_path)?;
                }
                self.motions.push(motion);
            }
            self.library.patches.push(NamedPatch {
                name: path.clone(),
                trim,
                surface: placed,
            });
        }
        for child in &prim.children {
            self.prim(child, &path, &placement)?;
        }
        let last = self.library.patches.len();
        let holds_more = last - first > usize::from(type_name == "NurbsPatch");
        if type_name != "NurbsPatch" && holds_more {
            self.library.groups.push(PatchGroup {
                name: path,
                patches: (first..last).collect(),
            });
        }
        Ok(())
    }
}

impl Walker<'_> {
    /// The placement of a prim whose own transform is `local`, under `parent`'s: a transform
    /// that changes over time starts a node of the motion.
    fn placement_under(&mut self, parent: &Placement, local: xform::LocalXform) -> Placement {
        let first = local.matrix_first();
        let world = if local.reset {
            first
        } else {
            parent.world * first
        };
        let (node, since) = if local.reset {
            (None, DMat4::IDENTITY)
        } else {
            (parent.node, parent.since)
        };
        if !(self.animated && local.varies()) {
            return Placement {
                world,
                node,
                since: since * first,
            };
        }
        let parent_reach = node.map_or((1.0, 0.0), |n| self.nodes[n].reach);
        let reach = compose_reach(compose_reach(parent_reach, reach_of(since)), local.reach());
        self.nodes.push(Node {
            parent: node,
            prefix: since,
            local,
            reach,
        });
        Placement {
            world,
            node: Some(self.nodes.len() - 1),
            since: DMat4::IDENTITY,
        }
    }

    /// How the patch `read`, placed at `placement`, moves.
    fn patch_motion(&self, read: nurbs_patch::PatchRead, placement: &Placement) -> PatchMotion {
        let (times, points) = if read.samples.is_empty() {
            (vec![0.0], vec![read.surface.control_points().collect()])
        } else {
            read.samples.into_iter().unzip()
        };
        PatchMotion {
            node: placement.node,
            since: placement.since,
            times,
            points,
        }
    }

    /// Refuses a moving patch whose transforms may carry a control point beyond the
    /// coordinates glint evaluates at some time: `a·|P| + b` with `(a, b)` the reach of its
    /// transforms and |P| its farthest point over its samples.
    fn check_reach(
        &self,
        motion: &PatchMotion,
        at: usize,
        shown_path: &str,
    ) -> Result<(), FormatError> {
        let node_reach = motion.node.map_or((1.0, 0.0), |n| self.nodes[n].reach);
        let (a, b) = compose_reach(node_reach, reach_of(motion.since));
        let farthest = motion
            .points
            .iter()
            .flatten()
            .map(|p| p.length())
            .fold(0.0f64, f64::max);
        let far = a * farthest + b;
        if far.is_finite() && far <= crate::geom::MAX_COORDINATE {
            return Ok(());
        }
        Err(self.error(
            at,
            format!(
                "{shown_path}: its animation may carry a control point as far as {far:e}, beyond ±{:e}",
                crate::geom::MAX_COORDINATE
            ),
        ))
    }
}

/// `surface` with its control points moved by `world`; a point moved beyond the coordinates
/// glint evaluates is refused.
fn place(
    surface: &crate::geom::NurbsSurface,
    world: DMat4,
) -> Result<crate::geom::NurbsSurface, String> {
    if world == DMat4::IDENTITY {
        return Ok(surface.clone());
    }
    let moved = surface.map_points(|p: DVec3| world.transform_point3(p));
    let far = moved
        .control_points()
        .map(|p| p.abs().max_element())
        .fold(0.0f64, f64::max);
    if far.is_nan() || far > crate::geom::MAX_COORDINATE {
        return Err(format!(
            "its transform places a control point at {far:e}, beyond ±{:e}",
            crate::geom::MAX_COORDINATE
        ));
    }
    Ok(moved)
}
