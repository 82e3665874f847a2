//! Named parts: groups of a model's patches from a library's `groups`, a `NAME.parts.ron`
//! beside the model, or an instance in the shot; selected as `INSTANCE/PART`, listed by
//! `glint patches`.

use std::path::Path;

use glint::formats::load_patches;
use glint::shot::load_shot;

use crate::common::{glint_with, repo_file, stderr, teapot};

/// A shot placing the teapot (with its parts file) and the car panels, with one highlight
/// entry per selector in `selectors`, and `instance_groups` written on the teapot instance.
fn shot_in(dir: &Path, selectors: &[&str], instance_groups: &str) -> std::path::PathBuf {
    for file in ["teapot.bpt", "teapot.parts.ron", "car_panels.ron"] {
        std::fs::copy(repo_file(&format!("patches/{file}")), dir.join(file)).unwrap();
    }
    let highlights: String = selectors
        .iter()
        .map(|s| {
            format!(
                "        (patches: \"{s}\", expr: Layer((stack: [], epsilon: 0.1, colour: (1, 1, 1)))),\n"
            )
        })
        .collect();
    let text = format!(
        r#"Shot(
    resolution: (32, 24),
    frames: (1, 1),
    fps: 24,
    output: "out/p.#.png",
    instances: [
        (name: "teapot", file: "teapot.bpt", material: "m"{instance_groups}),
        (name: "car", file: "car_panels.ron", material: "m",
         transform: (translate: (10, 0, 0))),
    ],
    materials: {{ "m": Cel(base: (0.2, 0.2, 0.2)) }},
    camera: (eye: (0, -12, 2), target: (0, 0, 1), projection: Perspective(fov_y_degrees: 40)),
    light: Directional(towards: (0, -1, 1)),
    highlights: [
{highlights}    ],
)
"#
    );
    let path = dir.join("shot.ron");
    std::fs::write(&path, text).unwrap();
    path
}

/// The names of the patches the highlight entry `entry` is on.
fn picked(shot: &glint::shot::Shot, entry: usize) -> Vec<String> {
    (0..shot.library.patches.len())
        .filter(|&p| shot.highlight_of(p) == Some(entry))
        .map(|p| shot.library.patches[p].name.clone())
        .collect()
}

#[test]
fn the_teapot_parts_cover_every_patch_once_and_sit_where_their_names_say() {
    let teapot = teapot();
    let mut owner = vec![None; teapot.patches.len()];
    for group in &teapot.groups {
        for &p in &group.patches {
            assert_eq!(owner[p], None, "patch {p} is in two parts");
            owner[p] = Some(group.name.as_str());
        }
    }
    assert!(owner.iter().all(Option::is_some), "{owner:?}");
    // Independent of the grouping: the highest point of the model is on the knob, the lowest
    // on the bottom, the farthest along +x on the spout and along −x on the handle.
    let extreme = |key: &dyn Fn(glam::DVec3) -> f64| {
        let (patch, _) = teapot
            .patches
            .iter()
            .enumerate()
            .flat_map(|(i, p)| p.surface.control_points().map(move |q| (i, key(q))))
            .fold(
                (0, f64::NEG_INFINITY),
                |best, c| if c.1 > best.1 { c } else { best },
            );
        owner[patch].unwrap()
    };
    assert_eq!(extreme(&|q| q.z), "knob");
    assert_eq!(extreme(&|q| -q.z), "bottom");
    assert_eq!(extreme(&|q| q.x), "spout");
    assert_eq!(extreme(&|q| -q.x), "handle");
    let lid = teapot.group("lid").unwrap();
    let knob = teapot.group("knob").unwrap();
    let top = |g: &glint::geom::PatchGroup| {
        g.patches
            .iter()
            .flat_map(|&p| teapot.patches[p].surface.control_points())
            .map(|q| q.z)
            .fold(f64::NEG_INFINITY, f64::max)
    };
    assert!(top(knob) > top(lid));
}

#[test]
fn selectors_pick_parts_as_they_pick_patches() {
    let dir = tempfile::tempdir().unwrap();
    let path = shot_in(
        dir.path(),
        &["teapot/lid", "car/glass", "teapot/sp*", "teapot/tip"],
        r#", groups: {"tip": [18, "19"]}"#,
    );
    let shot = load_shot(&path).unwrap();
    assert_eq!(
        picked(&shot, 0),
        ["teapot/24", "teapot/25", "teapot/26", "teapot/27"]
    );
    assert_eq!(picked(&shot, 1), ["car/windshield", "car/rear_window"]);
    // A later entry wins: the spout's tip is the fourth entry's, the rest the third's.
    assert_eq!(picked(&shot, 2), ["teapot/16", "teapot/17"]);
    assert_eq!(picked(&shot, 3), ["teapot/18", "teapot/19"]);
    // The parts file is one of the files the shot depends on.
    assert!(
        shot.inputs.iter().any(|p| p.ends_with("teapot.parts.ron")),
        "{:?}",
        shot.inputs
    );
    let names: Vec<&str> = shot
        .library
        .groups
        .iter()
        .map(|g| g.name.as_str())
        .collect();
    assert!(
        names.contains(&"teapot/tip") && names.contains(&"car/paint"),
        "{names:?}"
    );
}

