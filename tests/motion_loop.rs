//! The animator's commands on a moving shot: `glint place` puts the highlight where asked on
//! the surface as it is posed at the frame, `glint probe` reports the posed point, `glint sheet`
//! tiles the frames of the moving ball, and `--watch` renders again after an edit of a
//! transform key. Each check would fail if the model at rest were used: the ball has left its
//! rest place and turned a quarter turn by frame 10.

use std::path::{Path, PathBuf};

use glam::{DMat3, DVec3};
use glint::job::{Overrides, RenderJob};
use glint::picture::SheetLayout;
use glint::shot::Aov;

use crate::common::{glint, repo_file, stderr};

/// The image's side in pixels; the orthographic camera sees 6 units, 16 pixels a unit.
pub const SIZE: u32 = 96;

/// Where the ball is at frame `frame` of [`moving_ball_text`]: its centre's translation and its
/// turn about z in degrees, read from the keys written there (linear between keys, held after
/// the last).
pub fn ball_pose(frame: f64) -> (DVec3, f64) {
    let t = ((frame - 1.0) / 9.0).clamp(0.0, 1.0);
    let s = ((frame - 10.0) / 10.0).clamp(0.0, 1.0);
    let translate = DVec3::new(1.5 * t, 0.0, 0.5 * s);
    (translate, 90.0 * t)
}

/// A 30-frame shot of the unit ball that drives from the origin to x = 1.5 while turning a
/// quarter turn about z over frames 1–10, then rises by 0.5 over frames 10–20 and holds.
pub fn moving_ball_text() -> String {
    format!(
        r#"Shot(
    resolution: ({SIZE}, {SIZE}),
    frames: (1, 30),
    fps: 24,
    output: "out/m.####.png",
    instances: [(
        name: "ball",
        file: "sphere.ron",
        material: "blue",
        transform: (
            translate: [(1, (0.0, 0.0, 0.0)), (10, (1.5, 0.0, 0.0)), (20, (1.5, 0.0, 0.5))],
            axis: (0.0, 0.0, 1.0),
            degrees: [(1, 0.0), (10, 90.0)],
        ),
    )],
    materials: {{ "blue": Cel(base: (0.04, 0.07, 0.2), bands: [(0.05, (0.18, 0.32, 0.75))]) }},
    camera: (eye: (0.0, -6.0, 0.0), target: (0.0, 0.0, 0.0), projection: Orthographic(height: 6.0)),
    light: Directional(towards: (0.35, -1.0, 0.45)),
    highlights: [(
        patches: "ball/*",
        expr: Layer((stack: [Translate(alpha: 0.0, beta: 0.0)], epsilon: 0.02, colour: (1.0, 1.0, 1.0))),
    )],
    render: (preset: Preview),
)
"#
    )
}

/// The moving ball's shot written in `dir` beside a copy of the sphere; its path.
pub fn write_moving_ball(dir: &Path) -> PathBuf {
    std::fs::copy(repo_file("patches/sphere.ron"), dir.join("sphere.ron")).unwrap();
    let shot = dir.join("moving.ron");
    std::fs::write(&shot, moving_ball_text()).unwrap();
    shot
}

/// The pixel (centres at integers) where the camera sees world point `p`: x to the right,
/// z up, 16 pixels a unit about the image's centre.
fn pixel_of(p: DVec3) -> (f64, f64) {
    let centre = f64::from(SIZE) / 2.0 - 0.5;
    let scale = f64::from(SIZE) / 6.0;
    (centre + p.x * scale, centre - p.z * scale)
}

/// The centroid of the highlight matte of `shot` at `frame`, in pixel centres.
fn matte_centroid(shot: &Path, frame: f64) -> (f64, f64) {
    let overrides = Overrides {
        aovs: Some(vec![Aov::Matte]),
        ..Overrides::default()
    };
    let mut job = RenderJob::load(shot, &overrides).unwrap();
    let image = job.render_frame(frame).unwrap();
    let matte = image.aovs.matte.unwrap();
    let (centre, sum) = crate::common::matte_centroid_of(&matte, SIZE);
    assert!(sum > 3.0, "the highlight shows at frame {frame}");
    centre
}

