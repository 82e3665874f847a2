//! Placing a highlight on a pixel (`RenderJob::place`, `glint place`) and pinning it to a surface
//! point (`pin`): checked against a closed form on the sphere, and against the centroid of the
//! rendered matte on the sphere, the teapot body and the whole turntable.

use std::path::{Path, PathBuf};

use glam::{DVec3, Vec2};
use glint::job::{LayerChoice, Overrides, RenderJob};
use glint::shot::Aov;

use crate::common::{glint_with, repo_file, stderr};

/// A shot of one model with one highlight entry, written into `dir`.
#[derive(Clone)]
struct TestShot<'a> {
    model: &'a str,
    selector: &'a str,
    camera: String,
    light: String,
    layer: String,
    frames: (i64, i64),
    size: (u32, u32),
    render: &'a str,
}

impl TestShot<'_> {
    fn write(&self, dir: &Path, name: &str) -> PathBuf {
        let text = format!(
            r#"Shot(
    resolution: ({w}, {h}),
    frames: ({f0}, {f1}),
    fps: 24,
    output: "out/{name}.####.png",
    instances: [(name: "m", file: "{model}", material: "grey")],
    materials: {{ "grey": Cel(base: (0.1, 0.1, 0.1), bands: [(0.0, (0.5, 0.5, 0.5))]) }},
    camera: {camera},
    light: {light},
    highlights: [(patches: "{selector}", expr: Layer({layer}))],
    render: {render},
)"#,
            w = self.size.0,
            h = self.size.1,
            f0 = self.frames.0,
            f1 = self.frames.1,
            model = repo_file(self.model).display(),
            camera = self.camera,
            light = self.light,
            selector = self.selector,
            layer = self.layer,
            render = self.render,
        );
        let path = dir.join(format!("{name}.ron"));
        std::fs::write(&path, text).unwrap();
        path
    }
}

/// A small round highlight moved by one translation.
fn translated(alpha: f32, beta: f32, epsilon: f32) -> String {
    format!(
        "(stack: [Translate(alpha: {alpha}, beta: {beta})], epsilon: {epsilon}, colour: (1.0, 1.0, 1.0))"
    )
}

