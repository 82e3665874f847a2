//! USD text layers: the NURBS sphere and torus that the USD library writes are glint's own
//! surfaces; transforms place patches as USD composes them; random patches written as USDA read
//! back to the surfaces built in code; every refusal is one located line, exit 2.

use glam::DVec3;
use glint::formats::{load_patches, parse_usda};
use glint::geom::{NurbsSurface, PatchLibrary};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};

use crate::common::{flat_patch, glint_with as glint, repo_file, stderr};

/// The largest difference of point and first derivatives between `a` and `b` at `n` random
/// parameters of their (shared) domain.
fn largest_difference(a: &NurbsSurface, b: &NurbsSurface, n: usize, seed: u64) -> f64 {
    let domain = a.domain();
    assert_eq!(domain, b.domain());
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let mut most = 0.0f64;
    for _ in 0..n {
        let (u, v) = domain.lerp(rng.random::<f64>(), rng.random::<f64>());
        let (da, db) = (a.derivs(u, v, 1), b.derivs(u, v, 1));
        for (p, q) in [(da.point, db.point), (da.su, db.su), (da.sv, db.sv)] {
            most = most.max((p - q).abs().max_element());
        }
    }
    most
}

#[test]
fn the_usd_library_s_sphere_and_torus_are_glint_s_own() {
    for (usda, ron) in [
        ("patches/sphere.usda", "patches/sphere.ron"),
        ("patches/torus.usda", "patches/torus.ron"),
    ] {
        let from_usd = load_patches(&repo_file(usda)).unwrap();
        let own = load_patches(&repo_file(ron)).unwrap();
        assert_eq!(from_usd.patches.len(), 1, "{usda}");
        let difference = largest_difference(
            &from_usd.patches[0].surface,
            &own.patches[0].surface,
            500,
            7,
        );
        assert!(difference <= 1e-12, "{usda}: {difference:e} from {ron}");
    }
    // And through the command line, as a user probes it.
    let out = glint(&[
        "probe",
        repo_file("patches/sphere.usda").to_str().unwrap(),
        "--patch",
        "sphere",
        "--uv",
        "0.3,0.6",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
}

/// A bilinear patch (order 2 × 2) on the unit square, as USDA, under `/car` transformed by
/// `ops` (the text of its xformOps and their order).
fn hood(ops: &str, patch_ops: &str) -> String {
    format!(
        r#"#usda 1.0
(
    upAxis = "Z"
)

def Xform "car"
{{
{ops}
    def Scope "panels"
    {{
        def NurbsPatch "hood"
        {{
{patch_ops}
            int uVertexCount = 2
            int vVertexCount = 2
            int uOrder = 2
            int vOrder = 2
            double[] uKnots = [0, 0, 1, 1]
            double[] vKnots = [0, 0, 1, 1]
            point3f[] points = [(0, 0, 0), (1, 0, 0), (0, 1, 0.5), (1, 1, 0.25)]
        }}
        def NurbsPatch "roof"
        {{
            int uVertexCount = 2
            int vVertexCount = 2
            int uOrder = 2
            int vOrder = 2
            double[] uKnots = [0, 0, 1, 1]
            double[] vKnots = [0, 0, 1, 1]
            point3f[] points = [(0, 0, 1), (1, 0, 1), (0, 1, 1), (1, 1, 1)]
        }}
    }}
    def Material "paint"
    {{
        def Shader "surface"
        {{
            uniform token info:id = "UsdPreviewSurface"
            color3f inputs:diffuseColor.connect = </car/paint/other.outputs:rgb>
        }}
    }}
}}
"#
    )
}

#[test]
fn prims_become_patches_and_parts_placed_by_their_transforms() {
    let ops = r#"    double3 xformOp:translate = (10, 20, 30)
    float3 xformOp:rotateXYZ = (90, 0, 30)
    float3 xformOp:scale = (2, 2, 2)
    uniform token[] xformOpOrder = ["xformOp:translate", "xformOp:rotateXYZ", "xformOp:scale"]"#;
    let patch_ops = r#"            matrix4d xformOp:transform = ( (1, 0, 0, 0), (0, 1, 0, 0), (0, 0, 1, 0), (0, 0, 5, 1) )
            uniform token[] xformOpOrder = ["xformOp:transform"]"#;
    let library: PatchLibrary = parse_usda(&hood(ops, patch_ops), "car.usda").unwrap();
    let names: Vec<&str> = library.patches.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["car/panels/hood", "car/panels/roof"]);
    let groups: Vec<(&str, &[usize])> = library
        .groups
        .iter()
        .map(|g| (g.name.as_str(), g.patches.as_slice()))
        .collect();
    assert!(groups.contains(&("car", &[0, 1][..])), "{groups:?}");
    assert!(groups.contains(&("car/panels", &[0, 1][..])), "{groups:?}");
    // The hood's corner (1, 1, 0.25), lifted by 5 in its own frame, then scaled by 2, turned
    // 90° about x and then 30° about z, and moved by (10, 20, 30) — written out by hand.
    let p = DVec3::new(1.0, 1.0, 5.25) * 2.0;
    let about_x = DVec3::new(p.x, -p.z, p.y);
    let (s, c) = 30f64.to_radians().sin_cos();
    let about_z = DVec3::new(
        c * about_x.x - s * about_x.y,
        s * about_x.x + c * about_x.y,
        about_x.z,
    );
    let expected = about_z + DVec3::new(10.0, 20.0, 30.0);
    let hood = &library.patches[0].surface;
    let corner = hood.point(1.0, 1.0);
    assert!(
        (corner - expected).length() < 1e-9,
        "{corner} against {expected}"
    );
}

#[test]
fn groups_hold_the_patches_under_them_and_left_out_prims_hold_none() {
    let text = format!(
        r#"#usda 1.0
(
    upAxis = "Z"
)

def Xform "car"
{{
{kept}
    def Xform "empty"
    {{
    }}
    def Scope "looks"
    {{
        def Material "paint"
        {{
        }}
    }}
{inactive}
    def Xform "hidden"
    {{
        token visibility = "invisible"
{hidden}
    }}
    def Scope "doors"
    {{
{door}
    }}
{outer}
}}
"#,
        kept = flat_patch("hood", "", ""),
        inactive = flat_patch("spare", "(\n    active = false\n)", ""),
        hidden = flat_patch("ghost", "", ""),
        door = flat_patch("door", "", ""),
        outer = flat_patch("bonnet", "", &flat_patch("badge", "", "")),
    );
    let library = parse_usda(&text, "groups.usda").unwrap();
    let names: Vec<&str> = library.patches.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "car/hood",
            "car/doors/door",
            "car/bonnet",
            "car/bonnet/badge"
        ]
    );
    let groups: Vec<(&str, &[usize])> = library
        .groups
        .iter()
        .map(|g| (g.name.as_str(), g.patches.as_slice()))
        .collect();
    // A prim holding no patch is not a group, nor is a patch with patches under it; the
    // inactive and the invisible prims' patches are in none.
    assert_eq!(
        groups,
        [("car/doors", &[1][..]), ("car", &[0, 1, 2, 3][..])]
    );
}

