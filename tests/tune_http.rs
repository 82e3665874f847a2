//! `glint tune`'s server over real HTTP: every endpoint with good and bad input, the token,
//! Host and Origin checks, and the shot file — the one file it writes — unchanged after every
//! refused request.

use std::net::SocketAddr;
use std::path::{Path, PathBuf};

use glint::job::{Overrides, RenderJob};
use glint::shot::Aov;
use glint_cli::tune::{ServerOptions, Session, TuneServer};
use serde_json::{json, Value};

use crate::common::http::{request, Reply};
use crate::common::{glint, repo_file, stderr};

const SIZE: u32 = 160;

/// A copy of `shots/sphere_ops.ron` and its sphere, served.
struct Served {
    _dir: tempfile::TempDir,
    shot: PathBuf,
    server: TuneServer,
}

fn copy_sphere_ops(dir: &Path) -> PathBuf {
    std::fs::create_dir_all(dir.join("shots")).unwrap();
    std::fs::create_dir_all(dir.join("patches")).unwrap();
    std::fs::copy(
        repo_file("patches/sphere.ron"),
        dir.join("patches/sphere.ron"),
    )
    .unwrap();
    let shot = dir.join("shots/sphere_ops.ron");
    std::fs::copy(repo_file("shots/sphere_ops.ron"), &shot).unwrap();
    shot
}

fn serve(shot: &Path) -> TuneServer {
    let session = Session::open(shot, Some((SIZE, SIZE))).expect("the shot opens");
    TuneServer::start(session, &ServerOptions::default()).expect("the server starts")
}

impl Served {
    fn new() -> Self {
        let dir = tempfile::tempdir().unwrap();
        let shot = copy_sphere_ops(dir.path());
        let server = serve(&shot);
        Self {
            _dir: dir,
            shot,
            server,
        }
    }

    fn address(&self) -> SocketAddr {
        self.server.address()
    }

    fn text(&self) -> String {
        std::fs::read_to_string(&self.shot).unwrap()
    }

    fn get(&self, target: &str) -> Reply {
        let token = self.server.token().to_string();
        request(
            self.address(),
            "GET",
            target,
            &[("X-Glint-Token", &token)],
            b"",
        )
    }

    fn post(&self, target: &str, body: &Value) -> Reply {
        let token = self.server.token().to_string();
        let body = serde_json::to_vec(body).unwrap();
        request(
            self.address(),
            "POST",
            target,
            &[
                ("X-Glint-Token", &token),
                ("Content-Type", "application/json"),
            ],
            &body,
        )
    }
}

fn assert_status(reply: &Reply, status: u16) {
    assert_eq!(reply.status, status, "{}", reply.text());
}

/// The one-line error of a refused request.
fn error_of(reply: &Reply) -> String {
    let error = reply.json()["error"]
        .as_str()
        .unwrap_or_default()
        .to_string();
    assert!(
        !error.is_empty() && !error.contains('\n'),
        "{}",
        reply.text()
    );
    error
}

const ALPHA: &str = "highlights[0].layers[0].stack[0].alpha";
const EPSILON: &str = "highlights[0].layers[0].epsilon";

fn every_endpoint() -> Vec<(&'static str, &'static str, Value)> {
    let key = json!({"changes": [{"kind": "key", "path": ALPHA, "frame": 1, "value": [0.2]}]});
    vec![
        ("GET", "/", Value::Null),
        ("GET", "/api/state?frame=1", Value::Null),
        ("POST", "/api/frame", json!({"frame": 1})),
        ("POST", "/api/pick", json!({"frame": 1, "x": 80, "y": 80})),
        (
            "POST",
            "/api/drag",
            json!({"frame": 1, "x": 90, "y": 70, "highlight": 0, "layer": 0}),
        ),
        ("POST", "/api/commit", key),
        (
            "POST",
            "/api/draw",
            json!({"frame": 1, "highlight": 0, "layer": 0,
                   "points": [[90, 52], [103, 75], [77, 75]]}),
        ),
        ("POST", "/api/undo", Value::Null),
        ("POST", "/api/redo", Value::Null),
        ("GET", "/api/wait?version=0", Value::Null),
        ("GET", "/no/such/page", Value::Null),
    ]
}

#[test]
fn every_request_needs_the_token_and_the_server_s_own_host_and_origin() {
    let served = Served::new();
    let mut before = served.text();
    let address = served.address();
    let token = served.server.token().to_string();
    let own_host = format!("127.0.0.1:{}", address.port());
    let own_origin = format!("http://127.0.0.1:{}", address.port());
    let rebound_host = format!("attacker.example:{}", address.port());
    for (method, target, body) in every_endpoint() {
        let body = if body.is_null() {
            Vec::new()
        } else {
            serde_json::to_vec(&body).unwrap()
        };
        let cases: [(&[(&str, &str)], u16); 6] = [
            (&[], 401),
            (
                &[("X-Glint-Token", "0123456789abcdef0123456789abcdef")],
                401,
            ),
            (&[("X-Glint-Token", &token[..31])], 401),
            (&[("X-Glint-Token", &token), ("Host", &rebound_host)], 403),
            (&[("X-Glint-Token", &token), ("Host", "127.0.0.1:1")], 403),
            (
                &[
                    ("X-Glint-Token", &token),
                    ("Host", &own_host),
                    ("Origin", "http://attacker.example"),
                ],
                403,
            ),
        ];
        for (headers, status) in cases {
            let reply = request(address, method, target, headers, &body);
            assert_eq!(
                reply.status,
                status,
                "{method} {target} {headers:?}: {}",
                reply.text()
            );
            error_of(&reply);
            assert_eq!(
                served.text(),
                before,
                "{method} {target} {headers:?} changed the file"
            );
        }
        // The server's own origin passes the check (the answer is the endpoint's own).
        let reply = request(
            address,
            method,
            &format!(
                "{target}{}token={token}",
                if target.contains('?') { '&' } else { '?' }
            ),
            &[("Origin", &own_origin)],
            &body,
        );
        assert!(
            ![401, 403].contains(&reply.status),
            "{method} {target}: {}",
            reply.text()
        );
        before = served.text();
    }
}

