//! The animator's task on the teapot over a 48-frame camera orbit — a small squared highlight
//! held on the lid, a long streak stretching along the body, a crescent on the spout — done
//! end to end with glint's commands alone: the script writes the starting shot once and never
//! edits its text; every change after that is a `glint` command, its arguments read from what
//! earlier commands printed.

use std::path::{Path, PathBuf};

use glint::job::{Overrides, RenderJob};
use glint::shot::{load_shot, Aov};
use serde_json::Value;

use crate::common::{glint, repo_file, stderr};

/// The starting shot: the camera orbits the teapot in two keys of its azimuth; the lid's
/// highlight is a plain glint with a squaring at zero, the body's a translation and a scaling at
/// zero, the spout's two translated caps, one taken from the other.
const SHOT: &str = r#"Shot(
    resolution: (640, 360),
    frames: (1, 48),
    fps: 24,
    output: "../out/task/task.####.png",
    instances: [(name: "teapot", file: "../patches/teapot.bpt", material: "porcelain")],
    materials: {
        "porcelain": Cel(base: (0.10, 0.16, 0.32), bands: [(0.0, (0.30, 0.45, 0.80))]),
    },
    camera: (
        orbit: Sphere(azimuth: [(1, -100.0), (48, -60.0)], elevation: 22.0, distance: 9.5),
        target: (0.0, 0.0, 1.4),
        projection: Perspective(fov_y_degrees: 32.0),
    ),
    light: Directional(towards: (-0.352, -0.553, 0.755)),
    highlights: [
        (patches: "teapot/lid", expr: Layer((stack: [Square(sigma: 0.0, n: 2.0)], epsilon: 0.004, colour: (1.0, 1.0, 1.0)))),
        (patches: "teapot/body", expr: Layer((stack: [Translate(alpha: 0.0, beta: 0.0), Scale(delta: 0.0, axis: V)], epsilon: 0.01, colour: (1.0, 0.98, 0.9)))),
        (
            patches: "teapot/spout",
            expr: Subtract(
                Layer((stack: [Translate(alpha: 0.0, beta: 0.0)], epsilon: 0.012, colour: (1.0, 0.97, 0.88))),
                Layer((stack: [Translate(alpha: 0.0, beta: 0.0)], epsilon: 0.012, colour: (1.0, 1.0, 1.0))),
            ),
        ),
    ],
    render: (preset: Final, outlines: (width: 2.0, colour: (0.05, 0.04, 0.1))),
)
"#;

/// Runs `glint` with `args` in `dir`; its standard output, after checking it succeeded.
fn run(dir: &Path, args: &[&str]) -> String {
    let out = glint().current_dir(dir).args(args).output().unwrap();
    assert!(
        out.status.success(),
        "glint {}: {}",
        args.join(" "),
        stderr(&out)
    );
    String::from_utf8(out.stdout).unwrap()
}

/// `glint probe`'s pixel of (u, v) of `patch` at `frame`, and whether the frame shows it.
fn probe(dir: &Path, patch: &str, uv: (f64, f64), frame: u32) -> ((f64, f64), bool) {
    let out = run(
        dir,
        &[
            "probe",
            "work/task.ron",
            "--patch",
            patch,
            "--uv",
            &format!("{},{}", uv.0, uv.1),
            "--frame",
            &frame.to_string(),
        ],
    );
    let probed: Value = serde_json::from_str(&out).unwrap();
    let image = &probed[0]["image"];
    let pixel = (
        image["pixel"][0].as_f64().unwrap(),
        image["pixel"][1].as_f64().unwrap(),
    );
    (pixel, image["visible"].as_bool().unwrap())
}

/// The pixel argument `X,Y` of an image position.
fn pixel_arg((x, y): (f64, f64)) -> String {
    format!("{x:.1},{y:.1}")
}