fn job(path: &Path) -> RenderJob {
    let overrides = Overrides {
        aovs: Some(vec![Aov::Matte, Aov::PatchId]),
        ..Overrides::default()
    };
    RenderJob::load(path, &overrides).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The centroid, in pixel centres, of the matte within `radius` pixels of `at`, and whether the
/// matte is clear on the window's edge (the blob lies wholly inside).
fn matte_centroid(
    matte: &[f32],
    (width, height): (u32, u32),
    at: (f64, f64),
    radius: f64,
) -> Option<((f64, f64), bool)> {
    let (mut sum, mut sx, mut sy, mut edge) = (0.0, 0.0, 0.0, 0.0_f64);
    for y in 0..height {
        for x in 0..width {
            let (cx, cy) = (f64::from(x), f64::from(y));
            let d = ((cx - at.0).powi(2) + (cy - at.1).powi(2)).sqrt();
            let m = f64::from(matte[(y * width + x) as usize]);
            if d <= radius {
                sum += m;
                sx += m * cx;
                sy += m * cy;
                if d > radius - 1.5 {
                    edge = edge.max(m);
                }
            }
        }
    }
    (sum > 0.0).then(|| ((sx / sum, sy / sum), edge == 0.0))
}

/// How far the centroid of the matte within `radius` pixels of `at` lies from `at`, after
/// checking that there is a highlight there and that it lies wholly inside that window.
fn centroid_miss(matte: &[f32], size: (u32, u32), at: (f64, f64), radius: f64, what: &str) -> f64 {
    let (centroid, inside) = matte_centroid(matte, size, at, radius)
        .unwrap_or_else(|| panic!("{what}: no highlight near {at:?}"));
    assert!(inside, "{what}: the highlight is larger than the window");
    ((centroid.0 - at.0).powi(2) + (centroid.1 - at.1).powi(2)).sqrt()
}

/// The translation that puts the highlight centre on the unit sphere's point under `pixel`,
/// from the ray, the sphere and the half vector directly: `α = −(H, east)`,
/// `β = −(H, north)` at the hit point `p = N`, the sphere's frame (du, dv) being (east, north).
#[allow(clippy::too_many_arguments)]
fn sphere_closed_form(
    eye: DVec3,
    target: DVec3,
    perspective: Option<f64>,
    ortho_height: f64,
    light: DVec3,
    pixel: (f64, f64),
    (width, height): (u32, u32),
) -> (DVec3, Vec2) {
    let forward = (target - eye).normalize();
    let right = forward.cross(DVec3::Z).normalize();
    let up = right.cross(forward);
    let aspect = f64::from(width) / f64::from(height);
    let ndc_x = 2.0 * (pixel.0 + 0.5) / f64::from(width) - 1.0;
    let ndc_y = 1.0 - 2.0 * (pixel.1 + 0.5) / f64::from(height);
    let (origin, direction) = match perspective {
        Some(fov) => {
            let t = (fov.to_radians() / 2.0).tan();
            let d = forward + ndc_x * t * aspect * right + ndc_y * t * up;
            (eye, d.normalize())
        }
        None => {
            let half = ortho_height / 2.0;
            (
                eye + ndc_x * half * aspect * right + ndc_y * half * up,
                forward,
            )
        }
    };
    let b = origin.dot(direction);
    let c = origin.length_squared() - 1.0;
    let t = -b - (b * b - c).sqrt();
    let p = origin + t * direction;
    let v = match perspective {
        Some(_) => (eye - p).normalize(),
        None => -forward,
    };
    let h = (light.normalize() + v).normalize();
    let east = DVec3::new(-p.y, p.x, 0.0).normalize();
    let north = p.cross(east);
    let step = Vec2::new(-h.dot(east) as f32, -h.dot(north) as f32);
    (p, step)
}

#[test]
fn place_on_the_sphere_matches_the_closed_form_and_the_rendered_centroid() {
    let dir = tempfile::tempdir().unwrap();
    let size = (320, 240);
    let light = DVec3::new(0.3, -1.0, 0.5);
    let cases = [
        // (name, camera, eyes at frames 1 and 2, perspective fov)
        (
            "ortho",
            (DVec3::new(0.0, -6.0, 0.0), DVec3::new(-2.0, -5.5, 1.0)),
            None,
        ),
        (
            "persp",
            (DVec3::new(0.5, -5.0, 1.0), DVec3::new(3.0, -4.0, -1.0)),
            Some(30.0),
        ),
    ];
    let sphere = glint::geom::shapes::sphere(DVec3::ZERO, 1.0).unwrap();
    for (name, (eye1, eye2), fov) in cases {
        let projection = match fov {
            Some(f) => format!("Perspective(fov_y_degrees: {f})"),
            None => "Orthographic(height: 2.6)".to_string(),
        };
        let camera = format!(
            "(eye: [(1, ({}, {}, {})), (2, ({}, {}, {}))], target: (0.0, 0.0, 0.0), projection: {projection})",
            eye1.x, eye1.y, eye1.z, eye2.x, eye2.y, eye2.z
        );
        let shot = TestShot {
            model: "patches/sphere.ron",
            selector: "m/*",
            camera,
            light: format!(
                "Directional(towards: ({}, {}, {}))",
                light.x, light.y, light.z
            ),
            layer: translated(0.0, 0.0, 0.005),
            frames: (1, 2),
            size,
            render: "(preset: Final)",
        };
        let path = shot.write(dir.path(), name);
        let mut placing = job(&path);
        for (frame, eye) in [(1, eye1), (2, eye2)] {
            for pixel in [(160.0, 120.0), (135.0, 100.0), (190.0, 142.0)] {
                let placed = placing
                    .place(frame as f64, pixel, LayerChoice::default())
                    .unwrap();
                let (p, step) = sphere_closed_form(eye, DVec3::ZERO, fov, 2.6, light, pixel, size);
                let hit = sphere.point(placed.uv.0, placed.uv.1);
                assert!((hit - p).length() < 1e-6, "{name} {pixel:?}: {hit} vs {p}");
                assert!(
                    (placed.translation - step).length() < 1e-5,
                    "{name} frame {frame} {pixel:?}: {} vs closed form {step}",
                    placed.translation
                );

                // The highlight rendered with that translation is centred on the pixel.
                let solved = TestShot {
                    layer: translated(placed.translation.x, placed.translation.y, 0.005),
                    ..shot.clone()
                }
                .write(dir.path(), &format!("{name}_solved"));
                let image = job(&solved).render_frame(frame as f64).unwrap();
                let matte = image.aovs.matte.as_ref().unwrap();
                let what = format!("{name} frame {frame} {pixel:?}");
                let miss = centroid_miss(matte, size, pixel, 40.0, &what);
                assert!(miss < 1.0, "{what}: the centroid is {miss} px off");
            }
        }
    }
}

/// The turntable's camera and light, copied from the shipped shot.
fn turntable_camera_and_light() -> (String, String) {
    let text = std::fs::read_to_string(repo_file("shots/teapot_turntable.ron")).unwrap();
    let start = text.find("camera: (").unwrap() + "camera: ".len();
    let light = text.find("    light: ").unwrap();
    let camera = text[start..light]
        .trim_end()
        .trim_end_matches(',')
        .to_string();
    let end = light + text[light..].find('\n').unwrap();
    let light = text[light + "    light: ".len()..end]
        .trim_end_matches(',')
        .to_string();
    (camera, light)
}

#[test]
fn place_on_the_teapot_body_centres_the_rendered_highlight_on_the_pixel() {
    let dir = tempfile::tempdir().unwrap();
    let (camera, light) = turntable_camera_and_light();
    let size = (480, 270);
    let shot = TestShot {
        model: "patches/teapot.bpt",
        selector: "m/body",
        camera,
        light,
        layer: translated(0.0, 0.0, 0.0005),
        frames: (1, 96),
        size,
        render: "(preset: Final)",
    };
    let path = shot.write(dir.path(), "body");
    let mut placing = job(&path);
    for (frame, pixels) in [
        (1, [(185.0, 150.0), (230.0, 175.0), (205.0, 200.0)]),
        (60, [(200.0, 140.0), (250.0, 180.0), (165.0, 170.0)]),
    ] {
        for pixel in pixels {
            let placed = placing
                .place(f64::from(frame), pixel, LayerChoice::default())
                .unwrap_or_else(|e| panic!("frame {frame} {pixel:?}: {e}"));
            let solved = TestShot {
                layer: translated(placed.translation.x, placed.translation.y, 0.0005),
                ..shot.clone()
            }
            .write(dir.path(), "body_solved");
            let image = job(&solved).render_frame(f64::from(frame)).unwrap();
            let matte = image.aovs.matte.as_ref().unwrap();
            let what = format!("frame {frame} {pixel:?}");
            let miss = centroid_miss(matte, size, pixel, 30.0, &what);
            assert!(miss < 1.0, "{what}: the centroid is {miss} px off");
        }
    }
}

/// Where the pinned point of `job`'s shot is drawn at `frame`: its image position (pixel
/// centres at integers), if it lies in front of the eye.
fn projected(job: &RenderJob, patch: usize, uv: (f64, f64), frame: f64) -> Option<(f64, f64)> {
    let shot = job.shot();
    let camera = shot.at(frame).camera;
    let settings = job.settings();
    let p = shot.library.patches[patch]
        .surface
        .point(uv.0, uv.1)
        .as_vec3();
    let clip =
        camera.view_projection(settings.width as f32 / settings.height as f32) * p.extend(1.0);
    (clip.w > 0.0).then(|| {
        let ndc = clip.truncate() / clip.w;
        (
            (f64::from(ndc.x) + 1.0) * 0.5 * f64::from(settings.width) - 0.5,
            (1.0 - f64::from(ndc.y)) * 0.5 * f64::from(settings.height) - 0.5,
        )
    })
}

/// The turntable with a small highlight on the body, pinned to `(u, v)` of body patch 4 by
/// `pin`, or moved by `stack` alone.
fn pinned_turntable(dir: &Path, name: &str, layer_tail: &str) -> PathBuf {
    let (camera, light) = turntable_camera_and_light();
    TestShot {
        model: "patches/teapot.bpt",
        selector: "m/body",
        camera,
        light,
        layer: format!("(epsilon: 0.0002, colour: (1.0, 1.0, 1.0), {layer_tail})"),
        frames: (1, 96),
        size: (640, 360),
        render: "(preset: Preview, frames: Refined)",
    }
    .write(dir, name)
}

#[test]
fn a_pinned_highlight_stays_on_its_point_over_the_whole_turntable() {
    let dir = tempfile::tempdir().unwrap();
    let uv = (0.63, 0.39);
    let pin = format!("stack: [], pin: (patch: \"m/4\", u: {}, v: {})", uv.0, uv.1);
    let mut pinned = job(&pinned_turntable(dir.path(), "pinned", &pin));
    // The same highlight with the translation the pin solves on frame 1, kept on every frame.
    let first = pinned.shot().at(1.0).highlights[0].layers()[0].stack[0].clone();
    let glint::highlight::Op::Translate { alpha, beta } = first else {
        panic!("the pin puts a translation first: {first:?}");
    };
    let fixed = format!("stack: [Translate(alpha: {alpha}, beta: {beta})]");
    let mut unpinned = job(&pinned_turntable(dir.path(), "fixed", &fixed));

    let (mut checked, mut drift) = (0, 0.0_f64);
    for frame in 1..=96 {
        let frame = f64::from(frame);
        let at = projected(&pinned, 4, uv, frame).unwrap();
        let image = pinned.render_frame(frame).unwrap();
        let (w, h) = (image.width, image.height);
        let pixel = (at.0.round() as u32).min(w - 1) + (at.1.round() as u32).min(h - 1) * w;
        if image.aovs.patch_id.as_ref().unwrap()[pixel as usize] != 4 {
            continue; // The point is hidden on this frame.
        }
        let matte = image.aovs.matte.as_ref().unwrap();
        let what = format!("frame {frame}, pinned point at {at:?}");
        let miss = centroid_miss(matte, (w, h), at, 30.0, &what);
        assert!(miss < 1.0, "{what}: the centroid is {miss} px off");
        checked += 1;

        // Without the pin the highlight leaves the point.
        let image = unpinned.render_frame(frame).unwrap();
        let matte = image.aovs.matte.as_ref().unwrap();
        drift = drift.max(
            matte_centroid(matte, (w, h), at, 30.0).map_or(f64::INFINITY, |(c, _)| {
                ((c.0 - at.0).powi(2) + (c.1 - at.1).powi(2)).sqrt()
            }),
        );
    }
    assert!(
        checked >= 80,
        "the pinned point was visible on only {checked} of 96 frames"
    );
    assert!(
        drift > 5.0,
        "without the pin the highlight drifts only {drift} px: the test could not tell"
    );
}

#[test]
fn place_refuses_what_it_cannot_place_with_one_line_and_exit_code_2() {
    let dir = tempfile::tempdir().unwrap();
    let (camera, light) = turntable_camera_and_light();
    let write = |name: &str, selector: &'static str, layer: &str| {
        TestShot {
            model: "patches/teapot.bpt",
            selector,
            camera: camera.clone(),
            light: light.clone(),
            layer: layer.to_string(),
            frames: (1, 2),
            size: (320, 180),
            render: "(preset: Preview)",
        }
        .write(dir.path(), name)
    };
    let movable = write("ok", "m/body", &translated(0.0, 0.0, 0.01));
    let bare = write(
        "bare",
        "m/body",
        "(stack: [Scale(delta: 0.5)], epsilon: 0.01, colour: (1.0, 1.0, 1.0))",
    );
    let pinned = write(
        "pinned",
        "m/body",
        "(stack: [], epsilon: 0.01, colour: (1.0, 1.0, 1.0), pin: (patch: \"m/body\", member: 1, u: 0.5, v: 0.5))",
    );
    let lid = write("lid", "m/lid", &translated(0.0, 0.0, 0.01));
    let cases = [
        (&movable, "2,2", "shows no patch of the model"),
        (&movable, "400,20", "outside the 320×180 image"),
        (&bare, "125,95", "no Translate"),
        (&pinned, "125,95", "pin: (patch: \"m/"),
        (&lid, "125,95", "has no designed highlight"),
    ];
    for (shot, pixel, expected) in cases {
        let out = glint_with(&[
            "place",
            shot.to_str().unwrap(),
            "--frame",
            "1",
            "--pixel",
            pixel,
        ]);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{pixel}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.contains(expected),
            "{pixel}: expected '{expected}' in {err}"
        );
        assert!(out.stdout.is_empty());
    }

    // A good pixel prints the key; --json gives the same numbers to a script.
    let out = glint_with(&[
        "place",
        movable.to_str().unwrap(),
        "--pixel",
        "125,95",
        "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(report["path"], "highlights[0].layers[0].stack[0]");
    assert!(report["patch"].as_str().unwrap().starts_with("m/"));
    assert_eq!(report["parts"][0], "m/body");
    let residuals = report["residuals"].as_array().unwrap();
    assert_eq!(residuals.len(), 8, "one residual per body patch");
    let own = residuals
        .iter()
        .find(|r| r["patch"] == report["patch"])
        .unwrap();
    assert!(own["nearest"].as_f64().unwrap() < 1e-4 && own["covered"] == true);
}

#[test]
fn a_pin_on_no_patch_or_outside_its_domain_is_refused_where_it_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let (camera, light) = turntable_camera_and_light();
    for (pin, expected) in [
        (
            "(patch: \"m/bdy\", u: 0.5, v: 0.5)",
            "did you mean \"m/body\"?",
        ),
        (
            "(patch: \"m/body\", member: 8, u: 0.5, v: 0.5)",
            "member must be below 8",
        ),
        (
            "(patch: \"m/4\", u: [(1, 0.5), (2, 1.5)], v: 0.5)",
            "outside the domain",
        ),
    ] {
        let path = TestShot {
            model: "patches/teapot.bpt",
            selector: "m/body",
            camera: camera.clone(),
            light: light.clone(),
            layer: format!("(stack: [], epsilon: 0.01, colour: (1.0, 1.0, 1.0), pin: {pin})"),
            frames: (1, 2),
            size: (320, 180),
            render: "(preset: Preview)",
        }
        .write(dir.path(), "bad_pin");
        let out = glint_with(&["render", path.to_str().unwrap(), "--frames", "1"]);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains(expected), "expected '{expected}' in {err}");
        // Placed at the pin.
        let text = std::fs::read_to_string(&path).unwrap();
        let line = 1 + text.lines().position(|l| l.contains("pin:")).unwrap();
        assert!(err.contains(&format!("bad_pin.ron:{line}:")), "{err}");
    }
}

