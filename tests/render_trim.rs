//! Trimmed patches against analytic coverage: a plane with a circular hole and a sphere with its
//! cap trimmed away, each read from a USD layer, rendered with the `final` preset and compared
//! per pixel with ray-cast coverage of the shapes they stand for; no sample lands on what a
//! trim cuts away; the trim edges draw as lines on the analytic curve.

use std::sync::Arc;

use glam::{DVec3, Vec3};
use glint::formats::parse_usda;
use glint::geom::PatchLibrary;
use glint::highlight::Light;
use glint::render::{
    Antialias, Aovs, Camera, Outlines, PatchLook, Projection, RenderedFrame, Renderer, Scene,
    Settings, Stage, Tone,
};
use glint::toon::CelRamp;

const SIZE: u32 = 512;
/// Sub-samples per pixel side of the analytic coverage.
const TRUTH_SAMPLES: u32 = 8;

/// The nine homogeneous points `(u·w, v·w, w)` of the circle of radius `r` about (cu, cv) in
/// (u, v), as rational quadratic arcs, clockwise when `clockwise`.
fn circle_points(cu: f64, cv: f64, r: f64, clockwise: bool) -> Vec<(f64, f64, f64)> {
    let w = 0.5f64.sqrt();
    let mut corners = vec![
        (1.0, 0.0, 1.0),
        (1.0, 1.0, w),
        (0.0, 1.0, 1.0),
        (-1.0, 1.0, w),
        (-1.0, 0.0, 1.0),
        (-1.0, -1.0, w),
        (0.0, -1.0, 1.0),
        (1.0, -1.0, w),
        (1.0, 0.0, 1.0),
    ];
    if clockwise {
        corners.reverse();
    }
    corners
        .into_iter()
        .map(|(x, y, ww)| ((cu + r * x) * ww, (cv + r * y) * ww, ww))
        .collect()
}

