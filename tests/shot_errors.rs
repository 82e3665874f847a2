//! Bad shot files: each mistake is one error line naming the file, the line and column where the
//! mistake is written and a sentence a person can act on; exit code 2; nothing written.

use std::path::PathBuf;

use crate::common::glint;

const TEMPLATE: &str = r#"Shot(
    resolution: (64, 48),
    frames: (1, 10),
    fps: 24,
    output: "out/t.####.png",
    instances: [
        (name: "ball", file: "sphere.ron", material: "blue"),
    ],
    materials: {
        "blue": Cel(base: (0.1, 0.1, 0.3), bands: [(0.0, (0.2, 0.3, 0.8))]),
    },
    camera: (
        eye: (0.0, -6.0, 0.0),
        target: (0.0, 0.0, 0.0),
        projection: Perspective(fov_y_degrees: 30.0),
    ),
    light: Directional(towards: (0.3, -1.0, 0.4)),
    highlights: [
        (
            patches: "ball/*",
            expr: Layer((
                stack: [Translate(alpha: [(1, 0.0), (10, 0.3)], beta: 0.0), Scale(delta: 0.5)],
                epsilon: 0.05,
                colour: (1.0, 1.0, 1.0),
            )),
        ),
    ],
    render: (preset: Preview),
)
"#;

/// One mistake: the template with `from` replaced by `to`; the error must be at the first
/// occurrence of `at` in the file named `file` and contain every one of `says`.
struct Case {
    name: &'static str,
    from: &'static str,
    to: &'static str,
    file: &'static str,
    at: &'static str,
    says: &'static [&'static str],
}