#[test]
fn a_transform_may_place_a_control_point_on_the_edge_of_the_coordinates_glint_evaluates() {
    // The hood's points have x of 0 and 1: moved by 10⁶ − 1, the farthest lands on 10⁶ itself.
    let ops = r#"    double3 xformOp:translate = (999999, 0, 0)
    uniform token[] xformOpOrder = ["xformOp:translate"]"#;
    let library = parse_usda(&hood(ops, ""), "car.usda").unwrap();
    let corner = library.patches[0].surface.point(1.0, 0.0);
    assert_eq!(corner.x, glint::geom::MAX_COORDINATE);
}

#[test]
fn a_y_up_layer_is_turned_to_z_up() {
    let text = hood("", "").replace("upAxis = \"Z\"", "upAxis = \"Y\"");
    let library = parse_usda(&text, "car.usda").unwrap();
    // The roof at y = 1 in a y-up layer is at z = 1 here; its (0, 1, 1) corner at (0, -1, 1).
    let corner = library.patches[1].surface.point(0.0, 1.0);
    assert!(
        (corner - DVec3::new(0.0, -1.0, 1.0)).length() < 1e-12,
        "{corner}"
    );
}

/// One refusal: `from` in the hood layer replaced by `to`; the error is at the first `at` of
/// the new text and says each of `says`.
struct Refusal {
    name: &'static str,
    from: &'static str,
    to: &'static str,
    at: &'static str,
    says: &'static [&'static str],
}

