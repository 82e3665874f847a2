//! RON patch libraries: a list of named patches, each an exact shape or an explicit NURBS.
//! The format, with an annotated example, is described in `docs/patch-format.md`.

use glam::DVec3;
use serde::Deserialize;

use super::parse_ron::parse_ron;
use super::parts::{resolve_groups, GroupsSpec};
use super::ron_paths::Step::{Field, Index};
use super::FormatError;
use crate::geom::{shapes, GeomError, NamedPatch, NurbsSurface, PatchLibrary};

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LibraryFile {
    patches: Vec<PatchSpec>,
    /// Named parts: each a list of patch names or 0-based indices.
    #[serde(default)]
    groups: GroupsSpec,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PatchSpec {
    name: String,
    surface: BuiltSurface,
}

type Point = (f64, f64, f64);

/// A surface as written in the file. Validation runs while the file is parsed, so an error is
/// reported at the surface it concerns.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
enum SurfaceSpec {
    Sphere {
        radius: f64,
        #[serde(default)]
        center: Point,
    },
    Cylinder {
        radius: f64,
        height: f64,
    },
    Torus {
        major_radius: f64,
        minor_radius: f64,
    },
    Plane {
        width: f64,
        height: f64,
    },
    Bezier {
        points: Vec<Vec<Point>>,
    },
    Nurbs {
        degree: (usize, usize),
        knots_u: Vec<f64>,
        knots_v: Vec<f64>,
        points: Vec<Vec<Point>>,
        #[serde(default)]
        weights: Option<Vec<Vec<Weight>>>,
    },
}

/// A control point weight, checked where it is written: finite and greater than 0.
#[derive(Clone, Copy, Deserialize)]
#[serde(try_from = "f64")]
struct Weight(f64);

impl TryFrom<f64> for Weight {
    type Error = String;

    fn try_from(w: f64) -> Result<Self, String> {
        if w.is_finite() && w > 0.0 {
            Ok(Weight(w))
        } else {
            Err(format!(
                "weight {w} is not allowed: weights must be finite and greater than 0"
            ))
        }
    }
}

#[derive(Deserialize)]
#[serde(try_from = "SurfaceSpec")]
struct BuiltSurface(NurbsSurface);

impl TryFrom<SurfaceSpec> for BuiltSurface {
    type Error = GeomError;

    fn try_from(spec: SurfaceSpec) -> Result<Self, GeomError> {
        let net = |points: Vec<Vec<Point>>| -> Vec<Vec<DVec3>> {
            points
                .into_iter()
                .map(|row| row.into_iter().map(DVec3::from).collect())
                .collect()
        };
        let surface = match spec {
            SurfaceSpec::Sphere { radius, center } => shapes::sphere(center.into(), radius)?,
            SurfaceSpec::Cylinder { radius, height } => shapes::cylinder(radius, height)?,
            SurfaceSpec::Torus {
                major_radius,
                minor_radius,
            } => shapes::torus(major_radius, minor_radius)?,
            SurfaceSpec::Plane { width, height } => shapes::plane(width, height)?,
            SurfaceSpec::Bezier { points } => {
                let rows = points.len();
                let columns = points.first().map_or(0, Vec::len);
                shapes::bezier(
                    rows.saturating_sub(1),
                    columns.saturating_sub(1),
                    &net(points),
                )?
            }
            SurfaceSpec::Nurbs {
                degree: (degree_u, degree_v),
                knots_u,
                knots_v,
                points,
                weights,
            } => {
                let weights: Option<Vec<Vec<f64>>> = weights.map(|w| {
                    w.into_iter()
                        .map(|row| row.into_iter().map(|w| w.0).collect())
                        .collect()
                });
                NurbsSurface::new(
                    degree_u,
                    degree_v,
                    knots_u,
                    knots_v,
                    &net(points),
                    weights.as_deref(),
                )?
            }
        };
        Ok(BuiltSurface(surface))
    }
}

/// Reads a RON patch library; `path` is used in error messages only.
pub fn parse_patch_ron(text: &str, path: &str) -> Result<PatchLibrary, FormatError> {
    let file: LibraryFile = parse_ron(text, path)?;
    let mut patches: Vec<NamedPatch> = Vec::with_capacity(file.patches.len());
    for (index, spec) in file.patches.into_iter().enumerate() {
        if patches.iter().any(|p| p.name == spec.name) {
            return Err(FormatError::ron_at(
                text,
                path,
                &[Field("patches"), Index(index), Field("name")],
                format!(
                    "the patch name \"{}\" is used twice; patch names must be unique",
                    spec.name
                ),
            ));
        }
        patches.push(NamedPatch {
            name: spec.name,
            trim: None,
            surface: spec.surface.0,
        });
    }
    let groups = resolve_groups(&file.groups, &patches, &[]).map_err(|e| {
        FormatError::ron_at(text, path, &e.path(&[Field("groups")]), e.message.clone())
    })?;
    Ok(PatchLibrary { patches, groups })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn error_of(text: &str) -> String {
        parse_patch_ron(text, "m.ron").unwrap_err().to_string()
    }

    #[test]
    fn syntax_errors_and_unknown_fields_have_a_location() {
        let e = error_of("(patches: [(name: \"a\", surface: Sphere(radius: 1.0)]");
        assert!(e.starts_with("m.ron:1:"), "{e}");
        let e = error_of("(patches: [\n  (name: \"a\", surface: Sphere(radius: 1.0, colour: 1))])");
        assert!(e.starts_with("m.ron:2:") && e.contains("colour"), "{e}");
    }

    #[test]
    fn bad_weight_is_reported_where_it_is_written() {
        let text = "(patches: [(name: \"p\", surface: Nurbs(degree: (1, 1),\n knots_u: [0, 0, 1, 1], knots_v: [0, 0, 1, 1],\n points: [[(0, 0, 0), (0, 1, 0)], [(1, 0, 0), (1, 1, 0)]],\n weights: Some([[1, 1], [1, -2]]))\n)])";
        let e = error_of(text);
        assert!(e.starts_with("m.ron:4:"), "{e}");
        assert!(e.contains("weight -2"), "{e}");
    }

    #[test]
    fn wrong_knot_count_names_the_counts_and_the_line() {
        let text = "(patches: [\n(name: \"p\", surface: Nurbs(degree: (1, 1),\n knots_u: [0, 0, 1], knots_v: [0, 0, 1, 1],\n points: [[(0, 0, 0), (0, 1, 0)], [(1, 0, 0), (1, 1, 0)]]))\n])";
        let e = error_of(text);
        assert!(
            e.starts_with("m.ron:2:22: u direction: 3 knots given"),
            "{e}"
        );
        assert!(e.contains("needs 4"), "{e}");
    }

    #[test]
    fn duplicate_names_point_at_the_second() {
        let text = "(patches: [\n(name: \"a\", surface: Plane(width: 1, height: 1)),\n(name: \"a\", surface: Plane(width: 1, height: 1)),\n])";
        assert_eq!(
            error_of(text),
            "m.ron:3:8: the patch name \"a\" is used twice; patch names must be unique"
        );
        // The name written in a comment first does not mislead the location.
        let commented = format!("// \"a\" and \"a\" again\n{text}");
        assert!(
            error_of(&commented).starts_with("m.ron:4:8: "),
            "{}",
            error_of(&commented)
        );
    }
}
