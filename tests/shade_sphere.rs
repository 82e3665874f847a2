//! Designed shade against the analytic sphere: the exact NURBS unit sphere rendered with the
//! `final` preset and a two-colour cel ramp whose band edge sits at `N·L' = 0.3`, each shade
//! operation alone (and a keyed translation read between its keys), against the lit region
//! worked out here in closed form.
//!
//! The closed form: each of 8 × 8 sub-pixel samples is ray-cast to the unit sphere; at the hit
//! `p`, `N = p`, and the frame of the patch's parameterization (u east about +z, v from the
//! south to the north pole) is `du = (−N.y, N.x, 0)/|…|`, `dv = N × du`, checked below against
//! finite differences of the patch. The light's frame coordinates `(l_u, l_v, l_n)` go through
//! the operation's formula (docs/highlights.md, the `Op` docs), written out here in f64, each op
//! ending by normalizing; the sample is lit when `N·L' > 0.3`. A pixel's truth is the fraction
//! of its 64 samples that are lit.
//!
//! The render's lit coverage of a pixel is its colour projected onto the segment from the
//! shadow colour to the lit colour. Both are compared on the pixels wholly inside the sphere in
//! both (all samples on the sphere, alpha 1); silhouette pixels are left out of both alike. Soft
//! IoU `Σ min / Σ max` of the two coverages must reach 0.998 on every view, and every case's
//! closed form must differ from the undesigned one's by a clear margin.

use std::sync::Arc;

use glam::{DVec2, DVec3, Vec3, Vec4};
use glint::accuracy::AnalyticSphere;
use glint::formats::load_patches;
use glint::geom::NurbsSurface;
use glint::highlight::{
    Axis, DesignedLight, Expr, HighlightLight, Layer, Light, Op, ShadeStack, SquareStyle,
};
use glint::render::{Aovs, Camera, PatchLook, Projection, Renderer, Scene, Settings, Tone};
use glint::shot::load_shot_text;
use glint::toon::CelRamp;

use crate::common::root;

const SIZE: u32 = 256;
/// Sub-samples per pixel side of the closed form.
const SUB: u32 = 8;
/// The band edge: lit where `N·L' > THRESHOLD`.
const THRESHOLD: f64 = 0.3;
const SHADOW: Vec3 = Vec3::new(0.08, 0.1, 0.3);
const LIT: Vec3 = Vec3::new(0.7, 0.75, 0.9);
/// The least soft IoU of render and closed form.
const MINIMUM_IOU: f64 = 0.998;
/// The least `1 − IoU` between a case's closed form and the undesigned one's: 15 times what
/// the render may miss by.
const MINIMUM_CHANGE: f64 = 0.03;
/// The least lit area, in pixels, of every case in every view.
const MINIMUM_LIT_PIXELS: f64 = 1000.0;

/// A camera and the unit direction toward the light.
#[derive(Clone, Copy, Debug)]
struct View {
    name: &'static str,
    camera: Camera,
    light: DVec3,
}

fn camera(eye: DVec3, up: DVec3, projection: Projection) -> Camera {
    Camera {
        eye: eye.as_vec3(),
        target: Vec3::ZERO,
        up: up.as_vec3(),
        projection,
        near: 0.5,
        far: 20.0,
    }
}

const ORTHOGRAPHIC: Projection = Projection::Orthographic { height: 2.4 };

/// The light as the renderer receives it: the f32 unit vector, back in f64.
fn light(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z).normalize().as_vec3().as_dvec3()
}

/// The views every case is measured in:
/// - `front`: the band edge crosses the middle of the disc;
/// - `rim`: the light from behind and to the right, the lit region a crescent along the
///   silhouette, the edge close to it;
/// - `pole`: looking down on the north pole, the edge passing near it, where the frame turns
///   fastest;
/// - `perspective`: a perspective camera, lit from the left.
fn views() -> [View; 4] {
    [
        View {
            name: "front",
            camera: camera(DVec3::new(0.0, -5.0, 0.0), DVec3::Z, ORTHOGRAPHIC),
            light: light(0.75, -0.55, 0.35),
        },
        View {
            name: "rim",
            camera: camera(DVec3::new(0.0, -5.0, 0.0), DVec3::Z, ORTHOGRAPHIC),
            light: light(0.7, 0.65, 0.3),
        },
        View {
            name: "pole",
            camera: camera(DVec3::new(0.0, 0.0, 5.0), DVec3::Y, ORTHOGRAPHIC),
            light: light(0.9, 0.2, 0.33),
        },
        View {
            name: "perspective",
            camera: camera(
                DVec3::new(1.5, -4.5, 1.0),
                DVec3::Z,
                Projection::Perspective {
                    fov_y_degrees: 32.0,
                },
            ),
            light: light(-0.7, -0.4, 0.6),
        },
    ]
}