const REFUSALS: &[Refusal] = &[
    Refusal {
        name: "an up axis that is neither Y nor Z",
        from: "upAxis = \"Z\"",
        to: "upAxis = \"X\"",
        at: "\"X\"",
        says: &["upAxis \"X\" is neither \"Y\" nor \"Z\""],
    },
    Refusal {
        name: "missing attribute",
        from: "            double[] uKnots = [0, 0, 1, 1]\n            double[] vKnots = [0, 0, 1, 1]\n            point3f[] points = [(0, 0, 0)",
        to: "            double[] vKnots = [0, 0, 1, 1]\n            point3f[] points = [(0, 0, 0)",
        at: "def NurbsPatch \"hood\"",
        says: &["/car/panels/hood", "no `uKnots`"],
    },
    Refusal {
        name: "wrong array length",
        from: "[(0, 0, 0), (1, 0, 0), (0, 1, 0.5), (1, 1, 0.25)]",
        to: "[(0, 0, 0), (1, 0, 0), (0, 1, 0.5)]",
        at: "points = [(0, 0, 0), (1, 0, 0), (0, 1, 0.5)]",
        says: &["/car/panels/hood", "`points` has 3 points", "2 × 2 = 4"],
    },
    Refusal {
        name: "knots not non-decreasing",
        from: "            double[] uKnots = [0, 0, 1, 1]\n            double[] vKnots = [0, 0, 1, 1]\n            point3f[] points = [(0, 0, 0)",
        to: "            double[] uKnots = [0, 1, 0.5, 1]\n            double[] vKnots = [0, 0, 1, 1]\n            point3f[] points = [(0, 0, 0)",
        at: "uKnots = [0, 1, 0.5, 1]",
        says: &["`uKnots` decreases at knot 2"],
    },
    Refusal {
        name: "a vertex count that is not whole",
        from: "int uVertexCount = 2",
        to: "double uVertexCount = 2.5",
        at: "uVertexCount = 2.5",
        says: &["`uVertexCount` must be a whole number from 1 to 10⁶"],
    },
    Refusal {
        name: "a vertex count of none",
        from: "int vVertexCount = 2",
        to: "int vVertexCount = 0",
        at: "vVertexCount = 0",
        says: &["`vVertexCount` must be a whole number from 1 to 10⁶"],
    },
    Refusal {
        name: "a vertex count past 10⁶",
        from: "int uVertexCount = 2",
        to: "int uVertexCount = 1000001",
        at: "uVertexCount = 1000001",
        says: &["`uVertexCount` must be a whole number from 1 to 10⁶"],
    },
    Refusal {
        name: "order above the supported degree",
        from: "            int uOrder = 2\n            int vOrder = 2\n            double[] uKnots = [0, 0, 1, 1]\n            double[] vKnots = [0, 0, 1, 1]\n            point3f[] points = [(0, 0, 0)",
        to: "            int uOrder = 11\n            int vOrder = 2\n            double[] uKnots = [0, 0, 1, 1]\n            double[] vKnots = [0, 0, 1, 1]\n            point3f[] points = [(0, 0, 0)",
        at: "uOrder = 11",
        says: &["`uOrder` 11 is outside the orders glint evaluates, 2 to 10"],
    },
    Refusal {
        name: "a transform placing a control point beyond the coordinates glint evaluates",
        from: "def Xform \"car\"\n{",
        to: "def Xform \"car\"\n{\n    double3 xformOp:translate = (2000000, 0, 0)\n    uniform token[] xformOpOrder = [\"xformOp:translate\"]",
        at: "def NurbsPatch \"hood\"",
        says: &[
            "/car/panels/hood",
            "its transform places a control point at 2.000001e6, beyond ±1e6",
        ],
    },
    Refusal {
        name: "a reference",
        from: "def Xform \"car\"\n{",
        to: "def Xform \"car\" (\n    prepend references = @./body.usda@\n)\n{",
        at: "prepend references",
        says: &["prim \"car\"", "`references`", "flatten"],
    },
    Refusal {
        name: "a variant set",
        from: "    def Material \"paint\"",
        to: "    variantSet \"trim\" = {\n        \"sport\" {\n        }\n    }\n    def Material \"paint\"",
        at: "variantSet",
        says: &["variant set"],
    },
    Refusal {
        name: "an over",
        from: "    def Material \"paint\"",
        to: "    over \"extra\"\n    {\n    }\n    def Material \"paint\"",
        at: "over \"extra\"",
        says: &["`over` prims compose"],
    },
    Refusal {
        name: "a spline",
        from: "            point3f[] points = [(0, 0, 0), (1, 0, 0), (0, 1, 0.5), (1, 1, 0.25)]",
        to: "            point3f[] points.spline = {\n                1: [(0, 0, 0)],\n            }",
        at: "points.spline",
        says: &["`points` is animated by a spline"],
    },
    Refusal {
        name: "a trim without orders",
        from: "            int uVertexCount = 2\n            int vVertexCount = 2\n            int uOrder = 2",
        to: "            int[] trimCurve:counts = [1]\n            int uVertexCount = 2\n            int vVertexCount = 2\n            int uOrder = 2",
        at: "trimCurve:counts",
        says: &["/car/panels/hood", "trimmed but has no `trimCurve:orders`"],
    },
    Refusal {
        name: "a trim loop that is not closed",
        from: "            int uVertexCount = 2\n            int vVertexCount = 2\n            int uOrder = 2",
        to: "            int[] trimCurve:counts = [1]\n            int[] trimCurve:orders = [2]\n            int[] trimCurve:vertexCounts = [5]\n            double[] trimCurve:knots = [0, 0, 1, 2, 3, 4, 4]\n            double3[] trimCurve:points = [(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1), (0, 0.5, 1)]\n            int uVertexCount = 2\n            int vVertexCount = 2\n            int uOrder = 2",
        at: "trimCurve:points",
        says: &["/car/panels/hood", "trim loop 0 is not closed", "(0.000000, 0.500000)"],
    },
    Refusal {
        // The loop's gap is 10⁻⁵: past 10⁻⁶ of the domain's larger side (1), though not of
        // the v knots' values (about 100).
        name: "a trim loop not closed on a domain away from 0",
        from: "            double[] uKnots = [0, 0, 1, 1]\n            double[] vKnots = [0, 0, 1, 1]\n            point3f[] points = [(0, 0, 0), (1, 0, 0), (0, 1, 0.5), (1, 1, 0.25)]",
        to: "            double[] uKnots = [0, 0, 1, 1]\n            double[] vKnots = [100, 100, 101, 101]\n            point3f[] points = [(0, 0, 0), (1, 0, 0), (0, 1, 0.5), (1, 1, 0.25)]\n            int[] trimCurve:counts = [1]\n            int[] trimCurve:orders = [2]\n            int[] trimCurve:vertexCounts = [5]\n            double[] trimCurve:knots = [0, 0, 1, 2, 3, 4, 4]\n            double3[] trimCurve:points = [(0, 100, 1), (1, 100, 1), (1, 101, 1), (0, 101, 1), (0, 100.00001, 1)]",
        at: "trimCurve:points",
        says: &["/car/panels/hood", "trim loop 0 is not closed"],
    },
    Refusal {
        name: "a trim loop running the wrong way",
        from: "            int uVertexCount = 2\n            int vVertexCount = 2\n            int uOrder = 2",
        to: "            int[] trimCurve:counts = [1]\n            int[] trimCurve:orders = [2]\n            int[] trimCurve:vertexCounts = [5]\n            double[] trimCurve:knots = [0, 0, 1, 2, 3, 4, 4]\n            double3[] trimCurve:points = [(0.2, 0.2, 1), (0.2, 0.6, 1), (0.6, 0.6, 1), (0.6, 0.2, 1), (0.2, 0.2, 1)]\n            int uVertexCount = 2\n            int vVertexCount = 2\n            int uOrder = 2",
        at: "trimCurve:points",
        says: &["trim loop 0 runs clockwise", "inside 0 other loop"],
    },
    Refusal {
        name: "trim knots of the wrong count",
        from: "            int uVertexCount = 2\n            int vVertexCount = 2\n            int uOrder = 2",
        to: "            int[] trimCurve:counts = [1]\n            int[] trimCurve:orders = [2]\n            int[] trimCurve:vertexCounts = [5]\n            double[] trimCurve:knots = [0, 0, 1, 2, 3, 4]\n            double3[] trimCurve:points = [(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1), (0, 0, 1)]\n            int uVertexCount = 2\n            int vVertexCount = 2\n            int uOrder = 2",
        at: "trimCurve:knots",
        says: &["`trimCurve:knots` has 6 knots", "take 7"],
    },
    Refusal {
        name: "decreasing trim knots",
        from: "            int uVertexCount = 2\n            int vVertexCount = 2\n            int uOrder = 2",
        to: "            int[] trimCurve:counts = [1]\n            int[] trimCurve:orders = [2]\n            int[] trimCurve:vertexCounts = [5]\n            double[] trimCurve:knots = [0, 0, 1, 3, 2, 4, 4]\n            double3[] trimCurve:points = [(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1), (0, 0, 1)]\n            int uVertexCount = 2\n            int vVertexCount = 2\n            int uOrder = 2",
        at: "trimCurve:knots",
        says: &["knots of trim curve 0 decrease at knot 4"],
    },
    Refusal {
        name: "a trim curve of too high an order",
        from: "            int uVertexCount = 2\n            int vVertexCount = 2\n            int uOrder = 2",
        to: "            int[] trimCurve:counts = [1]\n            int[] trimCurve:orders = [11]\n            int[] trimCurve:vertexCounts = [11]\n            double[] trimCurve:knots = [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1, 1]\n            double3[] trimCurve:points = [(0, 0, 1), (0, 0, 1), (0, 0, 1), (0, 0, 1), (0, 0, 1), (0, 0, 1), (0, 0, 1), (0, 0, 1), (0, 0, 1), (0, 0, 1), (0, 0, 1)]\n            int uVertexCount = 2\n            int vVertexCount = 2\n            int uOrder = 2",
        at: "trimCurve:orders",
        says: &["trim curve has order 11", "orders 2 to 10"],
    },
    Refusal {
        name: "a trim point of weight 0",
        from: "            int uVertexCount = 2\n            int vVertexCount = 2\n            int uOrder = 2",
        to: "            int[] trimCurve:counts = [1]\n            int[] trimCurve:orders = [2]\n            int[] trimCurve:vertexCounts = [5]\n            double[] trimCurve:knots = [0, 0, 1, 2, 3, 4, 4]\n            double3[] trimCurve:points = [(0, 0, 1), (1, 0, 1), (1, 1, 0), (0, 1, 1), (0, 0, 1)]\n            int uVertexCount = 2\n            int vVertexCount = 2\n            int uOrder = 2",
        at: "trimCurve:points",
        says: &["trim curve 0", "weight"],
    },
    Refusal {
        name: "a mesh",
        from: "    def Material \"paint\"",
        to: "    def Mesh \"wheel\"\n    {\n    }\n    def Material \"paint\"",
        at: "def Mesh",
        says: &["/car/wheel is a Mesh", "NurbsPatch prims only"],
    },
    Refusal {
        name: "an op glint does not read",
        from: "def Xform \"car\"\n{\n",
        to: "def Xform \"car\"\n{\n    float3 xformOp:shear = (1, 0, 0)\n    uniform token[] xformOpOrder = [\"xformOp:shear\"]\n",
        at: "xformOp:shear = ",
        says: &["/car", "`xformOp:shear` is not an op glint reads"],
    },
    Refusal {
        name: "a range that starts inside the knots' domain and ends at its end",
        from: "            int uVertexCount = 2\n            int vVertexCount = 2\n            int uOrder = 2",
        to: "            double2 vRange = (0.5, 1)\n            int uVertexCount = 2\n            int vVertexCount = 2\n            int uOrder = 2",
        at: "vRange = (0.5, 1)",
        says: &["`vRange`", "not the knots' domain"],
    },
    Refusal {
        name: "a sub-range",
        from: "            int uVertexCount = 2\n            int vVertexCount = 2\n            int uOrder = 2",
        to: "            double2 uRange = (0, 0.5)\n            int uVertexCount = 2\n            int vVertexCount = 2\n            int uOrder = 2",
        at: "uRange = (0, 0.5)",
        says: &["`uRange`", "not the knots' domain"],
    },
];