#[test]
fn the_page_is_served_with_a_policy_that_keeps_other_sites_out() {
    let served = Served::new();
    let reply = served.get("/");
    assert_status(&reply, 200);
    assert!(
        reply.text().contains("<canvas id=\"view\""),
        "the page has its image"
    );
    let policy = reply.header("content-security-policy").unwrap_or_default();
    assert!(policy.contains("frame-ancestors 'none'"), "{policy}");
    assert_eq!(reply.header("cache-control"), Some("no-store"));
}

#[test]
fn the_state_has_each_parameter_s_value_keys_and_range() {
    let served = Served::new();
    let reply = served.get("/api/state?frame=12");
    assert_status(&reply, 200);
    let state = reply.json();
    assert_eq!(state["frames"], json!([1, 120]));
    assert_eq!(state["size"], json!([SIZE, SIZE]));
    let layer = &state["highlights"][0]["layers"][0];
    let names: Vec<&str> = (layer["ops"].as_array().unwrap().iter())
        .map(|op| op["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["Translate", "Rotate", "Scale", "Split", "Square"]);
    // The file keys alpha [(1, 0.0), (12, 0.35), (24, 0.0)].
    let alpha = &layer["ops"][0]["params"][0];
    assert_eq!(alpha["path"], ALPHA);
    assert!(
        (alpha["value"][0].as_f64().unwrap() - 0.35).abs() < 1e-6,
        "{alpha}"
    );
    assert_eq!(alpha["keys"], json!([1.0, 12.0, 24.0]));
    assert_eq!(
        (alpha["min"].as_f64(), alpha["max"].as_f64()),
        (Some(-1e6), Some(1e6))
    );
    let epsilon = layer["params"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == "epsilon")
        .unwrap();
    assert_eq!(epsilon["min_open"], true);
    assert_eq!(epsilon["max"].as_f64(), Some(2.0));
    // Between keys the value is interpolated.
    let reply = served.get("/api/state?frame=6.5");
    let alpha = &reply.json()["highlights"][0]["layers"][0]["ops"][0]["params"][0];
    assert!(
        (alpha["value"][0].as_f64().unwrap() - 0.175).abs() < 1e-6,
        "{alpha}"
    );

    for bad in ["/api/state?frame=soon", "/api/state?frame=1&colour=red"] {
        let reply = served.get(bad);
        assert_status(&reply, 400);
        error_of(&reply);
    }
}

fn pixels(reply: &Reply) -> Vec<u8> {
    assert_status(reply, 200);
    match reply.header("content-type") {
        Some("image/png") => image::load_from_memory(&reply.body)
            .unwrap()
            .to_rgba8()
            .into_raw(),
        _ => reply.body.clone(),
    }
}

#[test]
fn frames_arrive_raw_or_as_png_with_unsaved_changes_shown_but_not_written() {
    let served = Served::new();
    let before = served.text();
    let raw = served.post("/api/frame?format=raw", &json!({"frame": 1}));
    assert_eq!(raw.header("x-glint-width"), Some("160"));
    assert_eq!(raw.body.len(), (SIZE * SIZE * 4) as usize);
    let png = served.post("/api/frame", &json!({"frame": 1}));
    assert_eq!(png.header("content-type"), Some("image/png"));
    assert_eq!(
        pixels(&png),
        pixels(&raw),
        "PNG and raw carry the same pixels"
    );
    // A second frame with nothing changed reuses the surfaces.
    let again = served.post("/api/frame", &json!({"frame": 1}));
    let stages = again
        .header("x-glint-stages")
        .expect("every frame says which stages ran")
        .to_string();
    assert!(
        stages.contains("shade") && !stages.contains("tessellate") && !stages.contains("gbuffer"),
        "{stages}"
    );
    let first = raw
        .header("x-glint-stages")
        .expect("every frame says which stages ran");
    assert!(
        first.contains("tessellate") && first.contains("gbuffer"),
        "the first frame builds its surfaces: {first}"
    );

    let wider = json!({"frame": 1, "changes": [{"kind": "set", "path": EPSILON, "value": [0.2]}]});
    let changed = served.post("/api/frame", &wider);
    assert_ne!(pixels(&changed), pixels(&raw), "ε 0.2 shows");
    assert_eq!(served.text(), before, "a frame with changes writes nothing");
    let stages = changed
        .header("x-glint-stages")
        .expect("every frame says which stages ran")
        .to_string();
    assert!(
        !stages.contains("tessellate"),
        "a highlight change keeps the mesh: {stages}"
    );

    let overlays = served.post(
        "/api/frame",
        &json!({"frame": 1, "overlays": {"seams": true, "matte": true, "pins": true}}),
    );
    assert_ne!(pixels(&overlays), pixels(&raw), "the overlays are drawn");

    for (body, says) in [
        (
            json!({"frame": 1, "changes": [{"kind": "set", "path": EPSILON, "value": [3.0]}]}),
            "sphere_ops.ron:",
        ),
        (
            json!({"frame": 1, "changes": [{"kind": "set", "path": "highlights[0].layers[0].epsilom", "value": [0.1]}]}),
            "epsilon",
        ),
        (
            json!({"frame": 1, "changes": [{"kind": "set", "path": EPSILON, "value": [0.1, 0.2]}]}),
            "epsilon",
        ),
        (json!({"frame": 1, "quality": "ultra"}), "ultra"),
        (json!({"frame": "one"}), "expected f64"),
        (json!({"frame": 1, "zoom": 2}), "zoom"),
    ] {
        let reply = served.post("/api/frame", &body);
        assert_status(&reply, 400);
        let error = error_of(&reply);
        assert!(error.contains(says), "{body}: {error}");
    }
    let reply = served.post("/api/frame?format=jpeg", &json!({"frame": 1}));
    assert_status(&reply, 400);
    let token = served.server.token().to_string();
    let reply = request(
        served.address(),
        "POST",
        "/api/frame",
        &[("X-Glint-Token", &token)],
        b"{\"frame\": 1",
    );
    assert_status(&reply, 400);
    assert_eq!(served.text(), before);
}

#[test]
fn pick_names_the_patch_and_the_layers_under_a_pixel() {
    let served = Served::new();
    let reply = served.post("/api/pick", &json!({"frame": 1, "x": 80, "y": 80}));
    assert_status(&reply, 200);
    let pick = reply.json();
    assert_eq!(pick["patch"], "ball/sphere");
    assert_eq!(pick["highlight"], 0);
    // At frame 1 the highlight sits where H = N: toward the light's reflection, which the
    // sphere's centre pixel lies outside of unless the light is behind the camera.
    assert!(pick["covering"].is_array());
    for (x, y, says) in [
        (-3.0, 80.0, "outside"),
        (80.0, 500.0, "outside"),
        (1.0, 1.0, "no patch"),
    ] {
        let reply = served.post("/api/pick", &json!({"frame": 1, "x": x, "y": y}));
        assert_status(&reply, 400);
        assert!(
            error_of(&reply).contains(says),
            "({x}, {y}): {}",
            reply.text()
        );
    }
}

/// The centroid of the highlight matte of `shot` at `frame`, rendered at `SIZE`².
fn matte_centroid(shot: &Path, frame: f64) -> (f64, f64) {
    let overrides = Overrides {
        size: Some((SIZE, SIZE)),
        aovs: Some(vec![Aov::Matte]),
        ..Overrides::default()
    };
    let mut job = RenderJob::load(shot, &overrides).unwrap();
    let image = job.render_frame(frame).unwrap();
    let matte = image.aovs.matte.unwrap();
    let (centre, sum) = crate::common::matte_centroid_of(&matte, SIZE);
    assert!(sum > 10.0, "the highlight shows");
    centre
}

#[test]
fn a_drag_places_the_highlight_and_its_commit_keys_it_at_the_frame() {
    let served = Served::new();
    let before = served.text();
    let drop = (100.0, 65.0);
    let drag = json!({"frame": 5, "x": drop.0, "y": drop.1, "highlight": 0, "layer": 0});
    let reply = served.post("/api/drag", &drag);
    assert_status(&reply, 200);
    assert_eq!(
        served.text(),
        before,
        "a drag writes nothing until it is released"
    );
    let changes: Value = serde_json::from_str(reply.header("x-glint-changes").unwrap()).unwrap();
    let paths: Vec<&str> = (changes.as_array().unwrap().iter())
        .map(|c| c["path"].as_str().unwrap())
        .collect();
    assert_eq!(paths, [ALPHA, "highlights[0].layers[0].stack[0].beta"]);
    assert!(changes
        .as_array()
        .unwrap()
        .iter()
        .all(|c| c["kind"] == "key" && c["frame"] == 5.0));

    let reply = served.post("/api/commit", &json!({ "changes": changes }));
    assert_status(&reply, 200);
    let written = served.text();
    assert_ne!(written, before);
    let (x, y) = matte_centroid(&served.shot, 5.0);
    let miss = (x - drop.0).hypot(y - drop.1);
    assert!(
        miss <= 2.0,
        "the highlight's centroid ({x}, {y}) is {miss} px from the drop"
    );

    // Off the model, or a layer that does not exist: refused, the file as it was.
    for (body, says) in [
        (
            json!({"frame": 5, "x": 2, "y": 2, "highlight": 0, "layer": 0}),
            "no patch",
        ),
        (
            json!({"frame": 5, "x": 80, "y": 80, "highlight": 0, "layer": 4}),
            "no layer 4",
        ),
        (
            json!({"frame": 5, "x": 80, "y": 80, "highlight": 3, "layer": 0}),
            "entry 3",
        ),
    ] {
        let reply = served.post("/api/drag", &body);
        assert_status(&reply, 400);
        assert!(error_of(&reply).contains(says), "{body}: {}", reply.text());
        assert_eq!(served.text(), written);
    }
}

/// Drags layer 0 of highlight 0 to `drop` at `frame`, commits what the drag showed, and checks
/// that the highlight's centroid lands there; returns the changes.
/// How well the matte of `shot` rendered at `frame` fits the triangle `corners` (pixels): for
/// each corner, the distance from it of the covered pixel (matte ≥ ½) that lies farthest
/// toward it from the matte's centroid — a triangle's extreme toward a corner is that corner —
/// and the matte's area over the triangle's.
fn triangle_fit(shot: &Path, frame: f64, corners: &[(f64, f64); 3]) -> ([f64; 3], f64) {
    let overrides = Overrides {
        size: Some((SIZE, SIZE)),
        aovs: Some(vec![Aov::Matte]),
        ..Overrides::default()
    };
    let mut job = RenderJob::load(shot, &overrides).unwrap();
    let matte = job.render_frame(frame).unwrap().aovs.matte.unwrap();
    let ((cx, cy), area) = crate::common::matte_centroid_of(&matte, SIZE);
    let covered: Vec<(f64, f64)> = matte
        .iter()
        .enumerate()
        .filter(|(_, &m)| m >= 0.5)
        .map(|(i, _)| (f64::from(i as u32 % SIZE), f64::from(i as u32 / SIZE)))
        .collect();
    let misses = corners.map(|(x, y)| {
        let (dx, dy) = (x - cx, y - cy);
        let extreme = covered
            .iter()
            .max_by(|a, b| {
                let along = |p: &&(f64, f64)| (p.0 - cx) * dx + (p.1 - cy) * dy;
                along(a).total_cmp(&along(b))
            })
            .expect("the matte covers pixels");
        (extreme.0 - x).hypot(extreme.1 - y)
    });
    let [a, b, c] = corners;
    let triangle = ((b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1)).abs() / 2.0;
    (misses, area / triangle)
}

#[test]
fn a_drawn_triangle_is_written_as_an_outline_whose_matte_has_its_corners() {
    let served = Served::new();
    let before = served.text();
    let corners = [(90.0, 50.0), (105.0, 76.0), (75.0, 76.0)];
    let points: Vec<[f64; 2]> = corners.iter().map(|&(x, y)| [x, y]).collect();
    let reply = served.post(
        "/api/draw",
        &json!({"frame": 1, "highlight": 0, "layer": 0, "points": points}),
    );
    assert_status(&reply, 200);
    let change = &reply.json()["changes"][0];
    assert_eq!(change["kind"], "outline");
    assert!(change["key"].is_null(), "{change}");
    let text = served.text();
    let shot = glint::shot::load_shot(&served.shot).unwrap();
    let drawn = &shot.highlight_layers(0)[0].shape;
    let glint::highlight::Shape::Outline(outline) = drawn else {
        panic!("{text}")
    };
    assert_eq!(outline.segments.len(), 3, "{text}");
    assert!(text.contains("shape: Outline(["), "{text}");
    let (misses, ratio) = triangle_fit(&served.shot, 1.0, &corners);
    assert!(
        misses.iter().all(|&m| m <= 2.0),
        "corners {misses:?} px from the drawn ones"
    );
    assert!(
        (ratio - 1.0).abs() < 0.1,
        "the matte is {ratio} of the triangle"
    );

    // Keyed at frame 30 by asking, and at frame 50 because the outline is keyed now.
    let moved: Vec<[f64; 2]> = corners.iter().map(|&(x, y)| [x - 6.0, y + 4.0]).collect();
    for (frame, key) in [(30, true), (50, false)] {
        let reply = served.post(
            "/api/draw",
            &json!({"frame": frame, "highlight": 0, "layer": 0, "points": moved, "key": key}),
        );
        assert_status(&reply, 200);
        assert_eq!(
            reply.json()["changes"][0]["key"].as_f64(),
            Some(f64::from(frame))
        );
    }
    let state = served.get("/api/state?frame=30").json();
    let layer = &state["highlights"][0]["layers"][0];
    assert_eq!(layer["shape"], "keyed outline");
    assert_eq!(layer["shape_keys"], json!([30.0, 50.0]));

    // The disc again: the file as it was.
    let disc = json!({"changes": [{"kind": "disc", "highlight": 0, "layer": 0}]});
    assert_status(&served.post("/api/commit", &disc), 200);
    assert_eq!(served.text(), before);

    // As many points as an outline holds, and one more.
    let circle = |n: usize| -> Vec<[f64; 2]> {
        (0..n)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / n as f64;
                [90.0 + 6.0 * a.cos(), 66.0 + 6.0 * a.sin()]
            })
            .collect()
    };
    let most = glint::highlight::MAX_OUTLINE_SEGMENTS;
    let draw = |points: Vec<[f64; 2]>| {
        served.post(
            "/api/draw",
            &json!({"frame": 1, "highlight": 0, "layer": 0, "points": points}),
        )
    };
    let reply = draw(circle(most + 1));
    assert_status(&reply, 400);
    assert!(error_of(&reply).contains("at most 1024"));
    assert_eq!(served.text(), before);
    assert_status(&draw(circle(most)), 200);
}

