//! docs/tutorial.md run as a script: its shot written, every command of its `sh` blocks run in
//! order (but the one that keeps watching) — no edit of the shot by hand — and the highlights
//! it designs checked in the frames.

use std::path::Path;

use glint::job::{Overrides, RenderJob};
use glint::shot::Aov;

use crate::common::repo_file;

/// The tutorial's shot (its first `ron` block) and its commands (the lines of its `sh` blocks
/// that start with `glint`, without `#` comments), leaving out `--watch`.
fn script() -> (String, Vec<String>) {
    let doc = std::fs::read_to_string(repo_file("docs/tutorial.md")).unwrap();
    let block = |fence: &str| -> Vec<String> {
        doc.split(fence)
            .skip(1)
            .map(|b| b[..b.find("```").unwrap()].to_string())
            .collect()
    };
    let shot = block("```ron\n").remove(0);
    let commands = block("```sh\n")
        .iter()
        .flat_map(|b| b.lines().map(str::to_string).collect::<Vec<_>>())
        .map(|l| l.split(" #").next().unwrap().trim().to_string())
        .filter(|l| l.starts_with("glint ") && !l.contains("--watch"))
        .collect();
    (shot, commands)
}

/// Runs `command` (a line of the tutorial) with `sh` in `dir`, `glint` being the binary under
/// test.
fn run(dir: &Path, command: &str) {
    let out = crate::common::run_documented(dir, command);
    assert!(
        out.status.success(),
        "{command}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// The matte of `frame`, and its width.
fn matte(shot: &Path, frame: f64) -> (Vec<f32>, usize) {
    let overrides = Overrides {
        aovs: Some(vec![Aov::Matte]),
        ..Overrides::default()
    };
    let mut job = RenderJob::load(shot, &overrides).unwrap();
    let image = job.render_frame(frame).unwrap();
    (image.aovs.matte.unwrap(), image.width as usize)
}

/// The highlight's coverage summed within `radius` pixels of `(x, y)`.
fn covered_near(matte: &(Vec<f32>, usize), (x, y): (f64, f64), radius: f64) -> f64 {
    let (values, width) = matte;
    values
        .iter()
        .enumerate()
        .filter(|(i, _)| {
            let (px, py) = ((i % width) as f64, (i / width) as f64);
            (px - x).powi(2) + (py - y).powi(2) <= radius * radius
        })
        .map(|(_, &m)| f64::from(m))
        .sum()
}

/// Where (u, v) of `patch` lands in `frame` of `shot`, in pixels.
fn pixel_of(shot: &Path, patch: &str, uv: (f64, f64), frame: f64) -> (f64, f64) {
    let job = RenderJob::load(shot, &Overrides::default()).unwrap();
    let index = job
        .shot()
        .library
        .patches
        .iter()
        .position(|p| p.name == patch)
        .unwrap();
    let mut job = job;
    job.pixel_of(frame, index, uv).unwrap().pixel
}

#[test]
fn the_tutorial_designs_the_lid_body_and_spout_on_an_orbit_with_commands_alone() {
    let (shot, commands) = script();
    assert!(commands.len() >= 10, "{commands:?}");
    for needed in [
        "glint patches",
        "glint place",
        "glint layer",
        "glint key",
        "glint sheet",
    ] {
        assert!(commands.iter().any(|c| c.starts_with(needed)), "{needed}");
    }
    assert!(
        shot.contains("orbit: Sphere("),
        "the tutorial's camera orbits"
    );
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("work")).unwrap();
    std::fs::create_dir_all(dir.path().join("patches")).unwrap();
    for model in ["teapot.bpt", "teapot.parts.ron"] {
        std::fs::copy(
            repo_file(&format!("patches/{model}")),
            dir.path().join("patches").join(model),
        )
        .unwrap();
    }
    let file = dir.path().join("work/lid.ron");
    std::fs::write(&file, &shot).unwrap();
    let before_1 = matte(&file, 1.0);
    let before_light = n_dot_l(&file, 1.0);
    for command in &commands {
        run(dir.path(), command);
    }
    for picture in ["map", "sigma", "motion"] {
        assert!(dir.path().join(format!("out/lid/{picture}.png")).is_file());
    }
    let (after_1, after_48) = (matte(&file, 1.0), matte(&file, 48.0));
    let index = |m: &(Vec<f32>, usize), (x, y): (f64, f64)| {
        m.0[y.round() as usize * m.1 + x.round() as usize]
    };

    // The lid's glint: pinned to the point pointed at, which it stays on at frame 48, holding
    // its shape.
    let written = std::fs::read_to_string(&file).unwrap();
    let loaded = glint::shot::load_shot(&file).unwrap();
    let layer = loaded.highlight_layers(0)[0];
    let pin = layer.pin.as_ref().expect("the lid's layer is pinned");
    assert_eq!(pin.hold, Some(1), "{written}");
    let pinned = (f64::from(pin.u.at(1.0)), f64::from(pin.v.at(1.0)));
    let lid_1 = (369.0, 115.0);
    assert_eq!(covered_near(&before_1, lid_1, 12.0), 0.0);
    assert!(
        index(&after_1, lid_1) > 0.5,
        "no glint at the lid pixel on frame 1"
    );
    let lid_48 = pixel_of(&file, &pin.patch, pinned, 48.0);
    assert!(
        index(&after_48, lid_48) > 0.5,
        "no glint on the lid's point on frame 48"
    );

    // The body's streak on the point pointed at on frame 1, and on the same point on frame 48.
    let body_1 = (236.0, 208.0);
    assert_eq!(index(&before_1, body_1), 0.0);
    assert!(
        index(&after_1, body_1) > 0.5,
        "no streak where the body was pointed at"
    );
    let body_48 = pixel_of(&file, "teapot/5", (0.50155, 0.50151), 48.0);
    assert!(
        index(&after_48, body_48) > 0.5,
        "no streak on the body's point on frame 48"
    );

    // The spout's crescent: the second cap's centre cut out of the first, which still shows.
    let (spout, beside) = ((488.0, 163.0), (494.0, 158.0));
    assert_eq!(index(&before_1, spout), 0.0);
    assert_eq!(
        index(&after_1, beside),
        0.0,
        "the subtracted cap is not cut out"
    );
    let (was, is) = (
        covered_near(&before_1, spout, 25.0),
        covered_near(&after_1, spout, 25.0),
    );
    assert!(is > was + 10.0, "no crescent on the spout: {was} then {is}");

    // The body's lighter band (its edge at N·L′ = 0.55) now passes within a pixel of the point
    // pointed at, where the whole neighbourhood was inside it before.
    let pointed = (340, 220);
    let straddles = |n_dot_l: &(Vec<f32>, usize)| {
        let (values, width) = n_dot_l;
        let around: Vec<f32> = (pointed.1 - 1..=pointed.1 + 1)
            .flat_map(|y| (pointed.0 - 1..=pointed.0 + 1).map(move |x| values[y * width + x]))
            .collect();
        (
            around.iter().any(|&v| v >= 0.55),
            around.iter().any(|&v| v < 0.55),
        )
    };
    assert_eq!(
        straddles(&before_light),
        (true, false),
        "inside the band before"
    );
    assert_eq!(
        straddles(&n_dot_l(&file, 1.0)),
        (true, true),
        "the band's edge through the point after"
    );
}

/// The `N·L′` each pixel's tone reads at `frame`, and the image's width.
fn n_dot_l(shot: &Path, frame: f64) -> (Vec<f32>, usize) {
    let overrides = Overrides {
        aovs: Some(vec![Aov::NDotL]),
        ..Overrides::default()
    };
    let mut job = RenderJob::load(shot, &overrides).unwrap();
    let image = job.render_frame(frame).unwrap();
    (image.aovs.n_dot_l.unwrap(), image.width as usize)
}
