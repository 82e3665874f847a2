//! `glint probe` end to end: JSON output, and one clear located error with exit code 2 for each
//! kind of bad input.

use std::path::Path;

use crate::common::glint_with as glint;

use serde_json::Value;

fn vector(v: &Value) -> [f64; 3] {
    let a = v.as_array().unwrap();
    [0, 1, 2].map(|i| a[i].as_f64().unwrap())
}

fn assert_close(a: [f64; 3], b: [f64; 3]) {
    let d: f64 = a.iter().zip(&b).map(|(x, y)| (x - y).powi(2)).sum();
    assert!(d.sqrt() < 1e-12, "{a:?} vs {b:?}");
}

#[test]
fn probe_prints_the_sphere_frame_as_json() {
    let out = glint(&[
        "probe",
        "patches/sphere.ron",
        "--patch",
        "sphere",
        "--uv",
        "0.25,0.5",
        "--uv",
        "0.7,0",
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: Value = serde_json::from_slice(&out.stdout).unwrap();
    let probes = json.as_array().unwrap();
    assert_eq!(probes.len(), 2);
    // u = 1/4 is the meridian at 90° east, v = 1/2 the equator: the point (0, 1, 0).
    let p = &probes[0];
    assert_eq!(p["patch"], "sphere");
    assert_eq!((p["u"].as_f64(), p["v"].as_f64()), (Some(0.25), Some(0.5)));
    assert_close(vector(&p["point"]), [0.0, 1.0, 0.0]);
    assert_close(vector(&p["normal"]), [0.0, 1.0, 0.0]);
    assert_close(vector(&p["du"]), [-1.0, 0.0, 0.0]);
    assert_close(vector(&p["dv"]), [0.0, 0.0, 1.0]);
    assert_eq!(p["degenerate"], false);
    // The south pole: Su vanishes, the limit frame is used.
    let pole = &probes[1];
    assert_eq!(pole["degenerate"], true);
    assert_close(vector(&pole["su"]), [0.0, 0.0, 0.0]);
    assert_close(vector(&pole["normal"]), [0.0, 0.0, -1.0]);
}

/// Runs `glint probe` on `file` and returns stderr, checking exit code 2 and a single line.
fn probe_error(file: &Path, patch: &str, uv: &str) -> String {
    let out = glint(&[
        "probe",
        file.to_str().unwrap(),
        "--patch",
        patch,
        "--uv",
        uv,
    ]);
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    assert!(out.stdout.is_empty());
    let stderr = String::from_utf8(out.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    stderr
}

#[test]
fn unknown_patch_lists_the_names_and_out_of_domain_names_the_domain() {
    let e = probe_error(Path::new("patches/car_panels.ron"), "bonnet", "0.5,0.5");
    assert!(
        e.contains("no patch 'bonnet'") && e.contains("hood, windshield, roof"),
        "{e}"
    );
    let e = probe_error(Path::new("patches/sphere.ron"), "sphere", "1.5,0.5");
    assert!(
        e.contains("outside the domain") && e.contains("u in [0, 1]"),
        "{e}"
    );
    let e = probe_error(Path::new("patches/missing.ron"), "a", "0,0");
    assert!(e.starts_with("error: patches/missing.ron:"), "{e}");
}

#[test]
fn bad_patch_files_give_one_located_error_each() {
    let dir = tempfile::tempdir().unwrap();
    let nurbs = |knots_u: &str, points: &str, weights: &str| {
        format!(
            "(patches: [\n  (name: \"p\", surface: Nurbs(\n    degree: (1, 1),\n    knots_u: {knots_u},\n    knots_v: [0, 0, 1, 1],\n    points: {points},\n    weights: {weights},\n  )),\n])\n"
        )
    };
    let square = "[[(0, 0, 0), (0, 1, 0)], [(1, 0, 0), (1, 1, 0)]]";
    let cases: Vec<(&str, String, &str)> = vec![
        (
            "malformed.ron",
            "(patches: [(name: \"p\", surface: Sphere(radius: 1.0)\n])".into(),
            "malformed.ron:2:1: this `]` meets the `(` opened at line 1, column 12: a `)` is missing",
        ),
        (
            "knots.ron",
            nurbs("[0, 0, 1]", square, "None"),
            "knots.ron:2:24: u direction: 3 knots given, but degree 1 with 2 control points needs 4",
        ),
        (
            "zero_weight.ron",
            nurbs("[0, 0, 1, 1]", square, "Some([[1, 1], [0, 1]])"),
            "zero_weight.ron:7:29: weight 0 is not allowed",
        ),
        (
            "negative_weight.ron",
            nurbs("[0, 0, 1, 1]", square, "Some([[1, -0.5], [1, 1]])"),
            "negative_weight.ron:7:24: weight -0.5 is not allowed",
        ),
        (
            "net.ron",
            nurbs("[0, 0, 1, 1]", "[[(0, 0, 0), (0, 1, 0)], [(1, 0, 0)]]", "None"),
            "net.ron:2:24: control net is 2 rows of 1, expected 2 rows (u) of 2 points (v)",
        ),
        (
            "truncated.bpt",
            "1\n1 1\n0 0 0\n1 0 0\n0 1 0\n".into(),
            "truncated.bpt:5: the file ends where control point 3 of patch 0 (x y z) should follow",
        ),
        (
            "text.bpt",
            "1\n1 1\n0 0 0\n1 0 0\n0 one 0\n1 1 0\n".into(),
            "text.bpt:5: 'one' is not a valid number in control point 2 of patch 0 (x y z)",
        ),
    ];
    for (name, text, expected) in cases {
        let path = dir.path().join(name);
        std::fs::write(&path, text).unwrap();
        let e = probe_error(&path, "0", "0,0");
        let shown = format!("error: {}", dir.path().join(expected).display());
        assert!(
            e.starts_with(&shown),
            "{name}:\n  got      {e}  expected {shown}"
        );
    }
}