#[test]
fn a_drawn_point_off_the_highlight_s_patch_or_a_key_of_another_count_writes_nothing() {
    let served = Served::new();
    let before = served.text();
    let draw = |frame: u32, points: Value, key: bool| {
        served.post(
            "/api/draw",
            &json!({"frame": frame, "highlight": 0, "layer": 0, "points": points, "key": key}),
        )
    };
    for (points, says) in [
        (json!([[90, 50], [105, 76], [2, 2]]), "shows no patch"),
        (json!([[90, 50], [105, 76], [200, 76]]), "outside the"),
        (json!([[90, 50], [105, 76]]), "at least 3"),
        // The last point on the first is the same point: two are left.
        (json!([[90, 50], [105, 76], [90, 50]]), "at least 3"),
        (
            json!([[90, 50], [105, 76], [75, 76], [105, 50]]),
            "crosses itself",
        ),
        (json!(vec![[90, 50]; 2000]), "at most 1024"),
    ] {
        let reply = draw(1, points.clone(), false);
        assert_status(&reply, 400);
        let error = error_of(&reply);
        assert!(error.contains(says), "{points}: {error}");
        assert_eq!(served.text(), before, "{points}");
    }
    assert_status(&draw(1, json!([[90, 50], [105, 76], [75, 76]]), true), 200);
    let keyed = served.text();
    let reply = draw(12, json!([[90, 50], [105, 76], [90, 80], [75, 76]]), true);
    assert_status(&reply, 400);
    let error = error_of(&reply);
    assert!(
        error.contains(
            "the outline key at frame 12 would have 4 points but the key at frame 1 has 3"
        ),
        "{error}"
    );
    assert_eq!(served.text(), keyed);
}

