//! `glint render` and `glint inspect` end to end: frame lists, padding, resuming a killed
//! render, exit codes.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use crate::common::glint;

/// A small shot of the sphere with a keyed highlight, in a fresh folder.
fn shot(size: (u32, u32), preset: &str) -> (tempfile::TempDir, PathBuf) {
    let dir = tempfile::tempdir().unwrap();
    let sphere = crate::common::root().join("patches/sphere.ron");
    std::fs::copy(sphere, dir.path().join("sphere.ron")).unwrap();
    let text = format!(
        r#"Shot(
    resolution: ({}, {}),
    frames: (1, 12),
    fps: 24,
    output: "out/t.####.png",
    instances: [(name: "ball", file: "sphere.ron", material: "blue")],
    materials: {{"blue": Cel(base: (0.1, 0.1, 0.3), bands: [(0.0, (0.2, 0.3, 0.8))])}},
    camera: (eye: (0, -6, 0), target: (0, 0, 0), projection: Perspective(fov_y_degrees: 30)),
    light: Directional(towards: (0.3, -1.0, 0.4)),
    highlights: [(
        patches: "ball/*",
        expr: Layer((stack: [Translate(alpha: [(1, 0.0), (12, 0.4)], beta: 0)], epsilon: 0.05,
                     colour: (1, 1, 1))),
    )],
    render: (preset: {preset}),
)"#,
        size.0, size.1
    );
    let path = dir.path().join("shot.ron");
    std::fs::write(&path, text).unwrap();
    (dir, path)
}

fn run(command: &mut Command) -> Output {
    command.output().unwrap()
}

