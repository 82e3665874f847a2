//! Placing a cel band's edge on a pixel with a shade entry's translation (`glint place --shade`,
//! `RenderJob::place_shade`): after `--write`, the frame rendered through the library has the
//! band's edge within a pixel of the one pointed at, on the sphere and on the teapot's body;
//! and every point no translation can move the edge to is refused with exit 2 and one line.

use std::path::{Path, PathBuf};
use std::process::Output;
use std::sync::Arc;

use glint::render::{RenderedFrame, Renderer};
use glint::shot::load_shot;

use crate::common::{glint_with, repo_file, stderr};

/// The shadow's and the band's colours: pixels are told apart by their red, halfway between.
const BASE: f32 = 0.1;
const LIT: f32 = 0.9;

/// A shot of one instance of `model` lit by `light`, toned by `material`, with `shade` as its
/// `shade` list, written into `dir` as `name.ron`.
struct TestShot<'a> {
    model: &'a str,
    size: (u32, u32),
    frames: (i64, i64),
    camera: &'a str,
    light: &'a str,
    material: String,
    shade: &'a str,
}

impl TestShot<'_> {
    fn write(&self, dir: &Path, name: &str) -> PathBuf {
        let text = format!(
            r#"Shot(
    resolution: ({w}, {h}),
    frames: ({f0}, {f1}),
    fps: 24,
    output: "out/{name}.####.png",
    instances: [(name: "m", file: "{model}", material: "tone")],
    materials: {{ "tone": {material} }},
    camera: {camera},
    light: {light},
    shade: {shade},
    render: (preset: Preview),
)
"#,
            w = self.size.0,
            h = self.size.1,
            f0 = self.frames.0,
            f1 = self.frames.1,
            model = repo_file(self.model).display(),
            material = self.material,
            camera = self.camera,
            light = self.light,
            shade = self.shade,
        );
        let path = dir.join(format!("{name}.ron"));
        std::fs::write(&path, text).unwrap();
        path
    }
}

/// A two-tone cel ramp whose band starts at `threshold`.
fn two_tone(threshold: f32) -> String {
    format!("Cel(base: ({BASE}, {BASE}, {BASE}), bands: [({threshold}, ({LIT}, {LIT}, {LIT}))])")
}

/// The frame of the shot at `path` rendered through the library, with its patch ids.
fn render(path: &Path, frame: f64) -> RenderedFrame {
    let shot = load_shot(path).unwrap_or_else(|e| panic!("{e}"));
    let state = shot.at(frame);
    let mut scene = state.scene(&shot).unwrap();
    scene.aovs.patch_id = true;
    let mut renderer = Renderer::new(Arc::clone(&shot.library));
    renderer.render(&scene, &shot.settings).unwrap()
}

/// Per pixel: `None` off the model, else whether it shows the band (past the edge).
fn sides(image: &RenderedFrame) -> Vec<Option<bool>> {
    image
        .colour
        .iter()
        .map(|c| (c.w > 0.99).then_some(c.x > 0.5 * (BASE + LIT)))
        .collect()
}

/// The pixels within `radius` (a square) of `(x, y)`, with the pixel's side, all on the model.
fn window(
    sides: &[Option<bool>],
    width: u32,
    (x, y): (i64, i64),
    radius: i64,
) -> Option<Vec<bool>> {
    let height = sides.len() as i64 / i64::from(width);
    let mut out = Vec::new();
    for dy in -radius..=radius {
        for dx in -radius..=radius {
            let (px, py) = (x + dx, y + dy);
            if px < 0 || py < 0 || px >= i64::from(width) || py >= height {
                return None;
            }
            out.push(sides[(py * i64::from(width) + px) as usize]?);
        }
    }
    Some(out)
}

/// Whether `(x, y)` and its four neighbours, all on the model, lie on both sides of the edge.
fn edge_within_a_pixel(sides: &[Option<bool>], width: u32, (x, y): (i64, i64)) -> bool {
    let at = |px: i64, py: i64| sides[(py * i64::from(width) + px) as usize];
    let five = [
        at(x, y),
        at(x - 1, y),
        at(x + 1, y),
        at(x, y - 1),
        at(x, y + 1),
    ];
    five.iter().all(Option::is_some) && five.contains(&Some(true)) && five.contains(&Some(false))
}