fn drag_and_commit(served: &Served, frame: f64, drop: (f64, f64)) -> Vec<Value> {
    let drag = json!({"frame": frame, "x": drop.0, "y": drop.1, "highlight": 0, "layer": 0});
    let reply = served.post("/api/drag", &drag);
    assert_status(&reply, 200);
    let changes: Vec<Value> =
        serde_json::from_str(reply.header("x-glint-changes").unwrap()).unwrap();
    assert_status(
        &served.post("/api/commit", &json!({ "changes": changes })),
        200,
    );
    let (x, y) = matte_centroid(&served.shot, frame);
    let miss = (x - drop.0).hypot(y - drop.1);
    assert!(
        miss <= 2.0,
        "the highlight's centroid ({x}, {y}) is {miss} px from the drop"
    );
    changes
}

#[test]
fn a_layer_without_a_translation_gets_one_and_a_pinned_layer_moves_its_pin() {
    let served = Served::new();
    let remove =
        json!({"changes": [{"kind": "remove_op", "highlight": 0, "layer": 0, "index": 0}]});
    assert_status(&served.post("/api/commit", &remove), 200);
    let changes = drag_and_commit(&served, 30.0, (70.0, 95.0));
    let kinds: Vec<&str> = changes
        .iter()
        .map(|c| c["kind"].as_str().unwrap())
        .collect();
    assert_eq!(kinds, ["insert_op", "key", "key"]);
    assert!(
        served.text().contains("Translate(alpha: [(30, "),
        "{}",
        served.text()
    );

    let pinned = served.text().replace(
        "colour: (1.0, 1.0, 0.92),",
        "colour: (1.0, 1.0, 0.92),\n                pin: (patch: \"ball/sphere\", u: 0.7, v: 0.5),",
    );
    std::fs::write(&served.shot, pinned).unwrap();
    served.server.inputs_changed();
    let changes = drag_and_commit(&served, 30.0, (95.0, 60.0));
    let paths: Vec<&str> = changes
        .iter()
        .map(|c| c["path"].as_str().unwrap())
        .collect();
    assert_eq!(
        paths,
        [
            "highlights[0].layers[0].pin.u",
            "highlights[0].layers[0].pin.v"
        ]
    );
    assert!(
        served
            .text()
            .contains("pin: (patch: \"ball/sphere\", u: [(30, "),
        "{}",
        served.text()
    );
}

