//! `glint tune`'s answers checked against what they claim, by other means than the server's own:
//! a pick against `glint probe` and the rendered matte, a final-quality frame against the final
//! preset's render, the overlays against the matte and patch ids they draw from, and `--bind` /
//! `--allow-host` against the requests they should let in and keep out.

use std::net::SocketAddr;
use std::path::{Path, PathBuf};

use glint::formats::image_encoding::colour_rgba8;
use glint::job::{Overrides, RenderJob};
use glint::shot::{Aov, Preset};
use glint_cli::tune::{ServerOptions, Session, TuneServer};
use serde_json::{json, Value};

use crate::common::http::{request, Reply};
use crate::common::{glint, repo_file, stderr};

const WIDTH: u32 = 192;
const HEIGHT: u32 = 108;

/// A copy of `shots/teapot_turntable.ron` with the files it reads, served at WIDTH × HEIGHT.
struct Served {
    _dir: tempfile::TempDir,
    shot: PathBuf,
    server: TuneServer,
}

fn copy_turntable(dir: &Path) -> PathBuf {
    for folder in ["shots/looks", "patches"] {
        std::fs::create_dir_all(dir.join(folder)).unwrap();
    }
    for file in [
        "shots/teapot_turntable.ron",
        "shots/looks/studio.ron",
        "patches/teapot.bpt",
        "patches/teapot.parts.ron",
    ] {
        std::fs::copy(repo_file(file), dir.join(file)).unwrap();
    }
    dir.join("shots/teapot_turntable.ron")
}

impl Served {
    fn new() -> Self {
        let dir = tempfile::tempdir().unwrap();
        let shot = copy_turntable(dir.path());
        let session = Session::open(&shot, Some((WIDTH, HEIGHT))).expect("the shot opens");
        let server =
            TuneServer::start(session, &ServerOptions::default()).expect("the server starts");
        Self {
            _dir: dir,
            shot,
            server,
        }
    }

    fn post(&self, target: &str, body: &Value) -> Reply {
        let token = self.server.token().to_string();
        let body = serde_json::to_vec(body).unwrap();
        request(
            self.server.address(),
            "POST",
            target,
            &[
                ("X-Glint-Token", &token),
                ("Content-Type", "application/json"),
            ],
            &body,
        )
    }

    /// The frame's RGBA8 pixels as the server sends them raw.
    fn raw_frame(&self, body: &Value) -> Vec<u8> {
        let reply = self.post("/api/frame?format=raw", body);
        assert_eq!(reply.status, 200, "{}", reply.text());
        assert_eq!(reply.body.len(), (WIDTH * HEIGHT * 4) as usize);
        reply.body.clone()
    }
}

/// What a local render of `shot` at `frame` under `preset` gives: its colour as the server
/// encodes colour, its matte and its patch ids.
struct Local {
    rgba: Vec<u8>,
    matte: Vec<f32>,
    ids: Vec<u32>,
}

fn render_locally(shot: &Path, frame: f64, preset: Preset) -> Local {
    let overrides = Overrides {
        size: Some((WIDTH, HEIGHT)),
        preset: Some(preset),
        aovs: Some(vec![Aov::Matte, Aov::PatchId]),
        ..Overrides::default()
    };
    let mut job = RenderJob::load(shot, &overrides).unwrap();
    let image = job.render_frame(frame).unwrap();
    Local {
        rgba: colour_rgba8(&image.colour),
        matte: image.aovs.matte.unwrap(),
        ids: image.aovs.patch_id.unwrap(),
    }
}

/// `glint probe`'s image position of (u, v) on `patch` at `frame`, at the served size, and
/// whether it says the frame shows the point (under the final preset, whose fine mesh puts the
/// depth of what it draws close to the surface's).
fn probed_pixel(shot: &Path, patch: &str, uv: [f64; 2], frame: f64) -> ((f64, f64), bool) {
    let out = glint()
        .args([
            "probe",
            shot.to_str().unwrap(),
            "--patch",
            patch,
            "--uv",
            &format!("{},{}", uv[0], uv[1]),
            "--frame",
            &frame.to_string(),
            "--size",
            &format!("{WIDTH}x{HEIGHT}"),
            "--preset",
            "final",
        ])
        .output()
        .unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    let probed: Value = serde_json::from_slice(&out.stdout).unwrap();
    let image = &probed[0]["image"];
    let pixel = (
        image["pixel"][0].as_f64().unwrap(),
        image["pixel"][1].as_f64().unwrap(),
    );
    (pixel, image["visible"].as_bool().unwrap())
}