#[test]
fn a_connection_is_refused_on_what_glint_reads_and_left_alone_elsewhere() {
    // A colour primvar connected to a shader output: glint reads no primvar, so the
    // connection changes nothing.
    let colour =
        "            color3f[] primvars:displayColor.connect = </car/paint/surface.outputs:rgb>";
    let library = parse_usda(&hood("", colour), "car.usda").unwrap();
    assert_eq!(library.patches.len(), 2);
    // Knots connected to another prim's: glint would have to follow the connection.
    let knots = "            double[] uKnots.connect = </car/panels/roof.uKnots>";
    let e = parse_usda(&hood("", knots), "car.usda")
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("`uKnots` is connected to another attribute; glint reads written values only"),
        "{e}"
    );
}

/// The 1-based line and column of the first `needle` in `text`.
fn location(text: &str, needle: &str) -> (usize, usize) {
    let offset = text
        .find(needle)
        .unwrap_or_else(|| panic!("{needle:?} not in the text"));
    glint::formats::ron_location::position_of(text, offset)
}

#[test]
fn every_refusal_is_one_located_line_and_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let base = hood("", "");
    for case in REFUSALS {
        assert!(
            base.contains(case.from),
            "{}: the template lacks {:?}",
            case.name,
            case.from
        );
        let text = base.replacen(case.from, case.to, 1);
        let path = dir.path().join("car.usda");
        std::fs::write(&path, &text).unwrap();
        let out = glint(&[
            "probe",
            path.to_str().unwrap(),
            "--patch",
            "0",
            "--uv",
            "0.5,0.5",
        ]);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{}: {err}", case.name);
        assert_eq!(err.lines().count(), 1, "{}: {err}", case.name);
        let (line, col) = location(&text, case.at);
        let place = format!("car.usda:{line}:{col}: ");
        assert!(
            err.contains(&place),
            "{}: expected {place} in {err}",
            case.name
        );
        for says in case.says {
            assert!(
                err.contains(says),
                "{}: expected {says:?} in {err}",
                case.name
            );
        }
    }
}