#[test]
fn commits_are_checked_like_the_file_and_refused_ones_write_nothing() {
    let served = Served::new();
    let before = served.text();
    let refused = [
        (
            json!({"kind": "set", "path": "highlights[0].layers[0].stack[2].delta", "value": [3.0]}),
            "[0, 1]",
        ),
        (
            json!({"kind": "key", "path": ALPHA, "frame": 1, "value": [1e7]}),
            "alpha",
        ),
        (
            json!({"kind": "set", "path": "highlights[1].layers[0].epsilon", "value": [0.1]}),
            "highlights[1]",
        ),
        (
            json!({"kind": "delete", "path": EPSILON, "frame": 4}),
            "no key",
        ),
        (
            json!({"kind": "remove_op", "highlight": 0, "layer": 0, "index": 9}),
            "no operation 9",
        ),
        (
            json!({"kind": "insert_op", "highlight": 0, "layer": 0, "index": 0, "op": "Shear"}),
            "Shear",
        ),
        (
            json!({"kind": "pin_to", "highlight": 0, "layer": 0, "patch": "ball/nothing"}),
            "no pin",
        ),
        (
            json!({"kind": "pin", "highlight": 0, "layer": 0, "patch": "ball/nothing", "u": 0.5, "v": 0.5}),
            "ball/nothing",
        ),
        (
            json!({"kind": "pin", "highlight": 0, "layer": 0, "patch": "ball/sphere", "u": 1.5, "v": 0.5}),
            "1.5",
        ),
        (
            json!({"kind": "unpin", "highlight": 0, "layer": 0}),
            "no pin",
        ),
        (
            json!({"kind": "add_mask", "highlight": 0, "layer": 0, "extra": 1}),
            "extra",
        ),
    ];
    for (change, says) in refused {
        let reply = served.post("/api/commit", &json!({ "changes": [change] }));
        assert_status(&reply, 400);
        let error = error_of(&reply);
        assert!(error.contains(says), "{change}: {error}");
        assert_eq!(served.text(), before, "{change} changed the file");
    }
    // Changes in one commit are all made or none: the second is bad.
    let both = json!({"changes": [
        {"kind": "set", "path": EPSILON, "value": [0.05]},
        {"kind": "set", "path": EPSILON, "value": [-1.0]},
    ]});
    assert_status(&served.post("/api/commit", &both), 400);
    assert_eq!(served.text(), before);

    // Structure: an operation added, moved and removed, a mask added — comments kept.
    let steps = [
        json!({"kind": "insert_op", "highlight": 0, "layer": 0, "index": 5, "op": "Rotate"}),
        json!({"kind": "move_op", "highlight": 0, "layer": 0, "from": 5, "to": 0}),
        json!({"kind": "add_mask", "highlight": 0, "layer": 0}),
    ];
    for step in &steps {
        assert_status(
            &served.post("/api/commit", &json!({ "changes": [step] })),
            200,
        );
    }
    let state = served.get("/api/state?frame=1").json();
    let layer = &state["highlights"][0]["layers"][0];
    assert_eq!(layer["ops"][0]["name"], "Rotate");
    assert_eq!(layer["ops"].as_array().unwrap().len(), 6);
    assert_eq!(layer["has_mask"], true);
    let text = served.text();
    assert!(
        text.starts_with("// Each highlight operation of Anjyo"),
        "the comments are kept"
    );
    let remove = json!({"changes": [{"kind": "remove_op", "highlight": 0, "layer": 0, "index": 0}, {"kind": "remove_mask", "highlight": 0, "layer": 0}]});
    assert_status(&served.post("/api/commit", &remove), 200);
    assert_eq!(
        served.text(),
        before,
        "removing what was added gives the file back"
    );
}

