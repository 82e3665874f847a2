//! `glint bench loop`: a highlight edit re-runs only the shading (the surfaces and the lines are
//! the previous frame's) and a camera edit runs every stage, as the benchmark reports; a missing model is bad input.

use crate::common::{glint_with as glint, stderr};

#[test]
fn one_round_reports_both_edits_and_the_stages_each_ran() {
    let dir = tempfile::tempdir().unwrap();
    let out = glint(&[
        "bench",
        "loop",
        "--rounds",
        "1",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let stdout = String::from_utf8_lossy(&out.stdout);
    let line = |start: &str| {
        stdout
            .lines()
            .find(|l| l.starts_with(start) && l.contains(" ran "))
            .unwrap_or_else(|| panic!("no '{start}' stages line in:\n{stdout}"))
            .to_string()
    };
    assert!(
        line("highlight").ends_with("ran shade; reused tessellate, rasterize, gbuffer, outline"),
        "{stdout}"
    );
    assert!(
        line("camera").contains("ran tessellate, rasterize, gbuffer, shade"),
        "{stdout}"
    );
    assert!(stdout.contains("camera / highlight, total"), "{stdout}");
    for file in [
        "highlight.ron",
        "camera.ron",
        "highlight.1.png",
        "camera.1.png",
    ] {
        assert!(dir.path().join(file).exists(), "{file}");
    }
}

#[test]
fn a_missing_model_is_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    let out = glint(&[
        "bench",
        "loop",
        "--out",
        dir.path().to_str().unwrap(),
        "--teapot",
        "patches/missing.bpt",
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("missing.bpt"), "{}", stderr(&out));
    assert_eq!(stderr(&out).lines().count(), 1, "{}", stderr(&out));
}
