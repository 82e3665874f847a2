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

/// The ball shot's camera, as its text says: orthographic from `(0, −6, 1)` towards the origin,
/// 2.4 units tall, up +z, at `width × height`.
const BALL_SIZE: (u32, u32) = (200, 160);

/// Where `p` lands in the ball shot's image by the pinhole of an orthographic camera, worked out
/// here: right = forward × up normalized, up' = right × forward; pixel centres at integers.
fn ball_pixel(p: [f64; 3]) -> [f64; 2] {
    let (eye, target) = ([0.0, -6.0, 1.0], [0.0, 0.0, 0.0]);
    let f: Vec<f64> = (0..3).map(|i| target[i] - eye[i]).collect();
    let n = f.iter().map(|x| x * x).sum::<f64>().sqrt();
    let f = [f[0] / n, f[1] / n, f[2] / n];
    // forward × (0, 0, 1) = (f.y, −f.x, 0).
    let r = [f[1], -f[0], 0.0];
    let rn = (r[0] * r[0] + r[1] * r[1]).sqrt();
    let r = [r[0] / rn, r[1] / rn, 0.0];
    let u = [
        r[1] * f[2] - r[2] * f[1],
        r[2] * f[0] - r[0] * f[2],
        r[0] * f[1] - r[1] * f[0],
    ];
    let d = [p[0] - target[0], p[1] - target[1], p[2] - target[2]];
    let dot = |a: [f64; 3], b: [f64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let (w, h) = (f64::from(BALL_SIZE.0), f64::from(BALL_SIZE.1));
    let half_height = 1.2;
    let x = dot(d, r) / (half_height * w / h);
    let y = dot(d, u) / half_height;
    [(x + 1.0) * w / 2.0 - 0.5, (1.0 - y) * h / 2.0 - 0.5]
}

#[test]
fn probe_on_a_shot_says_where_a_point_lands_and_whether_the_frame_shows_it() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(
        crate::common::repo_file("patches/sphere.ron"),
        dir.path().join("sphere.ron"),
    )
    .unwrap();
    let shot = dir.path().join("ball.ron");
    let text = crate::common::ball_shot::BallShot {
        size: BALL_SIZE,
        epsilon: 0.05,
        lit: "(0.2, 0.3, 0.8)",
        include: None,
        preset: None,
    }
    .text();
    std::fs::write(&shot, text).unwrap();
    // The sphere's (u, v): u the longitude from +x, v from the south pole. The first faces the
    // camera, the second is on the far side, the third high on the front (where the exact
    // sphere's parameters are not proportional to angles: its point is the one probed).
    let points = [
        ((0.75, 0.5), Some([0.0, -1.0, 0.0]), true),
        ((0.25, 0.5), Some([0.0, 1.0, 0.0]), false),
        ((0.7, 0.8), None, true),
    ];
    let mut args = vec!["probe", shot.to_str().unwrap(), "--patch", "ball/sphere"];
    let uvs: Vec<String> = points
        .iter()
        .map(|((u, v), _, _)| format!("{u},{v}"))
        .collect();
    for uv in &uvs {
        args.extend(["--uv", uv]);
    }
    let out = glint(&args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: Value = serde_json::from_slice(&out.stdout).unwrap();
    for (probe, (uv, point, seen)) in json.as_array().unwrap().iter().zip(points) {
        let image = &probe["image"];
        let pixel = image["pixel"].as_array().unwrap();
        let point = point.unwrap_or_else(|| vector(&probe["point"]));
        let want = ball_pixel(point);
        for c in 0..2 {
            let got = pixel[c].as_f64().unwrap();
            assert!(
                (got - want[c]).abs() < 1e-3,
                "{uv:?}: {pixel:?} vs {want:?}"
            );
        }
        assert_eq!(image["size"], serde_json::json!([BALL_SIZE.0, BALL_SIZE.1]));
        assert_eq!(image["in_front"], true, "{uv:?}");
        assert_eq!(image["in_image"], true, "{uv:?}");
        assert_eq!(image["visible"], seen, "{uv:?}: {probe}");
    }
    // A patch file has no frame to land in.
    let out = glint(&[
        "probe",
        "patches/sphere.ron",
        "--patch",
        "sphere",
        "--uv",
        "0.5,0.5",
        "--size",
        "64x64",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--size and --preset"));
}
