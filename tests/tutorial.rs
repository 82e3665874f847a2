//! docs/tutorial.md run as a script: its shot written, every command of its `sh` blocks run in
//! order (but the one that keeps watching), and the highlights it designs checked in the frames.

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

#[test]
fn the_tutorial_designs_a_growing_lid_highlight_and_a_crescent_with_commands_alone() {
    let (shot, commands) = script();
    assert!(commands.len() >= 10, "{commands:?}");
    for needed in ["glint patches", "glint place", "glint key", "glint sheet"] {
        assert!(commands.iter().any(|c| c.starts_with(needed)), "{needed}");
    }
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
    let (before_1, before_48) = (matte(&file, 1.0), matte(&file, 48.0));
    let before_light = n_dot_l(&file, 1.0);
    for command in &commands {
        run(dir.path(), command);
    }
    for picture in ["map", "sigma", "motion"] {
        assert!(dir.path().join(format!("out/lid/{picture}.png")).is_file());
    }

    // The lid's highlight is on the pixels pointed at, where there was none, and it grows.
    let (after_1, after_48) = (matte(&file, 1.0), matte(&file, 48.0));
    let (lid_1, lid_48) = ((290.0, 100.0), (300.0, 100.0));
    assert_eq!(covered_near(&before_1, lid_1, 12.0), 0.0);
    assert_eq!(covered_near(&before_48, lid_48, 12.0), 0.0);
    let index = |(x, y): (f64, f64)| y as usize * after_1.1 + x as usize;
    assert!(
        after_1.0[index(lid_1)] > 0.5,
        "no highlight at the lid pixel on frame 1"
    );
    assert!(
        after_48.0[index(lid_48)] > 0.5,
        "no highlight at the lid pixel on frame 48"
    );
    let (small, large) = (
        covered_near(&after_1, lid_1, 40.0),
        covered_near(&after_48, lid_48, 40.0),
    );
    assert!(
        large > 2.0 * small,
        "the lid highlight grows: {small} then {large}"
    );

    // The crescent: none on the body before; after, the second cap's centre is cut out of the
    // first cap and what is left lies on the side away from it.
    let (first, second) = ((250.0, 200.0), (268.0, 186.0));
    assert_eq!(covered_near(&before_1, first, 40.0), 0.0);
    assert_eq!(
        covered_near(&after_1, second, 8.0),
        0.0,
        "the subtracted cap is not cut out"
    );
    let away = (2.0 * first.0 - second.0, 2.0 * first.1 - second.1);
    let crescent = covered_near(&after_1, away, 20.0);
    assert!(crescent > 50.0, "no crescent beside the cut: {crescent}");

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