const CASES: &[Case] = &[
    Case {
        name: "missing comma",
        from: "fps: 24,",
        to: "fps: 24",
        file: "shot.ron",
        // Right after the value the comma should follow, not at the next line.
        at: "\n    output:",
        says: &["`,` is missing here", "(line 5)"],
    },
    Case {
        name: "semicolon for comma",
        from: "epsilon: 0.05,",
        to: "epsilon: 0.05;",
        file: "shot.ron",
        at: ";",
        says: &["not `;`"],
    },
    Case {
        name: "equals for colon",
        from: "fps: 24,",
        to: "fps = 24,",
        file: "shot.ron",
        at: " = 24",
        says: &["not `=`"],
    },
    Case {
        name: "file cut short",
        from: "    render: (preset: Preview),\n)\n",
        to: "    render: (preset: Preview),\n",
        file: "shot.ron",
        at: "(\n    resolution",
        says: &["ends before this `(` is closed"],
    },
    Case {
        name: "misspelt field",
        from: "epsilon: 0.05",
        to: "epsilom: 0.05",
        file: "shot.ron",
        at: "epsilom",
        says: &["unknown field `epsilom`", "did you mean `epsilon`?"],
    },
    Case {
        name: "misspelt top-level field",
        from: "resolution: (64, 48)",
        to: "resolutoin: (64, 48)",
        file: "shot.ron",
        at: "resolutoin",
        says: &["did you mean `resolution`?"],
    },
    Case {
        name: "misspelt operation",
        from: "Scale(delta: 0.5)",
        to: "Scael(delta: 0.5)",
        file: "shot.ron",
        at: "Scael",
        says: &["unknown variant `Scael`", "did you mean `Scale`?"],
    },
    Case {
        name: "missing field",
        from: "    fps: 24,\n",
        to: "",
        file: "shot.ron",
        at: "Shot(",
        says: &["missing field `fps`"],
    },
    Case {
        name: "keys out of order",
        from: "alpha: [(1, 0.0), (10, 0.3)]",
        to: "alpha: [(10, 0.0), (5, 0.3)]",
        file: "shot.ron",
        at: "[(10, 0.0)",
        says: &["frame 5 follows frame 10"],
    },
    Case {
        name: "constant mixed with keys",
        from: "alpha: [(1, 0.0), (10, 0.3)]",
        to: "alpha: [(1, 0.0), 0.3]",
        file: "shot.ron",
        at: "[(1, 0.0), 0.3]",
        says: &["not a mix"],
    },
    Case {
        name: "epsilon out of range",
        from: "epsilon: 0.05",
        to: "epsilon: 2.5",
        file: "shot.ron",
        // At the layer whose value it is.
        at: "(\n                stack",
        says: &["layers[0]", "epsilon (ε) is 2.5", "(0, 2]"],
    },
    Case {
        name: "keyed value out of range at one key",
        from: "Scale(delta: 0.5)",
        to: "Scale(delta: [(1, 0.5), (8, 1.5)])",
        file: "shot.ron",
        // At the operation, which the message names as its parameter path does.
        at: "Scale(delta",
        // δ = 0.5 + (f − 1)/7 first exceeds 1 at frame 5.
        says: &["at frame 5", "layers[0]: stack[1] (Scale)", "scale delta (δ) is 1.07", "[0, 1]"],
    },
    Case {
        name: "selector matches no patch",
        from: "patches: \"ball/*\"",
        to: "patches: \"bal/*\"",
        file: "shot.ron",
        at: "\"bal/*\"",
        says: &["\"bal/*\" matches no patch", "did you mean \"ball/sphere\"?"],
    },
    Case {
        name: "missing patch file",
        from: "file: \"sphere.ron\"",
        to: "file: \"spere.ron\"",
        file: "shot.ron",
        at: "\"spere.ron\"",
        says: &["cannot read the patch file", "spere.ron"],
    },
    Case {
        name: "malformed patch file",
        from: "file: \"sphere.ron\"",
        to: "file: \"broken.ron\"",
        file: "shot.ron",
        at: "\"broken.ron\"",
        says: &["in the patch file", "broken.ron:2:"],
    },
    Case {
        name: "unknown material",
        from: "material: \"blue\"",
        to: "material: \"blu\"",
        file: "shot.ron",
        at: "\"blu\"",
        says: &["unknown material \"blu\"", "did you mean \"blue\"?"],
    },
    Case {
        name: "missing include",
        from: "    instances: [",
        to: "    includes: [\"looks/none.ron\"],\n    instances: [",
        file: "shot.ron",
        at: "\"looks/none.ron\"",
        says: &["does not exist"],
    },
    Case {
        name: "cyclic include",
        from: "    instances: [",
        to: "    includes: [\"a.ron\"],\n    instances: [",
        file: "b.ron",
        at: "\"a.ron\"",
        says: &["cycle"],
    },
    Case {
        name: "material defined twice",
        from: "    instances: [",
        to: "    includes: [\"looks.ron\"],\n    instances: [",
        file: "shot.ron",
        at: "\"blue\":",
        says: &["\"blue\" is already defined in", "looks.ron"],
    },
    Case {
        name: "output pattern without a frame number",
        from: "out/t.####.png",
        to: "out/t.png",
        file: "shot.ron",
        at: "\"out/t.png\"",
        says: &["no `#`", "overwrite"],
    },
    Case {
        name: "backwards frame range",
        from: "frames: (1, 10)",
        to: "frames: (10, 1)",
        file: "shot.ron",
        at: "(10, 1)",
        says: &["backwards"],
    },
    Case {
        name: "camera looking at itself",
        from: "target: (0.0, 0.0, 0.0)",
        to: "target: (0.0, -6.0, 0.0)",
        file: "shot.ron",
        at: "(\n        eye:",
        says: &["at frame 1", "eye and target are the same point"],
    },
    Case {
        name: "field of view out of range",
        from: "fov_y_degrees: 30.0",
        to: "fov_y_degrees: [(1, 30.0), (10, 190.0)]",
        file: "shot.ron",
        at: "(\n        eye:",
        says: &["at frame", "fov_y_degrees must be in [0.001, 179.9]"],
    },
    Case {
        name: "light direction of no length",
        from: "towards: (0.3, -1.0, 0.4)",
        to: "towards: (0.0, 0.0, 0.0)",
        file: "shot.ron",
        at: "(0.0, 0.0, 0.0))",
        says: &["has no length"],
    },
    Case {
        name: "duplicate instance",
        from: "        (name: \"ball\", file: \"sphere.ron\", material: \"blue\"),\n",
        to: "        (name: \"ball\", file: \"sphere.ron\", material: \"blue\"),\n        (name: \"ball\", file: \"sphere.ron\", material: \"blue\"),\n",
        file: "shot.ron",
        at: "\"ball\", file: \"sphere.ron\", material: \"blue\"),\n    ]",
        says: &["\"ball\" is used twice"],
    },
    Case {
        name: "band thresholds out of order",
        from: "bands: [(0.0, (0.2, 0.3, 0.8))]",
        to: "bands: [(0.5, (0.2, 0.3, 0.8)), (0.2, (0.3, 0.4, 0.9))]",
        file: "shot.ron",
        at: "\"blue\": Cel(",
        says: &["material \"blue\"", "thresholds must increase"],
    },
    Case {
        name: "selector of the wrong type",
        from: "patches: \"ball/*\"",
        to: "patches: 3",
        file: "shot.ron",
        at: "3,\n",
        says: &["a patch name pattern such as"],
    },
    Case {
        name: "zero resolution",
        from: "resolution: (64, 48)",
        to: "resolution: (0, 48)",
        file: "shot.ron",
        at: "(0, 48)",
        says: &["image size 0×48"],
    },
    Case {
        name: "a field named in a comment before it is written",
        from: "    frames: (1, 10),",
        to: "    // frames: (1, 10) was the range; fps: 0 was wrong\n    frames: (10, 1),",
        file: "shot.ron",
        at: "(10, 1)",
        says: &["backwards"],
    },
    Case {
        name: "second pattern of a list matches no patch",
        from: "patches: \"ball/*\"",
        to: "patches: [\"ball/*\", \"bal/0\"]",
        file: "shot.ron",
        at: "\"bal/0\"",
        says: &["\"bal/0\" matches no patch", "did you mean"],
    },
    Case {
        name: "out of range only at a key between frames",
        from: "fov_y_degrees: 30.0",
        to: "fov_y_degrees: [(1, 30.0), (2.5, 190.0), (4, 30.0)]",
        file: "shot.ron",
        at: "(\n        eye:",
        says: &["at frame 2.5:", "fov_y_degrees must be in [0.001, 179.9]"],
    },
    Case {
        name: "transform that cannot place",
        from: "material: \"blue\"),",
        to: "material: \"blue\", transform: (scale: 0.0)),",
        file: "shot.ron",
        at: "0.0)),",
        says: &["instance \"ball\"", "the scale 0 must lie in [1e-6, 1e6]"],
    },
    Case {
        name: "keyed scale out of range at a key",
        from: "material: \"blue\"),",
        to: "material: \"blue\", transform: (scale: [(1, 1.0), (5, 2e6)])),",
        file: "shot.ron",
        at: "[(1, 1.0), (5, 2e6)]",
        says: &["the scale 2000000 at frame 5 must lie in [1e-6, 1e6]"],
    },
    Case {
        name: "pivot out of range",
        from: "material: \"blue\"),",
        to: "material: \"blue\", transform: (pivot: (1e7, 0, 0), degrees: 10)),",
        file: "shot.ron",
        at: "(1e7, 0, 0)",
        says: &["the pivot (10000000, 0, 0) must lie within ±1e6"],
    },
    Case {
        name: "zero axis at a key",
        from: "material: \"blue\"),",
        to: "material: \"blue\", transform: (axis: [(1, (0, 0, 1)), (4, (0, 0, 0))], degrees: 30)),",
        file: "shot.ron",
        at: "[(1, (0, 0, 1)), (4, (0, 0, 0))]",
        says: &["the axis (0, 0, 0) at frame 4 must be a non-zero vector"],
    },
    Case {
        name: "moving part that is no part",
        from: "material: \"blue\"),",
        to: "material: \"blue\", groups: {\"top\": [0]}, parts: {\"tpo\": (degrees: 10)}),",
        file: "shot.ron",
        at: "\"tpo\"",
        says: &["instance \"ball\" has no part \"tpo\"", "its parts are \"top\""],
    },
    Case {
        name: "patch in two moving parents",
        from: "material: \"blue\"),",
        to: "material: \"blue\", groups: {\"a\": [0], \"b\": [0]}, parts: {\"a\": (degrees: [(1, 0), (9, 5)]), \"b\": (degrees: 5)}),",
        file: "shot.ron",
        at: "\"b\": (degrees",
        says: &["the parts \"a\" and \"b\"", "neither holds the other"],
    },
    Case {
        name: "transform carrying the model too far",
        from: "material: \"blue\"),",
        to: "material: \"blue\", transform: (translate: [(1, (0, 0, 0)), (9, (9e5, 0, 0))], scale: [(1, 1), (9, 2e5)])),",
        file: "shot.ron",
        at: "(translate: [(1,",
        says: &["can carry its patches up to", "beyond ±1e6"],
    },
    Case {
        name: "line styles without lines on",
        from: "    render: (preset: Preview),",
        to: "    lines: [(patches: \"ball/*\", width: 3.0)],\n    render: (preset: Preview),",
        file: "shot.ron",
        at: "[(patches: \"ball/*\", width: 3.0)]",
        says: &["line styles need lines on", "outlines: ()"],
    },
    Case {
        name: "line style picking by patches and material at once",
        from: "    render: (preset: Preview),",
        to: "    lines: [(patches: \"ball/*\", material: \"blue\", width: 3.0)],\n    render: (preset: Preview, outlines: ()),",
        file: "shot.ron",
        at: "(patches: \"ball/*\", material",
        says: &["give exactly one"],
    },
    Case {
        name: "line style selector matching nothing",
        from: "    render: (preset: Preview),",
        to: "    lines: [(patches: \"bal/*\", width: 3.0)],\n    render: (preset: Preview, outlines: ()),",
        file: "shot.ron",
        at: "\"bal/*\"",
        says: &["\"bal/*\" matches no patch", "did you mean"],
    },
    Case {
        name: "line style on a material the shot lacks",
        from: "    render: (preset: Preview),",
        to: "    lines: [(material: \"bleu\", colour: (1.0, 0.0, 0.0))],\n    render: (preset: Preview, outlines: ()),",
        file: "shot.ron",
        at: "\"bleu\"",
        says: &["no material \"bleu\"", "did you mean \"blue\""],
    },
    Case {
        name: "line width out of range at a key",
        from: "    render: (preset: Preview),",
        to: "    lines: [(patches: \"ball/*\", width: [(1, 2.0), (10, 80.0)])],\n    render: (preset: Preview, outlines: ()),",
        file: "shot.ron",
        at: "(patches: \"ball/*\", width: [",
        // Frame 9 is the first whole frame past 64 px.
        says: &["at frame 9:", "line width 71.3", "must be between 0 and 64"],
    },
    Case {
        name: "negative taper",
        from: "    render: (preset: Preview),",
        to: "    render: (preset: Preview, outlines: (taper: -1.0)),",
        file: "shot.ron",
        at: "(taper: -1.0)",
        says: &["line taper -1 must be between 0"],
    },
    Case {
        name: "hidden lines behind too many surfaces",
        from: "    render: (preset: Preview),",
        to: "    lines: [(patches: \"ball/*\", hidden: (levels: 17))],\n    render: (preset: Preview, outlines: ()),",
        file: "shot.ron",
        at: "(patches: \"ball/*\", hidden:",
        says: &["hidden lines' levels 17", "from 0 to 16 surfaces"],
    },
    Case {
        name: "a dash pattern with no positive length",
        from: "    render: (preset: Preview),",
        to: "    render: (preset: Preview, outlines: (hidden: (dash: [0.0, 0.0]))),",
        file: "shot.ron",
        at: "[0.0, 0.0]",
        says: &["dash pattern's lengths must add up to at least 1 pixel"],
    },
    Case {
        name: "a negative dash length",
        from: "    render: (preset: Preview),",
        to: "    lines: [(patches: \"ball/*\", hidden: (dash: [4.0, -2.0]))],\n    render: (preset: Preview, outlines: ()),",
        file: "shot.ron",
        at: "[4.0, -2.0]",
        says: &["dash length -2 must be between 0 and 1e4"],
    },
    Case {
        name: "a part material on a part the model lacks",
        from: "material: \"blue\"",
        to: "material: \"blue\", part_materials: {\"lidd\": \"blue\"}",
        file: "shot.ron",
        at: "\"lidd\"",
        says: &["unknown part \"lidd\""],
    },
    Case {
        name: "unknown kind of line",
        from: "    render: (preset: Preview),",
        to: "    render: (preset: Preview, outlines: (kinds: [Silhouette, Outline])),",
        file: "shot.ron",
        at: "Outline]",
        says: &["Outline", "Silhouette", "Intersection"],
    },
    Case {
        name: "an eye and an orbit",
        from: "        eye: (0.0, -6.0, 0.0),",
        to: "        eye: (0.0, -6.0, 0.0),\n        orbit: Sphere(azimuth: -90.0, elevation: 0.0, distance: 6.0),",
        file: "shot.ron",
        at: "Sphere(",
        says: &["both an `eye` and an `orbit`", "keep one"],
    },
    Case {
        name: "no eye",
        from: "        eye: (0.0, -6.0, 0.0),\n",
        to: "",
        file: "shot.ron",
        at: "(\n        target",
        says: &["no eye", "`eye: (x, y, z)`", "orbit: Sphere("],
    },
    Case {
        name: "orbit elevation out of range at a key",
        from: "        eye: (0.0, -6.0, 0.0),",
        to: "        orbit: Sphere(azimuth: -90.0, elevation: [(1, 0.0), (10, 95.0)], distance: 6.0),",
        file: "shot.ron",
        at: "[(1, 0.0), (10, 95.0)]",
        says: &["elevation is 95 at frame 10", "within ±89 degrees"],
    },
    Case {
        name: "orbit radius not positive",
        from: "        eye: (0.0, -6.0, 0.0),",
        to: "        orbit: Cylinder(azimuth: -90.0, radius: -6.5, height: 1.0),",
        file: "shot.ron",
        at: "-6.5",
        says: &["radius is -6.5 at frame 1", "above 0"],
    },
    Case {
        name: "unknown orbit shape",
        from: "        eye: (0.0, -6.0, 0.0),",
        to: "        orbit: Circle(azimuth: -90.0, radius: 6.0),",
        file: "shot.ron",
        at: "Circle",
        says: &["Circle", "Sphere", "Cylinder"],
    },
    Case {
        name: "unknown light for a highlight",
        from: "            )),\n        ),\n    ],",
        to: "            )),\n            light: Designd,\n        ),\n    ],",
        file: "shot.ron",
        at: "Designd",
        says: &["Designd", "Plain", "Designed"],
    },
    Case {
        name: "shade selector matching nothing",
        from: "    render: (preset: Preview),",
        to: "    shade: [(patches: \"bal/*\", stack: [Translate(alpha: 0.2, beta: 0.0)])],\n    render: (preset: Preview),",
        file: "shot.ron",
        at: "\"bal/*\"",
        says: &["bal/*", "ball/"],
    },
    Case {
        name: "shade operation out of range at a key",
        from: "    render: (preset: Preview),",
        to: "    shade: [(patches: \"ball/*\", stack: [Translate(alpha: 0.2, beta: 0.0), Scale(delta: [(1, 0.2), (10, 1.5)])])],\n    render: (preset: Preview),",
        file: "shot.ron",
        at: "Scale(delta: [(1, 0.2)",
        says: &["shade on \"ball/*\" at frame 7", "stack[1] (Scale)", "outside the allowed range"],
    },
    Case {
        name: "shade mask unordered",
        from: "    render: (preset: Preview),",
        to: "    shade: [(patches: \"ball/*\", stack: [Rotate(degrees: 10.0)], mask: Some((u: (0.6, 0.2), v: (0.0, 1.0), feather: 0.0)))],\n    render: (preset: Preview),",
        file: "shot.ron",
        at: "Some((u: (0.6",
        says: &["shade on \"ball/*\" at frame 1", "mask"],
    },
    Case {
        name: "misspelt shade field",
        from: "    render: (preset: Preview),",
        to: "    shade: [(patches: \"ball/*\", stakc: [])],\n    render: (preset: Preview),",
        file: "shot.ron",
        at: "stakc",
        says: &["unknown field `stakc`", "did you mean `stack`?"],
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

/// A folder with the sphere, a broken patch file, two includes that include each other and a
/// look library that defines "blue" again.
fn workspace() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    let sphere = crate::common::root().join("patches/sphere.ron");
    std::fs::copy(sphere, dir.path().join("sphere.ron")).unwrap();
    std::fs::write(
        dir.path().join("broken.ron"),
        "(patches: [\n  (name: \"s\", surface: Sphere(radius: -1.0))])",
    )
    .unwrap();
    std::fs::write(dir.path().join("a.ron"), "Looks(includes: [\"b.ron\"])").unwrap();
    std::fs::write(
        dir.path().join("b.ron"),
        "Looks(\n  includes: [\"a.ron\"],\n)",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("looks.ron"),
        "Looks(materials: {\"blue\": Cel(base: (0, 0, 1))})",
    )
    .unwrap();
    dir
}

#[test]
fn the_template_renders() {
    let dir = workspace();
    let shot = dir.path().join("shot.ron");
    std::fs::write(&shot, TEMPLATE).unwrap();
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
fn every_mistake_is_one_located_actionable_error_and_nothing_is_written() {
    assert!(CASES.len() >= 15);
    let dir = workspace();
    let mut failures = Vec::new();
    for case in CASES {
        assert!(
            TEMPLATE.contains(case.from),
            "{}: template lacks {}",
            case.name,
            case.from
        );
        let text = TEMPLATE.replacen(case.from, case.to, 1);
        let shot = dir.path().join("shot.ron");
        std::fs::write(&shot, &text).unwrap();
        let out = glint().arg("render").arg(&shot).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr).trim().to_string();
        let file_text = if case.file == "shot.ron" {
            text.clone()
        } else {
            std::fs::read_to_string(dir.path().join(case.file)).unwrap()
        };
        let (line, col) = location(&file_text, case.at);
        let path: PathBuf = dir.path().join(case.file);
        let expected = format!("error: {}:{line}:{col}: ", path.display());
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
