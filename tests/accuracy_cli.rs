//! `glint bench accuracy` refuses bad input at once, before any measuring: exit code 2 for a
//! bad option, a bad model or an output directory that cannot be made, with one line naming
//! the problem.

use crate::common::{glint_with as glint, stderr};

#[test]
fn a_resolution_out_of_range_is_a_usage_error() {
    let out = glint(&["bench", "accuracy", "--quick", "--resolution", "0"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("--resolution"), "{}", stderr(&out));
}

#[test]
fn a_missing_model_is_bad_input() {
    let out = glint(&[
        "bench",
        "accuracy",
        "--quick",
        "--teapot",
        "patches/missing.bpt",
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("missing.bpt"), "{}", stderr(&out));
}

#[test]
fn an_output_directory_that_cannot_be_made_fails_before_measuring() {
    let blocker = tempfile::NamedTempFile::new().unwrap();
    let inside = blocker.path().join("accuracy");
    let out = glint(&[
        "bench",
        "accuracy",
        "--quick",
        "--out",
        inside.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("cannot create"), "{}", stderr(&out));
    assert!(out.stdout.is_empty(), "nothing was measured");
}

#[test]
fn presets_only_measures_every_view_on_every_candidate_and_writes_one_table() {
    let dir = tempfile::tempdir().unwrap();
    let out = glint(&[
        "bench",
        "accuracy",
        "--presets-only",
        "--target-resolution",
        "32",
        "--repeats",
        "1",
        "--out",
        dir.path().to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let names: Vec<String> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, ["presets.csv"]);
    let table = std::fs::read_to_string(dir.path().join("presets.csv")).unwrap();
    let mut lines = table.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    let views = glint::accuracy::case::Case::all();
    let rungs = glint::accuracy::sweep::Sweep::presets(32, 1, 0).rungs.len();
    assert_eq!(rows.len(), views.len() * rungs);
    for view in &views {
        let (pose, stack) = (view.pose.to_string(), view.stack.to_string());
        let of_view = rows
            .iter()
            .filter(|r| r[column("pose")] == pose && r[column("stack")] == stack)
            .count();
        assert_eq!(of_view, rungs, "{view}");
    }
    for row in &rows {
        for name in ["one_minus_iou", "silhouette_one_minus_iou"] {
            let value: f64 = row[column(name)].parse().unwrap();
            assert!((0.0..=1.0).contains(&value), "{name} = {value} in {row:?}");
            // One sample a pixel may miss a highlight smaller than a pixel (ε = 10⁻³ at 32²);
            // `final` finds it.
            if row[column("preset")] == "final" {
                assert!(value < 1.0, "{name} = {value} in {row:?}");
            }
        }
        let silhouette: f64 = row[column("silhouette_px")].parse().unwrap();
        assert!((0.0..4.0).contains(&silhouette), "{row:?}");
        // A highlight thinner than half a pixel at this size has no boundary to measure.
        let boundary: f64 = row[column("boundary_px")].parse().unwrap();
        assert!(
            (0.0..4.0).contains(&boundary) || boundary == f64::INFINITY,
            "{row:?}"
        );
    }
    for preset in ["preview", "final"] {
        assert_eq!(
            rows.iter()
                .filter(|r| r[column("preset")] == preset)
                .count(),
            views.len(),
            "{preset}"
        );
    }
}