/// Whether pixel `(x, y)` and its eight neighbours all satisfy `test`.
fn all_around(x: u32, y: u32, test: impl Fn(usize) -> bool) -> bool {
    (-1i64..=1).all(|dy| {
        (-1i64..=1).all(|dx| {
            let (px, py) = (i64::from(x) + dx, i64::from(y) + dy);
            px >= 0
                && py >= 0
                && px < i64::from(WIDTH)
                && py < i64::from(HEIGHT)
                && test((py as u32 * WIDTH + px as u32) as usize)
        })
    })
}

#[test]
fn a_pick_is_where_probe_puts_its_point_with_the_parts_and_the_layers_the_matte_shows() {
    let served = Served::new();
    let frame = 1.0;
    let local = render_locally(&served.shot, frame, Preset::Preview);
    let (mut picked, mut covered, mut uncovered, mut parts_seen) = (0, 0, 0, Vec::new());
    for y in (6..HEIGHT - 6).step_by(9) {
        for x in (6..WIDTH - 6).step_by(11) {
            let id = local.ids[(y * WIDTH + x) as usize];
            // Well inside one patch: a pick there names it.
            if id == u32::MAX || !all_around(x, y, |k| local.ids[k] == id) {
                continue;
            }
            let reply = served.post("/api/pick", &json!({"frame": frame, "x": x, "y": y}));
            assert_eq!(reply.status, 200, "({x}, {y}): {}", reply.text());
            let pick = reply.json();
            let patch = pick["patch"].as_str().unwrap().to_string();
            assert_eq!(patch, format!("teapot/{id}"), "({x}, {y})");
            let uv = [
                pick["uv"][0].as_f64().unwrap(),
                pick["uv"][1].as_f64().unwrap(),
            ];
            let ((px, py), visible) = probed_pixel(&served.shot, &patch, uv, frame);
            assert!(
                visible,
                "({x}, {y}): probe says {patch} at {uv:?} is hidden"
            );
            let off = (px - f64::from(x)).hypot(py - f64::from(y));
            assert!(off < 0.25, "({x}, {y}): probe puts {uv:?} at ({px}, {py})");
            // The parts file: teapot.parts.ron groups patches by eights and fours.
            let expected_part = match id {
                0..=3 => "teapot/rim",
                4..=11 => "teapot/body",
                12..=15 => "teapot/handle",
                16..=19 => "teapot/spout",
                20..=23 => "teapot/knob",
                24..=27 => "teapot/lid",
                _ => "teapot/bottom",
            };
            let parts: Vec<&str> = pick["parts"]
                .as_array()
                .unwrap()
                .iter()
                .filter_map(Value::as_str)
                .collect();
            assert_eq!(parts, [expected_part], "({x}, {y})");
            if !parts_seen.contains(&expected_part) {
                parts_seen.push(expected_part);
            }
            // The layers it names cover the point: where the matte is whole all around the
            // pixel, the one layer of its entry covers; where it is empty all around, none.
            let covering = pick["covering"].as_array().unwrap().len();
            if all_around(x, y, |k| local.matte[k] >= 0.999) {
                assert_eq!(covering, 1, "({x}, {y}): under the matte");
                covered += 1;
            } else if all_around(x, y, |k| local.matte[k] <= 0.001) {
                assert_eq!(covering, 0, "({x}, {y}): off the matte");
                uncovered += 1;
            }
            picked += 1;
        }
    }
    assert!(picked >= 30, "{picked} pixels picked");
    assert!(parts_seen.len() >= 3, "parts seen: {parts_seen:?}");
    assert!(uncovered >= 10, "{uncovered} pixels off the matte");
    let _ = covered;
    // Under the body's broad highlight, some pixels well inside the matte.
    let mut under = 0;
    for y in 1..HEIGHT - 1 {
        for x in 1..WIDTH - 1 {
            if all_around(x, y, |k| local.matte[k] >= 0.999) && under < 5 {
                let reply = served.post("/api/pick", &json!({"frame": frame, "x": x, "y": y}));
                assert_eq!(reply.json()["covering"], json!([0]), "({x}, {y})");
                under += 1;
            }
        }
    }
    assert!(under > 0, "the body's highlight shows at frame 1");
}