#[test]
fn a_misspelt_part_suggests_the_part() {
    let dir = tempfile::tempdir().unwrap();
    let path = shot_in(dir.path(), &["teapot/lids"], "");
    let out = glint_with(&["render", path.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert!(err.contains("did you mean \"teapot/lid\""), "{err}");
    assert!(!dir.path().join("out").exists());
}

#[test]
fn a_bad_part_is_one_located_error_in_the_file_that_writes_it() {
    let dir = tempfile::tempdir().unwrap();
    let path = shot_in(dir.path(), &["teapot/lid"], "");
    // In the parts file beside the model.
    std::fs::write(
        dir.path().join("teapot.parts.ron"),
        "Parts(groups: {\n    \"lid\": [24, 25, 26, 27],\n    \"knob\": [20, 21, 32],\n})\n",
    )
    .unwrap();
    let out = glint_with(&["render", path.to_str().unwrap()]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("teapot.parts.ron:3:22:"), "{err}");
    assert!(err.contains("no patch 32"), "{err}");
    // On the instance in the shot.
    std::fs::copy(
        repo_file("patches/teapot.parts.ron"),
        dir.path().join("teapot.parts.ron"),
    )
    .unwrap();
    let path = shot_in(dir.path(), &["teapot/lid"], r#", groups: {"lid": [1]}"#);
    let out = glint_with(&["render", path.to_str().unwrap()]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("shot.ron:7:"), "{err}");
    assert!(err.contains("already defined"), "{err}");
}

#[test]
fn the_car_library_names_its_glass_and_paint() {
    let car = load_patches(&repo_file("patches/car_panels.ron")).unwrap();
    let names = |part: &str| -> Vec<&str> {
        car.group(part)
            .unwrap()
            .patches
            .iter()
            .map(|&p| car.patches[p].name.as_str())
            .collect()
    };
    assert_eq!(names("glass"), ["windshield", "rear_window"]);
    assert_eq!(names("paint"), ["hood", "roof", "trunk"]);
}

#[test]
fn glint_patches_lists_patches_parts_and_collapsed_edges() {
    let out = glint_with(&["patches", "patches/teapot.bpt", "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let listing: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let patches = listing["patches"].as_array().unwrap();
    assert_eq!(patches.len(), 32);
    let parts = listing["parts"].as_array().unwrap();
    let lid = parts.iter().find(|p| p["name"] == "lid").unwrap();
    assert_eq!(lid["patches"], serde_json::json!([24, 25, 26, 27]));
    // The knob's apex and the bottom's centre are points: one collapsed edge on each of their
    // patches, and the apex is where the control net's top row meets.
    let teapot = teapot();
    for (index, patch) in patches.iter().enumerate() {
        let collapsed = patch["collapsed"].as_array().unwrap().len();
        let part = patch["parts"][0].as_str().unwrap();
        let want = usize::from(part == "knob" || part == "bottom");
        assert_eq!(collapsed, want, "patch {index} ({part})");
        assert_eq!(patch["degree"], serde_json::json!([3, 3]));
    }
    let knob = &teapot.patches[20].surface;
    let apex = glam::DVec3::new(0.0, 0.0, 3.15);
    let on_apex = (0..4).all(|j| knob.control_point(0, j).0.distance(apex) < 1e-9)
        || (0..4).all(|j| knob.control_point(3, j).0.distance(apex) < 1e-9)
        || (0..4).all(|i| knob.control_point(i, 0).0.distance(apex) < 1e-9)
        || (0..4).all(|i| knob.control_point(i, 3).0.distance(apex) < 1e-9);
    assert!(on_apex);

    // Given a shot, the placed names selectors use.
    let out = glint_with(&["patches", "shots/teapot_turntable.ron"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let table = String::from_utf8(out.stdout).unwrap();
    assert!(table.contains("32 patches, 7 parts"), "{table}");
    assert!(
        table
            .lines()
            .any(|l| l.starts_with("teapot/lid") && l.ends_with("24-27")),
        "{table}"
    );

    // A parts file is not a model: it says which model to give instead.
    let out = glint_with(&["patches", "patches/teapot.parts.ron"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("teapot.bpt"), "{}", stderr(&out));

    // A file that is neither is exit 2 with its name.
    let out = glint_with(&["patches", "README.md"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("README.md"));
}
