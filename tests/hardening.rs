//! Hostile and degenerate input refused or handled at its cause: a shot with no patches, colours
//! and geometry outside the ranges that keep the arithmetic finite — each one line with its
//! place, exit 2, nothing written; never a panic.

use std::path::Path;
use std::process::Output;

use crate::common::{glint, stderr};

fn shot(dir: &Path, instances: &str, extra: &str) -> std::path::PathBuf {
    let text = format!(
        r#"Shot(
    resolution: (16, 16),
    frames: (1, 2),
    fps: 24,
    output: "out/s.####.png",
    instances: [{instances}],
    materials: {{"m": Cel(base: (0.1, 0.1, 0.1), bands: [(0.0, (0.5, 0.5, 0.5))])}},
    camera: (eye: (0.0, -6.0, 0.0), target: (0.0, 0.0, 0.0), projection: Orthographic(height: 2.4)),
    light: Directional(towards: (0.0, 1.0, 0.0)),
    highlights: [],{extra}
)"#
    );
    let path = dir.join("shot.ron");
    std::fs::write(&path, text).unwrap();
    path
}

/// A shot of a unit sphere (`ball.ron`, written beside it) with no highlight.
fn ball_shot(dir: &Path) -> std::path::PathBuf {
    let ball = "(patches: [(name: \"s\", surface: Sphere(radius: 1.0))])";
    std::fs::write(dir.join("ball.ron"), ball).unwrap();
    shot(
        dir,
        r#"(name: "ball", file: "ball.ron", material: "m")"#,
        "",
    )
}

fn run(dir: &Path, args: &[&str]) -> Output {
    glint().current_dir(dir).args(args).output().unwrap()
}

/// One line naming `file:line:`, exit 2, and no frame written.
fn assert_refused(dir: &Path, out: &Output, file: &str, says: &str) {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains(file) && err.contains(says), "{err}");
    assert!(!dir.join("out").exists(), "nothing is written");
}