#[test]
fn a_final_quality_frame_is_the_final_preset_s_render() {
    let served = Served::new();
    for frame in [1.0, 30.5] {
        let served_final = served.raw_frame(&json!({"frame": frame, "quality": "final"}));
        let local = render_locally(&served.shot, frame, Preset::Final);
        assert!(
            served_final == local.rgba,
            "frame {frame}: the final frame differs from the final preset's render"
        );
        let preview = served.raw_frame(&json!({"frame": frame}));
        assert!(
            preview != served_final,
            "frame {frame}: preview and final should differ"
        );
        assert_eq!(
            preview,
            render_locally(&served.shot, frame, Preset::Preview).rgba
        );
    }
}

#[test]
fn the_overlays_mark_the_matte_s_pixels_and_the_seams_between_patch_ids() {
    let served = Served::new();
    let frame = 1.0;
    let plain = served.raw_frame(&json!({"frame": frame}));
    let local = render_locally(&served.shot, frame, Preset::Preview);
    assert_eq!(plain, local.rgba);
    let (w, h) = (WIDTH as usize, HEIGHT as usize);
    let at = |k: usize| &plain[4 * k..4 * k + 4];

    // The matte: its edge (coverage crossing ½ to the right or below) drawn solid magenta,
    // the rest of it tinted, every other pixel as rendered.
    let matte = served.raw_frame(&json!({"frame": frame, "overlays": {"matte": true}}));
    let (mut edges, mut tinted) = (0, 0);
    for y in 0..h {
        for x in 0..w {
            let k = y * w + x;
            let m = local.matte[k];
            let inside = m >= 0.5;
            let edge = [(x + 1 < w).then(|| k + 1), (y + 1 < h).then(|| k + w)]
                .into_iter()
                .flatten()
                .any(|n| (local.matte[n] >= 0.5) != inside);
            let drawn = &matte[4 * k..4 * k + 4];
            if edge {
                assert_eq!(&drawn[..3], [255, 0, 200], "({x}, {y}): the matte's edge");
                edges += 1;
            } else if m > 0.0 {
                assert_ne!(drawn, at(k), "({x}, {y}): inside the matte, untinted");
                // Tinted toward magenta: green falls, or stays where there was none.
                assert!(drawn[1] <= at(k)[1], "({x}, {y})");
                tinted += 1;
            } else {
                assert_eq!(drawn, at(k), "({x}, {y}): off the matte, changed");
            }
        }
    }
    assert!(edges > 20 && tinted > 20, "{edges} edge, {tinted} tinted");

    // The seams: darkened exactly where the patch id changes to the right or below.
    let seams = served.raw_frame(&json!({"frame": frame, "overlays": {"seams": true}}));
    let mut seam_pixels = 0;
    for y in 0..h {
        for x in 0..w {
            let k = y * w + x;
            let id = local.ids[k];
            let seam = [(x + 1 < w).then(|| k + 1), (y + 1 < h).then(|| k + w)]
                .into_iter()
                .flatten()
                .any(|n| local.ids[n] != id);
            let drawn = &seams[4 * k..4 * k + 4];
            if seam {
                let before: u32 = at(k)[..3].iter().map(|&c| u32::from(c)).sum();
                let after: u32 = drawn[..3].iter().map(|&c| u32::from(c)).sum();
                assert!(
                    after < before || after <= 3 * 60,
                    "({x}, {y}): a seam not darkened"
                );
                seam_pixels += 1;
            } else {
                assert_eq!(drawn, at(k), "({x}, {y}): no seam, changed");
            }
        }
    }
    assert!(seam_pixels > 100, "{seam_pixels} seam pixels");
}