/// Runs `command` and checks that it exited with 0.
fn succeed(command: &mut Command) -> Output {
    let out = run(command);
    assert_eq!(
        out.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

fn files(folder: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(folder)
        .map(|entries| {
            entries
                .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    names.sort();
    names
}

#[test]
fn frame_lists_and_padding_pick_exactly_the_files() {
    let (dir, shot) = shot((32, 24), "Preview");
    let out = succeed(
        glint()
            .args(["render", "--frames", "2-6x2,9", "--out", "p/f.##.png"])
            .arg(&shot),
    );
    assert_eq!(
        files(&dir.path().join("p")),
        ["f.02.png", "f.04.png", "f.06.png", "f.09.png"]
    );
    // Not a terminal: one line per finished frame, then a summary.
    let stdout = String::from_utf8_lossy(&out.stdout);
    let frame_lines: Vec<&str> = stdout.lines().filter(|l| l.starts_with("frame ")).collect();
    assert_eq!(frame_lines.len(), 4, "{stdout}");
    assert!(frame_lines[3].starts_with("frame 9: "), "{stdout}");
}

#[test]
fn aovs_are_written_beside_the_frame_and_in_one_exr() {
    let (dir, shot) = shot((32, 24), "Preview");
    let out = succeed(
        glint()
            .args(["render", "--quiet", "--frames", "3", "--aov", "matte,depth"])
            .arg(&shot),
    );
    assert!(out.stdout.is_empty());
    assert_eq!(
        files(&dir.path().join("out")),
        [
            "t.0003.depth.png",
            "t.0003.exr",
            "t.0003.matte.png",
            "t.0003.png"
        ]
    );
}

#[test]
fn a_killed_render_resumes_with_skip_existing_and_leaves_only_whole_files() {
    let (dir, shot) = shot((360, 360), "Final");
    let out_dir = dir.path().join("out");
    let mut child = glint()
        .args(["render", "--quiet", "--threads", "1"])
        .arg(&shot)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    // Killed as soon as its first frame is on disk: the resume below then has frames to skip
    // and frames to render.
    let started = Instant::now();
    while !out_dir.join("t.0001.png").exists() && started.elapsed() < Duration::from_secs(120) {
        std::thread::sleep(Duration::from_millis(2));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    // A temporary file a killed process left behind, whether or not this one did.
    std::fs::write(out_dir.join(".t.0011.png.4242.tmp"), b"half a frame").unwrap();

    let before = files(&out_dir);
    let finished: Vec<&String> = before.iter().filter(|n| n.ends_with(".png")).collect();
    assert!(
        finished.iter().any(|n| *n == "t.0001.png"),
        "no frame written: {before:?}"
    );
    assert!(
        finished.len() < 12,
        "the render was not interrupted: {before:?}"
    );
    for name in &finished {
        image::open(out_dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    }

    let resumed = succeed(glint().args(["render", "--skip-existing"]).arg(&shot));
    let stdout = String::from_utf8_lossy(&resumed.stdout);
    assert_eq!(
        stdout.matches("exists, skipped").count(),
        finished.len(),
        "{stdout}"
    );
    // The frames the killed render did not finish, rendered now.
    let rendered = stdout.lines().filter(|l| l.ends_with(" ms)")).count();
    assert_eq!(rendered, 12 - finished.len(), "{stdout}");
    let after = files(&out_dir);
    let expected: Vec<String> = (1..=12).map(|f| format!("t.{f:04}.png")).collect();
    assert_eq!(after, expected, "temporary files or missing frames");
    for name in &after {
        image::open(out_dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

#[test]
fn exit_codes_tell_bad_input_from_a_failed_render() {
    let (dir, shot) = shot((32, 24), "Preview");
    // A frame outside the shot, a malformed list, an unknown AOV: bad input.
    for args in [
        &["--frames", "11-13"][..],
        &["--frames", "1-x"],
        &["--aov", "mate"],
        &["--size", "0x10"],
    ] {
        let out = run(glint().arg("render").args(args).arg(&shot));
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(!dir.path().join("out").exists(), "{args:?} wrote output");
    }
    // An output folder that cannot be made: bad input, nothing rendered.
    std::fs::write(dir.path().join("blocker"), b"a file").unwrap();
    let out = run(glint()
        .args(["render", "--out", "blocker/f.####.png"])
        .arg(&shot));
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("cannot create the output folder"),
        "{stderr}"
    );
    assert_eq!(stderr.trim().lines().count(), 1);

    // A frame that cannot be written once rendering is under way: a failure, after the frames
    // before it were written.
    std::fs::create_dir_all(dir.path().join("out/t.0003.png")).unwrap();
    let out = run(glint().args(["render", "--frames", "1-5"]).arg(&shot));
    assert_eq!(out.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("t.0003.png"), "{stderr}");
    assert_eq!(
        files(&dir.path().join("out")),
        ["t.0001.png", "t.0002.png", "t.0003.png"]
    );
}

#[test]
fn inspect_prints_the_interpolated_value_between_keys() {
    let (_dir, shot) = shot((32, 24), "Preview");
    // alpha runs from 0 at frame 1 to 0.4 at frame 12: at frame 6.5 it is 0.4 · 5.5 / 11.
    let out = succeed(glint().args(["inspect", "--frame", "6.5"]).arg(&shot));
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(stdout.contains("alpha: 0.2,"), "{stdout}");
    assert!(stdout.contains("eye: (0.0, -6.0, 0.0)"), "{stdout}");
    let out = run(glint()
        .args(["inspect", "--frame", "1", "--patch", "nothing/*"])
        .arg(&shot));
    assert_eq!(out.status.code(), Some(2));
}

/// The peak memory of `glint render` over two frames of the teapot turntable at 1920 × 1080
/// with two workers, as its `--report` gives it (the process's peak resident set); `None`
/// where the system does not say.
fn peak_memory_of_two_1080p_frames(preset: &str) -> Option<u64> {
    let dir = tempfile::tempdir().unwrap();
    let report = dir.path().join("report.jsonl");
    let out = dir.path().join("t.#.png");
    succeed(glint().args([
        "render",
        "shots/teapot_turntable.ron",
        "--frames",
        "1-2",
        "--preset",
        preset,
        "--size",
        "1920x1080",
        "--threads",
        "2",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
    ]));
    let text = std::fs::read_to_string(&report).unwrap();
    let last = text.lines().last().unwrap();
    let line: serde_json::Value = serde_json::from_str(last).unwrap();
    line["peak_memory_bytes"].as_u64()
}

#[test]
fn a_1080p_frame_holds_no_more_memory_than_a_farm_slot_is_promised() {
    // What the README's farm section promises a task at 1920 × 1080.
    for (preset, most) in [("preview", 200u64 << 20), ("final", 400 << 20)] {
        let Some(peak) = peak_memory_of_two_1080p_frames(preset) else {
            // Not Linux: the process's peak is not known.
            return;
        };
        assert!(
            peak > 20 << 20,
            "{preset}: {peak} B is too little to be the peak"
        );
        assert!(peak <= most, "{preset}: {} MB", peak >> 20);
    }
}
