//! A pin rides along on a moving part: in `shots/teapot_lid_opens.ron`, the small glint pinned
//! to a point of the lid is centred on that point's projection on every frame where the point
//! is seen, while the lid opens and closes.

use std::sync::Arc;

use glam::{DVec3, Vec2, Vec3};
use glint::render::{Camera, Renderer};
use glint::shot::{load_shot_text, Aov, Shot};

/// The entries of the `highlights: [ … ]` list of a shot's text, each as written.
fn highlight_entries(text: &str) -> (usize, usize, Vec<(usize, usize)>) {
    let open = text.find("highlights: [").expect("a highlights list") + "highlights: [".len();
    let bytes = text.as_bytes();
    let (mut depth, mut start, mut entries) = (0usize, None, Vec::new());
    let mut comment = false;
    let mut index = open;
    while index < bytes.len() {
        let b = bytes[index];
        if comment {
            comment = b != b'\n';
        } else if text[index..].starts_with("//") {
            comment = true;
        } else if b == b'(' || b == b'[' || b == b'{' {
            if depth == 0 {
                start = Some(index);
            }
            depth += 1;
        } else if b == b')' || b == b']' || b == b'}' {
            if depth == 0 {
                return (open, index, entries);
            }
            depth -= 1;
            if depth == 0 {
                entries.push((start.take().unwrap(), index + 1));
            }
        }
        index += 1;
    }
    panic!("the highlights list is not closed");
}

/// The shot's text with only its pinned highlight entry left.
fn only_the_pinned_highlight(text: &str) -> String {
    let (open, close, entries) = highlight_entries(text);
    let pinned: Vec<&str> = entries
        .iter()
        .map(|&(a, b)| &text[a..b])
        .filter(|entry| entry.contains("pin:"))
        .collect();
    assert_eq!(pinned.len(), 1, "one pinned highlight entry");
    assert!(
        entries.len() > 1,
        "the shot has other highlights to leave out"
    );
    format!("{}{},{}", &text[..open], pinned[0], &text[close..])
}

/// Where `point` falls on a `width × height` image seen by `camera`, in pixel units with pixel
/// `(i, j)`'s centre at `(i + ½, j + ½)`: `((x + 1) w / 2, (1 − y) h / 2)` of its normalized
/// device coordinates.
fn project(camera: &Camera, point: DVec3, (width, height): (u32, u32)) -> Vec2 {
    let clip = camera.view_projection(width as f32 / height as f32) * point.as_vec3().extend(1.0);
    let ndc = Vec3::new(clip.x, clip.y, clip.z) / clip.w;
    Vec2::new(
        (ndc.x + 1.0) * 0.5 * width as f32,
        (1.0 - ndc.y) * 0.5 * height as f32,
    )
}

/// The matte's coverage-weighted centroid and its area, pixel centres at `(i + ½, j + ½)`.
fn centroid(matte: &[f32], width: u32) -> (Vec2, f32) {
    let (mut sum, mut area) = (Vec2::ZERO, 0.0);
    for (p, &m) in matte.iter().enumerate() {
        let at = Vec2::new(
            (p as u32 % width) as f32 + 0.5,
            (p as u32 / width) as f32 + 0.5,
        );
        sum += m * at;
        area += m;
    }
    (sum / area.max(1e-6), area)
}

/// The pin of the shot's one pinned layer: its patch's index and its (u, v), read from the
/// text of `pin: (patch: "NAME", u: U, v: V)`.
fn pin_of(shot: &Shot, text: &str) -> (usize, f64, f64) {
    let pin = &text[text.find("pin: (").unwrap()..];
    let pin = &pin[..pin.find(')').unwrap()];
    let field = |name: &str| {
        let at = pin.find(&format!("{name}: ")).unwrap() + name.len() + 2;
        pin[at..]
            .split([',', ')'])
            .next()
            .unwrap()
            .trim()
            .to_string()
    };
    let patch = field("patch").trim_matches('"').to_string();
    let index = shot
        .library
        .patches
        .iter()
        .position(|p| p.name == patch)
        .unwrap_or_else(|| panic!("no patch {patch}"));
    (
        index,
        field("u").parse().unwrap(),
        field("v").parse().unwrap(),
    )
}

/// How far the glint's centroid may be from the pin's projection on any frame where the pin
/// is seen, in pixels.
const WITHIN: f32 = 1.0;
/// How far the pin's point on the unmoved lid must be from the glint once the lid has moved
/// (pixels): several pixels, so that missing the motion would fail the test.
const UNMOVED_AT_LEAST: f32 = 5.0;

#[test]
fn the_glint_pinned_to_the_lid_rides_along_as_the_lid_opens_and_closes() {
    let path = crate::common::repo_file("shots/teapot_lid_opens.ron");
    let text = only_the_pinned_highlight(&std::fs::read_to_string(&path).unwrap());
    let mut shot = load_shot_text(&path, text.clone()).unwrap_or_else(|e| panic!("{e}"));
    assert!(shot.moves());
    let (patch, u, v) = pin_of(&shot, &text);
    shot.aovs = vec![Aov::Matte, Aov::PatchId];
    let size = (640, 360);
    assert_eq!((shot.settings.width, shot.settings.height), size);
    // The shot as it renders: its own preset and anti-aliasing.
    let settings = shot.settings_with(None, None);
    let unmoved = Arc::clone(&shot.library);
    let mut renderer = Renderer::new(Arc::clone(&shot.library));
    let (mut seen, mut moved) = (0, 0);
    let mut offsets = Vec::new();
    for frame in shot.frames.0..=shot.frames.1 {
        let state = shot.at(frame as f64);
        let scene = state.scene(&shot).unwrap();
        let image = renderer.render(&scene, &settings).unwrap();
        let point = state.library.patches[patch].surface.point(u, v);
        let at = project(&state.camera, point, size);
        // Seen: the pin's patch is what the pixel under its point shows.
        let ids = image.aovs.patch_id.unwrap();
        let pixel = at.y.floor() as usize * size.0 as usize + at.x.floor() as usize;
        if ids.get(pixel) != Some(&(patch as u32)) {
            continue;
        }
        seen += 1;
        let (centre, area) = centroid(&image.aovs.matte.unwrap(), size.0);
        assert!(area > 4.0, "frame {frame}: no glint ({area} px)");
        offsets.push((frame, centre.distance(at), centre, at));
        // Where the lid has moved, the pin's point on the unmoved model is far from the glint.
        let still = unmoved.patches[patch].surface.point(u, v);
        if point.distance(still) > 0.3 {
            moved += 1;
            let wrong = centre.distance(project(&state.camera, still, size));
            assert!(
                wrong >= UNMOVED_AT_LEAST,
                "frame {frame}: the unmoved pin is only {wrong} px from the glint"
            );
        }
    }
    let frames = shot.frames.1 - shot.frames.0 + 1;
    let astray: Vec<_> = offsets.iter().filter(|o| o.1 > WITHIN).collect();
    assert!(
        astray.is_empty(),
        "the glint leaves its pin on frames (frame, px, centroid, pin) {astray:?}"
    );
    assert!(
        seen as i64 * 4 >= frames * 3,
        "the pin is seen on {seen} of {frames} frames"
    );
    assert!(moved >= 15, "the lid moved the pin on {moved} frames only");
}