#[test]
fn a_shot_without_patches_is_inspected_without_a_panic() {
    let dir = tempfile::tempdir().unwrap();
    let path = shot(dir.path(), "", "");
    let out = run(
        dir.path(),
        &["inspect", path.to_str().unwrap(), "--frame", "1"],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let out = run(
        dir.path(),
        &[
            "inspect",
            path.to_str().unwrap(),
            "--frame",
            "1",
            "--patch",
            "a/*",
        ],
    );
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("the shot has no patches"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn colours_beyond_their_range_are_refused_where_they_are_written() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("ball.ron"),
        "(patches: [(name: \"s\", surface: Sphere(radius: 1.0))])",
    )
    .unwrap();
    let ball = r#"(name: "ball", file: "ball.ron", material: "m")"#;
    for (colour, says) in [
        ("(NaN, 0.0, 0.0)", "must be finite"),
        (
            "(-1.0, 0.0, 0.0)",
            "line colour (-1, 0, 0) must have components from 0 to 1e4",
        ),
        (
            "(1e5, 0.0, 0.0)",
            "line colour (100000, 0, 0) must have components from 0 to 1e4",
        ),
        ("(0.0, inf, 0.0)", "must be finite"),
    ] {
        let extra = format!("\n    render: (outlines: (colour: {colour})),");
        let path = shot(dir.path(), ball, &extra);
        let out = run(dir.path(), &["render", path.to_str().unwrap()]);
        assert_refused(dir.path(), &out, "shot.ron:", says);
    }
    let layer = r#"
    highlights: [(patches: "*", expr: Layer((stack: [], epsilon: 0.1, colour: (2e4, 1.0, 1.0))))],"#;
    let path = shot(dir.path(), ball, "").to_str().unwrap().to_string();
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("\n    highlights: [],", layer);
    std::fs::write(&path, text).unwrap();
    let out = run(dir.path(), &["render", &path]);
    assert_refused(dir.path(), &out, "shot.ron:", "colour component");
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("(2e4, 1.0, 1.0)", "(1.0, 1.0, 1.0)")
        .replace("base: (0.1, 0.1, 0.1)", "base: (-0.1, 0.1, 0.1)");
    std::fs::write(&path, text).unwrap();
    let out = run(dir.path(), &["render", &path]);
    assert_refused(dir.path(), &out, "shot.ron:", "from 0 to 1e4");
}

#[test]
fn geometry_too_large_to_evaluate_is_refused_where_it_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let path = shot(
        dir.path(),
        r#"(name: "ball", file: "ball.ron", material: "m")"#,
        "",
    );
    let nurbs = |points: &str, weights: &str| {
        format!(
            "(patches: [(name: \"p\", surface: Nurbs(degree: (1, 1), knots_u: [0.0, 0.0, 1.0, 1.0], \
             knots_v: [0.0, 0.0, 1.0, 1.0], points: {points}, weights: Some({weights})))])"
        )
    };
    let square = "[[(0.0, 0.0, 0.0), (0.0, 1.0, 0.0)], [(1.0, 0.0, 0.0), (1.0, 1.0, 0.0)]]";
    for (model, says) in [
        (
            "(patches: [(name: \"s\", surface: Sphere(radius: 1e300))])".to_string(),
            "radius",
        ),
        (
            "(patches: [(name: \"t\", surface: Torus(major_radius: 1e308, minor_radius: 1.0))])"
                .to_string(),
            "major_radius",
        ),
        (nurbs(square, "[[1.0, 1e308], [1.0, 1.0]]"), "weight"),
        (nurbs(square, "[[1.0, 1e-9], [1.0, 1.0]]"), "weight"),
        (
            nurbs(
                "[[(0.0, 0.0, 0.0), (0.0, 1e308, 0.0)], [(1.0, 0.0, 0.0), (1.0, 1.0, 0.0)]]",
                "[[1.0, 1.0], [1.0, 1.0]]",
            ),
            "control point",
        ),
    ] {
        std::fs::write(dir.path().join("ball.ron"), &model).unwrap();
        let out = run(dir.path(), &["render", path.to_str().unwrap()]);
        assert_refused(dir.path(), &out, "ball.ron:", says);
        let probe = run(
            dir.path(),
            &["probe", "ball.ron", "--patch", "0", "--uv", "0.5,0.5"],
        );
        assert_eq!(probe.status.code(), Some(2), "{model}: {}", stderr(&probe));
    }
}

#[test]
fn a_light_passing_straight_behind_the_model_does_not_flash() {
    // Orthographic view from −y: V = −y everywhere, so a light toward +y is exactly L = −V.
    let dir = tempfile::tempdir().unwrap();
    let layer = r#"
    highlights: [(patches: "*", expr: Layer((stack: [], epsilon: 0.05, colour: (1.0, 1.0, 1.0))))],"#;
    let mut counts = Vec::new();
    for towards in [
        "(0.0, 1.0, 0.0)",
        "(0.001, 1.0, 0.0)",
        "(0.0, 1.0, -0.002)",
        "(-0.003, 1.0, 0.001)",
    ] {
        let path = ball_shot(dir.path());
        let text = std::fs::read_to_string(&path)
            .unwrap()
            .replace("\n    highlights: [],", layer)
            .replace("towards: (0.0, 1.0, 0.0)", &format!("towards: {towards}"));
        std::fs::write(&path, text).unwrap();
        let out = run(
            dir.path(),
            &[
                "render",
                path.to_str().unwrap(),
                "--size",
                "64x64",
                "--aov",
                "matte",
                "--frames",
                "1",
                "--quiet",
            ],
        );
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
        let matte = image::open(dir.path().join("out/s.0001.matte.png"))
            .unwrap()
            .to_luma8();
        let colour = image::open(dir.path().join("out/s.0001.png"))
            .unwrap()
            .to_rgba8();
        let lit = matte.pixels().filter(|p| p.0[0] > 127).count();
        let covered = colour.pixels().filter(|p| p.0[3] > 0).count();
        assert!(
            lit * 20 < covered,
            "{towards}: {lit} of {covered} pixels are highlight"
        );
        counts.push(lit);
        std::fs::remove_dir_all(dir.path().join("out")).unwrap();
    }
    let (least, most) = (counts.iter().min().unwrap(), counts.iter().max().unwrap());
    assert!(most <= &(2 * least.max(&1)), "{counts:?}");
}

