//! Rigid motion is exact: between keys, a keyed instance or part is placed where the keys'
//! linear interpolation puts it (control points against a rotation written out here, and
//! frames byte for byte against a shot placed there by constants), and a quarter turn keyed
//! about the view axis turns the rendered silhouette by 45° at its midpoint.

use std::sync::Arc;

use glam::DVec3;
use glint::geom::PatchLibrary;
use glint::render::{RenderedFrame, Renderer};
use glint::shot::{load_shot_text, Shot};

/// A shot of the teapot, `instance` being the fields of its instance after its file, with a
/// lit cel ramp, a glint on every patch and every kind of line.
fn teapot_shot(instance: &str, (width, height): (u32, u32), camera: &str) -> Shot {
    let text = format!(
        r#"Shot(
    resolution: ({width}, {height}),
    frames: (1, 9),
    fps: 24,
    output: "out/rigid.#.png",
    instances: [(name: "teapot", file: "../patches/teapot.bpt", material: "m"{instance})],
    materials: {{"m": Cel(base: (0.1, 0.16, 0.32), bands: [(0.0, (0.3, 0.45, 0.8)), (0.55, (0.45, 0.62, 0.95))])}},
    camera: {camera},
    light: Directional(towards: (-0.35, -0.55, 0.75)),
    highlights: [(patches: "teapot/*", expr: Layer((stack: [], epsilon: 0.03, colour: (1.0, 1.0, 1.0))))],
    render: (preset: Final, outlines: (width: 1.5, kinds: [Silhouette, Crease, Border, Intersection])),
)"#
    );
    // The shot is read as if it were a file of `shots/`; that file is not read.
    let path = crate::common::repo_file("shots/rigid_motion.ron");
    load_shot_text(&path, text).unwrap_or_else(|e| panic!("{e}"))
}

/// The perspective view of the rigid-motion shots: the teapot from the front right and above,
/// far enough for every placement to stay in the picture.
const VIEW: &str = "(eye: (7.0, -9.0, 6.0), target: (0.5, -0.3, 1.5), projection: Perspective(fov_y_degrees: 38.0))";

/// Renders `frame` of `shot` with `renderer`, with the patch-id and depth images.
fn render(renderer: &mut Renderer, shot: &Shot, frame: f64) -> RenderedFrame {
    let state = shot.at(frame);
    let mut scene = state.scene(shot).unwrap();
    scene.aovs.patch_id = true;
    scene.aovs.depth = true;
    renderer.render(&scene, &shot.settings).unwrap()
}

/// The colour's and the depth's bits, and the patch ids, of a frame.
fn bytes(image: &RenderedFrame) -> (Vec<u32>, Vec<u32>, Vec<u32>) {
    let colour = image
        .colour
        .iter()
        .flat_map(|c| c.to_array())
        .map(f32::to_bits)
        .collect();
    let depth = image.aovs.depth.as_ref().unwrap();
    let ids = image.aovs.patch_id.clone().unwrap();
    (colour, depth.iter().map(|d| d.to_bits()).collect(), ids)
}

/// `a + t (b − a)`, the linear interpolation between two keys.
fn lerp(a: f64, b: f64, t: f64) -> f64 {
    a + t * (b - a)
}

/// Componentwise `a + t (b − a)`.
fn lerp3(a: DVec3, b: DVec3, t: f64) -> DVec3 {
    DVec3::new(lerp(a.x, b.x, t), lerp(a.y, b.y, t), lerp(a.z, b.z, t))
}

/// Rodrigues' rotation of `v` by `degrees` about the unit axis `k`:
/// `v cos θ + (k × v) sin θ + k (k · v)(1 − cos θ)`.
fn rodrigues(v: DVec3, k: DVec3, degrees: f64) -> DVec3 {
    let (sin, cos) = degrees.to_radians().sin_cos();
    v * cos + k.cross(v) * sin + k * k.dot(v) * (1.0 - cos)
}

/// `translate + pivot + R(axis, degrees)(scale · (p − pivot))`, the rotation by Rodrigues.
fn place(p: DVec3, translate: DVec3, axis: DVec3, degrees: f64, scale: f64, pivot: DVec3) -> DVec3 {
    translate + pivot + rodrigues(scale * (p - pivot), axis.normalize(), degrees)
}

/// A point as RON, each coordinate written so that it reads back as the same f64.
fn ron3(p: DVec3) -> String {
    format!("({:?}, {:?}, {:?})", p.x, p.y, p.z)
}

/// The largest distance between the control points of two libraries, patch by patch.
fn largest_gap(a: &PatchLibrary, b: &[Vec<DVec3>]) -> f64 {
    a.patches
        .iter()
        .zip(b)
        .flat_map(|(patch, points)| {
            patch
                .surface
                .control_points()
                .zip(points)
                .map(|(p, q)| p.distance(*q))
        })
        .fold(0.0, f64::max)
}

