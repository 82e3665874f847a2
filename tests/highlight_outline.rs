//! Drawn outlines on the analytic sphere: the matte rendered under the `final` settings against
//! the region computed here from the outline and the sphere's exact frame, the disc as a special
//! case of an outline, and keyed outlines morphing point by point.
//!
//! The truth is computed without glint's highlight code: an orthographic ray along +y meets the
//! unit sphere at `p = (X, −√(1 − X² − Z²), Z)`, whose frame is `N = p`,
//! `du = (−N_y, N_x, 0)/|…|`, `dv = N × du` (the sphere patch's own frame); the half vector is
//! `normalize(L + V)` with `V = (0, −1, 0)`; a translation is `H ← normalize(H + α du + β dv)`
//! and a rotation by θ turns the tangent coordinates by −θ; the point is in the highlight where
//! `(H', N) > 0` and `t' = ((H', du), (H', dv))` is inside the outline by the even-odd rule,
//! the outline's Béziers flattened here into 512 pieces each.

use std::f64::consts::{PI, TAU};
use std::sync::Arc;

use glam::{DVec2, DVec3};
use glint::accuracy::AnalyticSphere;
use glint::anim::Track;
use glint::highlight::{Expr, Layer, Op, Outline, PreparedExpr, Segment, Shape};
use glint::render::{Aovs, Projection, Renderer, Settings};

const SIZE: u32 = 256;
/// Half the height of the orthographic view, as in `AnalyticSphere::new`.
const HALF: f64 = 1.2;

/// An outline piece as the test writes it.
#[derive(Clone, Copy, Debug)]
enum Piece {
    Corner(f64, f64),
    Bezier([f64; 2], [f64; 2], [f64; 2]),
}

fn outline(pieces: &[Piece]) -> Outline {
    Outline {
        segments: pieces
            .iter()
            .map(|p| match *p {
                Piece::Corner(x, y) => Segment::Corner([x as f32, y as f32]),
                Piece::Bezier(a, b, c) => Segment::Bezier([
                    [a[0] as f32, a[1] as f32],
                    [b[0] as f32, b[1] as f32],
                    [c[0] as f32, c[1] as f32],
                ]),
            })
            .collect(),
    }
}

/// The polygon of the pieces (as f32, as the layer gets them), each Bézier cut into 512 pieces.
fn polygon(pieces: &[Piece]) -> Vec<DVec2> {
    let f = |x: f64| f64::from(x as f32);
    let v = |p: [f64; 2]| DVec2::new(f(p[0]), f(p[1]));
    let end = |p: &Piece| match *p {
        Piece::Corner(x, y) => DVec2::new(f(x), f(y)),
        Piece::Bezier(_, _, c) => v(c),
    };
    let mut start = end(pieces.last().unwrap());
    let mut points = Vec::new();
    for p in pieces {
        match *p {
            Piece::Corner(..) => points.push(end(p)),
            Piece::Bezier(a, b, c) => {
                let (p1, p2, p3) = (v(a), v(b), v(c));
                for k in 1..=512 {
                    let t = k as f64 / 512.0;
                    let s = 1.0 - t;
                    points.push(
                        start * (s * s * s)
                            + p1 * (3.0 * s * s * t)
                            + p2 * (3.0 * s * t * t)
                            + p3 * (t * t * t),
                    );
                }
            }
        }
        start = end(p);
    }
    points
}