/// Starts `glint tune` on `shot` with `extra` options; its address and token.
fn start_tune(shot: &Path, extra: &[&str]) -> (std::process::Child, SocketAddr, String) {
    let mut child = glint()
        .args([
            "tune",
            shot.to_str().unwrap(),
            "--no-open",
            "--size",
            "64x36",
        ])
        .args(extra)
        .stdout(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut line = String::new();
    let mut stdout = std::io::BufReader::new(child.stdout.take().unwrap());
    std::io::BufRead::read_line(&mut stdout, &mut line).unwrap();
    let url = line
        .trim()
        .strip_prefix("glint tune: ")
        .unwrap_or_default()
        .to_string();
    let (address, token) = url
        .trim_start_matches("http://")
        .split_once("/?token=")
        .unwrap_or_else(|| panic!("no address in {line:?}"));
    let port: u16 = address.rsplit(':').next().unwrap().parse().unwrap();
    (
        child,
        SocketAddr::from(([127, 0, 0, 2], port)),
        token.to_string(),
    )
}

#[test]
fn bind_and_allow_host_let_in_the_names_they_give_and_keep_out_the_rest() {
    let dir = tempfile::tempdir().unwrap();
    let shot = copy_turntable(dir.path());
    // 127.0.0.2 is another address of the loopback network: a stand-in for a machine's address
    // on its network that this test can reach.
    let (mut child, address, token) = start_tune(
        &shot,
        &["--bind", "127.0.0.2", "--allow-host", "studio-ws-12"],
    );
    let port = address.port();
    let get = |host: &str, origin: Option<&str>| {
        let mut headers = vec![("X-Glint-Token", token.as_str()), ("Host", host)];
        if let Some(origin) = origin {
            headers.push(("Origin", origin));
        }
        request(address, "GET", "/api/state?frame=1", &headers, b"")
    };
    let named = |name: &str| format!("{name}:{port}");
    let origin = |name: &str| format!("http://{name}:{port}");
    let outcomes = [
        (named("127.0.0.2"), None, 200),
        (named("studio-ws-12"), None, 200),
        (named("studio-ws-12"), Some(origin("studio-ws-12")), 200),
        (named("localhost"), None, 200),
        (named("studio-ws-13"), None, 403),
        (named("evil.example"), None, 403),
        (named("studio-ws-12"), Some(origin("evil.example")), 403),
    ];
    let replies: Vec<(String, Option<String>, u16, Reply)> = outcomes
        .into_iter()
        .map(|(host, origin, status)| {
            let reply = get(&host, origin.as_deref());
            (host, origin, status, reply)
        })
        .collect();
    // Nothing listens on 127.0.0.1 at that port.
    let loopback = std::net::TcpStream::connect(SocketAddr::from(([127, 0, 0, 1], port)));
    child.kill().unwrap();
    child.wait().unwrap();
    for (host, origin, status, reply) in replies {
        assert_eq!(
            reply.status,
            status,
            "Host {host}, Origin {origin:?}: {}",
            reply.text()
        );
    }
    assert!(
        loopback.is_err(),
        "bound to 127.0.0.2, 127.0.0.1 answers too"
    );

    // An address this machine does not have is refused at once, in one line.
    let out = glint()
        .args([
            "tune",
            shot.to_str().unwrap(),
            "--no-open",
            "--bind",
            "192.0.2.1",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert_eq!(stderr(&out).lines().count(), 1, "{}", stderr(&out));
    assert!(
        stderr(&out).contains("cannot listen on 192.0.2.1"),
        "{}",
        stderr(&out)
    );
    // A bind that is not an address is refused by the options, naming it.
    let out = glint()
        .args([
            "tune",
            shot.to_str().unwrap(),
            "--no-open",
            "--bind",
            "studio",
        ])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("studio"), "{}", stderr(&out));
}

/// A copy of `shots/shade_design.ron` with the files it reads, served at WIDTH × HEIGHT.
fn serve_shade_design() -> Served {
    let dir = tempfile::tempdir().unwrap();
    copy_turntable(dir.path());
    let shot = dir.path().join("shots/shade_design.ron");
    std::fs::copy(repo_file("shots/shade_design.ron"), &shot).unwrap();
    let session = Session::open(&shot, Some((WIDTH, HEIGHT))).expect("the shot opens");
    let server = TuneServer::start(session, &ServerOptions::default()).expect("the server starts");
    Served {
        _dir: dir,
        shot,
        server,
    }
}

#[test]
fn a_shade_drag_keys_the_translation_that_puts_the_band_edge_under_the_pointer() {
    let served = serve_shade_design();
    let before = std::fs::read_to_string(&served.shot).unwrap();
    let frame = 1.0;
    let local = render_locally(&served.shot, frame, Preset::Preview);
    // Body pixels (patches 4 to 11) lit above the glaze's shadow edge (band 0, at 0.3), whose
    // N·L′ a translation can bring down to the edge.
    let pick = |x: u32, y: u32| {
        let reply = served.post("/api/pick", &json!({"frame": frame, "x": x, "y": y}));
        assert_eq!(reply.status, 200, "{}", reply.text());
        reply.json()
    };
    let mut candidates = Vec::new();
    for y in (10..HEIGHT - 10).step_by(4) {
        for x in (10..WIDTH - 10).step_by(9) {
            let id = local.ids[(y * WIDTH + x) as usize];
            if candidates.len() >= 3
                || !(4..=11).contains(&id)
                || !all_around(x, y, |k| local.ids[k] == id)
            {
                continue;
            }
            let picked = pick(x, y);
            assert_eq!(picked["shade"], json!([0]), "({x}, {y}): the body's entry");
            let n_dot_l = picked["n_dot_l"].as_f64().unwrap();
            if (0.32..0.84).contains(&n_dot_l) {
                candidates.push((x, y, n_dot_l));
            }
        }
    }
    assert_eq!(candidates.len(), 3, "three points to drag to");
    // Each drag from the shot as written: committed, checked, and undone.
    for &(x, y, n_dot_l) in &candidates {
        let reply = served.post(
            "/api/shade_drag?format=raw",
            &json!({"frame": frame, "x": x, "y": y, "band": 0}),
        );
        assert_eq!(reply.status, 200, "({x}, {y}): {}", reply.text());
        let changes: Value =
            serde_json::from_str(reply.header("x-glint-changes").unwrap()).unwrap();
        let paths: Vec<&str> = changes
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c["path"].as_str().unwrap())
            .collect();
        assert_eq!(paths, ["shade[0].stack[0].alpha", "shade[0].stack[0].beta"]);
        assert!(changes
            .as_array()
            .unwrap()
            .iter()
            .all(|c| c["frame"] == 1.0));
        assert_eq!(
            std::fs::read_to_string(&served.shot).unwrap(),
            before,
            "a drag writes nothing until it is committed"
        );
        // Committed, the band edge passes through the point: N·L′ there is the threshold.
        let reply = served.post("/api/commit", &json!({ "changes": changes }));
        assert_eq!(reply.status, 200, "{}", reply.text());
        assert_ne!(std::fs::read_to_string(&served.shot).unwrap(), before);
        let placed = pick(x, y)["n_dot_l"].as_f64().unwrap();
        assert!(
            (placed - 0.3).abs() < 1e-3,
            "({x}, {y}): N·L′ {placed} after the drag, {n_dot_l} before"
        );
        let reply = served.post("/api/undo", &Value::Null);
        assert_eq!(reply.status, 200, "{}", reply.text());
        assert_eq!(std::fs::read_to_string(&served.shot).unwrap(), before);
    }
    let written = before.clone();

    // Refused in one line: a patch no shade entry picks (the spout), and an entry without a
    // translation (the lid's split).
    let mut refused = Vec::new();
    for y in (4..HEIGHT - 4).step_by(3) {
        for x in (4..WIDTH - 4).step_by(3) {
            let id = local.ids[(y * WIDTH + x) as usize];
            let kind = match id {
                16..=19 => "no shade entry",
                24..=27 => "Translate",
                _ => continue,
            };
            if refused.contains(&kind) || !all_around(x, y, |k| local.ids[k] == id) {
                continue;
            }
            let reply = served.post("/api/shade_drag", &json!({"frame": frame, "x": x, "y": y}));
            assert_eq!(reply.status, 400, "({x}, {y}): {}", reply.text());
            let error = reply.json()["error"].as_str().unwrap().to_string();
            assert!(
                !error.contains('\n') && error.contains(kind),
                "({x}, {y}): {error}"
            );
            refused.push(kind);
        }
    }
    assert_eq!(refused.len(), 2, "{refused:?}");
    assert_eq!(std::fs::read_to_string(&served.shot).unwrap(), written);
}

/// The spout of the teapot seen from the side, its small highlight placed where its S-bend turns
/// the normals back, so that it shows twice on one patch; served at 320 × 240.
fn serve_spout() -> (tempfile::TempDir, PathBuf, TuneServer) {
    let dir = tempfile::tempdir().unwrap();
    let shot = dir.path().join("spout.ron");
    let write = |alpha: f32, beta: f32| {
        let text = format!(
            r#"Shot(
    resolution: (320, 240),
    frames: (1, 1),
    fps: 24,
    output: "out/spout.####.png",
    instances: [(name: "m", file: "{model}", material: "grey")],
    materials: {{ "grey": Cel(base: (0.1, 0.1, 0.1), bands: [(0.0, (0.5, 0.5, 0.5))]) }},
    camera: (eye: (1.0, -6.0, 2.0), target: (0.0, 0.0, 0.0), projection: Orthographic(height: 6.0)),
    light: Directional(towards: (0.26, -0.87, 0.43)),
    highlights: [(patches: "m/spout", expr: Layer((stack: [Translate(alpha: {alpha}, beta: {beta})], epsilon: 0.01, colour: (1.0, 1.0, 1.0))))],
    render: (preset: Final),
)"#,
            model = repo_file("patches/teapot.bpt").display(),
        );
        std::fs::write(&shot, text).unwrap();
    };
    write(0.0, 0.0);
    let mut job = RenderJob::load(&shot, &Overrides::default()).unwrap();
    let placed = job
        .place(1.0, (245.0, 88.0), glint::job::LayerChoice::default())
        .unwrap();
    write(placed.translation.x, placed.translation.y);
    let session = Session::open(&shot, None).expect("the shot opens");
    let server = TuneServer::start(session, &ServerOptions::default()).expect("the server starts");
    (dir, shot, server)
}

