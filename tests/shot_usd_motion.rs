//! An animated USD layer in a shot: each frame shows the time code the documented mapping gives
//! (`start + (frame − first) · per_frame`), the model's control points there are the linear mix of
//! the samples written in the file, held before the first and after the last, and the mapping's
//! refusals are one located line, exit 2.

use glam::DVec3;
use glint::shot::load_shot_text;

use crate::common::{glint, repo_file, stderr};
use crate::usd_motion::{flag_text, in_net_order, largest_gap, mix_at, samples_after, tuples};

/// A shot of the flag from frame 1 to 24 at `fps`, its instance with `extra` fields.
fn flag_shot(fps: u32, extra: &str) -> String {
    let flag = repo_file("patches/flag.usda");
    format!(
        r#"Shot(
    resolution: (64, 36),
    frames: (1, 24),
    fps: {fps},
    output: "out/f.####.png",
    instances: [(name: "flag", file: "{}", material: "m"{extra})],
    materials: {{"m": Cel(base: (0.5, 0.2, 0.1))}},
    camera: (eye: (0.6, -4.6, 1.6), target: (0.45, 0, 0.5), projection: Perspective(fov_y_degrees: 34)),
    light: Directional(towards: (-0.4, -0.7, 0.6)),
    render: (preset: Preview),
)
"#,
        flag.display()
    )
}

/// The cloth's samples as the file writes them, in the library's control-point order.
fn cloth_samples() -> Vec<(f64, Vec<DVec3>)> {
    samples_after(&flag_text(), "points.timeSamples = {")
        .into_iter()
        .map(|(t, v)| (t, in_net_order(&tuples(v), 5, 4)))
        .collect()
}

fn cloth_at(shot: &glint::shot::Shot, frame: f64) -> Vec<DVec3> {
    let library = shot.library_at(frame);
    let cloth = library
        .patches
        .iter()
        .find(|p| p.name.ends_with("/cloth"))
        .expect("the flag has a cloth");
    cloth.surface.control_points().collect()
}

#[test]
fn frames_show_the_mapped_time_code_the_points_mixed_linearly_and_held_at_both_ends() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("flag.ron");
    let samples = cloth_samples();
    // The layer's own timing: startTimeCode 1, 24 time codes a second, at 24 fps: frame = time code.
    let shot = load_shot_text(&path, flag_shot(24, "")).unwrap();
    assert!(shot.moves());
    for frame in [1.0, 2.5, 6.25, 11.999, 12.0, 13.75, 20.125, 24.0] {
        let gap = largest_gap(&cloth_at(&shot, frame), &mix_at(&samples, frame));
        assert!(gap <= 1e-12, "frame {frame}: {gap:e}");
    }
    // At 12 fps a frame is two time codes: frame f shows 1 + 2 (f − 1).
    let halved = load_shot_text(&path, flag_shot(12, "")).unwrap();
    for frame in [1.0, 3.3, 6.5, 12.0] {
        let code = 1.0 + 2.0 * (frame - 1.0);
        let gap = largest_gap(&cloth_at(&halved, frame), &mix_at(&samples, code));
        assert!(gap <= 1e-12, "frame {frame} (time code {code}): {gap:e}");
    }
    // An instance's own mapping: frame 1 at time code −5, 3 time codes a frame. Frames before
    // time code 1 hold the first sample, frames after 24 the last.
    let mapped = load_shot_text(
        &path,
        flag_shot(24, ", time_codes: (start: -5, per_frame: 3)"),
    )
    .unwrap();
    for frame in [1.0, 2.0, 2.9, 3.0, 4.5, 7.25, 10.5, 11.0, 15.0, 24.0] {
        let code = -5.0 + 3.0 * (frame - 1.0);
        let gap = largest_gap(&cloth_at(&mapped, frame), &mix_at(&samples, code));
        assert!(gap <= 1e-12, "frame {frame} (time code {code}): {gap:e}");
    }
    let first = &samples[0].1;
    let last = &samples[samples.len() - 1].1;
    assert!(largest_gap(&cloth_at(&mapped, 1.0), first) == 0.0);
    assert!(largest_gap(&cloth_at(&mapped, 24.0), last) == 0.0);
    // The vane turns with its rotateZ samples (0° at 1, 90° at 24): its far edge at frame 12.5
    // is at 45° · 11.5 / 23 about z.
    let vane = |frame: f64| -> Vec<DVec3> {
        let library = shot.library_at(frame);
        let p = library
            .patches
            .iter()
            .find(|p| p.name.ends_with("/vane"))
            .unwrap();
        p.surface.control_points().collect()
    };
    for frame in [1.0, 12.5, 24.0] {
        let degrees = 90.0 * (frame - 1.0) / 23.0;
        let tip = vane(frame)[0];
        let expected = (180.0 + degrees).to_radians();
        let angle = tip.y.atan2(tip.x);
        let gap = (angle - expected).sin().abs();
        assert!(
            gap < 1e-12,
            "frame {frame}: the vane's tip at {angle} rad, not {expected}"
        );
    }
}