/// Even-odd: an odd number of the polygon's edges cross the ray from `q` toward +x.
fn inside_polygon(points: &[DVec2], q: DVec2) -> bool {
    let n = points.len();
    let mut odd = false;
    for k in 0..n {
        let (a, b) = (points[k], points[(k + 1) % n]);
        if (a.y > q.y) != (b.y > q.y) {
            let x = a.x + (q.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if q.x < x {
                odd = !odd;
            }
        }
    }
    odd
}

/// The stack the test applies: translations and rotations, in order.
#[derive(Clone, Copy, Debug)]
enum Step {
    Translate(f64, f64),
    Rotate(f64),
}

fn ops(steps: &[Step]) -> Vec<Op> {
    steps
        .iter()
        .map(|s| match *s {
            Step::Translate(alpha, beta) => Op::Translate {
                alpha: alpha as f32,
                beta: beta as f32,
            },
            Step::Rotate(degrees) => Op::Rotate {
                degrees: degrees as f32,
            },
        })
        .collect()
}

/// The sphere's region: whether the image point (x, y) (pixels from the top left) sees the
/// sphere, and if so whether it is in the highlight.
struct Truth {
    /// The point is in the highlight where t' is inside every one of these.
    polygons: Vec<Vec<DVec2>>,
    steps: Vec<Step>,
    light: DVec3,
}

impl Truth {
    fn new(pieces: &[Piece], steps: &[Step]) -> Self {
        Self::of_all(&[pieces], steps)
    }

    /// The region inside every one of the outlines `all`.
    fn of_all(all: &[&[Piece]], steps: &[Step]) -> Self {
        Self {
            polygons: all.iter().map(|pieces| polygon(pieces)).collect(),
            steps: steps.to_vec(),
            light: DVec3::new(0.35, -1.0, 0.45).normalize(),
        }
    }

    fn at(&self, x: f64, y: f64) -> bool {
        let (wx, wz) = (
            (2.0 * x / f64::from(SIZE) - 1.0) * HALF,
            (1.0 - 2.0 * y / f64::from(SIZE)) * HALF,
        );
        let r2 = wx * wx + wz * wz;
        if r2 >= 1.0 {
            return false;
        }
        let n = DVec3::new(wx, -(1.0 - r2).sqrt(), wz);
        let du = DVec3::new(-n.y, n.x, 0.0).normalize();
        let dv = n.cross(du);
        let h = (self.light + DVec3::new(0.0, -1.0, 0.0)).normalize();
        let (mut t, mut hn) = (DVec2::new(h.dot(du), h.dot(dv)), h.dot(n));
        for step in &self.steps {
            match *step {
                Step::Translate(alpha, beta) => {
                    let moved = DVec3::new(t.x + alpha, t.y + beta, hn).normalize();
                    (t, hn) = (DVec2::new(moved.x, moved.y), moved.z);
                }
                Step::Rotate(degrees) => {
                    let (s, c) = degrees.to_radians().sin_cos();
                    t = DVec2::new(c * t.x + s * t.y, c * t.y - s * t.x);
                }
            }
        }
        hn > 0.0 && self.polygons.iter().all(|p| inside_polygon(p, t))
    }

    /// The fraction of each pixel in the highlight: where the four corners of a pixel and of its
    /// neighbours agree, 0 or 1; elsewhere 16 × 16 samples.
    fn matte(&self) -> Vec<f32> {
        let n = SIZE as usize;
        let corner: Vec<bool> = (0..=n)
            .flat_map(|j| (0..=n).map(move |i| (i, j)))
            .map(|(i, j)| self.at(i as f64, j as f64))
            .collect();
        let corner_at = |i: usize, j: usize| corner[j * (n + 1) + i];
        let mut matte = vec![0.0_f32; n * n];
        for j in 0..n {
            for i in 0..n {
                let (lo_i, hi_i) = (i.saturating_sub(1), (i + 2).min(n));
                let (lo_j, hi_j) = (j.saturating_sub(1), (j + 2).min(n));
                let first = corner_at(i, j);
                let uniform =
                    (lo_j..=hi_j).all(|b| (lo_i..=hi_i).all(|a| corner_at(a, b) == first));
                matte[j * n + i] = if uniform {
                    f32::from(u8::from(first))
                } else {
                    let k = 16;
                    let hits = (0..k * k)
                        .filter(|s| {
                            let x = i as f64 + ((s % k) as f64 + 0.5) / k as f64;
                            let y = j as f64 + ((s / k) as f64 + 0.5) / k as f64;
                            self.at(x, y)
                        })
                        .count();
                    hits as f32 / (k * k) as f32
                };
            }
        }
        matte
    }
}

/// Σ min / Σ max of two soft mattes.
fn soft_iou(a: &[f32], b: &[f32]) -> f64 {
    let (mut both, mut either) = (0.0_f64, 0.0_f64);
    for (x, y) in a.iter().zip(b) {
        both += f64::from(x.min(*y));
        either += f64::from(x.max(*y));
    }
    assert!(
        either > 500.0,
        "the highlight should cover a visible area, got {either} pixels"
    );
    both / either
}

/// The highlight matte of the layer rendered at 256² under the `final` settings.
fn rendered(layer: Layer) -> Vec<f32> {
    rendered_with(layer, Settings::final_quality(SIZE, SIZE))
}

/// The highlight matte of the layer rendered with `settings` (a square image).
fn rendered_with(layer: Layer, settings: Settings) -> Vec<f32> {
    let expr: PreparedExpr = Expr::Layer(layer).prepare().unwrap();
    let sphere = AnalyticSphere::new(Projection::Orthographic {
        height: 2.0 * HALF as f32,
    });
    let library = AnalyticSphere::library();
    let aovs = Aovs {
        matte: true,
        ..Aovs::default()
    };
    let scene = sphere.scene(&library, &expr, aovs);
    let frame = Renderer::new(Arc::clone(&library))
        .render(&scene, &settings)
        .unwrap();
    frame.aovs.matte.unwrap()
}

fn drawn(pieces: &[Piece], steps: &[Step]) -> Layer {
    Layer {
        shape: Shape::Outline(outline(pieces)),
        ..Layer::new(ops(steps), 0.05, [1.0, 1.0, 1.0])
    }
}

/// A five-pointed star of outer radius `outer`, inner `inner`, turned by `turn` radians.
fn star(outer: f64, inner: f64, turn: f64) -> Vec<Piece> {
    (0..10)
        .map(|k| {
            let a = turn + TAU * k as f64 / 10.0 + PI / 2.0;
            let r = if k % 2 == 0 { outer } else { inner };
            Piece::Corner(r * a.cos(), r * a.sin())
        })
        .collect()
}

/// A square with a V-shaped notch cut into its top and a narrow slot into its right side.
fn notched() -> Vec<Piece> {
    [
        (-0.35, -0.35),
        (0.35, -0.35),
        (0.35, -0.05),
        (0.05, -0.02),
        (0.05, 0.02),
        (0.35, 0.05),
        (0.35, 0.35),
        (0.12, 0.35),
        (0.0, 0.1),
        (-0.12, 0.35),
        (-0.35, 0.35),
    ]
    .iter()
    .map(|&(x, y)| Piece::Corner(x, y))
    .collect()
}

/// A heart: two Bézier lobes meeting at a notch on top, and a point at the bottom.
fn heart() -> Vec<Piece> {
    vec![
        Piece::Corner(0.0, -0.4),
        Piece::Bezier([-0.25, -0.2], [-0.45, 0.0], [-0.4, 0.18]),
        Piece::Bezier([-0.35, 0.38], [-0.08, 0.4], [0.0, 0.2]),
        Piece::Bezier([0.08, 0.4], [0.35, 0.38], [0.4, 0.18]),
        Piece::Bezier([0.45, 0.0], [0.25, -0.2], [0.0, -0.4]),
    ]
}

/// The moved and turned placement of every shape.
const MOVED: [Step; 2] = [Step::Translate(0.12, -0.08), Step::Rotate(35.0)];

fn assert_matches_truth(name: &str, pieces: &[Piece]) {
    for steps in [&[][..], &MOVED[..]] {
        let truth = Truth::new(pieces, steps).matte();
        let score = soft_iou(&rendered(drawn(pieces, steps)), &truth);
        assert!(score >= 0.998, "{name} with {steps:?}: soft IoU {score}");
    }
}

#[test]
fn a_star_matches_its_region_on_the_sphere_alone_and_moved_and_turned() {
    assert_matches_truth("star", &star(0.45, 0.18, 0.0));
}

#[test]
fn a_notched_polygon_matches_its_region_on_the_sphere_alone_and_moved_and_turned() {
    assert_matches_truth("notched polygon", &notched());
}

#[test]
fn a_bezier_heart_matches_its_region_on_the_sphere_alone_and_moved_and_turned() {
    assert_matches_truth("heart", &heart());
}

#[test]
fn the_disc_is_the_outline_of_its_circle() {
    let epsilon = 0.05_f64;
    let r = (1.0 - (1.0 - epsilon) * (1.0 - epsilon)).sqrt();
    let circle: Vec<Piece> = (0..256)
        .map(|k| {
            let a = TAU * k as f64 / 256.0;
            Piece::Corner(r * a.cos(), r * a.sin())
        })
        .collect();
    for steps in [&[][..], &MOVED[..]] {
        let disc = rendered(Layer::new(ops(steps), epsilon as f32, [1.0, 1.0, 1.0]));
        let drawn = rendered(drawn(&circle, steps));
        let score = soft_iou(&drawn, &disc);
        assert!(score >= 0.999, "{steps:?}: soft IoU {score}");
    }
}

/// The layer of a keyed outline read from RON as a shot reads it, at `frame`.
fn keyed_at(a: &[Piece], b: &[Piece], frame: f64) -> Layer {
    let key = |pieces: &[Piece]| {
        pieces
            .iter()
            .map(|p| match *p {
                Piece::Corner(x, y) => format!("({x}, {y})"),
                Piece::Bezier(p, q, e) => format!(
                    "Bezier(({}, {}), ({}, {}), ({}, {}))",
                    p[0], p[1], q[0], q[1], e[0], e[1]
                ),
            })
            .collect::<Vec<_>>()
            .join(", ")
    };
    let text = format!(
        "(stack: [], epsilon: 0.05, colour: (1.0, 1.0, 1.0), \
         shape: OutlineKeys([(1, [{}]), (9, [{}])]))",
        key(a),
        key(b)
    );
    let layer: Layer<Track<f32>> = ron::from_str(&text).unwrap();
    layer.map(|t| t.at(frame))
}

#[test]
fn a_morph_at_its_midpoint_is_the_outline_of_averaged_points_and_keeps_what_both_keys_cover() {
    // A star inflating into a near-decagon: every vertex moves outward along its own ray, so
    // each triangle (centre, v_k, v_k+1) of a frame holds the one before, and every frame holds
    // the first key; the matte must not lose any of it.
    let a = star(0.4, 0.16, 0.0);
    let b = star(0.48, 0.42, 0.0);
    let mean: Vec<Piece> = a
        .iter()
        .zip(&b)
        .map(|(p, q)| match (*p, *q) {
            (Piece::Corner(x0, y0), Piece::Corner(x1, y1)) => {
                Piece::Corner(0.5 * (x0 + x1), 0.5 * (y0 + y1))
            }
            _ => unreachable!("the stars are corners"),
        })
        .collect();
    let mid = rendered(keyed_at(&a, &b, 5.0));
    let averaged = rendered(drawn(&mean, &[]));
    let score = soft_iou(&mid, &averaged);
    assert!(
        score >= 0.998,
        "midpoint against averaged points: soft IoU {score}"
    );
    // Where both keys cover a pixel fully, every frame of the morph covers it.
    let (first, last) = (
        rendered(keyed_at(&a, &b, 1.0)),
        rendered(keyed_at(&a, &b, 9.0)),
    );
    let both: Vec<usize> = (0..first.len())
        .filter(|&i| first[i] >= 0.999 && last[i] >= 0.999)
        .collect();
    assert!(both.len() > 1000, "{}", both.len());
    for frame in [3.0, 5.0, 7.0] {
        let between = if frame == 5.0 {
            mid.clone()
        } else {
            rendered(keyed_at(&a, &b, frame))
        };
        let holes = both.iter().filter(|&&i| between[i] < 0.999).count();
        assert_eq!(
            holes, 0,
            "frame {frame}: {holes} pixels of both keys uncovered"
        );
    }
}

#[test]
fn a_star_turned_between_keys_keeps_at_its_midpoint_every_pixel_both_keys_cover() {
    // The star turned by 30° point by point: each point moves along a chord, so the lerped
    // outline at the midpoint is the star turned by 15° and shrunk by cos 15°, and its tips
    // fall short of where the two keys' tips overlap.
    let a = star(0.4, 0.16, 0.0);
    let b = star(0.4, 0.16, 30_f64.to_radians());
    let mean: Vec<Piece> = a
        .iter()
        .zip(&b)
        .map(|(p, q)| match (*p, *q) {
            (Piece::Corner(x0, y0), Piece::Corner(x1, y1)) => {
                Piece::Corner(0.5 * (x0 + x1), 0.5 * (y0 + y1))
            }
            _ => unreachable!("the stars are corners"),
        })
        .collect();
    // Each key renders as its region, so "covered in the key's own render" is its truth.
    for (name, key, frame) in [("first", &a, 1.0), ("last", &b, 9.0)] {
        let score = soft_iou(
            &rendered(keyed_at(&a, &b, frame)),
            &Truth::new(key, &[]).matte(),
        );
        assert!(score >= 0.998, "the {name} key: soft IoU {score}");
    }
    // The pixels at least half inside both keys' regions at once.
    let both = Truth::of_all(&[&a, &b], &[]).matte();
    let shared: Vec<usize> = (0..both.len()).filter(|&i| both[i] >= 0.5).collect();
    assert!(shared.len() > 1000, "{}", shared.len());
    // A lerp of the points alone leaves some of them: the test can fail.
    let lerp_only = Truth::new(&mean, &[]).matte();
    let cut = shared.iter().filter(|&&i| lerp_only[i] < 0.5).count();
    assert!(
        cut > 20,
        "the lerped star alone uncovers {cut} shared pixels"
    );
    let mid = rendered(keyed_at(&a, &b, 5.0));
    let holes: Vec<usize> = shared.iter().copied().filter(|&i| mid[i] < 0.5).collect();
    assert!(
        holes.is_empty(),
        "{} of {} pixels both keys cover are uncovered at the midpoint, e.g. pixel {:?}",
        holes.len(),
        shared.len(),
        holes
            .first()
            .map(|&i| (i % SIZE as usize, i / SIZE as usize))
    );
    // And the midpoint still holds the lerped outline (away from its edge's half-covered
    // pixels, where the rendered and computed coverage may fall either side of 1/2).
    let lost = (0..lerp_only.len())
        .filter(|&i| lerp_only[i] >= 0.6 && mid[i] < 0.5)
        .count();
    assert_eq!(lost, 0, "{lost} pixels of the lerped star uncovered");
}

#[test]
fn the_layers_documented_under_drawn_outlines_parse_prepare_and_render() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/highlights.md");
    let doc = std::fs::read_to_string(path).unwrap();
    let section = &doc[doc.find("## Drawn outlines").unwrap()..];
    let blocks: Vec<&str> = section
        .split("```ron\n")
        .skip(1)
        .map(|rest| &rest[..rest.find("```").unwrap()])
        .collect();
    assert_eq!(blocks.len(), 3, "the star, the heart and the keyed outline");
    for block in &blocks {
        let layer: Layer<Track<f32>> =
            ron::from_str(block).unwrap_or_else(|e| panic!("{e}\n{block}"));
        assert!(!layer.shape.is_disc());
        for frame in [1.0, 12.0, 24.0] {
            let at = layer.map(|t| t.at(frame));
            let matte = rendered_with(at, Settings::preview(64, 64));
            let covered: f32 = matte.iter().sum();
            assert!(covered > 20.0, "frame {frame}: {covered} pixels\n{block}");
        }
    }
}