/// The ray through the image point `(x, y)` (pixels from the top left) of a square
/// `SIZE × SIZE` image: forward `f = normalize(target − eye)`, right `r = normalize(f × up)`,
/// up `u = r × f`, and the point's normalized coordinates `(s, t) ∈ [−1, 1]²` (t up). Under
/// orthographic projection of height h the origin is `eye + (h/2)(s r + t u)` along f; under
/// perspective with `k = tan(fov/2)`, from the eye along `normalize(f + k (s r + t u))`.
fn ray(camera: &Camera, x: f64, y: f64) -> (DVec3, DVec3) {
    let (eye, target, up) = (
        camera.eye.as_dvec3(),
        camera.target.as_dvec3(),
        camera.up.as_dvec3(),
    );
    let f = (target - eye).normalize();
    let r = f.cross(up).normalize();
    let u = r.cross(f);
    let size = f64::from(SIZE);
    let (s, t) = (2.0 * x / size - 1.0, 1.0 - 2.0 * y / size);
    match camera.projection {
        Projection::Orthographic { height } => {
            let half = f64::from(height) / 2.0;
            (eye + half * (s * r + t * u), f)
        }
        Projection::Perspective { fov_y_degrees } => {
            let k = (f64::from(fov_y_degrees).to_radians() / 2.0).tan();
            (eye, (f + k * (s * r + t * u)).normalize())
        }
    }
}

/// The first point where the ray from `o` along the unit `d` meets the unit sphere:
/// `o + t d` with `t = −(o·d) − sqrt((o·d)² − (|o|² − 1))`.
fn hit(o: DVec3, d: DVec3) -> Option<DVec3> {
    let b = o.dot(d);
    let disc = b * b - (o.length_squared() - 1.0);
    (disc >= 0.0).then(|| o + (-b - disc.sqrt()) * d)
}

/// The frame `(du, dv, N)` of the sphere's parameterization at the unit normal `n` off the
/// poles: `du = (−n.y, n.x, 0)/|…|` (east), `dv = n × du` (north), `N = n`.
fn frame(n: DVec3) -> (DVec3, DVec3, DVec3) {
    let du = DVec3::new(-n.y, n.x, 0.0).normalize();
    (du, n.cross(du), n)
}

/// An operation on the light's frame coordinates, written out from its formula.
#[derive(Clone, Copy, Debug)]
enum HandOp {
    /// `t + (α, β)`.
    Translate(f64, f64),
    /// `(t_u, t_v) ← R(−θ)(t_u, t_v) = (cos θ t_u + sin θ t_v, cos θ t_v − sin θ t_u)`.
    Rotate(f64),
    /// `t − δ (t·a) a`, `a = (cos φ, sin φ)`: δ and φ in degrees.
    Scale(f64, f64),
    /// `t − (γ_u sgn t_u, γ_v sgn t_v)`, `sgn(0) = +1`.
    Split(f64, f64),
    /// `t (1 − σ (2 |t_u| |t_v| / |t|²)^n)`.
    SquareTangent(f64, f64),
    /// `t − σ (|sin 2θ_u|^n t_u, |sin 2θ_v|^n t_v)` with `cos θ_u = l_u`, `cos θ_v = l_v` of the
    /// unit L, so `|sin 2θ| = 2 |c| sqrt(1 − c²)`.
    SquarePerAxis(f64, f64),
}

fn sgn(x: f64) -> f64 {
    if x < 0.0 {
        -1.0
    } else {
        1.0
    }
}