#[test]
fn place_on_a_moving_ball_centres_the_highlight_on_the_asked_pixel_of_the_posed_surface() {
    let dir = tempfile::tempdir().unwrap();
    let shot = write_moving_ball(dir.path());
    // A point of the ball as it is at frame 10, right of and above its centre; the ball at rest
    // (radius 1 about the origin) does not reach it.
    let (centre, _) = ball_pose(10.0);
    let asked = pixel_of(centre + DVec3::new(0.3, -0.9, 0.25));
    let (x, y) = (asked.0.round(), asked.1.round());
    assert!(pixel_of(DVec3::new(1.0, 0.0, 0.0)).0 < x - 3.0);
    let pixel = format!("{x},{y}");

    let at_rest = glint()
        .args([
            "place",
            shot.to_str().unwrap(),
            "--frame",
            "1",
            "--pixel",
            &pixel,
        ])
        .output()
        .unwrap();
    assert_eq!(at_rest.status.code(), Some(2), "{}", stderr(&at_rest));
    assert!(
        stderr(&at_rest).contains("shows no patch"),
        "{}",
        stderr(&at_rest)
    );

    let placed = glint()
        .args([
            "place",
            shot.to_str().unwrap(),
            "--frame",
            "10",
            "--pixel",
            &pixel,
            "--write",
        ])
        .output()
        .unwrap();
    assert_eq!(placed.status.code(), Some(0), "{}", stderr(&placed));
    let (cx, cy) = matte_centroid(&shot, 10.0);
    let miss = (cx - x).hypot(cy - y);
    assert!(
        miss <= 1.5,
        "the highlight's centroid ({cx}, {cy}) is {miss} px from the asked ({x}, {y})"
    );
}

