//! Lines on the analytic sphere and torus, from cameras all around and above them: one closed
//! line where one is expected, centred on the true silhouette, of the width asked for.

use std::sync::Arc;

use glam::{DVec3, Mat4, Vec2, Vec3, Vec4};
use glint::formats::svg::svg_document;
use glint::geom::{shapes, NamedPatch, NurbsSurface, PatchLibrary};
use glint::highlight::Light;
use glint::render::{
    Aovs, Camera, Outlines, PatchLook, Projection, RenderedFrame, Renderer, Scene, Settings, Tone,
};
use glint::toon::CelRamp;

use crate::common::labels;

const SIZE: u32 = 200;
const FOV_DEGREES: f32 = 40.0;

fn library(surface: NurbsSurface) -> Arc<PatchLibrary> {
    Arc::new(PatchLibrary {
        patches: vec![NamedPatch {
            name: "shape".into(),
            trim: None,
            surface,
        }],
        groups: Vec::new(),
    })
}

/// The camera looking at the origin from `distance`, `elevation` degrees above the xy plane and
/// `azimuth` degrees round from +x.
fn camera(distance: f32, elevation: f32, azimuth: f32) -> Camera {
    let (e, a) = (elevation.to_radians(), azimuth.to_radians());
    Camera {
        eye: distance * Vec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin()),
        target: Vec3::ZERO,
        up: Vec3::Z,
        projection: Projection::Perspective {
            fov_y_degrees: FOV_DEGREES,
        },
        near: 0.1,
        far: 100.0,
    }
}

/// The 36 views: twelve azimuths at each of three heights above the equator, looking at the
/// origin from `distance`.
fn views(distance: f32) -> Vec<Camera> {
    let mut cameras = Vec::new();
    for elevation in [8.0f32, 38.0, 72.0] {
        for k in 0..12 {
            cameras.push(camera(distance, elevation, k as f32 * 30.0 + 7.0));
        }
    }
    cameras
}

/// The lines alone (the outline AOV's alpha) and the patch-id AOV of one frame.
fn lines(
    library: &Arc<PatchLibrary>,
    camera: Camera,
    width: f32,
    settings: &Settings,
) -> (Vec<f32>, Vec<u32>) {
    let frame = frame(library, camera, width, settings);
    let outline: &Vec<Vec4> = frame.aovs.outline.as_ref().unwrap();
    (
        outline.iter().map(|c| c.w).collect(),
        frame.aovs.patch_id.unwrap(),
    )
}