impl HandOp {
    /// The op on unit frame coordinates `l`, normalized after.
    fn apply(self, l: DVec3) -> DVec3 {
        let t = DVec2::new(l.x, l.y);
        let moved = match self {
            HandOp::Translate(alpha, beta) => t + DVec2::new(alpha, beta),
            HandOp::Rotate(degrees) => {
                let (s, c) = degrees.to_radians().sin_cos();
                DVec2::new(c * t.x + s * t.y, c * t.y - s * t.x)
            }
            HandOp::Scale(delta, phi) => {
                let (s, c) = phi.to_radians().sin_cos();
                let a = DVec2::new(c, s);
                t - delta * t.dot(a) * a
            }
            HandOp::Split(gu, gv) => t - DVec2::new(gu * sgn(t.x), gv * sgn(t.y)),
            HandOp::SquareTangent(sigma, n) => {
                let sin2theta = 2.0 * t.x.abs() * t.y.abs() / t.length_squared();
                t * (1.0 - sigma * sin2theta.powf(n))
            }
            HandOp::SquarePerAxis(sigma, n) => {
                let k = |c: f64| (2.0 * c.abs() * (1.0 - c * c).max(0.0).sqrt()).powf(n);
                t - sigma * DVec2::new(k(t.x) * t.x, k(t.y) * t.y)
            }
        };
        moved.extend(l.z).normalize()
    }
}

/// Whether the sphere point with unit normal `n`, lit from `light`, is lit after `ops`:
/// `N·L' > THRESHOLD`.
fn lit(ops: &[HandOp], light: DVec3, n: DVec3) -> bool {
    let (du, dv, n) = frame(n);
    let local = DVec3::new(light.dot(du), light.dot(dv), light.dot(n));
    let designed = ops.iter().fold(local, |l, op| op.apply(l));
    designed.z > THRESHOLD
}

/// What the closed form finds in one pixel: the fractions of its `SUB × SUB` samples that hit
/// the sphere, and that hit it where it is lit.
#[derive(Clone, Copy, Debug, Default)]
struct Truth {
    sphere: f64,
    lit: f64,
}

/// Per pixel of the `SIZE × SIZE` image of `view`, rows from the top: the fractions of its
/// `SUB × SUB` samples on the sphere, and on the sphere where it is lit after `ops`.
fn closed_form(view: &View, ops: &[HandOp]) -> Vec<Truth> {
    sampled(view, |p, _| lit(ops, view.light, p))
}

/// Per pixel of the `SIZE × SIZE` image of `view`, rows from the top: the fractions of its
/// `SUB × SUB` samples on the sphere, and of those where `inside(n, d)` holds, `n` the unit
/// normal at the sample's hit and `d` its ray's unit direction.
fn sampled(view: &View, inside: impl Fn(DVec3, DVec3) -> bool + Sync) -> Vec<Truth> {
    let inside = &inside;
    let mut out = vec![Truth::default(); (SIZE * SIZE) as usize];
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get());
    let rows_each = (SIZE as usize).div_ceil(threads);
    std::thread::scope(|scope| {
        for (chunk, rows) in out.chunks_mut(rows_each * SIZE as usize).enumerate() {
            scope.spawn(move || {
                for (k, cell) in rows.iter_mut().enumerate() {
                    let i = (chunk * rows_each * SIZE as usize + k) as u32;
                    let (px, py) = (f64::from(i % SIZE), f64::from(i / SIZE));
                    let (mut sphere, mut lit_samples) = (0u32, 0u32);
                    for s in 0..SUB * SUB {
                        let x = px + (f64::from(s % SUB) + 0.5) / f64::from(SUB);
                        let y = py + (f64::from(s / SUB) + 0.5) / f64::from(SUB);
                        let (o, d) = ray(&view.camera, x, y);
                        if let Some(p) = hit(o, d) {
                            sphere += 1;
                            lit_samples += u32::from(inside(p.normalize(), d));
                        }
                    }
                    let samples = f64::from(SUB * SUB);
                    *cell = Truth {
                        sphere: f64::from(sphere) / samples,
                        lit: f64::from(lit_samples) / samples,
                    };
                }
            });
        }
    });
    out
}

/// Per pixel of a render, its alpha and where its colour lies on the segment from [`SHADOW`]
/// to [`LIT`] (0 to 1, clamped: the lit share of what it covers, straight alpha). Panics on a
/// NaN component.
fn rendered_shares(colour: &[Vec4]) -> Vec<(f64, f64)> {
    let span = LIT - SHADOW;
    colour
        .iter()
        .enumerate()
        .map(|(i, c)| {
            assert!(c.is_finite(), "pixel {i} is {c}");
            let along = (c.truncate() - SHADOW).dot(span) / span.length_squared();
            (f64::from(c.w), f64::from(along.clamp(0.0, 1.0)))
        })
        .collect()
}

