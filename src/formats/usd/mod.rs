//! USD text layers (`.usda`): the `NurbsPatch` prims of one flattened layer, placed by their
//! `Xform` ancestors, named by their prim paths and grouped by their parents.
//!
//! What is read: `def` prims; `Xform`, `Scope` and untyped prims as groups (an `Xform`'s ops
//! transform everything under it); `NurbsPatch` prims ([`nurbs_patch`]) and their trim curves
//! ([`trim_curves`]); the layer's `upAxis`
//! (a `"Y"`-up layer is turned to glint's z up: `(x, y, z) ↦ (x, −z, y)`). Prims that are
//! inactive or invisible are left out, with everything under them, and so are prims of types
//! that draw nothing (materials, shaders, cameras, lights). What is refused, where it is
//! written: composition (`over`, `class`, references, payloads, inherits, specializes,
//! variants, sublayers), animated values (time samples, splines), connected attributes glint
//! reads, trim loops that are not closed or run the wrong way, and geometry glint does not draw
//! (meshes, curves, points, implicit shapes).

#[cfg(feature = "usd-binary")]
mod binary;
mod layer;
mod lexer;
mod nurbs_patch;
mod text;
mod trim_curves;
mod xform;

use glam::{DMat4, DVec3};

use super::FormatError;
use crate::geom::{NamedPatch, PatchGroup, PatchLibrary};
use layer::{Prim, Value};

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
/// and one part per prim above patches (`car`), holding every patch under it.
pub fn parse_usda(text: &str, shown: &str) -> Result<PatchLibrary, FormatError> {
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

/// Reads the binary USD layer at `path` (shown in errors as `shown`) as [`parse_usda`] reads a
/// text one. Its errors name the prim, having no line and column.
#[cfg(feature = "usd-binary")]
pub fn read_usdc(path: &std::path::Path, shown: &str) -> Result<PatchLibrary, FormatError> {
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
) -> Result<PatchLibrary, FormatError> {
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
    let mut library = PatchLibrary::default();
    let mut walker = Walker {
        library: &mut library,
        at,
    };
    for prim in &layer.prims {
        walker.prim(prim, "", up)?;
    }
    if library.patches.is_empty() {
        return Err(at(
            0,
            "the layer has no NurbsPatch prim to draw".to_string(),
        ));
    }
    Ok(library)
}

struct Walker<'a> {
    library: &'a mut PatchLibrary,
    at: &'a dyn Fn(usize, String) -> FormatError,
}

impl Walker<'_> {
    fn error(&self, offset: usize, message: String) -> FormatError {
        (self.at)(offset, message)
    }

    /// Reads `prim`, under the prim at `parent` (`""` at the root) whose world transform is
    /// `world`.
    fn prim(&mut self, prim: &Prim, parent: &str, world: DMat4) -> Result<(), FormatError> {
        let path = if parent.is_empty() {
            prim.name.clone()
        } else {
            format!("{parent}/{}", prim.name)
        };
        let shown_path = format!("/{path}");
        let invisible = matches!(
            prim.property("visibility").and_then(|p| p.value.as_ref()),
            Some(Value::Str(s)) if s == "invisible"
        );
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
        let world = if type_name == "Scope" {
            world
        } else {
            let (local, reset) = xform::local_transform(prim, &shown_path)
                .map_err(|e| self.error(e.at, e.message))?;
            if reset {
                local
            } else {
                world * local
            }
        };
        let first = self.library.patches.len();
        if type_name == "NurbsPatch" {
            if self.library.patches.len() >= MAX_PATCHES {
                return Err(self.error(
                    prim.at,
                    format!("the file has more than {MAX_PATCHES} patches"),
                ));
            }
            let (surface, mirrored) =
                nurbs_patch::surface(prim, &shown_path).map_err(|e| self.error(e.at, e.message))?;
            let trim = trim_curves::trim(prim, &shown_path, surface.domain(), mirrored)
                .map_err(|e| self.error(e.at, e.message))?;
            let placed = place(&surface, world)
                .map_err(|m| self.error(prim.at, format!("{shown_path}: {m}")))?;
            self.library.patches.push(NamedPatch {
                name: path.clone(),
                trim,
                surface: placed,
            });
        }
        for child in &prim.children {
            self.prim(child, &path, world)?;
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
