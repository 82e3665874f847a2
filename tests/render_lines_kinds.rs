//! The kinds of line a 2D pipeline asks for, against analytic truth: the light contour on the
//! sphere's terminator, hidden lines of a sphere behind a sphere exactly where the front one
//! covers its outline, and the teapot's lid rim where the body hides it.

use std::sync::Arc;

use glam::{DVec3, Mat4, Vec2, Vec3, Vec4};
use glint::geom::{shapes, NamedPatch, PatchLibrary};
use glint::highlight::{DesignedLight, Light, Op, ShadeStack};
use glint::render::{
    Aovs, Camera, Dash, HiddenLines, LineKind, LineKinds, LineStyle, Outlines, PatchLook,
    Projection, RenderedFrame, Renderer, Scene, Settings, Tone, VectorLines,
};
use glint::toon::CelRamp;

const SIZE: u32 = 240;
const FOV_DEGREES: f32 = 40.0;

/// The camera looking at `target` from `distance`, `elevation` degrees above the xy plane and
/// `azimuth` degrees round from +x.
fn camera(target: Vec3, distance: f32, elevation: f32, azimuth: f32) -> Camera {
    let (e, a) = (elevation.to_radians(), azimuth.to_radians());
    Camera {
        eye: target + distance * Vec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin()),
        target,
        up: Vec3::Z,
        projection: Projection::Perspective {
            fov_y_degrees: FOV_DEGREES,
        },
        near: 0.1,
        far: 100.0,
    }
}

/// Spheres of the given centres and radii, one patch each, named `sphere0`, `sphere1`, ….
fn spheres(balls: &[(DVec3, f64)]) -> Arc<PatchLibrary> {
    Arc::new(PatchLibrary {
        patches: balls
            .iter()
            .enumerate()
            .map(|(k, &(centre, radius))| NamedPatch {
                name: format!("sphere{k}"),
                trim: None,
                surface: shapes::sphere(centre, radius).unwrap(),
            })
            .collect(),
        groups: Vec::new(),
    })
}

/// One frame of `library`'s patches, each two-tone with `threshold` and its lines in `style`,
/// lit by `light`, with the outline and patch-id AOVs.
fn frame(
    library: &Arc<PatchLibrary>,
    (camera, light): (Camera, Light),
    (style, threshold): (LineStyle, f32),
    settings: &Settings,
) -> RenderedFrame {
    designed_frame(library, (camera, light, None), (style, threshold), settings)
}

/// [`frame`], the tone reading the designed light `designed`.
fn designed_frame(
    library: &Arc<PatchLibrary>,
    (camera, light, designed): (Camera, Light, Option<DesignedLight>),
    (style, threshold): (LineStyle, f32),
    settings: &Settings,
) -> RenderedFrame {
    let styles = vec![style; library.patches.len()];
    styled_frame(
        library,
        (camera, light, designed),
        (&styles, threshold),
        settings,
    )
}

/// [`designed_frame`] with patch k's lines in `styles[k]`.
fn styled_frame(
    library: &Arc<PatchLibrary>,
    (camera, light, designed): (Camera, Light, Option<DesignedLight>),
    (styles, threshold): (&[LineStyle], f32),
    settings: &Settings,
) -> RenderedFrame {
    let look = |style: &LineStyle| PatchLook {
        designed_light: designed.clone(),
        lines: Some(*style),
        tone: Tone::Cel(CelRamp::two_tone(
            Vec3::new(0.2, 0.3, 0.5),
            Vec3::new(0.5, 0.6, 0.9),
            threshold,
        )),
        highlight: None,
    };
    let scene = Scene {
        library,
        looks: styles.iter().map(look).collect(),
        camera,
        light,
        outlines: Some(Outlines {
            width: styles[0].width,
            colour: styles[0].colour,
            crease_degrees: 60.0,
            patch_borders: false,
        }),
        aovs: Aovs {
            outline: true,
            patch_id: true,
            ..Aovs::default()
        },
        materials: Vec::new(),
    };
    Renderer::new(Arc::clone(library))
        .render(&scene, settings)
        .unwrap()
}