/// The soft IoU of a render's lit region (`rendered_shares`) and the closed form's, over the
/// pixels wholly inside the sphere in both: there the render's lit coverage is its colour's
/// share, the closed form's its lit samples. Silhouette pixels are left out of both sums alike:
/// whether a sample of them is on the sphere at all is the silhouette's accuracy, not the
/// shade's.
fn lit_iou(render: &[(f64, f64)], truth: &[Truth]) -> f64 {
    let (rendered, closed): (Vec<f64>, Vec<f64>) = render
        .iter()
        .zip(truth)
        .filter(|((alpha, _), t)| *alpha >= 1.0 && t.sphere >= 1.0)
        .map(|((_, share), t)| (*share, t.lit))
        .unzip();
    soft_iou(&rendered, &closed)
}

/// `1 − soft IoU` of two closed forms' lit regions: how far apart they are.
fn change(a: &[Truth], b: &[Truth]) -> f64 {
    let lit = |t: &[Truth]| t.iter().map(|t| t.lit).collect::<Vec<_>>();
    1.0 - soft_iou(&lit(a), &lit(b))
}

/// Soft IoU `Σ min(a, b) / Σ max(a, b)`.
fn soft_iou(a: &[f64], b: &[f64]) -> f64 {
    let (min, max) = a.iter().zip(b).fold((0.0, 0.0), |(min, max), (x, y)| {
        (min + x.min(*y), max + x.max(*y))
    });
    min / max
}

fn ramp() -> CelRamp {
    CelRamp::two_tone(SHADOW, LIT, THRESHOLD as f32)
}

/// The sphere of `view` with `stack` designing the light its tone reads, rendered with the
/// `final` preset at `SIZE × SIZE`: its lit coverage.
fn rendered(view: &View, stack: &[Op]) -> Vec<(f64, f64)> {
    let library = AnalyticSphere::library();
    let designed = ShadeStack {
        stack: stack.to_vec(),
        mask: None,
    }
    .prepare()
    .unwrap();
    let scene = Scene {
        library: &library,
        looks: vec![PatchLook {
            tone: Tone::Cel(ramp()),
            designed_light: Some(DesignedLight::new(vec![designed])),
            highlight: None,
            lines: None,
        }],
        camera: view.camera,
        light: Light::Directional {
            towards: view.light.as_vec3(),
        },
        outlines: None,
        aovs: Aovs::default(),
        materials: Vec::new(),
    };
    let frame = Renderer::new(Arc::clone(&library))
        .render(&scene, &Settings::final_quality(SIZE, SIZE))
        .unwrap();
    rendered_shares(&frame.colour)
}

/// Asserts, on every view, that the render of `stack` matches the closed form of `ops` with
/// soft IoU ≥ [`MINIMUM_IOU`], and that the closed form differs from the undesigned one by at
/// least [`MINIMUM_CHANGE`].
fn assert_matches(name: &str, stack: &[Op], ops: &[HandOp]) {
    let mut failures = Vec::new();
    for view in views() {
        let truth = closed_form(&view, ops);
        let plain = closed_form(&view, &[]);
        let change = change(&truth, &plain);
        let lit_area: f64 = truth.iter().map(|t| t.lit).sum();
        let score = lit_iou(&rendered(&view, stack), &truth);
        eprintln!(
            "{name}, {}: soft IoU {score:.5}, {lit_area:.0} pixels lit, change {change:.4}",
            view.name
        );
        if lit_area < MINIMUM_LIT_PIXELS {
            failures.push(format!("{}: only {lit_area} pixels lit", view.name));
        }
        if change < MINIMUM_CHANGE {
            failures.push(format!(
                "{}: the op changes the lit region by {change}",
                view.name
            ));
        }
        if score < MINIMUM_IOU {
            failures.push(format!("{}: soft IoU {score:.5}", view.name));
        }
    }
    assert!(failures.is_empty(), "{name}: {}", failures.join(", "));
}