fn tuples(points: &[(f64, f64, f64)]) -> String {
    points
        .iter()
        .map(|(a, b, c)| format!("({a:?}, {b:?}, {c:?})"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The plane [−1, 1]² at z = 0 (u along x, v along y over [0, 1]²) with a hole of radius
/// `radius` (world units) about the origin: the domain as a counter-clockwise outer loop, the
/// hole a clockwise exact circle.
fn plate(radius: f64) -> Arc<PatchLibrary> {
    let outer = [
        (0.0, 0.0, 1.0),
        (1.0, 0.0, 1.0),
        (1.0, 1.0, 1.0),
        (0.0, 1.0, 1.0),
        (0.0, 0.0, 1.0),
    ];
    let mut points = outer.to_vec();
    points.extend(circle_points(0.5, 0.5, 0.5 * radius, true));
    let text = format!(
        r#"#usda 1.0
(
    upAxis = "Z"
)

def NurbsPatch "plate"
{{
    int uVertexCount = 2
    int vVertexCount = 2
    int uOrder = 2
    int vOrder = 2
    double[] uKnots = [0, 0, 1, 1]
    double[] vKnots = [0, 0, 1, 1]
    point3f[] points = [(-1, -1, 0), (1, -1, 0), (-1, 1, 0), (1, 1, 0)]
    int[] trimCurve:counts = [1, 1]
    int[] trimCurve:orders = [2, 3]
    int[] trimCurve:vertexCounts = [5, 9]
    double[] trimCurve:knots = [0, 0, 1, 2, 3, 4, 4, 0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1]
    double2[] trimCurve:ranges = [(0, 4), (0, 1)]
    double3[] trimCurve:points = [{}]
}}
"#,
        tuples(&points)
    );
    Arc::new(parse_usda(&text, "plate.usda").unwrap())
}

/// The shipped USD sphere (`patches/sphere.usda`, v from the south pole to the north) trimmed
/// to `v ≤ v_top`: one counter-clockwise loop round the kept rectangle, of which only the side
/// at `v_top` lies inside the domain and cuts.
fn capped_sphere(v_top: f64) -> Arc<PatchLibrary> {
    let text = std::fs::read_to_string(crate::common::repo_file("patches/sphere.usda")).unwrap();
    let loop_points = [
        (0.0, 0.0, 1.0),
        (1.0, 0.0, 1.0),
        (1.0, v_top, 1.0),
        (0.0, v_top, 1.0),
        (0.0, 0.0, 1.0),
    ];
    let trim = format!(
        "    int[] trimCurve:counts = [1]\n    int[] trimCurve:orders = [2]\n    int[] trimCurve:vertexCounts = [5]\n    double[] trimCurve:knots = [0, 0, 1, 2, 3, 4, 4]\n    double3[] trimCurve:points = [{}]\n}}",
        tuples(&loop_points)
    );
    let end = text.rfind('}').unwrap();
    let text = format!("{}{}{}", &text[..end], trim, &text[end + 1..]);
    Arc::new(parse_usda(&text, "capped_sphere.usda").unwrap())
}

fn camera(eye: Vec3) -> Camera {
    Camera {
        eye,
        target: Vec3::ZERO,
        up: Vec3::Z,
        projection: Projection::Perspective {
            fov_y_degrees: 40.0,
        },
        near: 0.1,
        far: 100.0,
    }
}

fn scene<'a>(library: &'a PatchLibrary, camera: Camera, outlines: Option<Outlines>) -> Scene<'a> {
    Scene {
        library,
        looks: vec![
            PatchLook {
                designed_light: None,
                lines: None,
                tone: Tone::Cel(CelRamp::two_tone(Vec3::splat(0.2), Vec3::splat(0.6), 0.0)),
                highlight: None,
            };
            library.patches.len()
        ],
        camera,
        light: Light::Directional {
            towards: Vec3::new(0.3, -0.8, 0.5).normalize(),
        },
        outlines,
        aovs: Aovs {
            uv: true,
            ..Aovs::default()
        },
        materials: Vec::new(),
    }
}

/// Per pixel, the fraction of its `TRUTH_SAMPLES²` sub-sample rays that meet a point `hit`
/// finds on the shape.
fn truth(camera: &Camera, hit: impl Fn(DVec3, DVec3) -> bool + Sync) -> Vec<f32> {
    (0..SIZE * SIZE)
        .map(|p| pixel_truth(camera, &hit, p, TRUTH_SAMPLES))
        .collect()
}

/// The fraction of pixel `p`'s `k²` sub-sample rays that meet a point `hit` finds on the shape.
fn pixel_truth(camera: &Camera, hit: &impl Fn(DVec3, DVec3) -> bool, p: u32, k: u32) -> f32 {
    let (x, y) = (p % SIZE, p / SIZE);
    let mut n = 0;
    for sy in 0..k {
        for sx in 0..k {
            let at = (
                f64::from(x) + (f64::from(sx) + 0.5) / f64::from(k),
                f64::from(y) + (f64::from(sy) + 0.5) / f64::from(k),
            );
            let (origin, direction) = camera.ray_through(at, (SIZE, SIZE));
            n += u32::from(hit(origin, direction.normalize()));
        }
    }
    n as f32 / (k * k) as f32
}

/// `Σ min / Σ max` of two coverages.
fn soft_iou(a: &[f32], b: &[f32]) -> f64 {
    let (both, either) = a.iter().zip(b).fold((0.0, 0.0), |(s, t), (&x, &y)| {
        (s + f64::from(x.min(y)), t + f64::from(x.max(y)))
    });
    both / either
}

/// Renders `library` at 512² with `final` and checks the alpha against `coverage` (`truth` of
/// `hit`): soft IoU at least 0.998, and nothing drawn on a pixel beyond what the shape covers
/// of it. A pixel none of whose `TRUTH_SAMPLES²` rays meets the shape may still hold a sliver
/// of it thinner than their spacing, which an edge drawn at one sample by its cover of the box
/// shows: there the alpha may exceed the cover that 128 × 128 rays find by 0.005 at most.
/// Returns the (u, v) of the pixels wholly covered.
fn assert_alpha_matches(
    library: &Arc<PatchLibrary>,
    camera: Camera,
    coverage: &[f32],
    hit: impl Fn(DVec3, DVec3) -> bool,
) -> Vec<glam::Vec2> {
    let frame = Renderer::new(Arc::clone(library))
        .render(
            &scene(library, camera, None),
            &Settings::final_quality(SIZE, SIZE),
        )
        .unwrap();
    let alpha: Vec<f32> = frame.colour.iter().map(|c| c.w).collect();
    // Every pixel finite, the limit normals at the sphere's poles (collapsed edges) included.
    assert!(frame.colour.iter().all(|c| c.is_finite()));
    let score = soft_iou(&alpha, coverage);
    assert!(score >= 0.998, "soft IoU of the alpha {score}");
    let stray: Vec<(usize, f32, f32)> = (0..alpha.len())
        .filter(|&p| coverage[p] == 0.0 && alpha[p] > 0.0)
        .map(|p| (p, alpha[p], pixel_truth(&camera, &hit, p as u32, 128)))
        .filter(|&(_, alpha, fine)| alpha > fine + 0.005)
        .collect();
    assert!(
        stray.is_empty(),
        "pixels drawn beyond the shape's cover: {stray:?}"
    );
    let uv = frame.aovs.uv.unwrap();
    (0..uv.len())
        .filter(|&p| alpha[p] >= 1.0)
        .map(|p| uv[p])
        .collect()
}

#[test]
fn a_plate_with_a_circular_hole_covers_what_the_plane_minus_the_disc_covers() {
    let radius = 0.6;
    let library = plate(radius);
    let camera = camera(Vec3::new(0.9, -2.2, 2.6));
    let hit = |o: DVec3, d: DVec3| {
        if d.z.abs() < 1e-12 {
            return false;
        }
        let t = -o.z / d.z;
        let p = o + d * t;
        t > 0.0 && p.x.abs() <= 1.0 && p.y.abs() <= 1.0 && p.x.hypot(p.y) >= radius
    };
    let coverage = truth(&camera, hit);
    let uv = assert_alpha_matches(&library, camera, &coverage, hit);
    // Every pixel drawn whole shows the plate, at or outside the hole's radius (to a fifth
    // of a pixel, about 10⁻³ in world units here).
    for uv in &uv {
        let r = 2.0 * (*uv - glam::Vec2::splat(0.5)).length();
        assert!(r >= (radius as f32) - 1e-3, "(u, v) {uv} is in the hole");
    }
}

#[test]
fn a_hole_rim_across_a_pixel_is_drawn_at_one_sample_with_its_area() {
    // Where the rim of the plate's hole crosses a pixel, `final` draws it at one sample: the
    // plate covers the box as the quadratic of the trim's signed distance over it says, beside
    // the background seen through the hole. Against 32 × 32 rays a pixel, the alpha of those
    // pixels is on average within a quarter of what 4 × 4 samples of every pixel come to
    // (0.0013 against 0.025 of a pixel), and the hole adds few pixels to those supersampled
    // (none for 742 crossed).
    let radius = 0.6;
    let library = plate(radius);
    let camera = camera(Vec3::new(0.9, -2.2, 2.6));
    let on_plane = |o: DVec3, d: DVec3| {
        let t = -o.z / d.z;
        (d.z.abs() > 1e-12 && t > 0.0).then(|| o + d * t)
    };
    let hit = |o: DVec3, d: DVec3| {
        on_plane(o, d)
            .is_some_and(|p| p.x.abs() <= 1.0 && p.y.abs() <= 1.0 && p.x.hypot(p.y) >= radius)
    };
    let coarse = truth(&camera, hit);
    // The pixels partly covered whose centre sees the plane within 0.05 of the rim (the
    // plate's outer edges are far from it).
    let crossed: Vec<(usize, f32)> = (0..SIZE * SIZE)
        .filter(|&p| coarse[p as usize] > 0.0 && coarse[p as usize] < 1.0)
        .filter(|&p| {
            let at = (f64::from(p % SIZE) + 0.5, f64::from(p / SIZE) + 0.5);
            let (o, d) = camera.ray_through(at, (SIZE, SIZE));
            on_plane(o, d.normalize()).is_some_and(|q| (q.x.hypot(q.y) - radius).abs() < 0.05)
        })
        .map(|p| (p as usize, pixel_truth(&camera, &hit, p, 32)))
        .collect();
    assert!(crossed.len() > 200, "{} pixels", crossed.len());
    let render = |library: &Arc<PatchLibrary>, antialias| {
        let settings = Settings {
            antialias,
            ..Settings::final_quality(SIZE, SIZE)
        };
        Renderer::new(Arc::clone(library))
            .render(&scene(library, camera, None), &settings)
            .unwrap()
    };
    let mean_error = |frame: &RenderedFrame| -> f32 {
        let error: f32 = crossed
            .iter()
            .map(|&(p, truth)| (frame.colour[p].w - truth).abs())
            .sum();
        error / crossed.len() as f32
    };
    let adaptive = render(&library, Antialias::Adaptive(4));
    let every = render(&library, Antialias::Supersample(4));
    // The rims are a stage of their own, which judges every crossed pixel, and only adaptive
    // anti-aliasing of a trimmed model runs it.
    assert!(adaptive.stats.ran(Stage::TrimEdges));
    let judged = adaptive.stats[Stage::TrimEdges].pixels;
    assert!(judged >= crossed.len() as u64, "{judged} judged");
    assert!(!every.stats.ran(Stage::TrimEdges));
    let (one, sixteen) = (mean_error(&adaptive), mean_error(&every));
    assert!(
        one * 4.0 < sixteen,
        "one sample: mean {one}; 4 × 4 samples: mean {sixteen}"
    );
    let mut whole = (*library).clone();
    whole.patches[0].trim = None;
    let plain = render(&Arc::new(whole), Antialias::Adaptive(4));
    assert!(!plain.stats.ran(Stage::TrimEdges));
    let added = adaptive.stats[Stage::Supersample].pixels as i64
        - plain.stats[Stage::Supersample].pixels as i64;
    assert!(
        added * 4 < crossed.len() as i64,
        "{added} more supersampled for {} crossed",
        crossed.len()
    );
}

#[test]
fn a_sphere_with_its_cap_trimmed_away_covers_what_the_cut_sphere_covers() {
    // z = 0.45 on the meridian: found on the surface by bisection, since the rational
    // parametrization is not the angle.
    let h = 0.45;
    let probe = capped_sphere(1.0);
    let surface = &probe.patches[0].surface;
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if surface.point(0.3, mid).z < h {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let library = capped_sphere(0.5 * (lo + hi));
    // From above the cut, so that the inside of the sphere shows through the opening and, near
    // its far rim, the background through it.
    let camera = camera(Vec3::new(0.6, -3.0, 2.4));
    let below = |top: f64| {
        move |o: DVec3, d: DVec3| {
            let b = o.dot(d);
            let disc = b * b - (o.length_squared() - 1.0);
            if disc < 0.0 {
                return false;
            }
            let s = disc.sqrt();
            [-b - s, -b + s]
                .iter()
                .any(|&t| t > 0.0 && (o + d * t).z <= top)
        }
    };
    let coverage = truth(&camera, below(h));
    // Through the opening the inside shows, and past its far rim the background: pixels the
    // whole sphere covers that the cut one does not.
    let whole = truth(&camera, below(2.0));
    let see_through = (0..coverage.len())
        .filter(|&p| whole[p] == 1.0 && coverage[p] == 0.0)
        .count();
    assert!(see_through > 1000, "{see_through}");
    let uv = assert_alpha_matches(&library, camera, &coverage, below(h));
    // No pixel drawn whole shows the cap.
    let v_top = 0.5 * (lo + hi) as f32;
    for uv in &uv {
        assert!(uv.y <= v_top + 1e-3, "(u, v) {uv} is on the cap");
    }
}

/// The pixel position of world point `p` on a `SIZE²` image.
fn to_pixel(camera: &Camera, p: DVec3) -> glam::Vec2 {
    let clip = camera.view_projection(1.0) * p.as_vec3().extend(1.0);
    let ndc = clip.truncate() / clip.w;
    glam::Vec2::new(
        (ndc.x + 1.0) * 0.5 * SIZE as f32,
        (1.0 - ndc.y) * 0.5 * SIZE as f32,
    )
}

#[test]
fn a_trim_edge_draws_as_a_border_on_the_analytic_circle_and_nothing_draws_inside_the_hole() {
    let radius = 0.6;
    let library = plate(radius);
    let camera = camera(Vec3::new(0.9, -2.2, 2.6));
    let width = 2.0;
    let outlines = Outlines {
        width,
        colour: Vec3::ZERO,
        crease_degrees: 60.0,
        patch_borders: false,
    };
    let mut scene = scene(&library, camera, Some(outlines));
    scene.aovs = Aovs {
        outline: true,
        ..Aovs::default()
    };
    let frame = Renderer::new(Arc::clone(&library))
        .render(&scene, &Settings::final_quality(SIZE, SIZE))
        .unwrap();
    let ink: Vec<f32> = frame.aovs.outline.unwrap().iter().map(|c| c.w).collect();
    // Along the circle, the line covers the pixel under it.
    let circle: Vec<glam::Vec2> = (0..720)
        .map(|k| {
            let a = std::f64::consts::TAU * f64::from(k) / 720.0;
            to_pixel(&camera, DVec3::new(radius * a.cos(), radius * a.sin(), 0.0))
        })
        .collect();
    for q in &circle {
        let p = (q.y as u32 * SIZE + q.x as u32) as usize;
        assert!(ink[p] >= 0.5, "the trim edge at {q} has ink {}", ink[p]);
    }
    // Inside the hole, farther than the line's half width and a pixel from the circle, no
    // ink: no line of a part the trim cuts away.
    for y in 0..SIZE {
        for x in 0..SIZE {
            let centre = glam::Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
            let (o, d) =
                camera.ray_through((f64::from(centre.x), f64::from(centre.y)), (SIZE, SIZE));
            let hit = o + d * (-o.z / d.z);
            let near_circle = circle
                .iter()
                .any(|q| q.distance(centre) <= 0.5 * width + 1.5);
            if hit.x.hypot(hit.y) < radius && !near_circle {
                let p = (y * SIZE + x) as usize;
                assert_eq!(ink[p], 0.0, "ink inside the hole at ({x}, {y})");
            }
        }
    }
}