#[test]
fn time_code_mappings_that_cannot_be_used_are_one_located_line() {
    let dir = tempfile::tempdir().unwrap();
    let sphere = repo_file("patches/sphere.ron");
    let cases = [
        (
            flag_shot(24, ", time_codes: (per_frame: 1e300)"),
            "(per_frame: 1e300)",
            "which is not finite",
        ),
        (
            flag_shot(24, ", time_codes: (start: 1e13)"),
            "(start: 1e13)",
            "within ±1e12",
        ),
        (
            flag_shot(24, ", time_codes: (start: 1)").replace(
                &repo_file("patches/flag.usda").display().to_string(),
                &sphere.display().to_string(),
            ),
            "(start: 1)",
            "has no time samples",
        ),
    ];
    for (text, at, says) in cases {
        let path = dir.path().join("shot.ron");
        std::fs::write(&path, &text).unwrap();
        let out = glint().arg("render").arg(&path).output().unwrap();
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        let offset = text.find(at).unwrap();
        let (line, col) = glint::formats::ron_location::position_of(&text, offset);
        let place = format!("shot.ron:{line}:{col}: ");
        assert!(
            err.contains(&place) && err.contains(says),
            "expected {place}…{says} in {err}"
        );
        assert!(!dir.path().join("out").exists());
    }
}

#[test]
fn a_frame_s_fingerprint_follows_the_samples_it_uses_and_no_other() {
    let dir = tempfile::tempdir().unwrap();
    let usda = dir.path().join("flag.usda");
    let text = flag_text();
    std::fs::write(&usda, &text).unwrap();
    let shot_text = flag_shot(24, "").replace(
        &repo_file("patches/flag.usda").display().to_string(),
        &usda.display().to_string(),
    );
    let path = dir.path().join("flag.ron");
    std::fs::write(&path, &shot_text).unwrap();
    let fingerprints = || -> Vec<String> {
        let job = glint::job::RenderJob::load(&path, &glint::job::Overrides::default()).unwrap();
        (1..=24)
            .map(|f| {
                job.fingerprint(f)
                    .expect("the job's files read")
                    .to_string()
            })
            .collect()
    };
    let before = fingerprints();
    // Frames 12 to 24 show time codes between the samples at 12 and 24; moving one point of the
    // last sample changes exactly them.
    let head = "            24: [(0, 0, 0), (0.5, -0, 0), (1, 0.125, 0),";
    assert!(
        text.contains(head),
        "the fixture's last sample starts {head}"
    );
    std::fs::write(
        &usda,
        text.replacen(
            head,
            "            24: [(0, 0, 0), (0.5, -0, 0), (1, 0.5, 0),",
            1,
        ),
    )
    .unwrap();
    let after = fingerprints();
    for f in 1..=24usize {
        let changed = before[f - 1] != after[f - 1];
        assert_eq!(changed, f > 12, "frame {f}");
    }
}