/// `p` on a square image of `SIZE` pixels through `view_projection` (pixel centres at
/// half-integers, y down), and whether it is in front of the eye.
fn on_image(view_projection: Mat4, p: DVec3) -> Option<Vec2> {
    let clip = view_projection * p.as_vec3().extend(1.0);
    (clip.w > 0.0).then(|| {
        let ndc = clip.truncate() / clip.w;
        Vec2::new(
            (ndc.x + 1.0) * 0.5 * SIZE as f32,
            (1.0 - ndc.y) * 0.5 * SIZE as f32,
        )
    })
}

/// `n` points of the circle of `radius` about `centre` in the plane square to `axis`.
fn circle(centre: DVec3, axis: DVec3, radius: f64, n: usize) -> Vec<DVec3> {
    let axis = axis.normalize();
    let u = axis.any_orthonormal_vector();
    let v = axis.cross(u);
    (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            centre + radius * (a.cos() * u + a.sin() * v)
        })
        .collect()
}

/// The sphere's outline seen from `eye`: where the line of sight touches it, the circle of
/// `(P − C)·(P − E) = 0` on it, about `C + (E − C) r²/d²` with radius `r √(1 − r²/d²)`.
fn outline(centre: DVec3, radius: f64, eye: DVec3, n: usize) -> Vec<DVec3> {
    let to_eye = eye - centre;
    let d2 = to_eye.length_squared();
    circle(
        centre + to_eye * (radius * radius / d2),
        to_eye,
        radius * (1.0 - radius * radius / d2).sqrt(),
        n,
    )
}

/// Whether the segment from `eye` to `point` passes through the sphere `(centre, radius)`
/// before it reaches the point.
fn sphere_hides(centre: DVec3, radius: f64, eye: DVec3, point: DVec3) -> bool {
    let d = point - eye;
    let f = eye - centre;
    let (a, b, c) = (d.dot(d), 2.0 * f.dot(d), f.dot(f) - radius * radius);
    let disc = b * b - 4.0 * a * c;
    if disc < 0.0 {
        return false;
    }
    let s = (-b - disc.sqrt()) / (2.0 * a);
    s > 0.0 && s < 1.0 - 1e-6
}

/// The points of every stroke of `lines` that `keep` picks, at most half a pixel apart.
fn stroke_points(
    lines: &VectorLines,
    keep: impl Fn(&glint::render::VectorStroke) -> bool,
) -> Vec<Vec2> {
    let mut out = Vec::new();
    for s in lines.strokes.iter().filter(|s| keep(s)) {
        let n = s.points.len();
        let segments = if s.closed { n } else { n - 1 };
        for k in 0..segments.max(1) {
            let (a, b) = (s.points[k], s.points[(k + 1) % n]);
            let steps = (a.distance(b) / 0.5).ceil().max(1.0) as usize;
            for i in 0..=steps {
                out.push(a.lerp(b, i as f32 / steps as f32));
            }
        }
    }
    out
}

/// The distance from `p` to the nearest of `points`.
fn nearest(points: &[Vec2], p: Vec2) -> f32 {
    points
        .iter()
        .map(|q| q.distance(p))
        .fold(f32::INFINITY, f32::min)
}

fn light_contour_style() -> LineStyle {
    LineStyle {
        kinds: LineKinds::of(&[LineKind::LightContour]),
        ..LineStyle::new(1.5, Vec3::ZERO)
    }
}