#[test]
fn the_camera_rays_here_are_the_renderer_s() {
    // A point along each ray projects, by the renderer's own view-projection, to the image
    // point the ray was cast through.
    for view in views() {
        let view_projection = view.camera.view_projection(1.0);
        for (x, y) in [(0.5, 0.5), (37.25, 200.0), (128.0, 128.0), (250.0, 12.5)] {
            let (o, d) = ray(&view.camera, x, y);
            let ndc = view_projection.project_point3((o + 3.0 * d).as_vec3());
            let size = SIZE as f32;
            let (px, py) = ((ndc.x + 1.0) / 2.0 * size, (1.0 - ndc.y) / 2.0 * size);
            assert!(
                (px - x as f32).abs() < 1e-3 && (py - y as f32).abs() < 1e-3,
                "{}: ({x}, {y}) projects to ({px}, {py})",
                view.name
            );
        }
    }
}

#[test]
fn the_closed_form_frame_is_the_patch_s_parameterization() {
    // The finite differences ∂S/∂u and ∂S/∂v of the sphere patch, normalized, are the frame's
    // du and dv at S(u, v), and ∂S/∂u × ∂S/∂v points outward: for the sphere the renderer
    // draws here and the one `patches/sphere.ron` describes.
    let ron = load_patches(&root().join("patches/sphere.ron")).unwrap();
    let library = AnalyticSphere::library();
    let surfaces: [&NurbsSurface; 2] = [&library.patches[0].surface, &ron.patches[0].surface];
    for surface in surfaces {
        let domain = surface.domain();
        let at = |s: f64, t: f64| {
            (
                domain.u.0 + s * (domain.u.1 - domain.u.0),
                domain.v.0 + t * (domain.v.1 - domain.v.0),
            )
        };
        for (s, t) in [
            (0.05, 0.5),
            (0.3, 0.2),
            (0.55, 0.85),
            (0.8, 0.6),
            (0.97, 0.4),
        ] {
            let (u, v) = at(s, t);
            let h = 1e-6;
            let p = surface.point(u, v);
            let su = (surface.point(u + h, v) - surface.point(u - h, v)) / (2.0 * h);
            let sv = (surface.point(u, v + h) - surface.point(u, v - h)) / (2.0 * h);
            assert!(
                (p.length() - 1.0).abs() < 1e-9,
                "({u}, {v}): {p} is on the sphere"
            );
            let (du, dv, n) = frame(p.normalize());
            assert!(
                su.normalize().dot(du) > 1.0 - 1e-8,
                "({u}, {v}): {su} vs {du}"
            );
            assert!(
                sv.normalize().dot(dv) > 1.0 - 1e-8,
                "({u}, {v}): {sv} vs {dv}"
            );
            assert!(su.cross(sv).normalize().dot(n) > 1.0 - 1e-8, "({u}, {v})");
        }
    }
}

#[test]
fn translation_along_du_and_dv_matches_the_closed_form() {
    for (alpha, beta) in [(-0.45_f32, 0.0_f32), (0.0, -0.7), (-0.3, 0.35)] {
        assert_matches(
            &format!("Translate({alpha}, {beta})"),
            &[Op::Translate { alpha, beta }],
            &[HandOp::Translate(f64::from(alpha), f64::from(beta))],
        );
    }
}

#[test]
fn rotation_before_a_scaling_matches_the_closed_form() {
    // Rotation alone leaves N·L; before a scaling along u it turns the scaling's axis by θ.
    let (degrees, delta) = (20.0_f32, 0.85_f32);
    let ops = [
        HandOp::Rotate(f64::from(degrees)),
        HandOp::Scale(f64::from(delta), 0.0),
    ];
    // It shows: the region differs from the scaling's alone.
    for view in views() {
        let rotated = closed_form(&view, &ops);
        let scaled = closed_form(&view, &ops[1..]);
        let change = change(&rotated, &scaled);
        assert!(change >= MINIMUM_CHANGE, "{}: {change}", view.name);
    }
    assert_matches(
        "Rotate + Scale",
        &[
            Op::Rotate { degrees },
            Op::Scale {
                delta,
                axis: Axis::U,
            },
        ],
        &ops,
    );
}

#[test]
fn scaling_along_u_v_and_an_angle_matches_the_closed_form() {
    for (delta, axis, phi) in [
        (0.85_f32, Axis::U, 0.0),
        (0.95, Axis::V, 90.0),
        (0.7, Axis::Angle(-30.0), -30.0),
    ] {
        assert_matches(
            &format!("Scale({delta}, {axis:?})"),
            &[Op::Scale { delta, axis }],
            &[HandOp::Scale(f64::from(delta), phi)],
        );
    }
}