/// A binary layer the USD library wrote (`scripts/usd/author_models.py`).
fn binary_fixture(name: &str) -> String {
    repo_file(&format!("tests/data/usd/{name}"))
        .to_str()
        .unwrap()
        .to_string()
}

#[cfg(not(feature = "usd-binary"))]
#[test]
fn a_binary_layer_is_refused_with_the_conversion_to_run() {
    let out = glint(&[
        "probe",
        &binary_fixture("sphere.usdc"),
        "--patch",
        "0",
        "--uv",
        "0,0",
    ]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("usdcat --flatten") && err.contains(".usda"),
        "{err}"
    );
}

#[cfg(feature = "usd-binary")]
#[test]
fn a_binary_layer_reads_as_its_text_does_and_refuses_what_it_refuses() {
    let binary = load_patches(std::path::Path::new(&binary_fixture("sphere.usdc"))).unwrap();
    let own = load_patches(&repo_file("patches/sphere.ron")).unwrap();
    assert_eq!(binary.patches[0].name, "sphere");
    let difference =
        largest_difference(&binary.patches[0].surface, &own.patches[0].surface, 500, 3);
    assert!(difference <= 1e-12, "{difference:e}");
    // A reference is composition: refused, naming the prim, exit 2.
    let out = glint(&[
        "probe",
        &binary_fixture("referencing.usdc"),
        "--patch",
        "0",
        "--uv",
        "0,0",
    ]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("/ball has references") && err.contains("flatten"),
        "{err}"
    );
}

/// A NURBS patch as [`NurbsSurface::new`] takes it: degrees, knots, points and weights.
struct Net {
    du: usize,
    dv: usize,
    ku: Vec<f64>,
    kv: Vec<f64>,
    points: Vec<Vec<DVec3>>,
    weights: Vec<Vec<f64>>,
}