/// `shots/sphere_ops.ron` and the patch file it reads, copied into `dir` as they sit in the
/// repository; the copied shot's path.
fn sphere_ops_copy(dir: &Path) -> PathBuf {
    let shots = dir.join("shots");
    std::fs::create_dir_all(&shots).unwrap();
    std::fs::create_dir_all(dir.join("patches")).unwrap();
    std::fs::copy(
        repo_file("patches/sphere.ron"),
        dir.join("patches/sphere.ron"),
    )
    .unwrap();
    let shot = shots.join("sphere_ops.ron");
    std::fs::copy(repo_file("shots/sphere_ops.ron"), &shot).unwrap();
    shot
}

#[test]
fn place_write_keys_the_translation_and_changes_nothing_else() {
    let dir = tempfile::tempdir().unwrap();
    let shot = sphere_ops_copy(dir.path());
    let before = std::fs::read_to_string(&shot).unwrap();

    let json = glint_with(&[
        "place",
        shot.to_str().unwrap(),
        "--frame",
        "30",
        "--pixel",
        "300,200",
        "--json",
    ]);
    assert!(json.status.success(), "{}", stderr(&json));
    let report: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
    let out = glint_with(&[
        "place",
        shot.to_str().unwrap(),
        "--frame",
        "30",
        "--pixel",
        "300,200",
        "--write",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let after = std::fs::read_to_string(&shot).unwrap();

    // Only the two tracks changed: α gained a key at 30 among its keys, β became that key.
    let tracks = |text: &str| glint::shot::track_texts(text).unwrap();
    let (old, new) = (tracks(&before), tracks(&after));
    assert_eq!(old.len(), new.len());
    let changed: Vec<String> = old
        .iter()
        .zip(&new)
        .filter(|(a, b)| a != b)
        .map(|(a, _)| a.0.to_string())
        .collect();
    assert_eq!(
        changed,
        [
            "highlights[0].layers[0].stack[0].alpha",
            "highlights[0].layers[0].stack[0].beta"
        ]
    );
    let unchanged_outside = |text: &str| {
        let line = text.lines().position(|l| l.contains("Translate(")).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        (lines[..line].join("\n"), lines[line + 1..].join("\n"))
    };
    assert_eq!(unchanged_outside(&before), unchanged_outside(&after));

    // Read back at frame 30, the layer's translation is the one placed.
    let loaded = glint::shot::load_shot(&shot).unwrap();
    let state = loaded.at(30.0);
    let glint::highlight::Op::Translate { alpha, beta } = state.highlights[0].layers()[0].stack[0]
    else {
        panic!("the first operation is a translation");
    };
    let want = (
        report["alpha"].as_f64().unwrap(),
        report["beta"].as_f64().unwrap(),
    );
    assert!(
        (f64::from(alpha) - want.0).abs() < 1e-5,
        "{alpha} vs {}",
        want.0
    );
    assert!(
        (f64::from(beta) - want.1).abs() < 1e-5,
        "{beta} vs {}",
        want.1
    );
}

#[test]
fn place_pin_writes_a_pin_on_the_point_under_the_pixel_and_moves_it() {
    let dir = tempfile::tempdir().unwrap();
    let shot = sphere_ops_copy(dir.path());
    let before = std::fs::read_to_string(&shot).unwrap();
    assert!(!before.contains("pin:"));
    for (pixel, at) in [("300,200", (300.0, 200.0)), ("180,260", (180.0, 260.0))] {
        let out = glint_with(&[
            "place",
            shot.to_str().unwrap(),
            "--frame",
            "30",
            "--pixel",
            pixel,
            "--pin",
            "--write",
            "--json",
        ]);
        assert!(out.status.success(), "{}", stderr(&out));
        let report: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
        let text = std::fs::read_to_string(&shot).unwrap();
        assert_eq!(text.matches("pin:").count(), 1, "{text}");
        assert!(text.contains(report["pin"].as_str().unwrap()), "{text}");
        // The pinned point is the one under the pixel: it projects back onto it.
        let mut pinned = job(&shot);
        let patch = pinned
            .shot()
            .pinned_patch(0, 0)
            .expect("the first layer is pinned");
        let uv = (report["u"].as_f64().unwrap(), report["v"].as_f64().unwrap());
        let back = projected(&pinned, patch, uv, 30.0).unwrap();
        let miss = ((back.0 - at.0).powi(2) + (back.1 - at.1).powi(2)).sqrt();
        assert!(miss < 0.5, "{pixel}: the pin projects to {back:?}");
        // Every track of the file as it was is as it was; the new ones are the pin's.
        let tracks = |text: &str| glint::shot::track_texts(text).unwrap();
        let (old, new) = (tracks(&before), tracks(&text));
        let added: Vec<String> = new
            .iter()
            .filter(|t| !old.contains(t))
            .map(|t| t.0.to_string())
            .collect();
        assert!(old.iter().all(|t| new.contains(t)));
        assert_eq!(
            added,
            [
                "highlights[0].layers[0].pin.u",
                "highlights[0].layers[0].pin.v"
            ]
        );
        assert!(pinned.render_frame(30.0).is_ok());
    }
}

/// `shot` with a shade entry translating the light of the body's tone, and its highlight
/// reading the light `reads` (`Plain` or `Designed`).
fn with_designed_light(shot: &Path, reads: &str) -> PathBuf {
    let text = std::fs::read_to_string(shot).unwrap();
    let tail = "))],\n    render:";
    assert!(text.contains(tail), "{text}");
    let designed = text.replace(
        tail,
        &format!(
            "), light: {reads})],\n    shade: [(patches: \"m/body\", stack: \
             [Translate(alpha: 0.3, beta: 0.15)])],\n    render:"
        ),
    );
    let path = shot.with_file_name(format!("designed_{reads}.ron"));
    std::fs::write(&path, designed).unwrap();
    path
}

#[test]
fn a_pinned_highlight_reading_the_designed_light_stays_on_its_point() {
    // The pin is solved on the half vector from L' where the highlight reads the designed
    // light: its matte stays on the point. The translation solved on the plain light, drawn
    // with the designed one, leaves it, so a pin solved on the wrong light would be seen.
    let dir = tempfile::tempdir().unwrap();
    let uv = (0.63, 0.39);
    let pin = format!("stack: [], pin: (patch: \"m/4\", u: {}, v: {})", uv.0, uv.1);
    let base = pinned_turntable(dir.path(), "pinned", &pin);
    let mut designed = job(&with_designed_light(&base, "Designed"));
    let plain = job(&with_designed_light(&base, "Plain"));
    let (mut checked, mut drift) = (0, 0.0_f64);
    for frame in (1..=96).step_by(5) {
        let frame = f64::from(frame);
        let at = projected(&designed, 4, uv, frame).unwrap();
        let image = designed.render_frame(frame).unwrap();
        let (w, h) = (image.width, image.height);
        let pixel = (at.0.round() as u32).min(w - 1) + (at.1.round() as u32).min(h - 1) * w;
        if image.aovs.patch_id.as_ref().unwrap()[pixel as usize] != 4 {
            continue;
        }
        let what = format!("frame {frame}, pinned point at {at:?}");
        let miss = centroid_miss(image.aovs.matte.as_ref().unwrap(), (w, h), at, 30.0, &what);
        assert!(miss < 1.0, "{what}: the centroid is {miss} px off");
        checked += 1;

        // The plain light's pin translation, drawn with the designed light.
        let solved = plain.shot().at(frame).highlights[0].layers()[0].stack[0].clone();
        let glint::highlight::Op::Translate { alpha, beta } = solved else {
            panic!("the pin puts a translation first: {solved:?}");
        };
        let fixed = format!("stack: [Translate(alpha: {alpha}, beta: {beta})]");
        let fixed = pinned_turntable(dir.path(), "fixed", &fixed);
        let mut wrong = job(&with_designed_light(&fixed, "Designed"));
        let image = wrong.render_frame(frame).unwrap();
        let matte = image.aovs.matte.as_ref().unwrap();
        drift = drift.max(
            matte_centroid(matte, (w, h), at, 30.0).map_or(f64::INFINITY, |(c, _)| {
                ((c.0 - at.0).powi(2) + (c.1 - at.1).powi(2)).sqrt()
            }),
        );
    }
    assert!(
        checked >= 15,
        "the point was visible on {checked} of 20 frames"
    );
    assert!(
        drift > 5.0,
        "the plain light's pin is only {drift} px off under the designed light: the test could \
         not tell"
    );
}

/// Reference blob count for a layer translated by `(α, β)` on one patch, seen orthographically
/// along `view` (unit, toward the eye) under a directional light `light` (unit, toward it),
/// written apart from glint's highlight code: on an `n × n` grid over the patch's domain, the
/// frame `(du, s·dv, s·N)` turned toward the eye (`s = sign(N·V)`), `h = (H·du, H·dv, H·N)` in
/// it, and the highlight where `1 − h_z / |h + (α, β, 0)| < ε`; its connected pieces (wrapping
/// round a closed direction of the domain), counting those whose least point is inside the
/// domain, or on a closed edge, and where the eye sees the patch's front (each case's back is
/// inside a closed body).
fn reference_centres(
    surface: &glint::geom::NurbsSurface,
    (view, light): (DVec3, DVec3),
    (alpha, beta, epsilon): (f64, f64, f64),
    (n, wrap_u, wrap_v): (usize, bool, bool),
) -> usize {
    let h = (light + view).normalize();
    let domain = surface.domain();
    let value = |i: usize, j: usize| {
        let u = domain.u.0 + (domain.u.1 - domain.u.0) * i as f64 / (n - 1) as f64;
        let v = domain.v.0 + (domain.v.1 - domain.v.0) * j as f64 / (n - 1) as f64;
        let f = surface.frame(u, v);
        let s = if f.normal.dot(view) < 0.0 { -1.0 } else { 1.0 };
        let local = DVec3::new(h.dot(f.du), s * h.dot(f.dv), s * h.dot(f.normal));
        1.0 - local.z / (local + DVec3::new(alpha, beta, 0.0)).length()
    };
    let values: Vec<f64> = (0..n * n).map(|k| value(k / n, k % n)).collect();
    let front = |k: usize| {
        let (i, j) = (k / n, k % n);
        let u = domain.u.0 + (domain.u.1 - domain.u.0) * i as f64 / (n - 1) as f64;
        let v = domain.v.0 + (domain.v.1 - domain.v.0) * j as f64 / (n - 1) as f64;
        surface.frame(u, v).normal.dot(view) >= 0.0
    };
    let inside = |k: usize| values[k] < epsilon;
    let mut seen = vec![false; n * n];
    let mut count = 0;
    for start in 0..n * n {
        if !inside(start) || seen[start] {
            continue;
        }
        seen[start] = true;
        let mut stack = vec![start];
        let mut least = (f64::INFINITY, 0usize);
        while let Some(k) = stack.pop() {
            if values[k] < least.0 {
                least = (values[k], k);
            }
            let (i, j) = (k / n, k % n);
            let step = |x: usize, d: i64, wrap: bool| -> Option<usize> {
                let y = x as i64 + d;
                if (0..n as i64).contains(&y) {
                    Some(y as usize)
                } else if wrap {
                    // The first and last samples of a closed direction are one point.
                    Some(if y < 0 { n - 2 } else { 1 })
                } else {
                    None
                }
            };
            let around = [
                step(i, -1, wrap_u).map(|a| (a, j)),
                step(i, 1, wrap_u).map(|a| (a, j)),
                step(j, -1, wrap_v).map(|b| (i, b)),
                step(j, 1, wrap_v).map(|b| (i, b)),
            ];
            for (a, b) in around.into_iter().flatten() {
                let m = a * n + b;
                if inside(m) && !seen[m] {
                    seen[m] = true;
                    stack.push(m);
                }
            }
        }
        let (i, j) = (least.1 / n, least.1 % n);
        let on_open_edge =
            (!wrap_u && (i == 0 || i == n - 1)) || (!wrap_v && (j == 0 || j == n - 1));
        if !on_open_edge && front(least.1) {
            count += 1;
        }
    }
    count
}

#[test]
fn place_lists_every_centre_a_layer_has_one_on_the_sphere_two_where_normals_repeat() {
    let dir = tempfile::tempdir().unwrap();
    let (eye, light) = (
        DVec3::new(1.0, -6.0, 2.0),
        DVec3::new(0.3, -1.0, 0.5).normalize(),
    );
    let view = eye.normalize();
    let camera = format!(
        "(eye: ({}, {}, {}), target: (0.0, 0.0, 0.0), projection: Orthographic(height: {{h}}))",
        eye.x, eye.y, eye.z
    );
    // (model, selector, orthographic height, ε, the pixel placed on, whether the reference
    // wraps in u and in v, the patch whose centres are counted): the torus, whose normals come
    // round twice, the teapot's spout, whose S-bend turns its normals back, and its lid, whose
    // normals repeat along a radius.
    let cases = [
        (
            "patches/sphere.ron",
            "m/*",
            2.6,
            0.05,
            (160.0, 120.0),
            (true, false),
            0usize,
        ),
        (
            "patches/torus.ron",
            "m/*",
            6.0,
            0.05,
            (162.0, 130.0),
            (true, true),
            0,
        ),
        (
            "patches/teapot.bpt",
            "m/spout",
            6.0,
            0.01,
            (245.0, 88.0),
            (false, false),
            16,
        ),
        (
            "patches/teapot.bpt",
            "m/lid",
            6.0,
            0.002,
            (155.0, 22.0),
            (false, false),
            25,
        ),
        // The lid with a larger ε: the two least points are one streak, joined along a curve
        // in (u, v) that a straight segment between them leaves.
        (
            "patches/teapot.bpt",
            "m/lid",
            6.0,
            0.01,
            (150.0, 22.0),
            (false, false),
            25,
        ),
    ];
    for (model, selector, height, epsilon, pixel, (wrap_u, wrap_v), counted) in cases {
        let shot = TestShot {
            model,
            selector,
            camera: camera.replace("{h}", &height.to_string()),
            light: format!(
                "Directional(towards: ({}, {}, {}))",
                light.x, light.y, light.z
            ),
            layer: translated(0.0, 0.0, epsilon),
            frames: (1, 1),
            size: (320, 240),
            render: "(preset: Final)",
        };
        let path = shot.write(dir.path(), "centres");
        let mut placing = job(&path);
        let placed = placing
            .place(1.0, pixel, LayerChoice::default())
            .unwrap_or_else(|e| panic!("{model}: {e}"));
        let library = &placing.shot().library;
        let (alpha, beta) = (
            f64::from(placed.translation.x),
            f64::from(placed.translation.y),
        );
        let on_patch: Vec<_> = placed
            .centres
            .iter()
            .filter(|c| c.patch == counted)
            .collect();
        let expected = reference_centres(
            &library.patches[counted].surface,
            (view, light),
            (alpha, beta, f64::from(epsilon)),
            (301, wrap_u, wrap_v),
        );
        println!(
            "{model}: {} centres on patch {counted}, {expected} in the reference; all: {:?}",
            on_patch.len(),
            placed.centres
        );
        assert_eq!(on_patch.len(), expected, "{model}");
        match (model, epsilon) {
            ("patches/sphere.ron", _) => assert_eq!(placed.centres.len(), 1, "one on the sphere"),
            ("patches/teapot.bpt", e) if selector == "m/lid" && e > 0.005 => {
                assert_eq!(on_patch.len(), 1, "one streak on the lid");
            }
            _ => assert!(on_patch.len() >= 2, "{model}: a second centre"),
        }
        // Each centre with the pixel it lands on, and the pixels apart.
        for c in &placed.centres {
            let at = c.pixel.expect("a pixel for every centre");
            assert!(at.pixel.0.is_finite() && at.pixel.1.is_finite());
        }
        for (a, b) in on_patch.iter().zip(on_patch.iter().skip(1)) {
            let (p, q) = (a.pixel.unwrap().pixel, b.pixel.unwrap().pixel);
            assert!(
                (p.0 - q.0).hypot(p.1 - q.1) > 2.0,
                "{model}: two centres at one pixel"
            );
        }
        // The centre placed on lands on the pixel asked for.
        let placed_centre = placed
            .centres
            .iter()
            .filter_map(|c| c.pixel)
            .map(|p| (p.pixel.0 - pixel.0).hypot(p.pixel.1 - pixel.1))
            .fold(f64::INFINITY, f64::min);
        assert!(
            placed_centre < 1.0,
            "{model}: {placed_centre} px from the pixel"
        );
    }
}

/// `place --at PATCH:U,V` names the surface point instead of pointing at it: on a point the
/// frame shows it solves what `--pixel` solves on that point's pixel; on a point the frame
/// hides (the sphere's far side) it still solves, and says where the point lands; `--pin`
/// pins there; a name the model lacks is refused with the nearest one.
#[test]
fn place_at_a_named_point_solves_as_at_its_pixel_seen_or_not() {
    let dir = tempfile::tempdir().unwrap();
    let shot = sphere_ops_copy(dir.path());
    let shot_arg = shot.to_str().unwrap();
    let json = |args: &[&str]| -> serde_json::Value {
        let mut all = vec!["place", shot_arg, "--frame", "30", "--json"];
        all.extend_from_slice(args);
        let out = glint_with(&all);
        assert!(out.status.success(), "{args:?}: {}", stderr(&out));
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let by_pixel = json(&["--pixel", "300,200"]);
    let (patch, u, v) = (
        by_pixel["patch"].as_str().unwrap().to_string(),
        by_pixel["u"].as_f64().unwrap(),
        by_pixel["v"].as_f64().unwrap(),
    );
    let by_name = json(&["--at", &format!("{patch}:{u},{v}")]);
    for key in ["alpha", "beta"] {
        let (a, b) = (
            by_pixel[key].as_f64().unwrap(),
            by_name[key].as_f64().unwrap(),
        );
        assert!((a - b).abs() < 1e-5, "{key}: {a} by pixel, {b} by name");
    }
    // The point lands on the pixel pointed at.
    let pixel = &by_name["pixel"];
    assert!(
        (pixel[0].as_f64().unwrap() - 300.0).abs() < 0.05
            && (pixel[1].as_f64().unwrap() - 200.0).abs() < 0.05,
        "{pixel}"
    );

    // The far side: solved all the same, a translation within the unit disc, with a warning
    // that the frame does not show the point.
    let far = format!("{patch}:{},{v}", (u + 0.5).rem_euclid(1.0));
    let hidden = json(&["--at", &far]);
    let (a, b) = (
        hidden["alpha"].as_f64().unwrap(),
        hidden["beta"].as_f64().unwrap(),
    );
    assert!(a.hypot(b) <= 1.0 + 1e-6, "({a}, {b})");
    let out = glint_with(&["place", shot_arg, "--frame", "30", "--at", &far]);
    assert!(out.status.success());
    assert!(stderr(&out).contains("does not show"), "{}", stderr(&out));
    let out = glint_with(&[
        "place",
        shot_arg,
        "--frame",
        "30",
        "--at",
        &format!("{patch}:{u},{v}"),
    ]);
    assert!(!stderr(&out).contains("does not show"), "{}", stderr(&out));

    // Pinned there.
    let out = glint_with(&[
        "place",
        shot_arg,
        "--frame",
        "30",
        "--at",
        &format!("{patch}:0.25,0.5"),
        "--pin",
        "--write",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = std::fs::read_to_string(&shot).unwrap();
    assert!(
        text.contains(&format!("pin: (patch: \"{patch}\", u: 0.25, v: 0.5)")),
        "{text}"
    );

    // A misspelt patch.
    let out = glint_with(&["place", shot_arg, "--at", "ball/spere:0.2,0.5"]);
    assert_eq!(out.status.code(), Some(2));
    let err = stderr(&out);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("did you mean \"ball/sphere\""), "{err}");
}