#[test]
fn command_line_mistakes_are_one_line_and_negative_frame_lists_read() {
    for args in [
        &["render", "shots/sphere_ops.ron", "--aovs", "matte"][..],
        &["rendr"],
        &["render", "shots/sphere_ops.ron", "--size", "big"],
        &["render"],
    ] {
        let out = glint().args(args).output().unwrap();
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert_eq!(
            stderr(&out).lines().count(),
            1,
            "{args:?}: {}",
            stderr(&out)
        );
    }
    let dir = tempfile::tempdir().unwrap();
    let path = ball_shot(dir.path());
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("frames: (1, 2)", "frames: (-5, 5)");
    std::fs::write(&path, text).unwrap();
    let out = run(
        dir.path(),
        &[
            "render",
            path.to_str().unwrap(),
            "--frames",
            "-5--4",
            "--quiet",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let written = std::fs::read_dir(dir.path().join("out")).unwrap().count();
    assert_eq!(written, 2, "frames -5 and -4");
}

#[test]
fn names_with_line_breaks_and_nul_cannot_split_an_error_line() {
    let dir = tempfile::tempdir().unwrap();
    let path = ball_shot(dir.path());
    let text = std::fs::read_to_string(&path).unwrap().replace(
        "\n    highlights: [],",
        "\n    highlights: [(patches: \"no\\nsuch\\u{0}patch\", expr: Layer((stack: [], epsilon: 0.1, colour: (1.0, 1.0, 1.0))))],",
    );
    std::fs::write(&path, text).unwrap();
    let out = run(dir.path(), &["render", path.to_str().unwrap()]);
    assert_refused(dir.path(), &out, "shot.ron:", "no\\nsuch\\u{0}patch");
    let out = run(
        dir.path(),
        &[
            "inspect",
            path.to_str().unwrap(),
            "--frame",
            "1",
            "--patch",
            "a\nb",
        ],
    );
    assert_eq!(stderr(&out).lines().count(), 1, "{}", stderr(&out));
}

#[test]
fn a_file_that_is_not_text_is_refused_at_its_first_bad_byte() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("shot.ron");
    std::fs::write(&path, b"Shot(\n    frames: (1, 2), \xff\n)").unwrap();
    let out = run(dir.path(), &["render", path.to_str().unwrap()]);
    assert_refused(dir.path(), &out, "shot.ron:2:21:", "not UTF-8");
    std::fs::write(dir.path().join("m.ron"), b"(patches: [\xc0])").unwrap();
    let out = run(
        dir.path(),
        &["probe", "m.ron", "--patch", "0", "--uv", "0,0"],
    );
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("m.ron:1:12:"), "{}", stderr(&out));
}

/// Renders frames 1-24 of a copy of `shots/sphere_ops.ron` twice at once into one folder,
/// `trials` times; both renders must succeed and leave the bytes one render alone leaves.
fn concurrent_renders(trials: usize) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("shots")).unwrap();
    std::fs::create_dir_all(dir.path().join("patches")).unwrap();
    std::fs::copy(
        crate::common::repo_file("patches/sphere.ron"),
        dir.path().join("patches/sphere.ron"),
    )
    .unwrap();
    let shot = dir.path().join("shots/sphere_ops.ron");
    std::fs::copy(crate::common::repo_file("shots/sphere_ops.ron"), &shot).unwrap();
    let render = |out: &str| {
        glint()
            .args([
                "render",
                shot.to_str().unwrap(),
                "--frames",
                "1-24",
                "--preset",
                "preview",
                "--size",
                "48x48",
                "--aov",
                "matte",
                "--quiet",
                "--out",
                out,
            ])
            .spawn()
            .unwrap()
    };
    let alone = dir.path().join("alone/s.####.png");
    assert!(render(alone.to_str().unwrap()).wait().unwrap().success());
    for trial in 0..trials {
        let both = dir.path().join(format!("both{trial}/s.####.png"));
        let (mut a, mut b) = (
            render(both.to_str().unwrap()),
            render(both.to_str().unwrap()),
        );
        let (a, b) = (a.wait().unwrap(), b.wait().unwrap());
        assert!(a.success() && b.success(), "trial {trial}: {a:?} {b:?}");
        let folder = both.parent().unwrap();
        let mut names: Vec<String> = std::fs::read_dir(folder)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        assert_eq!(
            names.len(),
            24 * 3,
            "trial {trial}: colour, matte and EXR, no temporary: {names:?}"
        );
        for name in names {
            let together = std::fs::read(folder.join(&name)).unwrap();
            let single = std::fs::read(alone.parent().unwrap().join(&name)).unwrap();
            assert!(together == single, "trial {trial}: {name} differs");
        }
    }
}