#[test]
fn hostile_bodies_are_refused_in_one_line_and_change_nothing() {
    let served = Served::new();
    let before = served.text();
    let key = |frame: Value, value: Value| json!({"kind": "key", "path": ALPHA, "frame": frame, "value": value});
    let many: Vec<Value> = (0..65).map(|_| key(json!(1), json!([0.1]))).collect();
    let deep = format!("{}1{}", "[".repeat(5000), "]".repeat(5000));
    let bodies = [
        json!({"changes": many}),
        json!({"changes": [key(json!("NaN"), json!([0.1]))]}),
        json!({"changes": [key(json!(1), json!([1e39]))]}),
        json!({"changes": [key(json!(1), json!([]))]}),
        json!({"changes": [key(json!(1), json!(["0.1"]))]}),
        json!({"changes": [{"kind": "set", "path": "x".repeat(100_000), "value": [0.1]}]}),
        json!({"changes": [{"kind": "set", "path": "highlights[99999999999999999999].layers[0].epsilon", "value": [0.1]}]}),
        json!({"changes": [{"kind": "remove_op", "highlight": 0, "layer": 0, "index": -1}]}),
        json!({"changes": [{"kind": "pin_to", "highlight": 0, "layer": 0, "patch": "\"), evil: ("}]}),
        json!({"changes": "all of them"}),
        json!([1, 2, 3]),
    ];
    for body in bodies {
        let reply = served.post("/api/commit", &body);
        assert_status(&reply, 400);
        error_of(&reply);
        assert_eq!(served.text(), before, "{body}");
    }
    let token = served.server.token().to_string();
    for raw in [
        deep.as_bytes(),
        b"\xff\xfe",
        b"",
        b"{\"changes\": [{\"kind\": \"set\", \"path\": \"\\u0000\"}]}",
    ] {
        let reply = request(
            served.address(),
            "POST",
            "/api/commit",
            &[("X-Glint-Token", &token)],
            raw,
        );
        assert_status(&reply, 400);
        error_of(&reply);
    }
    assert_eq!(served.text(), before);
    // A frame that is not a number.
    for frame in ["NaN", "inf", "-inf"] {
        let reply = served.get(&format!("/api/state?frame={frame}"));
        assert_status(&reply, 400);
        assert!(error_of(&reply).contains("not a finite number"));
    }
    // The server still answers, and takes as many changes as it says it takes.
    assert_status(&served.get("/api/state?frame=1"), 200);
    let most: Vec<Value> = (0..64).map(|_| key(json!(1), json!([0.1]))).collect();
    assert_status(
        &served.post("/api/commit", &json!({ "changes": most })),
        200,
    );
}