/// The centres overlay crosses every centre of the chosen layer, and the crosses are where the
/// highlight shows: each in view lies on its own blob of the rendered matte, the S-bend gives
/// two in view, and a blob without one is near a centre the frame hides (the spout's tip shows
/// an edge of a highlight centred out of sight). A frame with unsaved changes (a drag) carries
/// none.
#[test]
fn the_centres_overlay_crosses_each_blob_of_the_highlight_once() {
    let (_dir, shot, server) = serve_spout();
    let token = server.token().to_string();
    let post = |body: &Value| {
        let reply = request(
            server.address(),
            "POST",
            "/api/frame?format=raw",
            &[
                ("X-Glint-Token", &token),
                ("Content-Type", "application/json"),
            ],
            &serde_json::to_vec(body).unwrap(),
        );
        assert_eq!(reply.status, 200, "{}", reply.text());
        reply
    };
    let crossed = post(&json!({"frame": 1, "overlays": {"centres": [0, 0]}}));
    let listed = crossed
        .header("x-glint-centres")
        .expect("the centres")
        .to_string();
    let centres: Vec<(f64, f64, bool)> = listed
        .split(';')
        .map(|c| {
            let v: Vec<f64> = c.split(',').map(|x| x.parse().unwrap()).collect();
            (v[0], v[1], v[2] == 1.0)
        })
        .collect();
    let shown: Vec<(f64, f64)> = centres.iter().filter(|c| c.2).map(|c| (c.0, c.1)).collect();
    assert!(shown.len() >= 2, "{listed}");

    // The matte of a local render, its blobs apart.
    let overrides = Overrides {
        aovs: Some(vec![Aov::Matte]),
        ..Overrides::default()
    };
    let mut job = RenderJob::load(&shot, &overrides).unwrap();
    let image = job.render_frame(1.0).unwrap();
    let (w, h) = (image.width as usize, image.height as usize);
    let matte = image.aovs.matte.unwrap();
    let on: Vec<bool> = matte.iter().map(|&m| m >= 0.5).collect();
    let (label, sizes) = crate::common::labels(&on, (w, h));
    // The blob within 2 pixels of a point, if any.
    let blob_near = |(x, y): (f64, f64)| {
        let (cx, cy) = (x.round() as i64, y.round() as i64);
        (-2i64..=2)
            .flat_map(|dy| (-2i64..=2).map(move |dx| (cx + dx, cy + dy)))
            .filter(|&(px, py)| px >= 0 && py >= 0 && px < w as i64 && py < h as i64)
            .map(|(px, py)| label[py as usize * w + px as usize])
            .find(|&l| l != usize::MAX)
    };
    let mut held: Vec<usize> = shown
        .iter()
        .map(|&c| blob_near(c).unwrap_or_else(|| panic!("the cross at {c:?} is off the matte")))
        .collect();
    held.sort_unstable();
    held.dedup();
    assert_eq!(held.len(), shown.len(), "two crosses on one blob: {listed}");
    // Every other blob is where the frame shows part of a highlight whose centre it hides:
    // near a centre listed as out of view.
    let hidden: Vec<(f64, f64)> = centres
        .iter()
        .filter(|c| !c.2)
        .map(|c| (c.0, c.1))
        .collect();
    for (id, &size) in sizes.iter().enumerate() {
        if size < 4 || held.contains(&id) {
            continue;
        }
        let near_hidden = (0..label.len()).filter(|&k| label[k] == id).any(|k| {
            let (x, y) = ((k % w) as f64, (k / w) as f64);
            hidden
                .iter()
                .any(|&(cx, cy)| (x - cx).hypot(y - cy) <= 12.0)
        });
        assert!(
            near_hidden,
            "blob {id} of {size} px has no centre: {listed}"
        );
    }

    // Each cross is drawn: magenta on its arms, the frame as rendered elsewhere.
    let plain = post(&json!({"frame": 1}));
    assert!(plain.header("x-glint-centres").is_none());
    let (rgba, bare) = (&crossed.body, &plain.body);
    for &(x, y) in &shown {
        let (px, py) = (x.round() as usize + 5, y.round() as usize);
        let k = 4 * (py * w + px);
        assert_eq!(
            &rgba[k..k + 3],
            [255, 60, 200],
            "the arm right of ({x}, {y})"
        );
    }
    let far = 4 * (5 * w + 5);
    assert_eq!(&rgba[far..far + 4], &bare[far..far + 4]);

    // A frame with an unsaved change (as a drag sends) searches for no centres.
    let dragged = post(&json!({
        "frame": 1,
        "overlays": {"centres": [0, 0]},
        "changes": [{"kind": "set", "path": "highlights[0].layers[0].epsilon", "value": [0.012]}],
    }));
    assert!(dragged.header("x-glint-centres").is_none());
}