#[test]
fn the_sphere_s_light_contour_lies_on_the_analytic_terminator() {
    let ball = spheres(&[(DVec3::ZERO, 1.0)]);
    let mut worst = 0.0f32;
    // Lights from the side, from behind and straight down (the terminator then runs round
    // the sphere's equator); thresholds below, at and above 0.
    let lights = [
        (Vec3::new(0.3, -0.5, 0.8), 0.2),
        (Vec3::new(-0.7, 0.6, 0.2), -0.3),
        (Vec3::Z, 0.0),
        (Vec3::new(0.1, 0.9, -0.4), 0.55),
    ];
    for (l, (towards, threshold)) in lights.into_iter().enumerate() {
        let towards = towards.normalize();
        let light = Light::Directional { towards };
        for (settings, name) in [
            (Settings::preview(SIZE, SIZE), "preview"),
            (Settings::final_quality(SIZE, SIZE), "final"),
        ] {
            for k in 0..9 {
                let view = camera(
                    Vec3::ZERO,
                    4.0,
                    [8.0, 38.0, 72.0][k % 3],
                    40.0 * k as f32 + 7.0,
                );
                let eye = view.eye.as_dvec3();
                let view_projection = view.view_projection(1.0);
                let frame = frame(
                    &ball,
                    (view, light),
                    (light_contour_style(), threshold),
                    &settings,
                );
                let lines = frame.lines.as_deref().unwrap();
                assert!(
                    lines
                        .strokes
                        .iter()
                        .all(|s| s.kind == LineKind::LightContour && !s.hidden),
                    "light {l} {name} view {k}: only light contours"
                );
                // The terminator `N·L = t` on the unit sphere (N = P): the circle about
                // `t L` of radius `√(1 − t²)`, where the eye sees it.
                let l64 = towards.as_dvec3();
                let terminator: Vec<(Vec2, bool)> = circle(
                    l64 * f64::from(threshold),
                    l64,
                    (1.0 - f64::from(threshold).powi(2)).sqrt(),
                    20000,
                )
                .into_iter()
                .filter_map(|p| {
                    let seen = p.dot(eye - p) > 0.0;
                    on_image(view_projection, p).map(|q| (q, seen))
                })
                .collect();
                let seen: Vec<Vec2> = terminator.iter().filter(|t| t.1).map(|t| t.0).collect();
                // Where the far side turns its normal to the eye, its terminator is
                // `−P·L = t`.
                let far: Vec<Vec2> = circle(
                    -l64 * f64::from(threshold),
                    l64,
                    (1.0 - f64::from(threshold).powi(2)).sqrt(),
                    20000,
                )
                .into_iter()
                .filter(|p| p.dot(eye - *p) <= 0.0)
                .filter_map(|p| on_image(view_projection, p))
                .collect();
                let all: Vec<Vec2> = seen.iter().chain(&far).copied().collect();
                let outline_points: Vec<Vec2> = outline(DVec3::ZERO, 1.0, eye, 4000)
                    .into_iter()
                    .filter_map(|p| on_image(view_projection, p))
                    .collect();
                let points = stroke_points(lines, |_| true);
                // Every point on the terminator of the side it is on; on the seen side but
                // within the depth test's reach of the outline, where the far side's runs in
                // behind it.
                for &p in &points {
                    let off = nearest(&all, p);
                    worst = worst.max(off);
                    assert!(
                        off <= 0.5,
                        "light {l} {name} view {k}: a point {p} {off} px off the terminator, {} px from the outline",
                        nearest(&outline_points, p)
                    );
                    if nearest(&outline_points, p) > 2.0 {
                        let off = nearest(&seen, p);
                        assert!(
                            off <= 0.5,
                            "light {l} {name} view {k}: a point {off} px off the seen terminator"
                        );
                    }
                }
                // The whole seen terminator is drawn, but where it runs into the outline
                // (the last pixels there, where the light contour meets the silhouette and the
                // mesh's outline differs from the sphere's).
                for &q in &seen {
                    if nearest(&outline_points, q) > 3.0 {
                        let gap = nearest(&points, q);
                        assert!(
                            gap <= 1.0,
                            "light {l} {name} view {k}: the terminator at {q} is {gap} px from the line"
                        );
                    }
                }
            }
        }
    }
    println!("light contour: worst point {worst:.4} px off the analytic terminator");
}