fn place(shot: &Path, frame: i64, (x, y): (i64, i64), more: &[&str]) -> Output {
    let mut args = vec![
        "place".to_string(),
        shot.display().to_string(),
        "--frame".to_string(),
        frame.to_string(),
        "--pixel".to_string(),
        format!("{x},{y}"),
        "--shade".to_string(),
    ];
    args.extend(more.iter().map(ToString::to_string));
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    glint_with(&args)
}

fn assert_exit(out: &Output, code: i32) {
    assert_eq!(
        out.status.code(),
        Some(code),
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        stderr(out)
    );
}

/// Places band 0's edge on each of `pixels` at `frame` with --write, each on the shot as first
/// written, and checks after each that the edge was not near the pixel before and is within a
/// pixel of it after.
fn place_and_check(shot: &Path, frame: i64, pixels: &[(i64, i64)], width: u32) {
    let written = std::fs::read_to_string(shot).unwrap();
    for &pixel in pixels {
        std::fs::write(shot, &written).unwrap();
        let before = sides(&render(shot, frame as f64));
        let window_before = window(&before, width, pixel, 2).expect("on the model");
        assert!(
            window_before.iter().all(|&s| s == window_before[0]),
            "{pixel:?} at frame {frame}: the edge is already near"
        );
        let out = place(shot, frame, pixel, &["--band", "0", "--write"]);
        assert_exit(&out, 0);
        let after = sides(&render(shot, frame as f64));
        assert!(
            edge_within_a_pixel(&after, width, pixel),
            "{pixel:?} at frame {frame}: no edge within a pixel after placing\n{}",
            String::from_utf8_lossy(&out.stdout)
        );
    }
}

/// The sphere seen along +y through an orthographic camera 2.4 high: the outward normal under
/// the centre of pixel `(x, y)` of a `size` image, if the pixel shows the sphere.
fn sphere_normal((x, y): (i64, i64), size: (u32, u32)) -> Option<glam::DVec3> {
    let scale = 2.4 / f64::from(size.1);
    let wx = (x as f64 + 0.5 - f64::from(size.0) / 2.0) * scale;
    let wz = (f64::from(size.1) / 2.0 - (y as f64 + 0.5)) * scale;
    let r2 = wx * wx + wz * wz;
    (r2 < 1.0).then(|| glam::DVec3::new(wx, -(1.0 - r2).sqrt(), wz))
}

const SPHERE_CAMERA: &str =
    "(eye: (0.0, -6.0, 0.0), target: (0.0, 0.0, 0.0), projection: Orthographic(height: 2.4))";

/// The light of the sphere shot at frames 1 and 3.
const SPHERE_LIGHTS: [(f64, [f64; 3]); 2] = [(1.0, [0.5, -1.0, 0.4]), (3.0, [-0.3, -1.0, 0.6])];

fn sphere_shot(shade: &str, threshold: f32) -> TestShot<'_> {
    TestShot {
        model: "patches/sphere.ron",
        size: (120, 120),
        frames: (1, 3),
        camera: SPHERE_CAMERA,
        light: "Directional(towards: [(1, (0.5, -1.0, 0.4)), (3, (-0.3, -1.0, 0.6))])",
        material: two_tone(threshold),
        shade,
    }
}

/// Pixels of the sphere, on a coarse grid, whose `N·L` (the plain light at `frame`) lies in
/// `range` and whose 5 × 5 window shows one side: the first `count` in scan order spread
/// over the grid.
fn sphere_pixels(
    sides: &[Option<bool>],
    frame: f64,
    range: std::ops::Range<f64>,
    count: usize,
) -> Vec<(i64, i64)> {
    let size = (120, 120);
    let light = SPHERE_LIGHTS
        .iter()
        .find(|(f, _)| *f == frame)
        .map(|(_, l)| glam::DVec3::from_array(*l).normalize())
        .unwrap();
    let mut found = Vec::new();
    for y in (10..110).step_by(9) {
        for x in (10..110).step_by(11) {
            let Some(n) = sphere_normal((x, y), size) else {
                continue;
            };
            let uniform =
                window(sides, size.0, (x, y), 2).is_some_and(|w| w.iter().all(|&s| s == w[0]));
            if range.contains(&n.dot(light)) && uniform && n.y < -0.3 {
                found.push((x, y));
            }
        }
    }
    let step = (found.len() / count.max(1)).max(1);
    found.into_iter().step_by(step).take(count).collect()
}

