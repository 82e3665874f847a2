//! Frames that know what made them: fingerprints that change for exactly the frames an edit
//! changes, `glint verify` finding every kind of incomplete frame, `--skip-existing` rendering
//! again only stale frames, and `--report`'s lines.

use std::path::{Path, PathBuf};
use std::process::Output;

use glint::job::{Overrides, RenderJob, FINGERPRINT_KEY};
use glint::shot::{apply_edits, load_shot_text, parse_param_path, TrackEdit};

use crate::common::{glint, repo_file, stderr};

const ALPHA: &str = "highlights[0].layers[0].stack[0].alpha";

/// A copy of `shots/sphere_ops.ron` with its sphere, and the options every command here takes.
struct Farm {
    dir: tempfile::TempDir,
    shot: PathBuf,
}

impl Farm {
    fn new() -> Self {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(dir.path().join("shots")).unwrap();
        std::fs::create_dir_all(dir.path().join("patches")).unwrap();
        std::fs::copy(
            repo_file("patches/sphere.ron"),
            dir.path().join("patches/sphere.ron"),
        )
        .unwrap();
        let shot = dir.path().join("shots/sphere_ops.ron");
        std::fs::copy(repo_file("shots/sphere_ops.ron"), &shot).unwrap();
        Self { dir, shot }
    }

    fn frame(&self, frame: i64) -> PathBuf {
        self.dir.path().join(format!("out/s.{frame:04}.png"))
    }