#[test]
fn under_designed_shade_the_light_contour_follows_n_dot_l_prime() {
    // L' = normalize(L + α du + β dv) in the sphere's frame (east, north, outward): the
    // designed light's translation, written here in closed form.
    let (alpha, beta, threshold) = (0.4f64, -0.25f64, 0.2f64);
    let stack = ShadeStack {
        stack: vec![Op::Translate {
            alpha: alpha as f32,
            beta: beta as f32,
        }],
        mask: None,
    }
    .prepare()
    .unwrap();
    let designed = DesignedLight::new(vec![stack]);
    let towards = DVec3::new(0.3, -0.5, 0.8).normalize();
    let light = Light::Directional {
        towards: towards.as_vec3(),
    };
    // `N·L' − t` at the point `p` of the unit sphere, seen from its front (N = p).
    let g = |p: DVec3| {
        let east = DVec3::Z.cross(p).normalize();
        let north = p.cross(east);
        let local = DVec3::new(
            towards.dot(east) + alpha,
            towards.dot(north) + beta,
            towards.dot(p),
        );
        local.z / local.length() - threshold
    };
    let ball = spheres(&[(DVec3::ZERO, 1.0)]);
    for k in 0..4 {
        let view = camera(
            Vec3::ZERO,
            4.0,
            20.0 + 15.0 * k as f32,
            60.0 * k as f32 + 7.0,
        );
        let eye = view.eye.as_dvec3();
        let view_projection = view.view_projection(1.0);
        // The analytic contour: where g changes sign along each of 3000 meridians, away from
        // the poles (where east is undefined), on the side the eye sees.
        let mut truth = Vec::new();
        for i in 0..3000 {
            let lon = std::f64::consts::TAU * f64::from(i) / 3000.0;
            let at = |j: u32| {
                let lat = -1.5 + 3.0 * f64::from(j) / 3000.0;
                DVec3::new(lat.cos() * lon.cos(), lat.cos() * lon.sin(), lat.sin())
            };
            for j in 0..3000 {
                let (a, b) = (at(j), at(j + 1));
                let (ga, gb) = (g(a), g(b));
                if (ga < 0.0) != (gb < 0.0) {
                    let p = a.lerp(b, ga / (ga - gb)).normalize();
                    if p.dot(eye - p) > 0.0 {
                        truth.extend(on_image(view_projection, p));
                    }
                }
            }
        }
        assert!(truth.len() > 100, "view {k}: the contour is in view");
        let outline_points: Vec<Vec2> = outline(DVec3::ZERO, 1.0, eye, 4000)
            .into_iter()
            .filter_map(|p| on_image(view_projection, p))
            .collect();
        let drawn = designed_frame(
            &ball,
            (view, light, Some(designed.clone())),
            (light_contour_style(), threshold as f32),
            &Settings::final_quality(SIZE, SIZE),
        );
        let points = stroke_points(drawn.lines.as_deref().unwrap(), |_| true);
        assert!(!points.is_empty(), "view {k}");
        for &p in points
            .iter()
            .filter(|&&p| nearest(&outline_points, p) > 2.0)
        {
            let off = nearest(&truth, p);
            assert!(
                off <= 0.5,
                "view {k}: a point {off} px off the contour of N·L'"
            );
        }
        for &q in truth.iter().filter(|&&q| nearest(&outline_points, q) > 3.0) {
            let gap = nearest(&points, q);
            assert!(
                gap <= 1.0,
                "view {k}: the contour at {q} is {gap} px from the line"
            );
        }
    }
}

/// The back sphere, of radius 1 at the origin, and the front one, nearer the eye and off to
/// one side so that it covers part of the back one's outline.
const BACK: (DVec3, f64) = (DVec3::ZERO, 1.0);

fn hidden_style(levels: u32, dash: &[f32]) -> LineStyle {
    LineStyle {
        kinds: LineKinds::of(&[LineKind::Silhouette]),
        hidden: Some(HiddenLines {
            levels,
            width: 1.5,
            colour: Vec3::X,
            dash: Dash::try_new(dash).unwrap(),
        }),
        ..LineStyle::new(1.5, Vec3::ZERO)
    }
}