#[test]
fn the_band_edge_is_placed_on_the_pixel_on_the_sphere() {
    let dir = tempfile::tempdir().unwrap();
    let shade = r#"[(
        patches: "m/*",
        stack: [Translate(alpha: [(1, 0.0), (3, 0.1)], beta: 0.05), Square(sigma: 0.25, n: 2.0)],
    )]"#;
    let shot = sphere_shot(shade, 0.3).write(dir.path(), "sphere");
    for frame in [1, 3] {
        let now = sides(&render(&shot, frame as f64));
        // Lit points (the edge moves toward the light) and points in the band's shadow but on
        // the light's side (it moves away).
        let mut pixels = sphere_pixels(&now, frame as f64, 0.55..0.95, 2);
        pixels.extend(sphere_pixels(&now, frame as f64, 0.08..0.2, 1));
        assert_eq!(pixels.len(), 3, "frame {frame}: {pixels:?}");
        place_and_check(&shot, frame, &pixels, 120);
    }
    // α was keyed, so the placements keyed it at their frames; β was a constant and is one.
    let text = std::fs::read_to_string(&shot).unwrap();
    assert!(text.contains("alpha: [(1, "), "{text}");
    assert!(!text.contains("beta: ["), "{text}");
}

#[test]
fn the_band_edge_is_placed_on_the_pixel_on_the_teapot_body() {
    let dir = tempfile::tempdir().unwrap();
    let size = (200, 120);
    let shot = TestShot {
        model: "patches/teapot.bpt",
        size,
        frames: (1, 2),
        camera: "(eye: (5.5, -7.0, 4.5), target: (0.0, 0.0, 1.4), projection: Perspective(fov_y_degrees: 30.0))",
        light: "Directional(towards: [(1, (-0.4, -1.0, 0.8)), (2, (0.6, -1.0, 0.5))])",
        material: two_tone(0.3),
        shade: r#"[(patches: "m/body", stack: [Translate(alpha: 0.0, beta: 0.0)])]"#,
    }
    .write(dir.path(), "teapot");
    let loaded = load_shot(&shot).unwrap();
    for frame in [1, 2] {
        let image = render(&shot, f64::from(frame));
        let now = sides(&image);
        let ids = image.aovs.patch_id.clone().unwrap();
        // Lit pixels of the body, the 5 × 5 window around each on one body patch.
        let mut found = Vec::new();
        for y in (8..i64::from(size.1) - 8).step_by(7) {
            for x in (8..i64::from(size.0) - 8).step_by(7) {
                let id = ids[(y * i64::from(size.0) + x) as usize];
                let on_body = id != u32::MAX && !loaded.shade_of(id as usize).is_empty();
                let same = (-2..=2).all(|dy| {
                    (-2..=2).all(|dx| ids[((y + dy) * i64::from(size.0) + x + dx) as usize] == id)
                });
                let lit = window(&now, size.0, (x, y), 2).is_some_and(|w| w.iter().all(|&s| s));
                if on_body && same && lit {
                    found.push((x, y));
                }
            }
        }
        assert!(found.len() >= 3, "frame {frame}: {found:?}");
        let step = found.len() / 3;
        let pixels: Vec<(i64, i64)> = found.into_iter().step_by(step).take(3).collect();
        place_and_check(&shot, i64::from(frame), &pixels, size.0);
    }
}

/// `out` exited 2 with one line naming `shot` and containing `what`.
fn assert_refused(out: &Output, shot: &Path, what: &str) {
    assert_exit(out, 2);
    let message = stderr(out);
    assert_eq!(message.lines().count(), 1, "{message}");
    assert!(
        message.contains(&format!("{}: ", shot.display())),
        "{message}"
    );
    assert!(message.contains(what), "expected “{what}”: {message}");
}