/// Frames between keys (the keys are at 1 and 9), and the last key.
const FRAMES: [f64; 4] = [2.5, 4.0, 6.75, 9.0];

#[test]
fn a_keyed_instance_is_placed_exactly_where_its_keys_interpolate_between_them() {
    // Every number keyed from frame 1 to 9: a translation, a turn about a tilted axis through
    // a moving pivot, and a scale.
    let (t0, t1) = (DVec3::ZERO, DVec3::new(1.2, -0.8, 0.5));
    let axis = DVec3::new(0.3, -0.5, 1.0);
    let (d0, d1) = (0.0, 75.0);
    let (s0, s1) = (1.0, 0.75);
    let (p0, p1) = (DVec3::new(0.5, 0.0, 1.0), DVec3::new(0.2, 0.4, 1.5));
    let keyed = teapot_shot(
        &format!(
            ", transform: (translate: [(1, {}), (9, {})], axis: {}, degrees: [(1, {d0:?}), (9, {d1:?})], scale: [(1, {s0:?}), (9, {s1:?})], pivot: [(1, {}), (9, {})])",
            ron3(t0),
            ron3(t1),
            ron3(axis),
            ron3(p0),
            ron3(p1)
        ),
        (96, 64),
        VIEW,
    );
    assert!(keyed.moves());
    let model = crate::common::teapot();
    let mut renderer = Renderer::new(Arc::clone(&keyed.library));
    for frame in FRAMES {
        // The keys' linear interpolation, by hand; one fixed axis, so the angle is the
        // interpolated angle.
        let t = (frame - 1.0) / (9.0 - 1.0);
        let (translate, degrees) = (lerp3(t0, t1, t), lerp(d0, d1, t));
        let (scale, pivot) = (lerp(s0, s1, t), lerp3(p0, p1, t));
        let by_hand: Vec<Vec<DVec3>> = model
            .patches
            .iter()
            .map(|patch| {
                patch
                    .surface
                    .control_points()
                    .map(|p| place(p, translate, axis, degrees, scale, pivot))
                    .collect()
            })
            .collect();
        let posed = keyed.library_at(frame);
        let gap = largest_gap(&posed, &by_hand);
        assert!(gap < 1e-12, "frame {frame}: control points {gap:e} off");

        // The same teapot placed there by constants renders the same bytes.
        let fixed = teapot_shot(
            &format!(
                ", transform: (translate: {}, axis: {}, degrees: {degrees:?}, scale: {scale:?}, pivot: {})",
                ron3(translate),
                ron3(axis),
                ron3(pivot)
            ),
            (96, 64),
            VIEW,
        );
        assert!(!fixed.moves());
        let moving = render(&mut renderer, &keyed, frame);
        let still = render(&mut Renderer::new(Arc::clone(&fixed.library)), &fixed, 1.0);
        let covered = still.aovs.patch_id.as_ref().unwrap();
        assert!(covered.iter().filter(|&&id| id != u32::MAX).count() > 500);
        assert!(
            bytes(&moving) == bytes(&still),
            "frame {frame}: the keyed teapot differs from the teapot placed by hand"
        );
    }
}

#[test]
fn a_keyed_part_is_placed_exactly_where_its_keys_interpolate_between_them() {
    // The lid and its knob lift and turn open about a hinge at the back of the rim.
    let cover: Vec<usize> = (20..28).collect();
    let pivot = DVec3::new(-1.4, 0.0, 2.45);
    let axis = DVec3::Y;
    let (d0, d1) = (0.0, -50.0);
    let (t0, t1) = (DVec3::ZERO, DVec3::new(0.0, 0.0, 0.3));
    let groups = ", groups: {\"cover\": [20, 21, 22, 23, 24, 25, 26, 27]}";
    let keyed = teapot_shot(
        &format!(
            "{groups}, parts: {{\"cover\": (translate: [(1, {}), (9, {})], pivot: {}, axis: {}, degrees: [(1, {d0:?}), (9, {d1:?})])}}",
            ron3(t0),
            ron3(t1),
            ron3(pivot),
            ron3(axis)
        ),
        (96, 64),
        VIEW,
    );
    assert!(keyed.moves());
    let model = crate::common::teapot();
    let mut renderer = Renderer::new(Arc::clone(&keyed.library));
    for frame in FRAMES {
        let t = (frame - 1.0) / (9.0 - 1.0);
        let (translate, degrees) = (lerp3(t0, t1, t), lerp(d0, d1, t));
        let by_hand: Vec<Vec<DVec3>> = model
            .patches
            .iter()
            .enumerate()
            .map(|(index, patch)| {
                patch
                    .surface
                    .control_points()
                    .map(|p| {
                        if cover.contains(&index) {
                            place(p, translate, axis, degrees, 1.0, pivot)
                        } else {
                            p
                        }
                    })
                    .collect()
            })
            .collect();
        let posed = keyed.library_at(frame);
        let gap = largest_gap(&posed, &by_hand);
        assert!(gap < 1e-12, "frame {frame}: control points {gap:e} off");
        // The rest of the teapot stays exactly where it was.
        for (index, patch) in posed.patches.iter().enumerate() {
            if !cover.contains(&index) {
                assert_eq!(patch.surface, model.patches[index].surface, "patch {index}");
            }
        }

        let fixed = teapot_shot(
            &format!(
                "{groups}, parts: {{\"cover\": (translate: {}, pivot: {}, axis: {}, degrees: {degrees:?})}}",
                ron3(translate),
                ron3(pivot),
                ron3(axis)
            ),
            (96, 64),
            VIEW,
        );
        assert!(!fixed.moves());
        let moving = render(&mut renderer, &keyed, frame);
        let still = render(&mut Renderer::new(Arc::clone(&fixed.library)), &fixed, 1.0);
        assert!(
            bytes(&moving) == bytes(&still),
            "frame {frame}: the keyed lid differs from the lid placed by hand"
        );
    }
}

