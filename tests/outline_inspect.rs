//! `glint inspect` prints a layer's drawn shape in the shot's syntax: a fixed outline as
//! written, keyed outlines as the outline of their points at the frame, with the keys it lies
//! between; the printed outline pasted back as the shape reads the same.

use crate::common::glint;

const TEMPLATE: &str = r#"Shot(
    resolution: (48, 48),
    frames: (1, 9),
    fps: 24,
    output: "out/t.####.png",
    instances: [(name: "ball", file: "sphere.ron", material: "blue")],
    materials: {"blue": Cel(base: (0.1, 0.1, 0.3), bands: [(0.0, (0.2, 0.3, 0.8))])},
    camera: (eye: (0.0, -6.0, 0.0), target: (0.0, 0.0, 0.0), projection: Perspective(fov_y_degrees: 30.0)),
    light: Directional(towards: (0.3, -1.0, 0.4)),
    highlights: [
        (
            patches: "ball/*",
            expr: Layer((stack: [], epsilon: 0.05, colour: (1.0, 1.0, 1.0), shape: SHAPE)),
        ),
    ],
    render: (preset: Preview),
)
"#;

/// `glint inspect` of the shot with `shape` at `frame`: the layer's line.
fn layer_line(dir: &std::path::Path, shape: &str, frame: &str) -> String {
    let shot = dir.join("shot.ron");
    std::fs::write(&shot, TEMPLATE.replace("SHAPE", shape)).unwrap();
    let out = glint()
        .args(["inspect", "--frame", frame])
        .arg(&shot)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let report = String::from_utf8(out.stdout).unwrap();
    report
        .lines()
        .find(|l| l.trim_start().starts_with("layers[0]: "))
        .unwrap_or_else(|| panic!("no layer line in\n{report}"))
        .to_string()
}

/// The `shape: …` part of a layer line, up to the outline's closing `])`.
fn shape_of(line: &str) -> &str {
    let start = line
        .find("shape: ")
        .unwrap_or_else(|| panic!("no shape in {line}"))
        + 7;
    let end = start + line[start..].find("])").unwrap() + 2;
    &line[start..end]
}

fn workspace() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let sphere = crate::common::root().join("patches/sphere.ron");
    std::fs::copy(sphere, dir.path().join("sphere.ron")).unwrap();
    dir
}

#[test]
fn inspect_prints_a_fixed_outline_as_written_and_the_disc_not_at_all() {
    let dir = workspace();
    let heart = "Outline([(0.0, -0.4), Bezier((-0.25, -0.2), (-0.45, 0.0), (-0.4, 0.18)), \
                 (0.0, 0.2), Bezier((0.45, 0.0), (0.25, -0.2), (0.0, -0.4))])";
    let line = layer_line(dir.path(), heart, "3");
    assert_eq!(shape_of(&line), heart, "{line}");
    assert!(!line.contains("morphing"), "{line}");
    let disc = layer_line(dir.path(), "Disc", "3");
    assert!(!disc.contains("shape"), "{disc}");
}

#[test]
fn inspect_prints_keyed_outlines_as_their_points_at_the_frame_and_reads_back() {
    let dir = workspace();
    let (a, b) = (
        [(-0.2, -0.1), (0.2, -0.1), (0.0, 0.2)],
        [(-0.3, -0.2), (0.1, -0.1), (0.1, 0.3)],
    );
    let key = |points: &[(f64, f64)]| {
        let written: Vec<String> = points.iter().map(|(x, y)| format!("({x}, {y})")).collect();
        format!("[{}]", written.join(", "))
    };
    let keyed = format!("OutlineKeys([(1, {}), (9, {})])", key(&a), key(&b));
    // Frame 3 is a quarter of the way from frame 1 to frame 9.
    let line = layer_line(dir.path(), &keyed, "3");
    assert!(
        line.contains("(morphing from the key at frame 1 to the key at frame 9, 0.25 of the way)"),
        "{line}"
    );
    let printed = shape_of(&line);
    let numbers: Vec<f64> = printed
        .trim_start_matches("Outline([")
        .trim_end_matches("])")
        .split([',', '(', ')'])
        .filter_map(|w| w.trim().parse().ok())
        .collect();
    let want: Vec<f64> = a
        .iter()
        .zip(&b)
        .flat_map(|(p, q)| [p.0 + 0.25 * (q.0 - p.0), p.1 + 0.25 * (q.1 - p.1)])
        .collect();
    assert_eq!(numbers.len(), want.len(), "{printed}");
    for (got, want) in numbers.iter().zip(&want) {
        assert!((got - want).abs() < 1e-6, "{printed}: {got} against {want}");
    }
    // On a key: that key, with no morph said.
    let on_key = layer_line(dir.path(), &keyed, "9");
    assert_eq!(
        shape_of(&on_key),
        format!("Outline({})", key(&b)),
        "{on_key}"
    );
    // The printed outline, pasted back as the shape, prints the same.
    let again = layer_line(dir.path(), printed, "3");
    assert_eq!(shape_of(&again), printed);
}