#[test]
fn undo_and_redo_write_the_file_back_and_an_outside_edit_wins() {
    let served = Served::new();
    let before = served.text();
    let set = |v: f64| json!({"changes": [{"kind": "set", "path": EPSILON, "value": [v]}]});
    assert_status(&served.post("/api/commit", &set(0.05)), 200);
    let first = served.text();
    assert_status(&served.post("/api/commit", &set(0.07)), 200);
    let second = served.text();
    assert_status(&served.post("/api/undo", &Value::Null), 200);
    assert_eq!(served.text(), first);
    assert_status(&served.post("/api/undo", &Value::Null), 200);
    assert_eq!(served.text(), before);
    assert_status(&served.post("/api/undo", &Value::Null), 409);
    assert_status(&served.post("/api/redo", &Value::Null), 200);
    assert_eq!(served.text(), first);
    let version = served.get("/api/state?frame=1").json()["version"]
        .as_u64()
        .unwrap();

    // A text editor saves the file: the next change is refused (409) and the page told.
    let outside = second.replace("colour: (1.0, 1.0, 0.92)", "colour: (1.0, 0.5, 0.5)");
    std::fs::write(&served.shot, &outside).unwrap();
    let reply = served.post("/api/commit", &set(0.09));
    assert_status(&reply, 409);
    assert_eq!(served.text(), outside, "the outside edit is kept");
    let state = served.get("/api/state?frame=1").json();
    assert!(state["version"].as_u64().unwrap() > version);
    assert_eq!(state["undo"], 0, "the history no longer applies");
    assert!(
        state["history_note"]
            .as_str()
            .is_some_and(|n| n.contains("changed outside tune")),
        "{state}"
    );
    assert_status(&served.post("/api/undo", &Value::Null), 409);
    assert_status(&served.post("/api/commit", &set(0.09)), 200);
    assert!(served.text().contains("colour: (1.0, 0.5, 0.5)"));

    // With nothing to undo, an outside edit leaves the history nothing to note.
    let fresh = Served::new();
    let version = |served: &Served| served.get("/api/state?frame=1").json()["version"].as_u64();
    let was = version(&fresh);
    let outside = fresh
        .text()
        .replace("colour: (1.0, 1.0, 0.92)", "colour: (1.0, 0.5, 0.5)");
    assert_ne!(outside, fresh.text());
    std::fs::write(&fresh.shot, outside).unwrap();
    fresh.server.inputs_changed();
    let state = fresh.get("/api/state?frame=1").json();
    assert!(state["history_note"].is_null(), "{state}");
    assert!(state["version"].as_u64() > was, "{state}");
}

#[test]
fn a_waiting_page_hears_of_a_change() {
    let served = Served::new();
    let version = served.get("/api/state?frame=1").json()["version"]
        .as_u64()
        .unwrap();
    let address = served.address();
    let token = served.server.token().to_string();
    let waiter = std::thread::spawn(move || {
        let target = format!("/api/wait?version={version}");
        request(address, "GET", &target, &[("X-Glint-Token", &token)], b"")
    });
    std::thread::sleep(std::time::Duration::from_millis(200));
    let set = json!({"changes": [{"kind": "set", "path": EPSILON, "value": [0.05]}]});
    let committed = served.post("/api/commit", &set).json()["version"]
        .as_u64()
        .unwrap();
    let heard = waiter.join().unwrap().json()["version"].as_u64().unwrap();
    assert_eq!(heard, committed);
    assert!(heard > version);
    // An edit made elsewhere reaches the page the same way.
    let token = served.server.token().to_string();
    let waiter = std::thread::spawn(move || {
        let target = format!("/api/wait?version={committed}");
        request(address, "GET", &target, &[("X-Glint-Token", &token)], b"")
    });
    std::thread::sleep(std::time::Duration::from_millis(200));
    std::fs::write(
        &served.shot,
        served.text().replace("epsilon: 0.05", "epsilon: 0.04"),
    )
    .unwrap();
    served.server.inputs_changed();
    let heard = waiter.join().unwrap().json()["version"].as_u64().unwrap();
    let state = served.get("/api/state?frame=1").json();
    assert!(state["version"].as_u64().unwrap() > committed);
    assert_eq!(heard, state["version"].as_u64().unwrap());
    let epsilon = (state["highlights"][0]["layers"][0]["params"]
        .as_array()
        .unwrap()
        .iter())
    .find(|p| p["name"] == "epsilon")
    .unwrap()["value"][0]
        .as_f64()
        .unwrap();
    assert!((epsilon - 0.04).abs() < 1e-6);
}

#[test]
fn nothing_but_the_shot_file_is_written_and_includes_are_left_alone() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("patches")).unwrap();
    std::fs::copy(
        repo_file("patches/sphere.ron"),
        dir.path().join("patches/sphere.ron"),
    )
    .unwrap();
    let looks = r#"Looks(highlights: [(patches: "ball/*", expr: Layer((stack: [Translate(alpha: 0.1, beta: 0.0)], epsilon: 0.05, colour: (1.0, 1.0, 1.0))))])"#;
    std::fs::write(dir.path().join("looks.ron"), looks).unwrap();
    let shot = dir.path().join("shot.ron");
    let text = std::fs::read_to_string(repo_file("shots/sphere_ops.ron"))
        .unwrap()
        .replace("../patches/", "patches/")
        .replace(
            "    instances: [",
            "    includes: [\"looks.ron\"],\n    instances: [",
        );
    let start = text.find("    highlights: [").unwrap();
    let end = text.find("    render: (").unwrap();
    let text = format!("{}{}", &text[..start], &text[end..]);
    std::fs::write(&shot, &text).unwrap();
    let listing = |dir: &Path| {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    };
    let files_before = listing(dir.path());
    let server = serve(&shot);
    let token = server.token().to_string();
    let post = |target: &str, body: Value| {
        request(
            server.address(),
            "POST",
            target,
            &[("X-Glint-Token", &token)],
            &serde_json::to_vec(&body).unwrap(),
        )
    };
    let state = request(
        server.address(),
        "GET",
        "/api/state?frame=1",
        &[("X-Glint-Token", &token)],
        b"",
    )
    .json();
    assert_eq!(
        state["highlights"][0]["file_index"],
        Value::Null,
        "the include's highlight is shown, not editable"
    );
    let reply = post(
        "/api/drag",
        json!({"frame": 1, "x": 80, "y": 80, "highlight": 0, "layer": 0}),
    );
    assert_status(&reply, 400);
    assert!(error_of(&reply).contains("looks.ron"), "{}", reply.text());
    let reply = post(
        "/api/commit",
        json!({"changes": [{"kind": "set", "path": EPSILON, "value": [0.1]}]}),
    );
    assert_status(&reply, 400);
    assert_eq!(
        std::fs::read_to_string(dir.path().join("looks.ron")).unwrap(),
        looks
    );
    // An accepted change writes the shot file and nothing else, no temporary left behind.
    let reply = post(
        "/api/commit",
        json!({"changes": [{"kind": "set", "path": "camera.eye", "value": [0.0, -7.0, 0.0]}]}),
    );
    assert_status(&reply, 200);
    assert!(std::fs::read_to_string(&shot)
        .unwrap()
        .contains("eye: (0.0, -7.0, 0.0)"));
    assert_eq!(listing(dir.path()), files_before);
    server.stop();
}