#[test]
fn probe_of_a_shot_reports_the_point_where_the_frame_poses_it() {
    let dir = tempfile::tempdir().unwrap();
    let shot = write_moving_ball(dir.path());
    let (u, v) = (0.0, 0.5);
    // sphere.ron: u runs east from +x, v from the south pole, so (0, 0.5) is (1, 0, 0) at rest.
    let rest = DVec3::new(1.0, 0.0, 0.0);
    for frame in [1.0, 5.5, 10.0, 15.0, 30.0] {
        let out = glint()
            .args([
                "probe",
                shot.to_str().unwrap(),
                "--patch",
                "ball/sphere",
                "--frame",
                &frame.to_string(),
                "--uv",
                &format!("{u},{v}"),
            ])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
        let probes: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let point: Vec<f64> = probes[0]["point"]
            .as_array()
            .unwrap()
            .iter()
            .map(|x| x.as_f64().unwrap())
            .collect();
        let (translate, degrees) = ball_pose(frame);
        let expected = DMat3::from_rotation_z(degrees.to_radians()) * rest + translate;
        let got = DVec3::new(point[0], point[1], point[2]);
        assert!(
            got.distance(expected) < 1e-9,
            "frame {frame}: probed {got}, the pose puts it at {expected}"
        );
        let normal = &probes[0]["normal"];
        let n = DVec3::new(
            normal[0].as_f64().unwrap(),
            normal[1].as_f64().unwrap(),
            normal[2].as_f64().unwrap(),
        );
        let turned = DMat3::from_rotation_z(degrees.to_radians()) * rest;
        assert!(n.distance(turned) < 1e-9, "frame {frame}: normal {n}");
    }
    // A frame outside the shot is bad input, in one line.
    let out = glint()
        .args([
            "probe",
            shot.to_str().unwrap(),
            "--patch",
            "ball/sphere",
            "--frame",
            "31",
            "--uv",
            "0,0.5",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert_eq!(
        stderr(&out).trim_end().lines().count(),
        1,
        "{}",
        stderr(&out)
    );
}

#[test]
fn a_sheet_of_a_moving_shot_shows_the_ball_where_each_frame_poses_it() {
    let dir = tempfile::tempdir().unwrap();
    let shot = write_moving_ball(dir.path());
    let sheet = dir.path().join("sheet.png");
    let out = glint()
        .args([
            "sheet",
            shot.to_str().unwrap(),
            "--frames",
            "1,10",
            "--tile",
            &format!("{SIZE}x{SIZE}"),
            "--columns",
            "2",
            "--out",
            sheet.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let image = image::open(&sheet).unwrap().to_rgba8();
    let captions = ["frame 1".to_string(), "frame 10".to_string()];
    let layout = SheetLayout::new(&captions, (SIZE, SIZE), Some(2)).unwrap();
    assert_eq!(image.dimensions(), layout.size());
    // Where the ball is drawn in each tile: the tile is the frame as rendered, transparent
    // off the model.
    let drawn = |tile: usize, p: DVec3| {
        let (x, y) = pixel_of(p);
        let (ox, oy) = layout.tile_origin(tile);
        image.get_pixel(ox + x.round() as u32, oy + y.round() as u32)[3] > 0
    };
    let rest_left = DVec3::new(-0.7, 0.0, 0.0);
    let moved = ball_pose(10.0).0 + DVec3::new(0.6, 0.0, 0.0);
    assert!(
        drawn(0, rest_left) && !drawn(0, moved),
        "frame 1: the ball at rest"
    );
    assert!(
        drawn(1, moved) && !drawn(1, rest_left),
        "frame 10: the ball moved"
    );
}

/// How long any one event of the watch may take to show: far beyond what it needs, so that
/// only an event that never comes fails the test.
const DEADLINE: std::time::Duration = std::time::Duration::from_secs(120);

/// Whether the watched frame `frame` of the ball, 32×32, is drawn at world point `(x, z)`.
fn drawn_at(dir: &Path, frame: i64, (x, z): (f64, f64)) -> bool {
    let image = image::open(dir.join(format!("out/m.{frame:04}.png")))
        .unwrap()
        .to_rgba8();
    let scale = 32.0 / 6.0;
    let (px, py) = (15.5 + x * scale, 15.5 - z * scale);
    image.get_pixel(px.round() as u32, py.round() as u32)[3] > 0
}

/// The watching process, killed when the test ends however it ends.
struct Watching(std::process::Child);

impl Drop for Watching {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

#[test]
fn watch_renders_again_after_an_edit_of_a_transform_key() {
    use std::io::{BufRead, BufReader};
    use std::process::Stdio;

    let dir = tempfile::tempdir().unwrap();
    let shot = write_moving_ball(dir.path());
    let small = moving_ball_text().replace(&format!("({SIZE}, {SIZE})"), "(32, 32)");
    crate::common::ball_shot::save_as_an_editor_does(&shot, &small);
    let mut watching = Watching(
        glint()
            .args(["render", shot.to_str().unwrap(), "--watch"])
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .unwrap(),
    );
    let stdout = watching.0.stdout.take().unwrap();
    let (sender, lines) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stdout).lines().map_while(Result::ok) {
            if sender.send(line).is_err() {
                break;
            }
        }
    });
    let mut seen = Vec::new();
    let mut wait_for = |what: &str, wanted: &dyn Fn(&str) -> bool| loop {
        match lines.recv_timeout(DEADLINE) {
            Ok(line) => {
                seen.push(line.clone());
                if wanted(&line) {
                    return line;
                }
            }
            Err(_) => panic!("no {what} within {DEADLINE:?}; lines: {seen:#?}"),
        }
    };
    let written = |l: &str| l.contains("30 frames written");
    wait_for("first render", &written);
    wait_for("watching line", &|l: &str| l.starts_with("watching"));
    // Frame 25 holds the rise's last key: the ball's top is at z = 1.5, below (1.5, 1.78).
    let above = (1.5, 1.78);
    assert!(!drawn_at(dir.path(), 25, above) && drawn_at(dir.path(), 25, (1.5, 1.2)));

    let raised = small.replace("(20, (1.5, 0.0, 0.5))", "(20, (1.5, 0.0, 0.9))");
    assert_ne!(raised, small);
    crate::common::ball_shot::save_as_an_editor_does(&shot, &raised);
    let line = wait_for("render after the edit", &|l: &str| {
        written(l) && l.contains("moving.ron changed")
    });
    drop(watching);
    assert!(
        drawn_at(dir.path(), 25, above),
        "frame 25 shows the ball raised to z = 0.9: {line}"
    );
}

#[test]
fn the_patch_map_of_a_moving_shot_shows_the_model_where_the_frame_poses_it() {
    let dir = tempfile::tempdir().unwrap();
    let shot = write_moving_ball(dir.path());
    let map = |frame: &str| {
        let out_path = dir.path().join(format!("map{frame}.png"));
        let out = glint()
            .args(["patches", shot.to_str().unwrap(), "--map"])
            .arg(&out_path)
            .args(["--frame", frame, "--size", &format!("{SIZE}x{SIZE}")])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
        image::open(&out_path).unwrap().to_rgba8()
    };
    // Below the centre row, clear of the label: a point of the ball at rest, and one of the
    // ball where frame 10 has driven it.
    let rest_left = DVec3::new(-0.7, 0.0, -0.5);
    let moved = ball_pose(10.0).0 + DVec3::new(0.6, 0.0, -0.5);
    for (frame, shown, hidden) in [("1", rest_left, moved), ("10", moved, rest_left)] {
        let image = map(frame);
        let background = *image.get_pixel(0, 0);
        let at = |p: DVec3| {
            let (x, y) = pixel_of(p);
            *image.get_pixel(x.round() as u32, y.round() as u32)
        };
        assert_ne!(
            at(shown),
            background,
            "frame {frame}: the ball is drawn at {shown}"
        );
        assert_eq!(at(hidden), background, "frame {frame}: nothing at {hidden}");
    }
}