/// One frame of `library`'s patches, two-tone, with black lines `width` pixels wide and the
/// outline and patch-id AOVs.
fn frame(
    library: &Arc<PatchLibrary>,
    camera: Camera,
    width: f32,
    settings: &Settings,
) -> RenderedFrame {
    let scene = Scene {
        library,
        looks: vec![PatchLook {
            designed_light: None,
            lines: None,
            tone: Tone::Cel(CelRamp::two_tone(
                Vec3::new(0.2, 0.3, 0.5),
                Vec3::new(0.5, 0.6, 0.9),
                0.2,
            )),
            highlight: None,
        }],
        camera,
        light: Light::Directional {
            towards: Vec3::new(0.3, -0.5, 0.8).normalize(),
        },
        outlines: Some(Outlines {
            width,
            colour: Vec3::ZERO,
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

/// How many 8-connected components the pixels `on` marks form.
fn components(on: &[bool], size: (usize, usize)) -> usize {
    labels(on, size).1.len()
}

/// The regions of `on` pixels (4-connected) that do not touch the image's border.
fn enclosed(on: &[bool], (w, h): (usize, usize)) -> usize {
    let mut seen = vec![false; on.len()];
    let mut count = 0;
    for start in 0..on.len() {
        if !on[start] || seen[start] {
            continue;
        }
        let mut touches = false;
        let mut stack = vec![start];
        seen[start] = true;
        while let Some(p) = stack.pop() {
            let (x, y) = (p % w, p / w);
            touches |= x == 0 || y == 0 || x + 1 == w || y + 1 == h;
            let mut visit = |q: usize| {
                if on[q] && !seen[q] {
                    seen[q] = true;
                    stack.push(q);
                }
            };
            if x > 0 {
                visit(p - 1);
            }
            if x + 1 < w {
                visit(p + 1);
            }
            if y > 0 {
                visit(p - w);
            }
            if y + 1 < h {
                visit(p + w);
            }
        }
        count += usize::from(!touches);
    }
    count
}

/// The image bilinearly at `p` (pixel centres at half-integers), 0 outside.
fn bilinear(image: &[f32], (w, h): (usize, usize), p: Vec2) -> f32 {
    let q = p - 0.5;
    let (x0, y0) = (q.x.floor(), q.y.floor());
    let (fx, fy) = (q.x - x0, q.y - y0);
    let at = |x: f32, y: f32| {
        if x < 0.0 || y < 0.0 || x >= w as f32 || y >= h as f32 {
            0.0
        } else {
            image[y as usize * w + x as usize]
        }
    };
    let top = at(x0, y0) * (1.0 - fx) + at(x0 + 1.0, y0) * fx;
    let bottom = at(x0, y0 + 1.0) * (1.0 - fx) + at(x0 + 1.0, y0 + 1.0) * fx;
    top * (1.0 - fy) + bottom * fy
}

#[test]
fn the_sphere_s_silhouette_is_one_closed_line_on_the_true_outline_at_its_width() {
    let sphere = library(shapes::sphere(DVec3::ZERO, 1.0).unwrap());
    let size = (SIZE as usize, SIZE as usize);
    let distance = 4.0f32;
    // Seen from any point at distance D, a unit sphere's outline is the circle of the cone of
    // half-angle asin(1/D) about the line of sight: tan(asin(1/D)) / tan(fov/2) half-heights
    // from the image's centre.
    let radius =
        (1.0 / distance).asin().tan() / (0.5 * FOV_DEGREES.to_radians()).tan() * 0.5 * SIZE as f32;
    let centre = Vec2::splat(0.5 * SIZE as f32);
    for (settings, name) in [
        (Settings::preview(SIZE, SIZE), "preview"),
        (Settings::final_quality(SIZE, SIZE), "final"),
    ] {
        for (v, camera) in views(distance).into_iter().enumerate() {
            // Final is checked on every third view, to keep the suite short.
            if name == "final" && v % 3 != 0 {
                continue;
            }
            for width in [1.5f32, 3.0] {
                let (alpha, _) = lines(&sphere, camera, width, &settings);
                let inked: Vec<bool> = alpha.iter().map(|&a| a >= 0.5).collect();
                assert_eq!(components(&inked, size), 1, "{name} view {v} width {width}");
                // Closed: the line parts the image in two, inside and outside.
                let clear: Vec<bool> = alpha.iter().map(|&a| a < 0.5).collect();
                assert_eq!(
                    enclosed(&clear, size),
                    1,
                    "{name} view {v} width {width}: not closed"
                );
                for k in 0..72 {
                    let a = (k as f32 * 5.0 + 1.0).to_radians();
                    let along = Vec2::new(a.cos(), a.sin());
                    let step = 0.05;
                    let (mut sum, mut moment) = (0.0f32, 0.0f32);
                    let mut s = radius - 3.0 * width - 2.0;
                    while s <= radius + 3.0 * width + 2.0 {
                        let value = bilinear(&alpha, size, centre + along * s);
                        sum += value * step;
                        moment += value * s * step;
                        s += step;
                    }
                    let middle = moment / sum;
                    assert!(
                        (middle - radius).abs() <= 0.5,
                        "{name} view {v} width {width} at {}°: centred {} px off",
                        k * 5 + 1,
                        middle - radius
                    );
                    assert!(
                        (sum - width).abs() <= 0.25,
                        "{name} view {v} width {width} at {}°: {sum} px wide",
                        k * 5 + 1
                    );
                }
            }
        }
    }
}

/// Whether the segment from `eye` to just before `point` enters the torus (about +z, tube
/// centre radius `major`, tube radius `minor`): `(√(x² + y²) − major)² + z² < minor²` at one of
/// 4000 points along it.
fn torus_hides(major: f64, minor: f64, eye: DVec3, point: DVec3) -> bool {
    (0..4000).any(|k| {
        let p = eye.lerp(point, k as f64 / 4000.0 * (1.0 - 1e-3));
        let ring = (p.x * p.x + p.y * p.y).sqrt() - major;
        ring * ring + p.z * p.z < minor * minor * (1.0 - 1e-9)
    })
}

/// The torus's contour seen from `eye`, as points on the image of `view_projection`, each with
/// whether it is visible: on the tube's circle at angle θ the normal is
/// `N = (cos φ cos θ, cos φ sin θ, sin φ)`, and `N·(P − E) = 0` reads
/// `A cos φ + B sin φ = −minor` with `A = major − E·(cos θ, sin θ, 0)` and `B = −E_z`.
fn torus_contour(major: f64, minor: f64, eye: DVec3, view_projection: Mat4) -> Vec<(Vec2, bool)> {
    let mut points = Vec::new();
    for k in 0..3000 {
        let theta = k as f64 / 3000.0 * std::f64::consts::TAU;
        let a = major - eye.x * theta.cos() - eye.y * theta.sin();
        let b = -eye.z;
        let rho = (a * a + b * b).sqrt();
        if minor > rho {
            continue;
        }
        let alpha = b.atan2(a);
        let spread = (-minor / rho).acos();
        for phi in [alpha + spread, alpha - spread] {
            let ring = major + minor * phi.cos();
            let p = DVec3::new(ring * theta.cos(), ring * theta.sin(), minor * phi.sin());
            let clip = view_projection * p.as_vec3().extend(1.0);
            let ndc = clip.truncate() / clip.w;
            let on_image = Vec2::new(
                (ndc.x + 1.0) * 0.5 * SIZE as f32,
                (1.0 - ndc.y) * 0.5 * SIZE as f32,
            );
            points.push((on_image, !torus_hides(major, minor, eye, p)));
        }
    }
    points
}

#[test]
fn the_torus_s_contours_are_the_visible_true_contour_unbroken() {
    let (major, minor) = (2.0, 0.5);
    let torus = library(shapes::torus(major, minor).unwrap());
    let size = (SIZE as usize, SIZE as usize);
    let settings = Settings::preview(SIZE, SIZE);
    let width = 2.0f32;
    for (v, camera) in views(9.0).into_iter().enumerate() {
        let (alpha, _) = lines(&torus, camera, width, &settings);
        let contour = torus_contour(
            major,
            minor,
            camera.eye.as_dvec3(),
            camera.view_projection(1.0),
        );
        // The visible contour drawn independently: every pixel within the half width of a
        // visible point. As many separate lines as the rendered ones.
        let reference: Vec<bool> = (0..size.0 * size.1)
            .map(|p| {
                let centre = Vec2::new((p % size.0) as f32 + 0.5, (p / size.0) as f32 + 0.5);
                contour
                    .iter()
                    .any(|&(q, visible)| visible && q.distance(centre) <= 0.5 * width)
            })
            .collect();
        let inked: Vec<bool> = alpha.iter().map(|&a| a >= 0.5).collect();
        assert_eq!(
            components(&inked, size),
            components(&reference, size),
            "view {v}: separate lines"
        );
        for (p, _) in inked.iter().enumerate().filter(|(_, &on)| on) {
            let centre = Vec2::new((p % size.0) as f32 + 0.5, (p / size.0) as f32 + 0.5);
            // Every inked pixel lies on the visible contour, within the line's half width and
            // the half pixel of its anti-aliased edge (a pixel more where visibility changes).
            let nearest = |visible: bool| {
                contour
                    .iter()
                    .filter(|&&(_, seen)| seen == visible)
                    .map(|(q, _)| q.distance(centre))
                    .fold(f32::INFINITY, f32::min)
            };
            assert!(
                nearest(true) <= 0.5 * width + 0.5
                    || (nearest(false) <= 0.5 * width + 1.5 && nearest(true) <= 0.5 * width + 3.0),
                "view {v}: an inked pixel {} px from the visible contour",
                nearest(true)
            );
        }
        // No gaps: every visible point of the contour, away from where it goes out of sight,
        // is inked.
        for &(q, _) in contour.iter().filter(|&&(q, visible)| {
            visible && contour.iter().all(|&(r, seen)| seen || r.distance(q) > 3.0)
        }) {
            let (x, y) = (q.x as usize, q.y as usize);
            assert!(
                alpha[y * size.0 + x] >= 0.5,
                "view {v}: a gap at ({:.1}, {:.1})",
                q.x,
                q.y
            );
        }
    }
}

/// Where `p` lands on a `size`-pixel square image through `view_projection`, in pixels.
fn on_image(view_projection: Mat4, p: DVec3, size: f32) -> Vec2 {
    let c = view_projection * p.as_vec3().extend(1.0);
    Vec2::new(
        (c.x / c.w + 1.0) * 0.5 * size,
        (1.0 - c.y / c.w) * 0.5 * size,
    )
}

#[test]
fn a_plate_s_open_borders_seen_nearly_edge_on_are_inked_unbroken_at_one_sample() {
    // A 2 × 2 plate seen from 5° to 18° above its plane (its far border at 4° and more):
    // nothing hides its borders, though the plate itself lies nearer than its far border over
    // the pixels about it. The final preset tests the lines against one sample a pixel.
    let library = library(shapes::plane(2.0, 2.0).unwrap());
    let settings = Settings::final_quality(SIZE, SIZE);
    let corners = [
        DVec3::new(-1.0, -1.0, 0.0),
        DVec3::new(1.0, -1.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(-1.0, 1.0, 0.0),
    ];
    let mut views = 0;
    for elevation in [5.0f32, 8.0, 12.0, 18.0] {
        for k in 0..8 {
            let camera = camera(5.0, elevation, k as f32 * 45.0 + 10.0);
            let view_projection = camera.view_projection(1.0);
            let (alpha, _) = lines(&library, camera, 2.0, &settings);
            let size = (SIZE as usize, SIZE as usize);
            // Every point of the four borders, 100 to a side, away from the corners where two
            // lines end, is inked.
            for side in 0..4 {
                let (a, b) = (corners[side], corners[(side + 1) % 4]);
                for i in 5..=95 {
                    let p = on_image(
                        view_projection,
                        a.lerp(b, f64::from(i) / 100.0),
                        SIZE as f32,
                    );
                    assert!(
                        bilinear(&alpha, size, p) >= 0.5,
                        "{elevation}° up, azimuth {k}: side {side} not inked at ({:.1}, {:.1})",
                        p.x,
                        p.y
                    );
                }
            }
            views += 1;
        }
    }
    assert_eq!(views, 32);
}

/// The paths of an SVG document `svg_document` wrote, as (kind, points, closed, tapered): the
/// kind from the group each is in, its points read back from its `d`.
fn svg_paths(svg: &str) -> Vec<(String, Vec<Vec2>, bool, bool)> {
    let mut kind = String::new();
    let mut paths = Vec::new();
    for line in svg.lines().map(str::trim) {
        if let Some(rest) = line.strip_prefix("<g id=\"") {
            if line.contains("class=\"lines ") {
                kind = rest[..rest.find('"').unwrap()].to_string();
            }
        }
        if !line.starts_with("<path") {
            continue;
        }
        let d = &line[line.find(" d=\"").unwrap() + 4..];
        let d = &d[..d.find('"').unwrap()];
        let closed = d.ends_with('Z');
        let points = d
            .trim_end_matches('Z')
            .split(['M', 'L'])
            .filter(|p| !p.is_empty())
            .map(|p| {
                let (x, y) = p.split_once(' ').unwrap();
                Vec2::new(x.parse().unwrap(), y.parse().unwrap())
            })
            .collect();
        paths.push((
            kind.clone(),
            points,
            closed,
            line.contains("class=\"taper\""),
        ));
    }
    paths
}

#[test]
fn the_sphere_s_silhouette_in_svg_is_one_closed_path_on_the_true_outline() {
    let sphere = library(shapes::sphere(DVec3::ZERO, 1.0).unwrap());
    let distance = 4.0f32;
    // The outline's circle, as in the raster test above.
    let radius =
        (1.0 / distance).asin().tan() / (0.5 * FOV_DEGREES.to_radians()).tan() * 0.5 * SIZE as f32;
    let centre = Vec2::splat(0.5 * SIZE as f32);
    let mut worst = 0.0f32;
    for (settings, name) in [
        (Settings::preview(SIZE, SIZE), "preview"),
        (Settings::final_quality(SIZE, SIZE), "final"),
    ] {
        for (v, camera) in views(distance).into_iter().enumerate() {
            let frame = frame(&sphere, camera, 2.0, &settings);
            let svg = svg_document(frame.lines.as_deref().unwrap(), &[]);
            let paths = svg_paths(&svg);
            assert_eq!(paths.len(), 1, "{name} view {v}: {svg}");
            let (kind, points, closed, tapered) = &paths[0];
            assert_eq!(kind, "silhouette", "{name} view {v}");
            assert!(*closed && !tapered, "{name} view {v}: a closed stroke");
            // Around the whole circle, not a piece of it: no gap wider than 10° between
            // neighbouring points.
            let mut angles: Vec<f32> = points
                .iter()
                .map(|p| (*p - centre).y.atan2((*p - centre).x))
                .collect();
            angles.sort_by(f32::total_cmp);
            let widest = angles
                .windows(2)
                .map(|w| w[1] - w[0])
                .chain([angles[0] + std::f32::consts::TAU - angles[angles.len() - 1]])
                .fold(0.0, f32::max);
            assert!(
                widest < 10f32.to_radians(),
                "{name} view {v}: a gap of {widest} rad"
            );
            for p in points {
                let off = (p.distance(centre) - radius).abs();
                worst = worst.max(off);
                assert!(
                    off <= 0.25,
                    "{name} view {v}: a point {off} px off the outline"
                );
            }
        }
    }
    println!("sphere: worst point {worst:.4} px off the analytic outline");
}

#[test]
fn the_torus_s_contours_in_svg_lie_on_its_true_contour() {
    let (major, minor) = (2.0, 0.5);
    let torus = library(shapes::torus(major, minor).unwrap());
    let settings = Settings::preview(SIZE, SIZE);
    for (v, camera) in views(9.0).into_iter().enumerate() {
        let frame = frame(&torus, camera, 2.0, &settings);
        let svg = svg_document(frame.lines.as_deref().unwrap(), &[]);
        let contour = torus_contour(
            major,
            minor,
            camera.eye.as_dvec3(),
            camera.view_projection(1.0),
        );
        let paths = svg_paths(&svg);
        assert!(!paths.is_empty(), "view {v}");
        // Seen from above, the inner contour is a line of its own beside the outer one.
        let closed = paths.iter().filter(|p| p.2).count();
        if v >= 24 {
            assert_eq!(closed, 2, "view {v}: outer and inner contour, each closed");
        }
        for (kind, points, _, _) in &paths {
            assert_eq!(kind, "silhouette", "view {v}");
            // On the contour; and where it is hidden, no further into the hidden part than
            // the raster's lines go (a gap under 3 px is bridged).
            for p in points {
                let nearest = |visible: Option<bool>| {
                    contour
                        .iter()
                        .filter(|(_, seen)| visible.is_none_or(|v| v == *seen))
                        .map(|(q, _)| q.distance(*p))
                        .fold(f32::INFINITY, f32::min)
                };
                let on = nearest(None);
                assert!(on <= 0.25, "view {v}: a point {on} px off the contour");
                let seen = nearest(Some(true));
                assert!(
                    seen <= 3.0,
                    "view {v}: a point {seen} px from the visible contour"
                );
            }
        }
    }
}