/// `glint place --json` of the spout's first cap on `pixel` at frame 1, written when `write`.
fn place_spout_cap(dir: &Path, pixel: (f64, f64), write: bool) -> Value {
    let pixel = pixel_arg(pixel);
    let mut args = vec![
        "place",
        "work/task.ron",
        "--frame",
        "1",
        "--pixel",
        &pixel,
        "--highlight",
        "2",
        "--layer",
        "0",
        "--json",
    ];
    if write {
        args.push("--write");
    }
    serde_json::from_str(&run(dir, &args)).unwrap()
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

/// The matte at the pixel nearest image position `(x, y)`.
fn matte_at(matte: &(Vec<f32>, usize), (x, y): (f64, f64)) -> f32 {
    matte.0[y.round() as usize * matte.1 + x.round() as usize]
}

fn workspace() -> (tempfile::TempDir, PathBuf) {
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
    let shot = dir.path().join("work/task.ron");
    std::fs::write(&shot, SHOT).unwrap();
    (dir, shot)
}

#[test]
fn the_lid_body_spout_task_runs_on_glint_s_commands_alone() {
    let (dir, shot) = workspace();
    let dir = dir.path();
    let file = "work/task.ron";

    // The lid: pinned to the point under the middle of patch 24, holding the shape it has at
    // frame 1, squared.
    let (lid, seen) = probe(dir, "teapot/24", (0.5, 0.5), 1);
    assert!(seen);
    run(
        dir,
        &[
            "place",
            file,
            "--frame",
            "1",
            "--pixel",
            &pixel_arg(lid),
            "--highlight",
            "0",
            "--pin",
            "--write",
        ],
    );
    run(dir, &["layer", file, "--highlight", "0", "--hold", "1"]);
    run(
        dir,
        &[
            "key",
            file,
            "--at",
            "highlights[0].layers[0].stack[0].sigma",
            "--value",
            "0.2",
        ],
    );

    // The body: placed where pointed at frame 1, keyed on the same surface point at frame 48
    // (named, not pointed at), stretched more and more along v.
    let (body, _) = probe(dir, "teapot/5", (0.5, 0.5), 1);
    let placed: Value = serde_json::from_str(&run(
        dir,
        &[
            "place",
            file,
            "--frame",
            "1",
            "--pixel",
            &pixel_arg(body),
            "--highlight",
            "1",
            "--json",
            "--write",
        ],
    ))
    .unwrap();
    let point = (
        placed["patch"].as_str().unwrap().to_string(),
        placed["u"].as_f64().unwrap(),
        placed["v"].as_f64().unwrap(),
    );
    let at = format!("{}:{},{}", point.0, point.1, point.2);
    run(
        dir,
        &[
            "place",
            file,
            "--frame",
            "48",
            "--at",
            &at,
            "--highlight",
            "1",
            "--write",
        ],
    );
    for (frame, delta) in [("1", "0.3"), ("48", "0.85")] {
        run(
            dir,
            &[
                "key",
                file,
                "--at",
                "highlights[1].layers[0].stack[1].delta",
                "--frame",
                frame,
                "--value",
                delta,
            ],
        );
    }

    // The spout: a cap placed on patch 16, a second cap beside it taken out of it. The first
    // shows more than once; `place` lists every centre, and a mask over the u the placed one
    // lies in keeps it alone.
    let (spout, _) = probe(dir, "teapot/16", (0.5, 0.5), 1);
    let first = place_spout_cap(dir, spout, true);
    let beside = (spout.0 + 6.0, spout.1 - 5.0);
    run(
        dir,
        &[
            "place",
            file,
            "--frame",
            "1",
            "--pixel",
            &pixel_arg(beside),
            "--highlight",
            "2",
            "--layer",
            "1",
            "--write",
        ],
    );
    // The spout's tip turns its normals back: the cap shows there too.
    let centres = first["centres"].as_array().unwrap();
    assert!(centres.len() > 1, "{first}");
    {
        let u = first["u"].as_f64().unwrap();
        run(
            dir,
            &[
                "layer",
                file,
                "--highlight",
                "2",
                "--layer",
                "0",
                "--add-mask",
            ],
        );
        for (bound, value) in [("0", (u - 0.2).max(0.0)), ("1", (u + 0.2).min(1.0))] {
            run(
                dir,
                &[
                    "key",
                    file,
                    "--at",
                    &format!("highlights[2].layers[0].mask.u[{bound}]"),
                    "--value",
                    &format!("{value:.3}"),
                ],
            );
        }
    }

    // What the commands made: the lid pinned and holding frame 1's shape on every frame; the
    // body's translation keyed at 1 and 48, its scaling growing; every frame renders.
    let loaded = load_shot(&shot).unwrap();
    let text = std::fs::read_to_string(&shot).unwrap();
    assert!(text.contains("hold: 1"), "{text}");
    for frame in [12.0, 48.0] {
        let state = loaded.at(frame);
        assert!(
            state.highlights[0].layers()[0].shape_map.is_some(),
            "frame {frame}"
        );
    }
    let (at_1, at_48) = (matte(&shot, 1.0), matte(&shot, 48.0));
    // The lid's glint stays on its point.
    for (frame, m) in [(1, &at_1), (48, &at_48)] {
        let (pixel, seen) = probe(dir, "teapot/24", (0.5, 0.5), frame);
        if seen {
            assert!(
                matte_at(m, pixel) > 0.5,
                "frame {frame}: the lid's glint is off its point"
            );
        }
    }
    // The body's streak is on the same surface point at both frames.
    let (body_48, seen) = probe(dir, &point.0, (point.1, point.2), 48);
    assert!(seen, "the body's point is hidden at frame 48");
    assert!(
        matte_at(&at_1, body) > 0.5,
        "frame 1: no highlight where the body was pointed at"
    );
    assert!(
        matte_at(&at_48, body_48) > 0.5,
        "frame 48: no highlight on the body's point"
    );
    // The spout: the second cap's centre cut out of the first cap, which still shows about it.
    assert_eq!(
        matte_at(&at_1, beside),
        0.0,
        "the subtracted cap is not cut out"
    );
    let (values, width) = &at_1;
    let shown = values
        .iter()
        .enumerate()
        .filter(|(i, &m)| {
            let (x, y) = ((i % width) as f64, (i / width) as f64);
            m > 0.5 && (x - spout.0).hypot(y - spout.1) <= 25.0
        })
        .count();
    assert!(shown >= 10, "{shown} pixels of the spout's highlight");
    // The mask keeps only the placed centre.
    {
        let again = place_spout_cap(dir, spout, false);
        assert_eq!(again["centres"].as_array().unwrap().len(), 1, "{again}");
    }
    run(
        dir,
        &[
            "render", file, "--frames", "1-48x12", "--preset", "preview", "--quiet",
        ],
    );
}
