//! `glint layer` end to end: each structural edit of a layer written into its file with the
//! rest of the file as it was, undone by its inverse byte for byte, drawn outlines read back as
//! written, and refusals with one line and exit code 2 that write nothing.

use std::path::Path;

use crate::common::{glint_with, repo_file, stderr};

/// A copy of `shots/sphere_ops.ron` and its patch file in `dir`; the shot's path as text.
fn sphere_ops(dir: &Path) -> String {
    std::fs::create_dir_all(dir.join("shots")).unwrap();
    std::fs::create_dir_all(dir.join("patches")).unwrap();
    std::fs::copy(
        repo_file("patches/sphere.ron"),
        dir.join("patches/sphere.ron"),
    )
    .unwrap();
    let shot = dir.join("shots/sphere_ops.ron");
    std::fs::copy(repo_file("shots/sphere_ops.ron"), &shot).unwrap();
    shot.to_str().unwrap().to_string()
}

/// The stack of layer 0 of highlight 0 as the shot reads at frame 1, each operation's name.
fn stack(shot: &str) -> Vec<String> {
    let shot = glint::shot::load_shot(Path::new(shot)).unwrap();
    shot.at(1.0).highlights[0].layers()[0]
        .stack
        .iter()
        .map(|op| op.name().to_string())
        .collect()
}

fn layer(shot: &str, edit: &[&str]) -> std::process::Output {
    let mut args = vec!["layer", shot, "--highlight", "0"];
    args.extend_from_slice(edit);
    glint_with(&args)
}

#[test]
fn layer_edits_write_the_layer_and_their_inverses_give_the_file_back() {
    let dir = tempfile::tempdir().unwrap();
    let shot = sphere_ops(dir.path());
    let original = std::fs::read_to_string(&shot).unwrap();
    let before = stack(&shot);
    assert!(before.len() >= 2, "{before:?}");

    let out = layer(
        &shot,
        &["--insert-op", "Rotate(degrees: 20.0)", "--at", "0"],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        String::from_utf8_lossy(&out.stdout).contains("inserted Rotate(degrees: 20.0) at stack[0]")
    );
    let mut want = vec!["Rotate".to_string()];
    want.extend(before.iter().cloned());
    assert_eq!(stack(&shot), want);

    // Moved to the end and back, then removed: the file as it was.
    let last = before.len().to_string();
    let out = layer(&shot, &["--move-op", "0", "--to", &last]);
    assert!(out.status.success(), "{}", stderr(&out));
    let mut moved = before.clone();
    moved.push("Rotate".to_string());
    assert_eq!(stack(&shot), moved);
    assert!(layer(&shot, &["--move-op", &last, "--to", "0"])
        .status
        .success());
    assert!(layer(&shot, &["--remove-op", "0"]).status.success());
    assert_eq!(std::fs::read_to_string(&shot).unwrap(), original);

    // A mask added covers the whole patch; removed, the file is as it was.
    assert!(layer(&shot, &["--add-mask"]).status.success());
    let masked = glint::shot::load_shot(Path::new(&shot)).unwrap();
    let mask = masked.at(1.0).highlights[0].layers()[0]
        .mask
        .clone()
        .unwrap();
    assert_eq!((mask.u, mask.v), ((0.0, 1.0), (0.0, 1.0)));
    assert!(layer(&shot, &["--remove-mask"]).status.success());
    assert_eq!(std::fs::read_to_string(&shot).unwrap(), original);
}

