//! Bad drawn outlines in a shot: each is one error line naming the file, the line and column of
//! the layer's `shape` (or of the mistake, for what the reader refuses), exit code 2, and no
//! frame written.

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
            expr: Layer((
                stack: [Translate(alpha: 0.1, beta: 0.0), Rotate(degrees: 20.0)],
                epsilon: 0.05,
                colour: (1.0, 1.0, 1.0),
                shape: SHAPE,
            )),
        ),
    ],
    render: (preset: Preview),
)
"#;

/// One bad shape: the error is at the first occurrence of `at` and says every one of `says`.
struct Case {
    name: &'static str,
    shape: &'static str,
    at: &'static str,
    says: &'static [&'static str],
}

const CASES: &[Case] = &[
    Case {
        name: "two points",
        shape: "Outline([(0.0, 0.1), (0.1, 0.0)])",
        at: "Outline(",
        says: &["layers[0]: outline:", "at least 3 distinct points", "it has 2"],
    },
    Case {
        name: "a bow tie",
        shape: "Outline([(0.0, 0.0), (0.2, 0.2), (0.2, 0.0), (0.0, 0.2)])",
        at: "Outline(",
        says: &["crosses itself near (0.1000, 0.1000)", "point 2 and point 4"],
    },
    Case {
        name: "a point that is not a number",
        shape: "Outline([(0.0, 0.1), (NaN, 0.0), (0.0, -0.1)])",
        at: "Outline(",
        says: &["point 2 of the outline", "not a finite number"],
    },
    Case {
        name: "a point past the bound",
        shape: "Outline([(0.0, 0.1), (1.5, 0.0), (0.0, -0.1)])",
        at: "Outline(",
        says: &["point 2 of the outline is (1.5, 0)", "|t'| ≤ 0.99"],
    },
    Case {
        name: "a Bézier control past the bound",
        shape: "Outline([(0.0, 0.1), Bezier((0.9, 0.9), (0.1, 0.0), (0.1, 0.0)), (0.0, -0.1)])",
        at: "Outline(",
        says: &["point 2 of the outline is (0.9, 0.9)"],
    },
    Case {
        name: "keys with different counts",
        shape: "OutlineKeys([(1, [(0.0, 0.1), (0.1, 0.0), (0.0, -0.1)]), (9, [(0.0, 0.1), (0.1, 0.0), (0.0, -0.1), (-0.1, 0.0)])])",
        at: "OutlineKeys(",
        says: &["the outline key at frame 1 has 3 points but the key at frame 9 has 4"],
    },
    Case {
        name: "a piece of no kind",
        shape: "Outline([(0.0, 0.1), Curve((0.1, 0.1), (0.1, 0.0), (0.1, 0.0)), (0.0, -0.1)])",
        at: "Curve(",
        says: &["a corner (x, y) or a Bezier((x1, y1), (x2, y2), (x, y))"],
    },
];

/// The 1-based line and column of the first `needle` in `text`.
fn location(text: &str, needle: &str) -> (usize, usize) {
    let offset = text
        .find(needle)
        .unwrap_or_else(|| panic!("`{needle}` not in the file"));
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before[before.rfind('\n').map_or(0, |i| i + 1)..]
        .chars()
        .count()
        + 1;
    (line, col)
}

fn workspace() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let sphere = crate::common::root().join("patches/sphere.ron");
    std::fs::copy(sphere, dir.path().join("sphere.ron")).unwrap();
    dir
}

#[test]
fn a_drawn_star_renders_in_a_shot() {
    let dir = workspace();
    let shot = dir.path().join("shot.ron");
    let star = "Outline([(0.0, 0.3), (0.07, 0.1), (0.29, 0.09), (0.11, -0.04), (0.18, -0.24), \
                (0.0, -0.12), (-0.18, -0.24), (-0.11, -0.04), (-0.29, 0.09), (-0.07, 0.1)])";
    std::fs::write(&shot, TEMPLATE.replace("SHAPE", star)).unwrap();
    let out = glint()
        .args(["render", "--quiet", "--frames", "1"])
        .arg(&shot)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(dir.path().join("out/t.0001.png").exists());
}

#[test]
fn a_morph_that_collapses_between_its_keys_renders_every_frame() {
    // Each corner goes to the opposite one: both keys are the same rectangle, and at frame 5
    // every point is at the centre. Keys are checked; the frames between render, the collapsed
    // one empty, and none is refused.
    let dir = workspace();
    let shot = dir.path().join("shot.ron");
    let morph = "OutlineKeys([(1, [(-0.2, -0.1), (0.2, -0.1), (0.2, 0.1), (-0.2, 0.1)]), \
                 (9, [(0.2, 0.1), (-0.2, 0.1), (-0.2, -0.1), (0.2, -0.1)])])";
    std::fs::write(&shot, TEMPLATE.replace("SHAPE", morph)).unwrap();
    let out = glint()
        .args(["render", "--quiet"])
        .arg(&shot)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for frame in 1..=9 {
        assert!(dir.path().join(format!("out/t.{frame:04}.png")).exists());
    }
}

#[test]
fn every_bad_outline_is_one_located_error_and_nothing_is_written() {
    let dir = workspace();
    let mut failures = Vec::new();
    for case in CASES {
        let text = TEMPLATE.replace("SHAPE", case.shape);
        let shot = dir.path().join("shot.ron");
        std::fs::write(&shot, &text).unwrap();
        let out = glint().arg("render").arg(&shot).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr).trim().to_string();
        let (line, col) = location(&text, case.at);
        let expected = format!("error: {}:{line}:{col}: ", shot.display());
        let ok = out.status.code() == Some(2)
            && stderr.lines().count() == 1
            && stderr.starts_with(&expected)
            && case.says.iter().all(|s| stderr.contains(s))
            && !dir.path().join("out").exists();
        if !ok {
            failures.push(format!(
                "{}: exit {:?}\n  expected {expected}… {:?}\n  got      {stderr}",
                case.name,
                out.status.code(),
                case.says
            ));
        }
    }
    assert!(failures.is_empty(), "\n{}", failures.join("\n"));
}