/// The angle in degrees, in (−90°, 90°], of the principal axis of the pixels `on` marks: the
/// direction of largest second moment about their centroid,
/// `½ atan2(2 μ_xy, μ_xx − μ_yy)`, with y measured upward.
fn principal_axis_degrees(on: &[bool], (w, h): (usize, usize)) -> f64 {
    let points: Vec<(f64, f64)> = (0..w * h)
        .filter(|&p| on[p])
        .map(|p| ((p % w) as f64 + 0.5, -((p / w) as f64 + 0.5)))
        .collect();
    let n = points.len() as f64;
    let (cx, cy) = points
        .iter()
        .fold((0.0, 0.0), |(x, y), p| (x + p.0 / n, y + p.1 / n));
    let (mut xx, mut yy, mut xy) = (0.0, 0.0, 0.0);
    for (x, y) in &points {
        let (dx, dy) = (x - cx, y - cy);
        xx += dx * dx;
        yy += dy * dy;
        xy += dx * dy;
    }
    0.5 * (2.0 * xy).atan2(xx - yy).to_degrees()
}

/// `a − b` for axis angles, which repeat every 180°: in (−90°, 90°].
fn axis_turn(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(180.0);
    if d > 90.0 {
        d - 180.0
    } else {
        d
    }
}

/// How far the measured turn may be from the keyed one: the silhouette is about 150 pixels
/// long, so a pixel's worth of staircase at its ends moves its axis by well under half a degree.
const TURN_TOLERANCE_DEGREES: f64 = 0.5;

#[test]
fn a_quarter_turn_keyed_about_the_view_axis_turns_the_silhouette_by_45_degrees_at_its_midpoint() {
    // From straight above, orthographic: the teapot's outline (body, spout and handle) is
    // longer along x than across, so its principal axis is well defined.
    let size = (160usize, 160usize);
    let above = "(eye: (0.0, 0.0, 10.0), target: (0.0, 0.0, 0.0), up: (0.0, 1.0, 0.0), projection: Orthographic(height: 8.0))";
    let shot = teapot_shot(
        ", transform: (axis: (0, 0, 1), degrees: [(1, 0), (9, 90)])",
        (size.0 as u32, size.1 as u32),
        above,
    );
    let mut renderer = Renderer::new(Arc::clone(&shot.library));
    let settings = shot.settings_with(Some(glint::shot::Preset::Preview), None);
    let mut axis_at = |frame: f64| {
        let state = shot.at(frame);
        let mut scene = state.scene(&shot).unwrap();
        scene.aovs.patch_id = true;
        let image = renderer.render(&scene, &settings).unwrap();
        let on: Vec<bool> = image
            .aovs
            .patch_id
            .unwrap()
            .iter()
            .map(|&id| id != u32::MAX)
            .collect();
        assert!(on.iter().filter(|&&o| o).count() > 4000, "frame {frame}");
        principal_axis_degrees(&on, size)
    };
    let first = axis_at(1.0);
    // The spout–handle line lies along x at the start.
    assert!(first.abs() < 5.0, "the axis starts at {first}°");
    for (frame, keyed) in [(5.0, 45.0), (9.0, 90.0)] {
        let turn = axis_turn(axis_at(frame), first);
        // At 90° the axis is defined up to a half turn: −90° is the same axis as 90°.
        let off = axis_turn(turn, keyed).abs();
        assert!(
            off <= TURN_TOLERANCE_DEGREES,
            "frame {frame}: the silhouette turned {turn}°, keyed {keyed}°"
        );
    }
    // The measure sees turns: a quarter of the way, the axis has not turned 45°.
    let early = axis_turn(axis_at(3.0), first);
    assert!(
        (early - 22.5).abs() <= TURN_TOLERANCE_DEGREES,
        "frame 3: {early}°"
    );
}