#[test]
fn a_sphere_behind_a_sphere_has_hidden_lines_exactly_where_the_front_one_covers_its_outline() {
    let settings = Settings::final_quality(SIZE, SIZE);
    for k in 0..6 {
        let view = camera(
            Vec3::ZERO,
            6.0,
            10.0 + 12.0 * k as f32,
            25.0 + 50.0 * k as f32,
        );
        let eye = view.eye.as_dvec3();
        let view_projection = view.view_projection(1.0);
        // The front sphere: a third of the way to the eye, pushed aside across the view.
        let side = (eye.cross(DVec3::Z)).normalize();
        let front = (eye / 3.0 + side * 0.7, 0.55);
        let library = spheres(&[BACK, front]);
        let light = Light::Directional {
            towards: Vec3::new(0.3, -0.5, 0.8).normalize(),
        };
        // The back sphere's analytic outline, each point hidden or not by the front sphere.
        let truth: Vec<(Vec2, bool)> = outline(BACK.0, BACK.1, eye, 8000)
            .into_iter()
            .filter_map(|p| {
                on_image(view_projection, p).map(|q| (q, sphere_hides(front.0, front.1, eye, p)))
            })
            .collect();
        let hidden_truth: Vec<Vec2> = truth.iter().filter(|t| t.1).map(|t| t.0).collect();
        let seen_truth: Vec<Vec2> = truth.iter().filter(|t| !t.1).map(|t| t.0).collect();
        assert!(
            hidden_truth.len() > 400 && seen_truth.len() > 400,
            "view {k}: the front sphere covers part of the back one's outline"
        );

        let drawn = frame(
            &library,
            (view, light),
            (hidden_style(2, &[]), 0.2),
            &settings,
        );
        let lines = drawn.lines.as_deref().unwrap();
        let back = lines.parts.iter().position(|p| p == "sphere0").unwrap() as u32;
        let hidden = stroke_points(lines, |s| s.hidden && s.part == back);
        let seen = stroke_points(lines, |s| !s.hidden && s.part == back);
        // Every hidden point on the hidden part of the outline, every visible one on the seen
        // part (within the depth test's reach of where one turns into the other).
        for &p in &hidden {
            let off = nearest(&hidden_truth, p);
            assert!(
                off <= 1.5,
                "view {k}: a hidden point {off} px from the hidden outline"
            );
            assert!(nearest(&truth.iter().map(|t| t.0).collect::<Vec<_>>(), p) <= 0.25);
        }
        for &p in &seen {
            let off = nearest(&seen_truth, p);
            assert!(
                off <= 1.5,
                "view {k}: a visible point {off} px from the seen outline"
            );
        }
        // The whole outline is drawn, hidden and seen, away from where one turns into the
        // other (a gap under 3 px is bridged there).
        for (truth, drawn, what) in [
            (&hidden_truth, &hidden, "hidden"),
            (&seen_truth, &seen, "seen"),
        ] {
            let other = if what == "hidden" {
                &seen_truth
            } else {
                &hidden_truth
            };
            for &q in truth.iter().filter(|&&q| nearest(other, q) > 3.0) {
                let gap = nearest(drawn, q);
                assert!(
                    gap <= 1.0,
                    "view {k}: the {what} outline at {q} is {gap} px from a line"
                );
            }
        }
        // The front sphere's outline hides nothing of itself.
        let front_part = lines.parts.iter().position(|p| p == "sphere1").unwrap() as u32;
        assert!(!lines
            .strokes
            .iter()
            .any(|s| s.hidden && s.part == front_part));
        // In pixels: the hidden outline is inked in the hidden colour.
        let outline_aov: &Vec<Vec4> = drawn.aovs.outline.as_ref().unwrap();
        let inked_red = |q: Vec2| {
            let (x, y) = (q.x as usize, q.y as usize);
            (y.saturating_sub(1)..=(y + 1).min(SIZE as usize - 1)).any(|y| {
                (x.saturating_sub(1)..=(x + 1).min(SIZE as usize - 1)).any(|x| {
                    let c = outline_aov[y * SIZE as usize + x];
                    c.w >= 0.5 && c.x > 0.5 && c.y < 0.2
                })
            })
        };
        let away: Vec<Vec2> = hidden_truth
            .iter()
            .copied()
            .filter(|&q| nearest(&seen_truth, q) > 3.0)
            .collect();
        let red = away.iter().filter(|&&q| inked_red(q)).count();
        assert!(
            red as f64 >= 0.99 * away.len() as f64,
            "view {k}: {red} of {} hidden outline points inked red",
            away.len()
        );

        // Behind one surface at most, the outline is not drawn where the front sphere (its
        // near and far side) hides it.
        let one = frame(
            &library,
            (view, light),
            (hidden_style(1, &[]), 0.2),
            &settings,
        );
        let one = one.lines.as_deref().unwrap();
        let hidden_one = stroke_points(one, |s| s.hidden && s.part == back);
        assert!(
            hidden_one.iter().all(|&p| nearest(&seen_truth, p) <= 3.0),
            "view {k}: at level 1, hidden lines behind two surfaces"
        );

        // Dashed, in pixels: along the hidden outline, ink where the pattern draws (6 px and
        // the round caps' 0.75 px at each end) and none where it leaves out: about 7.5 of
        // every 10 px. The front sphere's hidden lines are solid: each patch's are dashed in
        // its own style's pattern.
        if k == 0 {
            let styles = [hidden_style(2, &[6.0, 4.0]), hidden_style(2, &[])];
            let dashed = styled_frame(&library, (view, light, None), (&styles, 0.2), &settings);
            let aov: &Vec<Vec4> = dashed.aovs.outline.as_ref().unwrap();
            let red_at = |q: Vec2| {
                let c = aov[q.y as usize * SIZE as usize + q.x as usize];
                c.w >= 0.5 && c.x > 0.5 && c.y < 0.2
            };
            let share = away.iter().filter(|&&q| red_at(q)).count() as f64 / away.len() as f64;
            assert!(
                (0.55..=0.9).contains(&share),
                "view {k}: {share} of the hidden outline dashed"
            );
            let svg = glint::formats::svg::svg_document(dashed.lines.as_deref().unwrap(), &[]);
            assert!(svg.contains("<g id=\"hidden-silhouette\" class=\"lines hidden silhouette\""));
            assert!(svg.contains("stroke-dasharray=\"6 4\""), "{svg}");
        }
    }
}