#[test]
fn points_no_translation_reaches_are_refused_with_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let translate = r#"[(patches: "m/*", stack: [Translate(alpha: 0.0, beta: 0.0)])]"#;
    // Frame 1's light: N·L of the plain light at a pixel of the sphere.
    let light = glam::DVec3::from_array(SPHERE_LIGHTS[0].1).normalize();
    let lit = (75, 45);
    let dark = (11, 60);
    let n_dot_l = |p| sphere_normal(p, (120, 120)).unwrap().dot(light);
    assert!(n_dot_l(lit) > 0.6 && n_dot_l(dark) < -0.15);

    // A point facing away from the light, the band on the light's side.
    let shot = sphere_shot(translate, 0.3).write(dir.path(), "signs");
    let before = std::fs::read_to_string(&shot).unwrap();
    let out = place(&shot, 1, dark, &["--write"]);
    assert_refused(
        &out,
        &shot,
        "no translation of the light changes the sign of N·L",
    );
    assert_eq!(std::fs::read_to_string(&shot).unwrap(), before);

    // A band at threshold 0: the terminator.
    let shot = sphere_shot(translate, 0.0).write(dir.path(), "zero");
    let out = place(&shot, 1, lit, &[]);
    assert_refused(&out, &shot, "threshold above 0, on the light's side");

    // A point outside the entry's mask: no translation changes N·L' there.
    let masked = r#"[(patches: "m/*", stack: [Translate(alpha: 0.0, beta: 0.0)],
        mask: Some((u: (0.1, 0.2), v: (0.0, 1.0), feather: 0.0)))]"#;
    let shot = sphere_shot(masked, 0.3).write(dir.path(), "masked");
    let out = place(&shot, 1, lit, &[]);
    assert_refused(&out, &shot, "no translation of shade entry 0");
    assert_refused(&out, &shot, "outside the entry's mask");

    // An entry without a translation, named.
    let square = r#"[(patches: "m/*", stack: [Square(sigma: 0.2, n: 2.0)])]"#;
    let shot = sphere_shot(square, 0.3).write(dir.path(), "square");
    let out = place(&shot, 1, lit, &[]);
    assert_refused(&out, &shot, "shade entry 0 (shade[0] in");
    assert_refused(&out, &shot, "has no Translate to place");

    // A band the material does not have.
    let shot = sphere_shot(translate, 0.3).write(dir.path(), "bands");
    let out = place(&shot, 1, lit, &["--band", "1"]);
    assert_refused(&out, &shot, "so no band 1");

    // An X-Toon tone has no bands.
    let mut xtoon = sphere_shot(translate, 0.3);
    xtoon.material = format!(
        "XToon(texture: \"{}\", detail: Depth(z_min: 9.0, r: 3.5))",
        repo_file("textures/abstraction.png").display()
    );
    let shot = xtoon.write(dir.path(), "xtoon");
    let out = place(&shot, 1, lit, &[]);
    assert_refused(&out, &shot, "X-Toon");
}

#[test]
fn a_patch_without_the_entry_is_refused_with_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let size = (200, 120);
    let shot = TestShot {
        model: "patches/teapot.bpt",
        size,
        frames: (1, 1),
        camera: "(eye: (5.5, -7.0, 4.5), target: (0.0, 0.0, 1.4), projection: Perspective(fov_y_degrees: 30.0))",
        light: "Directional(towards: (-0.4, -1.0, 0.8))",
        material: two_tone(0.3),
        shade: r#"[
            (patches: "m/body", stack: [Translate(alpha: 0.0, beta: 0.0)]),
            (patches: "m/lid", stack: [Translate(alpha: 0.0, beta: 0.0)]),
        ]"#,
    }
    .write(dir.path(), "parts");
    let loaded = load_shot(&shot).unwrap();
    let image = render(&shot, 1.0);
    let ids = image.aovs.patch_id.clone().unwrap();
    let pixel_where = |keep: &dyn Fn(&[u32]) -> bool| -> (i64, i64) {
        let at = ids
            .iter()
            .position(|&id| id != u32::MAX && keep(loaded.shade_of(id as usize)))
            .unwrap();
        ((at % size.0 as usize) as i64, (at / size.0 as usize) as i64)
    };
    // The spout or handle: no entry picks it.
    let bare = pixel_where(&|entries| entries.is_empty());
    let out = place(&shot, 1, bare, &[]);
    assert_refused(&out, &shot, "has no shade entry");
    // The body with the lid's entry.
    let body = pixel_where(&|entries| entries == [0]);
    let out = place(&shot, 1, body, &["--entry", "1"]);
    assert_refused(&out, &shot, "shade entry 1 does not pick");
}

#[test]
fn place_help_describes_the_shade_placing() {
    let out = glint_with(&["place", "--help"]);
    assert_exit(&out, 0);
    let help = String::from_utf8_lossy(&out.stdout).into_owned();
    for words in [
        "--shade",
        "--entry",
        "--band",
        "Placing the shadow",
        "threshold 0",
    ] {
        assert!(help.contains(words), "{words}:\n{help}");
    }
    let doc = std::fs::read_to_string(repo_file("docs/highlights.md")).unwrap();
    let section = &doc[doc.find("## Placing the shadow").expect("the section")..];
    assert!(section.contains("glint place"), "{section}");
}