/// With the pins overlay a still frame also shows where each pin's point goes over the shot: a
/// yellow dot on every frame's landing, each where `glint probe` puts the pinned point on that
/// frame; a frame with unsaved changes (a drag) leaves the track out.
#[test]
fn the_pins_overlay_dots_each_pin_s_track_where_probe_puts_its_point() {
    let served = Served::new();
    let frame = 1.0;
    let dotted = served.raw_frame(&json!({"frame": frame, "overlays": {"pins": true}}));
    let plain = served.raw_frame(&json!({"frame": frame}));
    let (current, _) = probed_pixel(&served.shot, "teapot/4", [0.63, 0.39], frame);
    let w = WIDTH as usize;
    let mut checked = 0;
    for other in [20.0, 48.0, 75.0, 96.0] {
        let (pixel, _) = probed_pixel(&served.shot, "teapot/4", [0.63, 0.39], other);
        let (x, y) = (pixel.0.round(), pixel.1.round());
        // Away from the current frame's pin marker, inside the image.
        if (x - current.0).hypot(y - current.1) < 11.0
            || x < 0.0
            || y < 0.0
            || x >= f64::from(WIDTH)
            || y >= f64::from(HEIGHT)
        {
            continue;
        }
        let k = 4 * (y as usize * w + x as usize);
        assert_eq!(
            &dotted[k..k + 3],
            [255, 220, 0],
            "frame {other}'s dot at ({x}, {y})"
        );
        assert_ne!(&plain[k..k + 3], [255, 220, 0]);
        checked += 1;
    }
    assert!(checked >= 2, "{checked} dots checked");

    // With an unsaved change, the pin is marked but no track is drawn.
    let change =
        json!([{"kind": "set", "path": "highlights[0].layers[0].epsilon", "value": [0.012]}]);
    let changed = served.raw_frame(&json!({"frame": frame, "changes": change}));
    let changed_pins =
        served.raw_frame(&json!({"frame": frame, "overlays": {"pins": true}, "changes": change}));
    let (pixel, _) = probed_pixel(&served.shot, "teapot/4", [0.63, 0.39], 96.0);
    let k = 4 * (pixel.1.round() as usize * w + pixel.0.round() as usize);
    assert_eq!(
        &changed_pins[k..k + 4],
        &changed[k..k + 4],
        "a track drawn during a drag"
    );
}

