//! Fingerprints of a moving shot: an edit of a transform key changes the fingerprints of exactly
//! the frames whose pose it changes, `glint verify` names those frames and only those, and a
//! farm task renders them again while it keeps the others.

use std::os::unix::fs::MetadataExt;
use std::path::{Path, PathBuf};
use std::process::Command;

use glint::job::{Overrides, RenderJob};
use glint::shot::load_shot_text;

use crate::common::{glint, stderr};
use crate::motion_loop::{moving_ball_text, write_moving_ball};

/// The key of the rise at frame 20 in [`moving_ball_text`], and the same key raised: frames
/// 11–30 (the stretch 10–20 and the hold after it) are posed anew; frames 1–10 are not.
const LAST_KEY: (&str, &str) = ("(20, (1.5, 0.0, 0.5))", "(20, (1.5, 0.0, 0.9))");

/// The first key of the drive, moved: only frames 1–9, before the key at 10, are posed anew.
const FIRST_KEY: (&str, &str) = ("(1, (0.0, 0.0, 0.0))", "(1, (-0.5, 0.0, 0.0))");

fn edited((from, to): (&str, &str)) -> String {
    let text = moving_ball_text();
    assert_eq!(
        text.matches(from).count(),
        1,
        "{from} is one key of the shot"
    );
    text.replace(from, to)
}

/// The fingerprints of frames 1–30 of `text`, read as the shot at `shot`, at `size`.
fn fingerprints_at(shot: &Path, text: &str, size: Option<(u32, u32)>) -> Vec<String> {
    let overrides = Overrides {
        frames: Some((1..=30).collect()),
        size,
        ..Overrides::default()
    };
    let job = RenderJob::new(load_shot_text(shot, text.to_string()).unwrap(), &overrides).unwrap();
    (1..=30).map(|f| job.fingerprint(f).unwrap().0).collect()
}

fn fingerprints(shot: &Path, text: &str) -> Vec<String> {
    fingerprints_at(shot, text, None)
}

/// The frames whose fingerprints differ between the two lists of frames 1–30.
fn changed(before: &[String], after: &[String]) -> Vec<i64> {
    (1..=30)
        .filter(|&f| before[f as usize - 1] != after[f as usize - 1])
        .collect()
}

#[test]
fn a_transform_key_edit_changes_the_fingerprints_of_exactly_the_frames_it_poses_anew() {
    let dir = tempfile::tempdir().unwrap();
    let shot = write_moving_ball(dir.path());
    let before = fingerprints(&shot, &moving_ball_text());
    // Every frame of the drive and the rise is posed differently from the others.
    let distinct: std::collections::HashSet<&String> = before[..20].iter().collect();
    assert_eq!(distinct.len(), 20, "frames 1–20 each have their own pose");
    assert!(
        before[19..].iter().all(|f| *f == before[19]),
        "frames 20–30 hold one pose and share its fingerprint"
    );

    let raised = fingerprints(&shot, &edited(LAST_KEY));
    assert_eq!(changed(&before, &raised), (11..=30).collect::<Vec<_>>());
    let moved = fingerprints(&shot, &edited(FIRST_KEY));
    assert_eq!(changed(&before, &moved), (1..=9).collect::<Vec<_>>());
}

/// The options every command here takes: frames 1–30 of `shot` at 32×32, preview.
fn run(shot: &Path, command: &str) -> std::process::Output {
    glint()
        .args([
            command,
            shot.to_str().unwrap(),
            "--frames",
            "1-30",
            "--size",
            "32x32",
        ])
        .output()
        .unwrap()
}

#[test]
fn verify_names_exactly_the_frames_a_transform_key_edit_poses_anew() {
    let dir = tempfile::tempdir().unwrap();
    let shot = write_moving_ball(dir.path());
    let rendered = run(&shot, "render");
    assert_eq!(rendered.status.code(), Some(0), "{}", stderr(&rendered));
    let verified = run(&shot, "verify");
    assert_eq!(verified.status.code(), Some(0), "{}", stderr(&verified));

    std::fs::write(&shot, edited(LAST_KEY)).unwrap();
    let verified = run(&shot, "verify");
    let out = String::from_utf8_lossy(&verified.stdout);
    assert_eq!(verified.status.code(), Some(1), "{out}");
    assert!(out.contains("made from other inputs"), "{out}");
    assert!(out.ends_with("render again: --frames 11-30\n"), "{out}");
}

/// The frame files of the moving ball's folder.
fn frame_file(dir: &Path, frame: i64) -> PathBuf {
    dir.join(format!("out/m.{frame:04}.png"))
}

#[test]
fn a_farm_task_renders_again_only_the_frames_a_later_key_edit_poses_anew() {
    let dir = tempfile::tempdir().unwrap();
    let shot = write_moving_ball(dir.path());
    let out = glint()
        .args([
            "farm",
            "slurm",
            shot.to_str().unwrap(),
            "--frames",
            "1-30",
            "--chunk",
            "8",
            "--size",
            "32x32",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let script = dir.path().join("array.sh");
    std::fs::write(&script, &out.stdout).unwrap();
    // Task 1 of the array renders frames 9–16, as a Slurm task would run it.
    let task = || {
        let out = Command::new("bash")
            .arg(&script)
            .env("SLURM_ARRAY_TASK_ID", "1")
            .env("SLURM_ARRAY_JOB_ID", "7")
            .env("SLURM_CPUS_PER_TASK", "1")
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    };
    task();
    let files = |frame| std::fs::metadata(frame_file(dir.path(), frame)).unwrap();
    let first: Vec<u64> = (9..=16).map(|f| files(f).ino()).collect();

    std::fs::write(&shot, edited(LAST_KEY)).unwrap();
    task();
    // A frame written again is a new file renamed over the old one: a new inode.
    let kept: Vec<i64> = (9..=16)
        .filter(|&f| files(f).ino() == first[f as usize - 9])
        .collect();
    assert_eq!(
        kept,
        [9, 10],
        "frames 9 and 10 keep their pose; 11–16 do not"
    );
    // What was written again carries the edited shot's fingerprints.
    let text = std::fs::read_to_string(&shot).unwrap();
    let expected = fingerprints_at(&shot, &text, Some((32, 32)));
    for frame in 9..=16 {
        let stamp = glint::formats::png::try_read_png_text(
            &frame_file(dir.path(), frame),
            glint::job::FINGERPRINT_KEY,
        );
        assert_eq!(
            stamp,
            Ok(Some(expected[frame as usize - 1].clone())),
            "frame {frame}"
        );
    }
}