    fn run(&self, command: &str, extra: &[&str]) -> Output {
        let out = self.dir.path().join("out/s.####.png");
        let mut args = vec![
            command,
            self.shot.to_str().unwrap(),
            "--frames",
            "1-30",
            "--preset",
            "preview",
            "--size",
            "32x32",
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        glint().args(&args).output().unwrap()
    }

    fn render(&self, extra: &[&str]) -> Output {
        let out = self.run("render", &[&["--quiet"], extra].concat());
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
        out
    }

    fn verify(&self) -> (Option<i32>, String) {
        let out = self.run("verify", &[]);
        (
            out.status.code(),
            String::from_utf8_lossy(&out.stdout).into_owned(),
        )
    }

    /// Keys alpha at frame 12 to 0.3 (the file keys it 0.35 there, between keys at 1 and 24).
    fn edit_key(&self) {
        let text = std::fs::read_to_string(&self.shot).unwrap();
        let path = parse_param_path(&text, ALPHA).unwrap();
        let edit = TrackEdit::Key {
            frame: 12.0,
            value: "0.3".to_string(),
        };
        std::fs::write(&self.shot, apply_edits(&text, &[(path, edit)]).unwrap()).unwrap();
    }
}

fn fingerprints(shot: &Path, text: &str, overrides: &Overrides) -> Vec<String> {
    let job = RenderJob::new(load_shot_text(shot, text.to_string()).unwrap(), overrides).unwrap();
    (1..=30).map(|f| job.fingerprint(f).unwrap().0).collect()
}

#[test]
fn an_edited_key_changes_the_fingerprints_of_exactly_the_frames_it_changes() {
    let farm = Farm::new();
    let text = std::fs::read_to_string(&farm.shot).unwrap();
    let overrides = Overrides {
        frames: Some((1..=30).collect()),
        ..Overrides::default()
    };
    let before = fingerprints(&farm.shot, &text, &overrides);
    farm.edit_key();
    let edited = std::fs::read_to_string(&farm.shot).unwrap();
    let after = fingerprints(&farm.shot, &edited, &overrides);
    let changed: Vec<i64> = (1..=30)
        .filter(|&f| before[f as usize - 1] != after[f as usize - 1])
        .collect();
    // Alpha is linear between keys at 1, 12 and 24: every frame strictly between 1 and 24.
    assert_eq!(changed, (2..=23).collect::<Vec<_>>());
    // The thread count changes no byte, so no fingerprint; the size changes every one.
    let threads = Overrides {
        threads: Some(1),
        ..overrides.clone()
    };
    assert_eq!(fingerprints(&farm.shot, &edited, &threads), after);
    let size = Overrides {
        size: Some((33, 32)),
        ..overrides
    };
    let resized = fingerprints(&farm.shot, &edited, &size);
    assert!(resized.iter().zip(&after).all(|(a, b)| a != b));
}

#[test]
fn every_file_of_a_frame_carries_its_fingerprint() {
    let farm = Farm::new();
    farm.render(&["--aov", "matte,depth"]);
    let overrides = Overrides {
        size: Some((32, 32)),
        preset: Some(glint::shot::Preset::Preview),
        aovs: Some(vec![glint::shot::Aov::Matte, glint::shot::Aov::Depth]),
        output: Some(farm.dir.path().join("out/s.####.png")),
        ..Overrides::default()
    };
    let job = RenderJob::load(&farm.shot, &overrides).unwrap();
    let expected = job.fingerprint(3).unwrap().0;
    let files = job.frame_files(3);
    assert_eq!(files.len(), 4, "colour, matte, depth, EXR: {files:?}");
    for file in &files {
        let stamp = if file.extension().unwrap() == "exr" {
            glint::formats::exr::try_read_exr_text(file, FINGERPRINT_KEY)
        } else {
            glint::formats::png::try_read_png_text(file, FINGERPRINT_KEY)
        };
        assert_eq!(stamp, Ok(Some(expected.clone())), "{}", file.display());
    }
}

#[test]
fn verify_passes_a_complete_render() {
    let farm = Farm::new();
    farm.render(&[]);
    let (code, out) = farm.verify();
    assert_eq!(code, Some(0), "{out}");
    assert!(
        out.contains("30 frames checked: 30 complete, 0 to render again"),
        "{out}"
    );
}

/// Renders all 30 frames, damages some with `damage`, and checks that verify lists exactly
/// `expected` to render again, naming `problem`.
fn verify_finds(damage: impl Fn(&Farm), expected: &str, problem: &str) {
    let farm = Farm::new();
    farm.render(&[]);
    damage(&farm);
    let (code, out) = farm.verify();
    assert_eq!(code, Some(1), "{out}");
    assert!(out.contains(problem), "{out}");
    let spec = out.lines().last().unwrap_or_default();
    assert_eq!(spec, format!("render again: --frames {expected}"), "{out}");
}

#[test]
fn verify_finds_a_missing_frame() {
    verify_finds(
        |farm| std::fs::remove_file(farm.frame(7)).unwrap(),
        "7",
        "missing",
    );
}

#[test]
fn verify_finds_a_truncated_frame() {
    verify_finds(
        |farm| {
            let bytes = std::fs::read(farm.frame(9)).unwrap();
            std::fs::write(farm.frame(9), &bytes[..bytes.len() / 2]).unwrap();
        },
        "9",
        "does not decode",
    );
}

#[test]
fn verify_finds_a_folder_in_a_frame_s_place() {
    verify_finds(
        |farm| {
            std::fs::remove_file(farm.frame(4)).unwrap();
            std::fs::create_dir(farm.frame(4)).unwrap();
        },
        "4",
        "not a regular file",
    );
}

#[test]
fn verify_finds_a_frame_of_the_wrong_size() {
    verify_finds(
        |farm| {
            let other = farm.dir.path().join("other/o.####.png");
            let out = glint()
                .args([
                    "render",
                    farm.shot.to_str().unwrap(),
                    "--frames",
                    "5",
                    "--preset",
                    "preview",
                    "--size",
                    "40x32",
                    "--out",
                    other.to_str().unwrap(),
                    "--quiet",
                ])
                .output()
                .unwrap();
            assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
            std::fs::copy(farm.dir.path().join("other/o.0005.png"), farm.frame(5)).unwrap();
        },
        "5",
        "40×32 instead of 32×32",
    );
}

#[test]
fn verify_finds_stale_frames_and_skip_existing_renders_exactly_them() {
    let farm = Farm::new();
    farm.render(&[]);
    farm.edit_key();
    let (code, out) = farm.verify();
    assert_eq!(code, Some(1), "{out}");
    assert!(out.ends_with("render again: --frames 2-23\n"), "{out}");
    assert!(out.contains("made from other inputs"), "{out}");

    // `any` trusts every frame that exists; the default renders exactly the stale ones.
    let report = farm.dir.path().join("report.jsonl");
    farm.render(&["--skip-existing=any", "--report", report.to_str().unwrap()]);
    assert!(!report.exists(), "nothing was written");
    farm.render(&["--skip-existing", "--report", report.to_str().unwrap()]);
    let lines: Vec<serde_json::Value> = std::fs::read_to_string(&report)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let frames: Vec<i64> = lines.iter().map(|l| l["frame"].as_i64().unwrap()).collect();
    assert_eq!(frames, (2..=23).collect::<Vec<_>>());
    let line = &lines[0];
    assert_eq!(line["fingerprint"].as_str().unwrap().len(), 32);
    assert!(line["path"].as_str().unwrap().ends_with("s.0002.png"));
    assert!(line["stages"]["shade"].as_f64().is_some(), "{line}");
    assert!(
        line["peak_memory_bytes"].as_u64().unwrap() > 1_000_000,
        "{line}"
    );
    assert!(!line["host"].as_str().unwrap().is_empty());
    let (code, out) = farm.verify();
    assert_eq!(code, Some(0), "{out}");
}