#[test]
fn layer_edits_that_cannot_be_made_exit_2_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let shot = sphere_ops(dir.path());
    let original = std::fs::read_to_string(&shot).unwrap();
    for (edit, says) in [
        (vec!["--remove-op", "9"], "no operation 9"),
        (
            vec!["--insert-op", "Scale(delta: 0.5", "--at", "0"],
            "is not an operation",
        ),
        (vec!["--insert-op", "Scale(delta: -3.0)"], "delta"),
        (vec!["--unpin"], "no pin to remove"),
        (vec!["--remove-mask"], "no mask to remove"),
    ] {
        let out = layer(&shot, &edit);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{edit:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{edit:?}: {err}");
        assert!(err.contains(says), "{edit:?}: {err}");
        assert_eq!(
            std::fs::read_to_string(&shot).unwrap(),
            original,
            "{edit:?}"
        );
    }
    let out = glint_with(&["layer", &shot, "--highlight", "7", "--add-mask"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("no highlight 7"), "{}", stderr(&out));
}

/// The corners of layer 0 of highlight 0's outline as the shot reads at `frame`; empty for
/// the disc.
fn outline_at(shot: &str, frame: f64) -> Vec<[f32; 2]> {
    use glint::highlight::{Segment, Shape};
    let shot = glint::shot::load_shot(Path::new(shot)).unwrap();
    let state = shot.at(frame);
    let corners = |o: &glint::highlight::Outline| -> Vec<[f32; 2]> {
        o.segments
            .iter()
            .map(|s| match s {
                Segment::Corner(p) => *p,
                Segment::Bezier(_) => panic!("a Bezier where corners were drawn"),
            })
            .collect()
    };
    match &state.highlights[0].layers()[0].shape {
        Shape::Disc => Vec::new(),
        Shape::Outline(o) => corners(o),
        Shape::Morph(m) => corners(&m.lerped()),
    }
}

fn near(got: &[[f32; 2]], want: &[[f32; 2]], tolerance: f32) -> bool {
    got.len() == want.len()
        && got
            .iter()
            .zip(want)
            .all(|(g, w)| (g[0] - w[0]).abs() <= tolerance && (g[1] - w[1]).abs() <= tolerance)
}

#[test]
fn outlines_drawn_and_keyed_read_back_as_written_and_the_disc_gives_the_file_back() {
    let dir = tempfile::tempdir().unwrap();
    let shot = sphere_ops(dir.path());
    let original = std::fs::read_to_string(&shot).unwrap();
    let triangle = [[0.0, 0.3], [0.259_81, -0.15], [-0.259_81, -0.15]];
    let out = layer(
        &shot,
        &[
            "--outline",
            "(0.0, 0.3), (0.25981, -0.15), (-0.25981, -0.15)",
        ],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(String::from_utf8_lossy(&out.stdout).contains("drew an outline of 3 points"));
    // Written to 4 places: within half a unit of the last.
    assert!(near(&outline_at(&shot, 1.0), &triangle, 0.5e-4));
    assert!(near(&outline_at(&shot, 60.0), &triangle, 0.5e-4));
    let written = std::fs::read_to_string(&shot).unwrap();
    assert!(written.contains("(0.2598, -0.15)"), "{written}");

    // Keyed at 10 and 30: halfway between, every coordinate is halfway.
    let small = [[0.0, 0.2], [0.2, -0.1], [-0.2, -0.1]];
    let big = [[0.0, 0.4], [0.4, -0.2], [-0.4, -0.2]];
    for (points, frame) in [
        ("(0.0, 0.2), (0.2, -0.1), (-0.2, -0.1)", "10"),
        ("(0.0, 0.4), (0.4, -0.2), (-0.4, -0.2)", "30"),
    ] {
        let out = layer(&shot, &["--outline", points, "--key-at", frame]);
        assert!(out.status.success(), "{}", stderr(&out));
    }
    assert!(near(&outline_at(&shot, 1.0), &small, 1e-6));
    assert!(near(&outline_at(&shot, 30.0), &big, 1e-6));
    let mid: Vec<[f32; 2]> = small
        .iter()
        .zip(&big)
        .map(|(a, b)| [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0])
        .collect();
    assert!(near(&outline_at(&shot, 20.0), &mid, 1e-6));

    // Back to the disc: the file as it was.
    let out = layer(&shot, &["--disc"]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(outline_at(&shot, 1.0).is_empty());
    assert_eq!(std::fs::read_to_string(&shot).unwrap(), original);
}

#[test]
fn outlines_that_cannot_be_drawn_exit_2_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let shot = sphere_ops(dir.path());
    let out = layer(
        &shot,
        &[
            "--outline",
            "(0.0, 0.2), (0.2, -0.1), (-0.2, -0.1)",
            "--key-at",
            "12",
        ],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let keyed = std::fs::read_to_string(&shot).unwrap();
    for (edit, says) in [
        (
            vec![
                "--outline",
                "(0, 0), (0.1, 0), (0.1, 0.1), (0, 0.1)",
                "--key-at",
                "24",
            ],
            "the outline key at frame 24 would have 4 points but the key at frame 12 has 3",
        ),
        (
            vec!["--outline", "(0, 0), (0.2, 0.2), (0.2, 0), (0, 0.2)"],
            "crosses itself",
        ),
        (
            vec!["--outline", "(0, 0), (0.995, 0), (0, 0.1)"],
            "outside the allowed",
        ),
        (vec!["--outline", "(0, 0), (0.1, 0)"], "at least 3"),
        (vec!["--outline", "(0, 0), (0.1"], "not a list of corners"),
        (
            vec!["--outline", "(0, 0), (0.1, 0), (0, 0.1)", "--key-at", "inf"],
            "finite",
        ),
    ] {
        let out = layer(&shot, &edit);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{edit:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{edit:?}: {err}");
        assert!(err.contains(says), "{edit:?}: {err}");
        assert_eq!(std::fs::read_to_string(&shot).unwrap(), keyed, "{edit:?}");
    }
    assert!(layer(&shot, &["--disc"]).status.success());
    let plain = std::fs::read_to_string(&shot).unwrap();
    let out = layer(&shot, &["--disc"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("disc already"), "{}", stderr(&out));
    assert_eq!(std::fs::read_to_string(&shot).unwrap(), plain);
}

/// Runs every `glint layer` line of `text`, in order, in a fresh copy of the shots.
fn run_examples(text: &str) {
    let examples: Vec<&str> = text
        .lines()
        .map(str::trim)
        .filter(|l| l.starts_with("glint layer "))
        .collect();
    assert!(examples.len() >= 4, "{examples:?}");
    let dir = crate::cli_key::workspace();
    for command in examples {
        let out = crate::common::run_documented(dir.path(), command);
        assert_eq!(out.status.code(), Some(0), "{command}: {}", stderr(&out));
        assert!(!out.stdout.is_empty(), "{command}");
    }
}

#[test]
fn the_help_and_documented_examples_run_in_turn() {
    let help = glint_with(&["layer", "--help"]);
    run_examples(&String::from_utf8(help.stdout).unwrap());
    let doc = std::fs::read_to_string(repo_file("docs/shot-format.md")).unwrap();
    run_examples(&doc[doc.find("## Editing from the command line").unwrap()..]);
    let doc = std::fs::read_to_string(repo_file("docs/highlights.md")).unwrap();
    let drawing = &doc[doc.find("### Drawing an outline").unwrap()..];
    run_examples(
        &drawing[..drawing[4..]
            .find("\n#")
            .map_or(drawing.len(), |end| end + 4)],
    );
}
