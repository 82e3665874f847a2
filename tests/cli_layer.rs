//! `glint layer` end to end: each structural edit of a layer written into its file with the
//! rest of the file as it was, undone by its inverse byte for byte, and refusals with one line
//! and exit code 2 that write nothing.

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
}