#[test]
fn split_along_u_and_v_matches_the_closed_form() {
    for (gamma_u, gamma_v) in [(0.35_f32, 0.0_f32), (0.0, 0.6)] {
        assert_matches(
            &format!("Split({gamma_u}, {gamma_v})"),
            &[Op::Split { gamma_u, gamma_v }],
            &[HandOp::Split(f64::from(gamma_u), f64::from(gamma_v))],
        );
    }
}

#[test]
fn squaring_in_both_styles_matches_the_closed_form() {
    for (sigma, n, style) in [
        (0.7_f32, 1.0_f32, SquareStyle::Tangent),
        (0.9, 1.0, SquareStyle::PerAxis),
    ] {
        let hand = match style {
            SquareStyle::Tangent => HandOp::SquareTangent(f64::from(sigma), f64::from(n)),
            SquareStyle::PerAxis => HandOp::SquarePerAxis(f64::from(sigma), f64::from(n)),
        };
        assert_matches(
            &format!("Square({sigma}, {n}, {style:?})"),
            &[Op::Square { sigma, n, style }],
            &[hand],
        );
    }
}

/// A shot of the unit sphere (`patches/sphere.ron`) in `view`, its tone the two-colour ramp,
/// with a shade translation along du keyed `(1, 0.0)`, `(3, −0.6)`.
fn keyed_shot(view: &View) -> String {
    let c = view.camera;
    let v = |v: Vec3| format!("({:?}, {:?}, {:?})", v.x, v.y, v.z);
    let projection = match c.projection {
        Projection::Orthographic { height } => format!("Orthographic(height: {height:?})"),
        Projection::Perspective { fov_y_degrees } => {
            format!("Perspective(fov_y_degrees: {fov_y_degrees:?})")
        }
    };
    format!(
        r#"Shot(
    resolution: ({SIZE}, {SIZE}),
    frames: (1, 3),
    fps: 24,
    output: "out/keyed.####.png",
    instances: [(name: "ball", file: "../patches/sphere.ron", material: "paint")],
    materials: {{"paint": Cel(base: {shadow}, bands: [({THRESHOLD:?}, {lit})])}},
    camera: (eye: {eye}, target: {target}, up: {up}, projection: {projection},
             near: {near:?}, far: {far:?}),
    light: Directional(towards: {light}),
    highlights: [],
    shade: [
        (patches: "ball/*", stack: [Translate(alpha: [(1, 0.0), (3, -0.6)], beta: 0.0)]),
    ],
    render: (preset: Final),
)"#,
        shadow = v(SHADOW),
        lit = v(LIT),
        eye = v(c.eye),
        target = v(c.target),
        up = v(c.up),
        near = c.near,
        far = c.far,
        light = v(view.light.as_vec3()),
    )
}

