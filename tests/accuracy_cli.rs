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