#[test]
fn the_teapot_s_lid_rim_is_drawn_hidden_where_the_body_covers_it() {
    let teapot = crate::common::teapot();
    let settings = Settings::final_quality(SIZE * 2, SIZE);
    // From low down, the body's wall stands in front of the lid's rim.
    let view = Camera {
        eye: Vec3::new(1.0, -9.0, 1.6),
        target: Vec3::new(0.0, 0.0, 1.6),
        up: Vec3::Z,
        projection: Projection::Perspective {
            fov_y_degrees: 30.0,
        },
        near: 0.1,
        far: 100.0,
    };
    let library = Arc::new(PatchLibrary {
        groups: vec![glint::geom::PatchGroup {
            name: "lid".into(),
            patches: vec![24, 25, 26, 27],
        }],
        ..(*teapot).clone()
    });
    let light = Light::Directional {
        towards: Vec3::new(0.3, -0.5, 0.8).normalize(),
    };
    let style = LineStyle {
        hidden: Some(HiddenLines {
            levels: 1,
            width: 1.0,
            colour: Vec3::X,
            dash: Dash::SOLID,
        }),
        ..LineStyle::new(1.5, Vec3::ZERO)
    };
    let drawn = frame(&library, (view, light), (style, 0.2), &settings);
    let lines = drawn.lines.as_deref().unwrap();
    let lid = lines.parts.iter().position(|p| p == "lid").unwrap() as u32;
    let hidden = stroke_points(lines, |s| {
        s.hidden && s.part == lid && s.kind == LineKind::Border
    });
    assert!(
        hidden.len() > 200,
        "the lid's rim is drawn hidden: {} points",
        hidden.len()
    );
    // Where it is drawn hidden, the frame shows another patch, not the lid.
    let ids = drawn.aovs.patch_id.as_ref().unwrap();
    let (w, _) = (SIZE as usize * 2, SIZE as usize);
    let covered = hidden
        .iter()
        .filter(|p| {
            let id = ids[p.y as usize * w + p.x as usize];
            id != u32::MAX && !(24..=27).contains(&id)
        })
        .count();
    assert!(
        covered as f64 >= 0.97 * hidden.len() as f64,
        "{covered} of {} hidden lid-rim points lie where another surface shows",
        hidden.len()
    );
}