#[test]
fn two_renders_of_the_same_frames_at_once_both_succeed_with_the_same_bytes() {
    concurrent_renders(3);
}

#[test]
fn skip_existing_clears_a_killed_run_s_temporaries_of_every_file_but_a_running_one_s() {
    let dir = tempfile::tempdir().unwrap();
    let path = ball_shot(dir.path());
    let out_dir = dir.path().join("out");
    std::fs::create_dir_all(&out_dir).unwrap();
    let mut child = std::process::Command::new("true").spawn().unwrap();
    child.wait().unwrap();
    let host = glint::formats::atomic::host_name()
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' {
                c
            } else {
                '-'
            }
        })
        .collect::<String>();
    let dead = format!(".s.0001.matte.png.{host}.{}.tmp", child.id());
    let running = format!(".s.0001.matte.png.{host}.1.tmp");
    for name in [&dead, &running] {
        std::fs::write(out_dir.join(name), b"half").unwrap();
    }
    let resume = || {
        let out = run(
            dir.path(),
            &[
                "render",
                path.to_str().unwrap(),
                "--aov",
                "matte",
                "--skip-existing",
                "--quiet",
            ],
        );
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    };
    resume();
    assert!(
        !out_dir.join(&dead).exists(),
        "a killed run's temporary goes"
    );
    assert!(
        out_dir.join(&running).exists(),
        "pid 1 is running: its temporary stays"
    );
    assert!(out_dir.join("s.0001.matte.png").is_file());
    // Resumed again with every frame done and skipped: a temporary a killed run left beside a
    // finished frame goes all the same.
    std::fs::write(out_dir.join(&dead), b"half").unwrap();
    resume();
    assert!(
        !out_dir.join(&dead).exists(),
        "a killed run's temporary goes when its frame is skipped"
    );
    assert!(out_dir.join(&running).exists());
}

#[test]
fn absurd_thread_counts_and_endless_files_are_refused_before_any_work() {
    let dir = tempfile::tempdir().unwrap();
    let path = ball_shot(dir.path());
    let out = run(
        dir.path(),
        &["render", path.to_str().unwrap(), "--threads", "100000"],
    );
    assert_refused(dir.path(), &out, "shot.ron", "worker threads");
    if Path::new("/dev/zero").exists() {
        let text = std::fs::read_to_string(&path).unwrap().replace(
            "    instances: [",
            "    includes: [\"/dev/zero\"],\n    instances: [",
        );
        std::fs::write(&path, text).unwrap();
        let out = run(dir.path(), &["render", path.to_str().unwrap()]);
        assert_refused(dir.path(), &out, "/dev/zero", "not a regular file");
    }
}