#[test]
fn a_keyed_translation_read_between_its_keys_matches_the_closed_form() {
    // Frame 2, halfway between the keys: α = −0.3.
    let mut failures = Vec::new();
    for view in views() {
        let path = root().join("shots/shade_keyed_sphere.ron");
        let shot = load_shot_text(&path, keyed_shot(&view)).unwrap();
        let state = shot.at(2.0);
        let scene = state.scene(&shot).unwrap();
        let Light::Directional { towards } = scene.light else {
            panic!("a directional light");
        };
        assert!(
            (towards.as_dvec3() - view.light).length() < 1e-6,
            "{}: the shot's light {towards}",
            view.name
        );
        assert_eq!(scene.camera, view.camera, "{}", view.name);
        let settings = shot.settings_with(None, None);
        assert_eq!(settings, Settings::final_quality(SIZE, SIZE));
        let frame = Renderer::new(Arc::clone(&shot.library))
            .render(&scene, &settings)
            .unwrap();
        let render = rendered_shares(&frame.colour);
        let truth = closed_form(&view, &[HandOp::Translate(-0.3, 0.0)]);
        // Neither key's value: the region differs from α = 0 and from α = 0.6.
        for key in [0.0, -0.6] {
            let other = closed_form(&view, &[HandOp::Translate(key, 0.0)]);
            let change = change(&truth, &other);
            assert!(
                change >= 0.02,
                "{}: α = {key} is too close, {change}",
                view.name
            );
        }
        let score = lit_iou(&render, &truth);
        if score < MINIMUM_IOU {
            failures.push(format!("{}: soft IoU {score:.5}", view.name));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join(", "));
}

/// The highlight's ε in the tests of which light it reads.
const EPSILON: f64 = 0.05;

/// Whether the sphere point with unit normal `n`, seen along the ray direction `d`, is inside
/// the ε-disc of an identity layer whose highlight vector starts from the light designed by
/// `ops` (the scene's light when `ops` is empty): `H = normalize(L' + V)` with `V = −d` (toward
/// the eye under both projections), inside where `‖N − H‖²/2 < ε`.
fn in_highlight(ops: &[HandOp], light: DVec3, n: DVec3, d: DVec3) -> bool {
    let (du, dv, n) = frame(n);
    let local = DVec3::new(light.dot(du), light.dot(dv), light.dot(n));
    let designed = ops.iter().fold(local, |l, op| op.apply(l));
    let l = designed.x * du + designed.y * dv + designed.z * n;
    let h = (l - d).normalize();
    (n - h).length_squared() / 2.0 < EPSILON
}

/// The sphere of `view` with `stack` designing its light and an identity layer of ε
/// [`EPSILON`] reading the light `reads`, rendered with the `final` preset at `SIZE × SIZE`:
/// per pixel its alpha and its highlight matte.
fn rendered_matte(view: &View, stack: &[Op], reads: HighlightLight) -> Vec<(f64, f64)> {
    let library = AnalyticSphere::library();
    let designed = ShadeStack {
        stack: stack.to_vec(),
        mask: None,
    }
    .prepare()
    .unwrap();
    let highlight = Expr::Layer(Layer::new(vec![], EPSILON as f32, [1.0, 1.0, 1.0]))
        .prepare()
        .unwrap();
    let scene = Scene {
        library: &library,
        looks: vec![PatchLook {
            tone: Tone::Cel(ramp()),
            designed_light: Some(DesignedLight::new(vec![designed]).read_by_highlight(reads)),
            highlight: Some(highlight),
            lines: None,
        }],
        camera: view.camera,
        light: Light::Directional {
            towards: view.light.as_vec3(),
        },
        outlines: None,
        aovs: Aovs {
            matte: true,
            ..Aovs::default()
        },
        materials: Vec::new(),
    };
    let frame = Renderer::new(Arc::clone(&library))
        .render(&scene, &Settings::final_quality(SIZE, SIZE))
        .unwrap();
    let matte = frame.aovs.matte.expect("the matte AOV");
    frame
        .colour
        .iter()
        .zip(matte)
        .map(|(c, m)| {
            assert!(m.is_finite(), "a matte of {m}");
            (f64::from(c.w), f64::from(m))
        })
        .collect()
}

#[test]
fn a_highlight_reads_the_plain_light_unless_its_entry_asks_for_the_designed_one() {
    // The light translated along du and dv: the plain highlight stays where the closed form
    // from L puts it, the one reading the designed light moves to where the closed form from L'
    // puts it, and the two closed forms are clearly apart.
    let stack = [Op::Translate {
        alpha: 0.35,
        beta: -0.2,
    }];
    let ops = [HandOp::Translate(0.35, -0.2)];
    let mut failures = Vec::new();
    for view in views() {
        let plain = sampled(&view, |n, d| in_highlight(&[], view.light, n, d));
        let designed = sampled(&view, |n, d| in_highlight(&ops, view.light, n, d));
        let apart = change(&plain, &designed);
        for (reads, truth) in [
            (HighlightLight::Plain, &plain),
            (HighlightLight::Designed, &designed),
        ] {
            let area: f64 = truth.iter().map(|t| t.lit).sum();
            let score = lit_iou(&rendered_matte(&view, &stack, reads), truth);
            eprintln!(
                "{reads:?}, {}: soft IoU {score:.5}, {area:.0} pixels, apart {apart:.3}",
                view.name
            );
            if area < 200.0 {
                failures.push(format!("{reads:?}, {}: only {area} pixels", view.name));
            }
            if score < 0.99 {
                failures.push(format!("{reads:?}, {}: soft IoU {score:.5}", view.name));
            }
        }
        if apart < 0.3 {
            failures.push(format!(
                "{}: the two highlights overlap, {apart}",
                view.name
            ));
        }
    }
    assert!(failures.is_empty(), "{}", failures.join(", "));
}