/// A random valid NURBS patch: degrees 1–4, 1–6 more points than the degree along each
/// direction, clamped or unclamped increasing knots, coordinates and weights that are
/// exact in single precision (USD's `point3f`).
fn random_patch(seed: u64) -> Net {
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let degree = |rng: &mut rand::rngs::StdRng| rng.random_range(1..=4usize);
    let (du, dv) = (degree(&mut rng), degree(&mut rng));
    let (nu, nv) = (du + rng.random_range(1..=6), dv + rng.random_range(1..=6));
    // Distinct knots (multiplicity 1), clamped at both ends or not.
    let knots = |rng: &mut rand::rngs::StdRng, n: usize, d: usize| {
        let clamped = rng.random_bool(0.5);
        let free = if clamped { n - d - 1 } else { n + d + 1 };
        let mut pool: Vec<u32> = (1..256).collect();
        let mut k: Vec<f64> = (0..free)
            .map(|_| f64::from(pool.swap_remove(rng.random_range(0..pool.len()))) / 256.0)
            .collect();
        k.sort_by(f64::total_cmp);
        if clamped {
            let mut full = vec![0.0; d + 1];
            full.extend(k);
            full.extend(vec![1.0; d + 1]);
            full
        } else {
            k
        }
    };
    let (ku, kv) = (knots(&mut rng, nu, du), knots(&mut rng, nv, dv));
    let coordinate =
        |rng: &mut rand::rngs::StdRng| f64::from(rng.random_range(-400..400i32) as f32 * 0.25);
    let points = (0..nu)
        .map(|_| {
            (0..nv)
                .map(|_| {
                    DVec3::new(
                        coordinate(&mut rng),
                        coordinate(&mut rng),
                        coordinate(&mut rng),
                    )
                })
                .collect()
        })
        .collect();
    let weights = (0..nu)
        .map(|_| {
            (0..nv)
                .map(|_| f64::from(rng.random_range(1..=16u32)) * 0.25)
                .collect()
        })
        .collect();
    Net {
        du,
        dv,
        ku,
        kv,
        points,
        weights,
    }
}