#[test]
fn a_frame_needing_more_memory_than_the_ceiling_is_refused_before_rendering() {
    let dir = tempfile::tempdir().unwrap();
    let path = ball_shot(dir.path());
    let path = path.to_str().unwrap();
    // 4096² at `final`: about 2.6 GB.
    let out = run(
        dir.path(),
        &[
            "render",
            path,
            "--size",
            "4096x4096",
            "--preset",
            "final",
            "--max-memory",
            "1G",
        ],
    );
    assert_refused(
        dir.path(),
        &out,
        "shot.ron",
        "above 1.1 GB (the ceiling --max-memory sets)",
    );
    assert!(
        stderr(&out).contains("raise the ceiling with --max-memory"),
        "{}",
        stderr(&out)
    );
    // A mesh too dense for the ceiling: 50 spheres at 256 segments per span (4 × 2 spans
    // each, 525 k vertices a sphere).
    let balls: Vec<String> = (0..50)
        .map(|k| format!(r#"(name: "b{k}", file: "ball.ron", material: "m")"#))
        .collect();
    let dense = shot(
        dir.path(),
        &balls.join(", "),
        "\n    render: (tessellation: PerSpan(u: 256, v: 256)),",
    );
    let dense = dense.to_str().unwrap();
    let out = run(
        dir.path(),
        &["render", dense, "--size", "32x32", "--max-memory", "2G"],
    );
    // 26 M vertices at 200 B, and the image and the workers' tiles.
    assert_refused(dir.path(), &out, "shot.ron", "GB, above 2.1 GB");
    let needs: f64 = stderr(&out)
        .split("needs about ")
        .nth(1)
        .and_then(|rest| rest.split(' ').next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{}", stderr(&out)));
    assert!((5.2..6.0).contains(&needs), "{}", stderr(&out));
    // The sphere at a size and density that fit is rendered.
    let path = ball_shot(dir.path());
    let path = path.to_str().unwrap();
    let out = run(
        dir.path(),
        &[
            "render",
            path,
            "--size",
            "32x32",
            "--frames",
            "1",
            "--max-memory",
            "1G",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    for bad in ["lots", "-1G", "0"] {
        let out = run(dir.path(), &["render", path, "--max-memory", bad]);
        assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
        assert_eq!(stderr(&out).lines().count(), 1, "{}", stderr(&out));
    }
}

#[test]
fn camera_light_and_placement_beyond_their_ranges_are_refused_where_they_are_written() {
    let dir = tempfile::tempdir().unwrap();
    let ball = r#"(name: "ball", file: "ball.ron", material: "m")"#;
    ball_shot(dir.path());
    let base = std::fs::read_to_string(dir.path().join("shot.ron")).unwrap();
    let camera = "camera: (eye: (0.0, -6.0, 0.0), target: (0.0, 0.0, 0.0), projection: Orthographic(height: 2.4)),";
    let light = "light: Directional(towards: (0.0, 1.0, 0.0)),";
    let cases = [
        (camera, "camera: (eye: (0.0, -2e7, 0.0), target: (0.0, 0.0, 0.0), projection: Orthographic(height: 2.4)),", "within ±1e6"),
        (camera, "camera: (eye: (0.0, -6.0, 0.0), target: (0.0, 0.0, 0.0), up: (0.0, 0.0, 1e30), projection: Orthographic(height: 2.4)),", "within ±1e6"),
        (camera, "camera: (eye: (0.0, -6.0, 0.0), target: (0.0, 0.0, 0.0), projection: Orthographic(height: 2.4), near: 1e-12),", "near and far"),
        (camera, "camera: (eye: (0.0, -6.0, 0.0), target: (0.0, 0.0, 0.0), projection: Orthographic(height: 2.4), far: 1e30),", "near and far"),
        (camera, "camera: (eye: (0.0, -6.0, 0.0), target: (0.0, 0.0, 0.0), projection: Perspective(fov_y_degrees: 179.99)),", "fov_y_degrees"),
        (camera, "camera: (eye: (0.0, -6.0, 0.0), target: (0.0, 0.0, 0.0), projection: Perspective(fov_y_degrees: 1e-30)),", "fov_y_degrees"),
        (camera, "camera: (eye: (0.0, -6.0, 0.0), target: (0.0, 0.0, 0.0), projection: Orthographic(height: 1e30)),", "height"),
        // Eye and target meet at frame 1 only, between two keys that are fine.
        (camera, "camera: (eye: [(0, (0.0, -1.0, 0.0)), (2, (0.0, 1.0, 0.0))], target: (0.0, 0.0, 0.0), projection: Orthographic(height: 2.4)),", "same point"),
        (light, "light: Point(position: (0.0, -3e7, 0.0)),", "within ±1e6"),
        (ball, r#"(name: "ball", file: "ball.ron", material: "m", transform: (scale: 1e7))"#, "the scale 10000000 must lie in [1e-6, 1e6]"),
        (ball, r#"(name: "ball", file: "ball.ron", material: "m", transform: (translate: (1e300, 0.0, 0.0)))"#, "within ±1e6"),
        (ball, r#"(name: "ball", file: "ball.ron", material: "m", transform: (translate: (999999.5, 0.0, 0.0)))"#, "beyond ±1e6"),
        (ball, r#"(name: "ball", file: "ball.ron", material: "m", transform: (degrees: 1e300))"#, "within ±1e6"),
    ];
    for (from, to, says) in cases {
        assert!(base.contains(from), "{from}");
        std::fs::write(dir.path().join("shot.ron"), base.replace(from, to)).unwrap();
        let out = run(dir.path(), &["render", "shot.ron", "--size", "8x8"]);
        assert_refused(dir.path(), &out, "shot.ron:", says);
    }
}

#[test]
fn a_file_included_along_many_paths_is_read_once() {
    // Twelve levels, each including the next three times: 3¹² includes, 13 files.
    let dir = tempfile::tempdir().unwrap();
    let depth = 12;
    for k in 0..depth {
        let next = if k + 1 < depth {
            vec![format!("\"d{}.ron\"", k + 1); 3].join(", ")
        } else {
            String::new()
        };
        let materials = if k + 1 == depth {
            r#"materials: {"deep": Cel(base: (0.2, 0.2, 0.2), bands: [])},"#
        } else {
            ""
        };
        std::fs::write(
            dir.path().join(format!("d{k}.ron")),
            format!("(includes: [{next}], {materials})"),
        )
        .unwrap();
    }
    let path = ball_shot(dir.path());
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::write(
        &path,
        text.replace("instances:", "includes: [\"d0.ron\"],\n    instances:"),
    )
    .unwrap();
    let shot = glint::shot::load_shot(&path).unwrap();
    // The shot, twelve includes, the ball: each once; and the material defined deepest is
    // defined once, not once per path to it.
    assert_eq!(shot.inputs.len(), depth + 2, "{:?}", shot.inputs);
    assert_eq!(shot.material_names().filter(|n| *n == "deep").count(), 1);
    // A cycle is still one.
    std::fs::write(dir.path().join("d11.ron"), "(includes: [\"d3.ron\"])").unwrap();
    let e = glint::shot::load_shot(&path).unwrap_err().to_string();
    assert!(e.contains("makes a cycle") && e.contains("d11.ron"), "{e}");
}

#[test]
fn a_frame_whose_view_needs_a_mesh_beyond_the_ceiling_is_refused_when_it_comes() {
    // Forty frames, the camera far from the sphere but for frame 2, where it nearly touches
    // it: the estimate before rendering looks at 16 of the frames, frame 2 not among them, and
    // the renderer refuses that frame's mesh before making it.
    let dir = tempfile::tempdir().unwrap();
    let path = ball_shot(dir.path());
    let text = std::fs::read_to_string(&path).unwrap()
        .replace("frames: (1, 2)", "frames: (1, 40)")
        .replace(
            "camera: (eye: (0.0, -6.0, 0.0),",
            "camera: (eye: [(1, (0.0, -60.0, 0.0)), (2, (0.0, -1.01, 0.0)), (3, (0.0, -60.0, 0.0))],",
        )
        .replace("Orthographic(height: 2.4)", "Perspective(fov_y_degrees: 30.0)");
    std::fs::write(&path, text).unwrap();
    let out = run(
        dir.path(),
        &[
            "render",
            "shot.ron",
            "--size",
            "16x16",
            "--preset",
            "preview",
            "--max-memory",
            "65M",
        ],
    );
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("frame 2") && err.contains("the mesh for this view would have"),
        "{err}"
    );
    // With room for the near view's mesh, every frame renders.
    let out = run(
        dir.path(),
        &[
            "render",
            "shot.ron",
            "--size",
            "16x16",
            "--preset",
            "preview",
            "--frames",
            "1-3",
            "--max-memory",
            "80M",
        ],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
}