#[test]
fn a_drag_moves_a_pin_across_its_highlight_s_patches_and_refuses_a_patch_of_another() {
    let served = Served::new();
    let frame = 1.0;
    let drag = |highlight: u32, (x, y): (f64, f64)| {
        let body = json!({"frame": frame, "x": x, "y": y, "highlight": highlight, "layer": 0});
        served.post("/api/drag", &body)
    };
    let error = |reply: &Reply| {
        assert_eq!(reply.status, 400, "{}", reply.text());
        reply.json()["error"].as_str().unwrap().to_string()
    };
    // The body's highlight (entries[1]) is pinned to teapot/4; teapot/5 is of the body too.
    let (on_body, seen) = probed_pixel(&served.shot, "teapot/5", [0.5, 0.5], frame);
    assert!(seen, "teapot/5's middle is seen at frame 1");
    let reply = drag(1, on_body);
    assert_eq!(reply.status, 200, "{}", reply.text());
    let changes: Vec<Value> =
        serde_json::from_str(reply.header("x-glint-changes").unwrap()).unwrap();
    assert_eq!(changes[0]["kind"], "pin_to", "{changes:?}");
    assert_eq!(changes[0]["patch"], "teapot/5", "{changes:?}");
    // The lid has the other highlight: the pin cannot go there.
    let (on_lid, seen) = probed_pixel(&served.shot, "teapot/24", [0.5, 0.5], frame);
    assert!(seen, "teapot/24's middle is seen at frame 1");
    let e = error(&drag(1, on_lid));
    assert!(
        e.contains("pinned to teapot/4") && e.contains("another highlight"),
        "{e}"
    );
    // Nor does the every-patch glint (unpinned, no translation) go onto the body's patches.
    let e = error(&drag(0, on_body));
    assert!(
        e.contains("teapot/5, under the pointer, does not have highlight 0"),
        "{e}"
    );
    // Keys of the pin at another frame belong to its patch: it stays there.
    let key = json!({"changes": [{"kind": "key", "path": "highlights[1].layers[0].pin.u", "frame": 30, "value": [0.6]}]});
    assert_eq!(served.post("/api/commit", &key).status, 200);
    let e = error(&drag(1, on_body));
    assert!(e.contains("keys at other frames"), "{e}");
}

#[test]
fn a_look_library_changed_on_disk_is_drawn_on_the_next_frame() {
    let served = Served::new();
    let frame = json!({"frame": 1});
    let before = served.raw_frame(&frame);
    // The shot's file is unchanged: only the look library it includes is.
    let looks = served.shot.parent().unwrap().join("looks/studio.ron");
    let text = std::fs::read_to_string(&looks).unwrap();
    let warmer = text.replace("(0.30, 0.45, 0.80)", "(0.80, 0.45, 0.30)");
    assert_ne!(warmer, text);
    std::fs::write(&looks, warmer).unwrap();
    served.server.inputs_changed();
    let after = served.raw_frame(&frame);
    let changed = before
        .chunks(4)
        .zip(after.chunks(4))
        .filter(|(a, b)| a != b)
        .count();
    assert!(
        changed > 200,
        "{changed} pixels changed with the porcelain's colour"
    );
}