/// The patch as USDA, points with u varying fastest.
fn as_usda(net: &Net) -> String {
    let Net {
        du,
        dv,
        ku,
        kv,
        points,
        weights,
    } = net;
    let (nu, nv) = (points.len(), points[0].len());
    let list = |values: Vec<String>| format!("[{}]", values.join(", "));
    let mut ps = Vec::new();
    let mut ws = Vec::new();
    for j in 0..nv {
        for i in 0..nu {
            let p = points[i][j];
            ps.push(format!("({}, {}, {})", p.x, p.y, p.z));
            ws.push(format!("{}", weights[i][j]));
        }
    }
    format!(
        "#usda 1.0\n\ndef NurbsPatch \"p\"\n{{\n    int uVertexCount = {nu}\n    int vVertexCount = {nv}\n    int uOrder = {}\n    int vOrder = {}\n    double[] uKnots = {}\n    double[] vKnots = {}\n    point3f[] points = {}\n    double[] pointWeights = {}\n}}\n",
        du + 1,
        dv + 1,
        list(ku.iter().map(f64::to_string).collect()),
        list(kv.iter().map(f64::to_string).collect()),
        list(ps),
        list(ws),
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn random_patches_written_as_usda_read_back_to_the_same_surface(seed in any::<u64>()) {
        let net = random_patch(seed);
        let built = NurbsSurface::new(net.du, net.dv, net.ku.clone(), net.kv.clone(), &net.points, Some(&net.weights)).unwrap();
        let text = as_usda(&net);
        let read = parse_usda(&text, "p.usda").unwrap();
        prop_assert_eq!(read.patches.len(), 1);
        let difference = largest_difference(&read.patches[0].surface, &built, 50, seed);
        prop_assert_eq!(difference, 0.0, "{}", text);
    }
}

#[test]
fn the_documented_layer_reads_as_documented() {
    let doc = std::fs::read_to_string(repo_file("docs/patch-format.md")).unwrap();
    let block = doc.split("```usda\n").nth(1).unwrap();
    let block = &block[..block.find("```").unwrap()];
    let library = parse_usda(block, "patch-format.md").unwrap();
    assert_eq!(library.patches.len(), 1);
    assert_eq!(library.patches[0].name, "car/hood");
    assert_eq!(library.groups.len(), 1);
    assert_eq!(library.groups[0].name, "car");
    // Turned 90° about z, then lifted by 0.5: the (0, 0) corner stays over the origin.
    let corner = library.patches[0].surface.point(0.0, 0.0);
    assert!(
        (corner - DVec3::new(0.0, 0.0, 0.5)).length() < 1e-12,
        "{corner}"
    );
    let far = library.patches[0].surface.point(1.0, 0.0);
    assert!((far - DVec3::new(0.0, 2.0, 0.5)).length() < 1e-12, "{far}");

    // The trimmed plate: a square hole [0.3, 0.7]² in (u, v), the rest kept.
    let block = doc.split("```usda\n").nth(2).unwrap();
    let block = &block[..block.find("```").unwrap()];
    let plate = &parse_usda(block, "patch-format.md").unwrap().patches[0];
    assert!(plate.trim.is_some());
    for (u, v, kept) in [
        (0.5, 0.5, false),
        (0.31, 0.69, false),
        (0.29, 0.5, true),
        (0.9, 0.1, true),
    ] {
        assert_eq!(plate.keeps(u, v), kept, "({u}, {v})");
    }
}

/// `read` is a library of patches whose control points are all finite, or a refusal of
/// `text` (shown as `shown`) at a line and column inside it, in one line.
fn read_or_refused_at_a_place(
    read: Result<PatchLibrary, glint::formats::FormatError>,
    text: &str,
    shown: &str,
) -> Result<(), TestCaseError> {
    match read {
        Ok(library) => {
            prop_assert!(library.control_points().all(|p| p.is_finite()));
        }
        Err(glint::formats::FormatError::Usd {
            path,
            line,
            col,
            message,
        }) => {
            prop_assert_eq!(path, shown);
            prop_assert!(
                line >= 1 && line <= text.lines().count() + 1,
                "line {}",
                line
            );
            prop_assert!(col >= 1, "col {}", col);
            prop_assert!(
                !message.is_empty() && !message.contains('\n'),
                "{:?}",
                message
            );
        }
        Err(other) => prop_assert!(false, "not a located refusal: {}", other),
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Hostile text — the layer cut anywhere, or with any character replaced — is read into
    /// finite patches or refused at a place in it, in one line; never a panic.
    #[test]
    fn a_damaged_layer_is_refused_not_a_panic(cut in 0usize..2000, at in 0usize..2000, with in any::<char>()) {
        let text = hood("    double3 xformOp:translate = (1, 2, 3)\n    uniform token[] xformOpOrder = [\"xformOp:translate\"]", "");
        let cut = cut.min(text.len());
        let cut = (0..=cut).rev().find(|&k| text.is_char_boundary(k)).unwrap();
        read_or_refused_at_a_place(parse_usda(&text[..cut], "cut.usda"), &text[..cut], "cut.usda")?;
        let chars: Vec<char> = text.chars().collect();
        let at = at % chars.len();
        let changed: String = chars
            .iter()
            .enumerate()
            .map(|(k, &c)| if k == at { with } else { c })
            .collect();
        read_or_refused_at_a_place(parse_usda(&changed, "changed.usda"), &changed, "changed.usda")?;
    }
}

/// A flat patch over [0, 1]² with a square hole `[0.3, 0.6] × [0.2, 0.7]` in (u, v): the domain
/// as the outer loop, counter-clockwise, the hole clockwise, each one order-2 curve; `extra`
/// is written into the prim.
fn holed(extra: &str) -> String {
    format!(
        r#"#usda 1.0
def NurbsPatch "sheet"
{{
{extra}
    int uVertexCount = 2
    int vVertexCount = 2
    int uOrder = 2
    int vOrder = 2
    double[] uKnots = [0, 0, 1, 1]
    double[] vKnots = [0, 0, 1, 1]
    point3f[] points = [(0, 0, 0), (2, 0, 0), (0, 1, 0.5), (2, 1, 0.25)]
    int[] trimCurve:counts = [1, 1]
    int[] trimCurve:orders = [2, 2]
    int[] trimCurve:vertexCounts = [5, 5]
    double[] trimCurve:knots = [0, 0, 1, 2, 3, 4, 4, 0, 0, 1, 2, 3, 4, 4]
    double2[] trimCurve:ranges = [(0, 4), (0, 4)]
    double3[] trimCurve:points = [(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1), (0, 0, 1), (0.6, 0.4, 2), (0.6, 1.4, 2), (1.2, 1.4, 2), (1.2, 0.4, 2), (0.6, 0.4, 2)]
}}
"#
    )
}

#[test]
fn a_trimmed_patch_keeps_what_its_loops_keep_whichever_way_it_is_handed() {
    let right = glint::formats::parse_usda(&holed(""), "sheet.usda").unwrap();
    let left = glint::formats::parse_usda(
        &holed("    uniform token orientation = \"leftHanded\""),
        "sheet.usda",
    )
    .unwrap();
    let (r, l) = (&right.patches[0], &left.patches[0]);
    assert!(r.trim.is_some());
    // The hole's points are homogeneous, weight 2: (0.3, 0.2) to (0.6, 0.7).
    let in_hole = |u: f64, v: f64| (0.3..=0.6).contains(&u) && (0.2..=0.7).contains(&v);
    let mut rng = rand::rngs::StdRng::seed_from_u64(7);
    let mut next = || rng.random::<f64>();
    for _ in 0..2000 {
        let (u, v) = (next(), next());
        let near_edge = [u - 0.3, u - 0.6, v - 0.2, v - 0.7]
            .iter()
            .any(|d| d.abs() < 1e-9);
        if near_edge {
            continue;
        }
        assert_eq!(r.keeps(u, v), !in_hole(u, v), "({u}, {v})");
        // Left-handed, v runs the other way: the same point of the sheet, kept alike.
        let (p, q) = (r.surface.point(u, v), l.surface.point(u, 1.0 - v));
        assert!((p - q).length() < 1e-12);
        assert_eq!(l.keeps(u, 1.0 - v), r.keeps(u, v), "({u}, {v})");
    }
    // `glint probe` says which points the trim cuts away.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("sheet.usda");
    std::fs::write(&path, holed("")).unwrap();
    let out = glint(&[
        "probe",
        path.to_str().unwrap(),
        "--patch",
        "sheet",
        "--uv",
        "0.5,0.5",
        "--uv",
        "0.1,0.5",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let probes: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(probes[0]["trimmed_away"], true);
    assert_eq!(probes[1]["trimmed_away"], false);
}

#[test]
fn glint_patches_counts_the_trim_loops_of_the_shipped_trimmed_models() {
    let out = glint(&[
        "patches",
        repo_file("patches/speaker.usda").to_str().unwrap(),
        "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let listing: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let loops = |name: &str| {
        listing["patches"]
            .as_array()
            .unwrap()
            .iter()
            .find(|p| p["name"] == name)
            .unwrap_or_else(|| panic!("no patch {name}"))["trim_loops"]
            .as_u64()
            .unwrap()
    };
    // The front: its outer boundary, the port and the grille's 20 holes; a side: its boundary
    // and a handle slot; the caps untrimmed.
    assert_eq!(loops("speaker/body/front"), 22);
    assert_eq!(loops("speaker/body/left"), 2);
    assert_eq!(loops("speaker/body/top"), 0);
}

/// Asserts that the sheet read from a variant of [`holed`] (named `what`) keeps what
/// `holed("")` keeps, inside the hole, about it and near the outer loop.
fn assert_keeps_as_holed(read: &glint::geom::PatchLibrary, what: &str) {
    let exact = glint::formats::parse_usda(&holed(""), "sheet.usda").unwrap();
    for (u, v) in [(0.5, 0.5), (0.1, 0.1), (0.9, 0.95), (0.45, 0.45)] {
        let (a, b) = (&read.patches[0], &exact.patches[0]);
        assert_eq!(a.keeps(u, v), b.keeps(u, v), "{what} at ({u}, {v})");
    }
}

#[test]
fn a_usd_trim_curve_s_range_may_pass_its_knots_domain_by_a_rounding_slack_and_no_more() {
    // The knots' domain is (0, 4): the slack is 1e-9 · (1 + 4).
    let ranges = "double2[] trimCurve:ranges = [(0, 4), (0, 4)]";
    let with = |range: &str| {
        holed("").replace(
            ranges,
            &format!("double2[] trimCurve:ranges = [{range}, (0, 4)]"),
        )
    };
    for within in ["(0, 4.0000000045)", "(-4.5e-9, 4)"] {
        let read = glint::formats::parse_usda(&with(within), "sheet.usda")
            .unwrap_or_else(|e| panic!("{within}: {e}"));
        assert_keeps_as_holed(&read, within);
    }
    for beyond in ["(0, 4.000000006)", "(-6e-9, 4)", "(2, 2)", "(3, 1)"] {
        let text = with(beyond);
        let e = glint::formats::parse_usda(&text, "sheet.usda")
            .err()
            .unwrap_or_else(|| panic!("{beyond} was read"))
            .to_string();
        let (line, _) = location(&text, "trimCurve:ranges");
        assert!(e.contains(&format!("sheet.usda:{line}:")), "{beyond}: {e}");
        assert!(
            e.contains("trim curve 0 has the range")
                && e.contains("not within its knots' domain (0, 4)"),
            "{beyond}: {e}"
        );
    }
}

#[test]
fn a_usd_trim_loop_whose_next_curve_does_not_begin_where_the_last_ended_is_refused() {
    // The outer loop as two curves, the second beginning at `join`; the hole as in `holed`.
    let two = |join: &str| {
        holed("")
            .replace("counts = [1, 1]", "counts = [2, 1]")
            .replace("orders = [2, 2]", "orders = [2, 2, 2]")
            .replace("vertexCounts = [5, 5]", "vertexCounts = [3, 3, 5]")
            .replace(
                "knots = [0, 0, 1, 2, 3, 4, 4, 0,",
                "knots = [0, 0, 1, 2, 2, 0, 0, 1, 2, 2, 0,",
            )
            .replace(
                "ranges = [(0, 4), (0, 4)]",
                "ranges = [(0, 2), (0, 2), (0, 4)]",
            )
            .replace(
                "points = [(0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1), (0, 0, 1),",
                &format!(
                    "points = [(0, 0, 1), (1, 0, 1), (1, 1, 1), {join}, (0, 1, 1), (0, 0, 1),"
                ),
            )
    };
    let joined = glint::formats::parse_usda(&two("(1, 1, 1)"), "sheet.usda").unwrap();
    assert_keeps_as_holed(&joined, "joined");
    let text = two("(0.9, 1, 1)");
    let e = glint::formats::parse_usda(&text, "sheet.usda")
        .expect_err("a loop with a gap was read")
        .to_string();
    let (line, _) = location(&text, "trimCurve:points");
    assert!(e.contains(&format!("sheet.usda:{line}:")), "{e}");
    assert!(
        e.contains(
            "trim loop 0 is not closed: its curve 0 ends at (1.000000, 1.000000) but the next begins at (0.900000, 1.000000)"
        ),
        "{e}"
    );
}
