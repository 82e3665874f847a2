//! `glint key` end to end, on copies of the shipped shots in a fresh folder: one track edited in
//! place with every other byte kept, bad paths and values refused with exit 2 and nothing
//! written, keys deleted, and the examples of `--help` and docs/shot-format.md run.

use std::path::Path;
use std::process::Output;

use crate::common::{repo_file, stderr};

/// A folder holding copies of `shots/` (with `looks/`), `patches/` and `textures/`.
pub(crate) fn workspace() -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    for folder in ["shots", "shots/looks", "patches", "textures"] {
        std::fs::create_dir_all(dir.path().join(folder)).unwrap();
        for entry in std::fs::read_dir(repo_file(folder)).unwrap() {
            let path = entry.unwrap().path();
            if path.is_file() {
                std::fs::copy(
                    &path,
                    dir.path().join(folder).join(path.file_name().unwrap()),
                )
                .unwrap();
            }
        }
    }
    dir
}

/// Runs `glint key ARGS` in `dir`.
fn key(dir: &Path, args: &[&str]) -> Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_glint"))
        .current_dir(dir)
        .arg("key")
        .args(args)
        .output()
        .unwrap()
}

fn stdout(out: &Output) -> String {
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn read(dir: &Path, file: &str) -> String {
    std::fs::read_to_string(dir.join(file)).unwrap()
}

fn shipped(file: &str) -> String {
    std::fs::read_to_string(repo_file(file)).unwrap()
}

/// The names in `folder`, sorted.
fn names(folder: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(folder)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// `text` with `old`, which occurs in it once, replaced by `new`.
fn replaced(text: &str, old: &str, new: &str) -> String {
    assert_eq!(text.matches(old).count(), 1, "{old}");
    text.replace(old, new)
}

fn assert_exit(out: &Output, code: i32) {
    assert_eq!(out.status.code(), Some(code), "{}", stderr(out));
}

#[test]
fn a_key_changes_its_track_alone_and_prints_it() {
    let dir = workspace();
    let shots = dir.path().join("shots");
    let before = names(&shots);
    let file = "shots/sphere_ops.ron";
    let alpha = "highlights[0].layers[0].stack[0].alpha";
    let out = key(
        dir.path(),
        &[file, "--at", alpha, "--frame", "12", "--value", "0.5"],
    );
    assert_exit(&out, 0);
    let keys = "(1, 0.0), (12, 0.35), (24, 0.0)";
    let expected = replaced(&shipped(file), keys, "(1, 0.0), (12, 0.5), (24, 0.0)");
    assert_eq!(read(dir.path(), file), expected);
    assert_eq!(stdout(&out), "[(1, 0.0), (12, 0.5), (24, 0.0)]\n");

    // A new key goes between its neighbours, on the list's line; the highlight picked by its
    // pattern is the same entry.
    let by_pattern = "highlights[\"ball/*\"].layers[0].stack[0].alpha";
    let out = key(
        dir.path(),
        &[file, "--at", by_pattern, "--frame", "18", "--value", "-0.2"],
    );
    assert_exit(&out, 0);
    let expected = replaced(&expected, "(12, 0.5), (24", "(12, 0.5), (18, -0.2), (24");
    assert_eq!(read(dir.path(), file), expected);
    // Written atomically: no temporary file is left beside it.
    assert_eq!(names(&shots), before);
}

#[test]
fn a_key_in_a_list_of_one_key_a_line_gets_a_line_of_its_own() {
    let dir = workspace();
    let file = "shots/teapot_light_orbit.ron";
    let out = key(
        dir.path(),
        &[
            file,
            "--at",
            "light.towards",
            "--frame",
            "5",
            "--value",
            "(-0.6, -0.4, 0.64)",
        ],
    );
    assert_exit(&out, 0);
    let expected = replaced(
        &shipped(file),
        "            (9, (-0.4924",
        "            (5, (-0.6, -0.4, 0.64)),\n            (9, (-0.4924",
    );
    assert_eq!(read(dir.path(), file), expected);
}

#[test]
fn a_bad_path_exits_2_naming_the_nearest_valid_path_and_writes_nothing() {
    let dir = workspace();
    let file = "shots/teapot_turntable.ron";
    for (written, nearest) in [
        (
            "highlights[1].layers[0].epsilom",
            "highlights[1].layers[0].epsilon",
        ),
        (
            "highlights[1].layers[0].stack[0].sigma",
            "highlights[1].layers[0].stack[1].sigma",
        ),
        (
            "highlights[1].layers[0].pin.w",
            "highlights[1].layers[0].pin.u",
        ),
        (
            "camera.projection.height",
            "camera.projection.fov_y_degrees",
        ),
        (
            "highlights[\"teapot/*\"].layers[0].colour[3]",
            "highlights[\"teapot/*\"].layers[0].colour[0]",
        ),
    ] {
        let out = key(dir.path(), &[file, "--at", written, "--value", "0.5"]);
        assert_exit(&out, 2);
        let message = stderr(&out);
        assert_eq!(message.lines().count(), 1, "{message}");
        assert!(message.contains(file), "{message}");
        assert!(
            message.contains(&format!("the nearest valid path is `{nearest}`")),
            "{message}"
        );
        assert_eq!(stdout(&out), "");
    }
    // A material of an include is edited in the include.
    let out = key(
        dir.path(),
        &[
            file,
            "--at",
            "materials{\"porcelain\"}.base",
            "--value",
            "(0, 0, 1)",
        ],
    );
    assert_exit(&out, 2);
    assert!(
        stderr(&out).contains("this file defines no material \"porcelain\"; the materials of its includes (looks/studio.ron) are edited in those files"),
        "{}",
        stderr(&out)
    );
    assert_eq!(read(dir.path(), file), shipped(file));
}

#[test]
fn delete_removes_a_key_and_the_last_key_leaves_the_constant_it_held() {
    let dir = workspace();
    let file = "shots/crescent.ron";
    let alpha = "highlights[0].layers[1].stack[1].alpha";
    let out = key(
        dir.path(),
        &[file, "--at", alpha, "--frame", "36", "--delete"],
    );
    assert_exit(&out, 0);
    assert_eq!(stdout(&out), "[(1, 0.6), (72, 0.6)]\n");
    let once = replaced(
        &shipped(file),
        "(1, 0.6), (36, 0.12), (72, 0.6)",
        "(1, 0.6), (72, 0.6)",
    );
    assert_eq!(read(dir.path(), file), once);

    // No key there: exit 2, the keys it has named, nothing written.
    let out = key(
        dir.path(),
        &[file, "--at", alpha, "--frame", "36", "--delete"],
    );
    assert_exit(&out, 2);
    assert!(
        stderr(&out).contains("has no key at frame 36; its keys are at frames 1, 72"),
        "{}",
        stderr(&out)
    );
    assert_eq!(read(dir.path(), file), once);

    for frame in ["1", "72"] {
        assert_exit(
            &key(
                dir.path(),
                &[file, "--at", alpha, "--frame", frame, "--delete"],
            ),
            0,
        );
    }
    let constant = replaced(&shipped(file), "[(1, 0.6), (36, 0.12), (72, 0.6)]", "0.6");
    assert_eq!(read(dir.path(), file), constant);
}

#[test]
fn a_value_the_shot_cannot_take_exits_2_at_its_place_and_writes_nothing() {
    let dir = workspace();
    let file = "shots/teapot_turntable.ron";
    let epsilon = "highlights[1].layers[0].epsilon";
    for (value, said) in [
        ("5", "outside the allowed range (0, 2]"),
        ("(1, 2)", "expected a number"),
        ("x", "cannot be used"),
    ] {
        let out = key(dir.path(), &[file, "--at", epsilon, "--value", value]);
        assert_exit(&out, 2);
        let message = stderr(&out);
        assert_eq!(message.lines().count(), 1, "{message}");
        assert!(message.contains(said), "{message}");
        // FILE:LINE:COL of the layer or the value.
        assert!(message.contains(&format!("{file}:")), "{message}");
        assert!(
            message.split(':').nth(2).unwrap().parse::<usize>().is_ok(),
            "{message}"
        );
        assert_eq!(stdout(&out), "");
    }
    let out = key(
        dir.path(),
        &[file, "--at", epsilon, "--frame", "inf", "--value", "0.1"],
    );
    assert_exit(&out, 2);
    assert_eq!(read(dir.path(), file), shipped(file));
}

#[test]
fn dry_run_shows_before_and_after_and_list_shows_every_track() {
    let dir = workspace();
    let file = "shots/looks/studio.ron";
    let threshold = "materials{\"clay\"}.bands[0].threshold";
    let out = key(
        dir.path(),
        &[
            file,
            "--at",
            threshold,
            "--frame",
            "12",
            "--value",
            "0.1",
            "--dry-run",
        ],
    );
    assert_exit(&out, 0);
    let line = shipped(file)
        .lines()
        .position(|l| l.contains("(0.05, (0.75"))
        .unwrap()
        + 1;
    assert_eq!(
        stdout(&out),
        format!("{file}:{line}:22: {threshold}\n- 0.05\n+ [(12, 0.1)]\n")
    );
    assert_eq!(read(dir.path(), file), shipped(file));

    let out = key(dir.path(), &[file, "--list"]);
    assert_exit(&out, 0);
    let listed = stdout(&out);
    assert_eq!(listed.lines().count(), 8, "{listed}");
    assert!(
        listed.contains(&format!("{threshold} = 0.05\n")),
        "{listed}"
    );
    assert!(
        listed.contains("materials{\"porcelain\"}.bands[1].colour = (0.45, 0.62, 0.95)\n"),
        "{listed}"
    );
}

/// The `glint key` commands of `text`: lines (after blanks) that start with `glint key`, with
/// `#` comments dropped.
fn commands(text: &str) -> Vec<String> {
    text.lines()
        .map(str::trim)
        .filter(|l| l.starts_with("glint key "))
        .map(|l| l.split(" #").next().unwrap().trim().to_string())
        .collect()
}

/// Runs each of `commands` with `sh` in `dir`, `glint` being the binary under test.
fn run_all(dir: &Path, commands: &[String]) {
    for command in commands {
        let out = crate::common::run_documented(dir, command);
        assert_exit(&out, 0);
        assert!(!stdout(&out).is_empty(), "{command}");
    }
}

#[test]
fn the_help_examples_run() {
    let help = std::process::Command::new(env!("CARGO_BIN_EXE_glint"))
        .args(["key", "--help"])
        .output()
        .unwrap();
    let examples = commands(&stdout(&help));
    assert!(examples.len() >= 4, "{examples:?}");
    run_all(workspace().path(), &examples);
}

#[test]
fn the_documented_examples_run_and_their_paths_resolve() {
    let doc = shipped("docs/shot-format.md");
    let section = &doc[doc.find("## Editing from the command line").unwrap()..];
    let examples = commands(section);
    assert!(examples.len() >= 4, "{examples:?}");
    run_all(workspace().path(), &examples);
}

/// Runs `glint inspect FILE --frame FRAME` in `dir`.
fn inspect(dir: &Path, file: &str, frame: &str) -> String {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_glint"))
        .current_dir(dir)
        .args(["inspect", file, "--frame", frame])
        .output()
        .unwrap();
    assert_exit(&out, 0);
    stdout(&out)
}

/// The numbers written in `line`: runs of digits, `-` and `.` after a blank or `(` and before
/// a `,` or `)`.
fn numbers(line: &str) -> Vec<&str> {
    line.split([' ', '(', '['])
        .map(|word| word.trim_end_matches([',', ')', ']', ':']))
        .filter(|word| {
            !word.is_empty()
                && word.contains(|c: char| c.is_ascii_digit())
                && word
                    .chars()
                    .all(|c| c.is_ascii_digit() || c == '-' || c == '.')
        })
        .collect()
}

#[test]
fn inspect_prints_values_in_the_shot_syntax_that_key_takes_back() {
    let dir = workspace();
    for file in [
        "shots/crescent.ron",
        "shots/sphere_ops.ron",
        "shots/xtoon_shape_torus.ron",
        "shots/xtoon_receding_shadows.ron",
    ] {
        let report = inspect(dir.path(), file, "7.3");
        for line in report.lines().skip(1) {
            for rust_only in ["Some(", "None", " { ", "ShapeDetail"] {
                assert!(!line.contains(rust_only), "{file}: {line}");
            }
            // The values: what follows `NAME: ` or `layers[0]: `.
            let Some((_, values)) = line.split_once(": ") else {
                continue;
            };
            for number in numbers(values) {
                let digits = number.trim_start_matches('-').replace('.', "");
                let significant = digits.trim_start_matches('0').trim_end_matches('0');
                assert!(significant.len() <= 6, "{file}: {number} in {line}");
            }
        }
    }

    // The Translate of the crescent's subtracted layer between its keys, pasted back as a key
    // at that frame, reads the same there.
    let file = "shots/crescent.ron";
    let before = inspect(dir.path(), file, "7.3");
    let translate = before
        .lines()
        .find(|l| l.contains("Translate(alpha: "))
        .unwrap();
    let alpha = translate
        .split("alpha: ")
        .nth(1)
        .unwrap()
        .split(',')
        .next()
        .unwrap();
    let at = "highlights[0].layers[1].stack[1].alpha";
    let out = key(
        dir.path(),
        &[file, "--at", at, "--frame", "7.3", "--value", alpha],
    );
    assert_exit(&out, 0);
    assert!(
        stdout(&out).contains(&format!("(7.3, {alpha})")),
        "{}",
        stdout(&out)
    );
    assert_eq!(inspect(dir.path(), file, "7.3"), before);
}

#[cfg(unix)]
#[test]
fn the_file_keeps_its_permissions_and_a_read_only_file_is_left_alone() {
    use std::os::unix::fs::PermissionsExt;
    let dir = workspace();
    let file = "shots/sphere_ops.ron";
    let path = dir.path().join(file);
    let epsilon = "highlights[0].layers[0].epsilon";
    std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o640)).unwrap();
    assert_exit(
        &key(dir.path(), &[file, "--at", epsilon, "--value", "0.03"]),
        0,
    );
    let mode = std::fs::metadata(&path).unwrap().permissions().mode();
    assert_eq!(mode & 0o777, 0o640);
    let edited = read(dir.path(), file);
    assert_eq!(
        edited,
        replaced(&shipped(file), "epsilon: 0.025", "epsilon: 0.03")
    );

    std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o444)).unwrap();
    let out = key(dir.path(), &[file, "--at", epsilon, "--value", "0.04"]);
    assert_exit(&out, 1);
    assert!(stderr(&out).contains("read-only"), "{}", stderr(&out));
    assert_eq!(read(dir.path(), file), edited);
}