#[test]
fn the_command_listens_on_loopback_and_refuses_a_bad_shot_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("bad.ron");
    std::fs::write(&bad, "Shot(frames: (1, 2)").unwrap();
    let out = glint()
        .args(["tune", bad.to_str().unwrap(), "--no-open"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert_eq!(stderr(&out).lines().count(), 1, "{}", stderr(&out));
    assert!(stderr(&out).contains("bad.ron:1:"), "{}", stderr(&out));

    let shot = copy_sphere_ops(dir.path());
    let mut child = glint()
        .args([
            "tune",
            shot.to_str().unwrap(),
            "--no-open",
            "--size",
            "64x64",
        ])
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
    assert!(url.starts_with("http://127.0.0.1:"), "{line}");
    let (address, token) = url
        .trim_start_matches("http://")
        .split_once("/?token=")
        .unwrap();
    let address: SocketAddr = address.parse().unwrap();
    assert!(address.ip().is_loopback());
    // The same port again is refused at once.
    let again = glint()
        .args([
            "tune",
            shot.to_str().unwrap(),
            "--no-open",
            "--port",
            &address.port().to_string(),
        ])
        .output()
        .unwrap();
    assert_eq!(again.status.code(), Some(2), "{}", stderr(&again));
    assert!(
        stderr(&again).contains("cannot listen"),
        "{}",
        stderr(&again)
    );
    let reply = request(address, "GET", &format!("/?token={token}"), &[], b"");
    child.kill().unwrap();
    child.wait().unwrap();
    assert_status(&reply, 200);
}

/// The moving ball of `tests/motion_loop.rs`, served at 160×160.
fn serve_moving_ball() -> Served {
    let dir = tempfile::tempdir().unwrap();
    let shot = crate::motion_loop::write_moving_ball(dir.path());
    let server = serve(&shot);
    Served {
        _dir: dir,
        shot,
        server,
    }
}

/// The pixel of a 160×160 frame of the moving ball where the camera sees `(x, z)`: 160 pixels
/// over the orthographic camera's 6 units, z up.
fn ball_pixel(x: f64, z: f64) -> (f64, f64) {
    let scale = f64::from(SIZE) / 6.0;
    let centre = f64::from(SIZE) / 2.0 - 0.5;
    (centre + x * scale, centre - z * scale)
}

#[test]
fn on_a_moving_shot_frames_show_the_scrubbed_pose_and_a_drag_keys_the_moved_surface() {
    let served = serve_moving_ball();
    // Frame 10 shows the ball moved right by 1.5 and turned; frame 1 shows it at rest.
    let alpha_at = |frame: f64, (x, z): (f64, f64)| {
        let raw = served.post("/api/frame?format=raw", &json!({"frame": frame}));
        let rgba = pixels(&raw);
        let (px, py) = ball_pixel(x, z);
        rgba[(py.round() as usize * SIZE as usize + px.round() as usize) * 4 + 3]
    };
    let (rest_left, moved_right) = ((-0.7, 0.0), (2.1, 0.0));
    assert!(alpha_at(1.0, rest_left) > 0 && alpha_at(1.0, moved_right) == 0);
    assert!(alpha_at(10.0, moved_right) > 0 && alpha_at(10.0, rest_left) == 0);

    // A pick at frame 10 finds the ball where it moved, a point the ball at rest does not reach.
    let drop = ball_pixel(1.8, 0.25);
    let (x, y) = (drop.0.round(), drop.1.round());
    let reply = served.post("/api/pick", &json!({"frame": 10, "x": x, "y": y}));
    assert_status(&reply, 200);
    assert_eq!(reply.json()["patch"], "ball/sphere", "{}", reply.text());
    let reply = served.post("/api/pick", &json!({"frame": 1, "x": x, "y": y}));
    assert_status(&reply, 400);

    // A drag there keys the translation that centres the highlight on the turned ball's point.
    let changes = drag_and_commit(&served, 10.0, (x, y));
    assert!(changes.iter().all(|c| c["frame"] == 10.0), "{changes:?}");
}
