//! One highlight across several patches: a layer `frame: Along(axis: …)` acts along one
//! direction field over the patches it spans, so a translated, stretched highlight keeps its
//! boundary across the seams of patches parameterized in different directions; the same layer
//! in each patch's own frame (the default) steps there.
//!
//! The model is a dome `z = −c (x² + y²)` over `[−3, 3] × [−1, 1]`, cut at x = −1 and x = 1 into
//! three biquadratic Bezier patches that are pieces of the one polynomial surface (edges shared
//! exactly, the surface smooth across them): the first with u along +x, the middle with u
//! along −x, the last with u along +y and v along +x. Seen from straight above in a parallel
//! projection of 100 pixels per unit, under a light straight above, the initial half vector is
//! +z everywhere and the seams are the pixel columns' boundaries at 220 and 420.

use std::sync::Arc;

use glam::{DVec3, Vec3};
use glint::geom::{shapes, NamedPatch, PatchGroup, PatchLibrary};
use glint::highlight::{Axis, Expr, Layer, LayerFrame, Light, Op};
use glint::render::{
    Aovs, Camera, PatchLook, Projection, RenderedFrame, Renderer, Scene, Settings, Tone,
};
use glint::toon::CelRamp;

const WIDTH: u32 = 640;
const HEIGHT: u32 = 360;
/// Pixels per world unit: the view shows 3.6 units from top to bottom.
const SCALE: f64 = 100.0;
/// The dome's curvature: `z = −C (x² + y²)`.
const C: f64 = 0.15;
/// The seams' x in world units, and the pixel columns' boundaries they project to.
const SEAMS: [f64; 2] = [-1.0, 1.0];
/// The image row boundary that y = 0 projects to: the highlights below are symmetric about it.
const MIDDLE_ROW: usize = HEIGHT as usize / 2;

/// The pixel x of world x.
fn column_of(x: f64) -> f64 {
    0.5 * f64::from(WIDTH) + SCALE * x
}

/// The biquadratic Bezier patch of the dome over `x ∈ [x0, x1]`, `y ∈ [y0, y1]`, with u along x
/// from x0 to x1 and v along y from y0 to y1, or with u along y and v along x when `swapped`.
/// The dome's Bezier net over a rectangle is exact: x and y are linear, and the coefficients
/// of `x²` over `[x0, x1]` are `(x0², x0 x1, x1²)`.
fn dome_patch(name: &str, (x0, x1): (f64, f64), (y0, y1): (f64, f64), swapped: bool) -> NamedPatch {
    let xs = [x0, 0.5 * (x0 + x1), x1];
    let ys = [y0, 0.5 * (y0 + y1), y1];
    let bx = [x0 * x0, x0 * x1, x1 * x1];
    let by = [y0 * y0, y0 * y1, y1 * y1];
    let point = |i: usize, j: usize| DVec3::new(xs[i], ys[j], -C * (bx[i] + by[j]));
    let points: Vec<Vec<DVec3>> = (0..3)
        .map(|a| {
            (0..3)
                .map(|b| if swapped { point(b, a) } else { point(a, b) })
                .collect()
        })
        .collect();
    NamedPatch::new(name, shapes::bezier(2, 2, &points).unwrap())
}

/// The three patches of the dome as one part, `strip`.
fn strip() -> Arc<PatchLibrary> {
    let patches = vec![
        dome_patch("forward", (-3.0, -1.0), (-1.0, 1.0), false),
        dome_patch("reversed", (1.0, -1.0), (-1.0, 1.0), false),
        dome_patch("swapped", (1.0, 3.0), (-1.0, 1.0), true),
    ];
    Arc::new(PatchLibrary {
        patches,
        groups: vec![PatchGroup {
            name: "strip".into(),
            patches: vec![0, 1, 2],
        }],
    })
}

/// The layer: translated by α along its du and stretched along it, ε = 0.01.
fn layer(alpha: f32, frame: LayerFrame) -> Layer {
    let mut layer = Layer::new(
        vec![
            Op::Translate { alpha, beta: 0.0 },
            Op::Scale {
                delta: 0.6,
                axis: Axis::U,
            },
        ],
        0.01,
        [1.0, 1.0, 1.0],
    );
    layer.frame = frame;
    layer
}

const ALONG_X: LayerFrame = LayerFrame::Along {
    axis: [1.0, 0.0, 0.0],
};

/// The scene of `library` seen from straight above, every patch under `highlight`, with the
/// matte and the patch ids.
fn scene<'a>(library: &'a PatchLibrary, highlight: &Layer) -> Scene<'a> {
    let eye = Vec3::new(0.0, 0.0, 10.0);
    let prepared = Expr::Layer(highlight.clone()).prepare().unwrap();
    Scene {
        library,
        looks: library
            .patches
            .iter()
            .map(|_| PatchLook {
                designed_light: None,
                tone: Tone::Cel(CelRamp::two_tone(
                    Vec3::new(0.2, 0.3, 0.5),
                    Vec3::new(0.5, 0.6, 0.9),
                    0.2,
                )),
                highlight: Some(prepared.clone()),
                lines: None,
            })
            .collect(),
        camera: Camera {
            eye,
            target: Vec3::ZERO,
            up: Vec3::Y,
            projection: Projection::Orthographic {
                height: (f64::from(HEIGHT) / SCALE) as f32,
            },
            near: 0.1,
            far: 100.0,
        },
        light: Light::Directional {
            towards: eye.normalize(),
        },
        outlines: None,
        aovs: Aovs {
            matte: true,
            patch_id: true,
            ..Aovs::default()
        },
        materials: Vec::new(),
    }
}

/// The strip under `highlight` at the finished preset, through `renderer`.
fn render(renderer: &mut Renderer, library: &PatchLibrary, highlight: &Layer) -> RenderedFrame {
    let scene = scene(library, highlight);
    renderer
        .render(&scene, &Settings::final_quality(WIDTH, HEIGHT))
        .unwrap()
}

fn matte(frame: &RenderedFrame) -> &[f32] {
    frame.aovs.matte.as_deref().unwrap()
}

/// The highlight's upper and lower boundary in pixel column `column`, in pixel rows: the row
/// boundary [`MIDDLE_ROW`] less the matte summed over the rows above it, and plus the matte
/// summed over the rows below. For a highlight that covers the middle rows and is convex along
/// the column, each sum is the exact distance from the middle to the boundary at the column's
/// centre, since each pixel's matte is the fraction of it the highlight covers (a straight edge
/// across a column of pixels covers, in all, the area between the middle and the edge). An
/// empty column gives both at the middle.
fn boundaries(matte: &[f32], column: usize) -> (f64, f64) {
    let at = |row: usize| f64::from(matte[row * WIDTH as usize + column]);
    let above: f64 = (0..MIDDLE_ROW).map(at).sum();
    let below: f64 = (MIDDLE_ROW..HEIGHT as usize).map(at).sum();
    (MIDDLE_ROW as f64 - above, MIDDLE_ROW as f64 + below)
}

/// How far apart the highlight's boundaries are where they meet the seam at pixel x `seam` (a
/// column boundary), from each side: each side's boundary at the seam extrapolated linearly
/// from the two columns nearest it on that side; the larger of the upper and lower
/// differences. Also the highlight's height along the seam, from the left.
fn seam_mismatch(matte: &[f32], seam: usize) -> (f64, f64) {
    let (l2, l1) = (boundaries(matte, seam - 2), boundaries(matte, seam - 1));
    let (r1, r2) = (boundaries(matte, seam), boundaries(matte, seam + 1));
    // Column centres at seam − 1.5, seam − 0.5 | seam + 0.5, seam + 1.5.
    let left = |a: f64, b: f64| b + 0.5 * (b - a);
    let right = |a: f64, b: f64| a - 0.5 * (b - a);
    let upper = (left(l2.0, l1.0) - right(r1.0, r2.0)).abs();
    let lower = (left(l2.1, l1.1) - right(r1.1, r2.1)).abs();
    (upper.max(lower), left(l2.1, l1.1) - left(l2.0, l1.0))
}

/// The pixel column boundary of the seam at world x `x`, checked against the patch ids: the
/// columns either side of it lie on patches `before` and `after`.
fn seam_column(frame: &RenderedFrame, x: f64, before: u32, after: u32) -> usize {
    let column = column_of(x);
    assert_eq!(column.fract(), 0.0, "the seam lies on a column boundary");
    let column = column as usize;
    let ids = frame.aovs.patch_id.as_deref().unwrap();
    for row in [MIDDLE_ROW - 40, MIDDLE_ROW, MIDDLE_ROW + 40] {
        let id = |c: usize| ids[row * WIDTH as usize + c];
        assert_eq!((id(column - 1), id(column)), (before, after), "row {row}");
    }
    column
}

#[test]
fn a_layer_along_an_axis_meets_itself_across_seams_and_the_patch_frames_step() {
    let library = strip();
    let mut renderer = Renderer::new(Arc::clone(&library));
    // α = −0.3 centres the highlight at x ≈ −1.05, across the first seam; α = 0.3 at
    // x ≈ 1.05, across the second (sin λ = α at its centre, where tan λ = 2 C x).
    let cases = [(-0.3, SEAMS[0], 0, 1), (0.3, SEAMS[1], 1, 2)];
    for (alpha, x, before, after) in cases {
        let frame = render(&mut renderer, &library, &layer(alpha, ALONG_X));
        let seam = seam_column(&frame, x, before, after);
        let m = matte(&frame);
        assert!(m.iter().all(|c| c.is_finite() && (0.0..=1.0).contains(c)));
        // The highlight covers the middle rows on both sides, as the sums need.
        for column in [seam - 2, seam - 1, seam, seam + 1] {
            for row in [MIDDLE_ROW - 1, MIDDLE_ROW] {
                assert!(
                    m[row * WIDTH as usize + column] > 0.999,
                    "α {alpha}: {column}"
                );
            }
        }
        let (mismatch, height) = seam_mismatch(m, seam);
        assert!(
            height > 40.0,
            "α {alpha}: the highlight crosses the seam, {height} px high"
        );
        assert!(
            mismatch < 0.5,
            "α {alpha}: the boundaries meet {mismatch} px apart at the seam x = {x}"
        );
    }

    // The same layer in each patch's own frame: at α = −0.3 the first patch moves it toward
    // −x and the middle one (u reversed) toward +x, and the middle one's part meets nothing
    // of the last one's (whose du runs along y): both seams step by tens of pixels.
    let frame = render(&mut renderer, &library, &layer(-0.3, LayerFrame::Patch));
    for (x, before, after) in [(SEAMS[0], 0, 1), (SEAMS[1], 1, 2)] {
        let seam = seam_column(&frame, x, before, after);
        let (mismatch, _) = seam_mismatch(matte(&frame), seam);
        assert!(
            mismatch > 10.0,
            "in the patches' frames the boundaries step at x = {x}, by {mismatch} px"
        );
    }
}

#[test]
fn a_layer_along_an_axis_changes_its_area_smoothly_as_it_crosses_a_seam() {
    let library = strip();
    let mut renderer = Renderer::new(Arc::clone(&library));
    // α from 0.15 to 0.38 carries the centre from x ≈ 0.5 to x ≈ 1.4, across the seam at
    // x = 1 (α ≈ 0.29), while the highlight stays clear of the strip's sides.
    let alphas: Vec<f32> = (0..30).map(|k| 0.15 + 0.23 * k as f32 / 29.0).collect();
    let areas: Vec<f64> = alphas
        .iter()
        .map(|&alpha| {
            let frame = render(&mut renderer, &library, &layer(alpha, ALONG_X));
            matte(&frame).iter().map(|&c| f64::from(c)).sum()
        })
        .collect();
    let steps: Vec<f64> = areas.windows(2).map(|w| w[1] - w[0]).collect();
    // No step is more than three times the median step: a piece of the highlight moved or lost
    // at the seam would change the area by thousands of px² in one step. The renderer's
    // anti-aliasing leaves a few px² of noise in each step.
    let mut sizes: Vec<f64> = steps.iter().map(|d| d.abs()).collect();
    sizes.sort_by(f64::total_cmp);
    let median = sizes[sizes.len() / 2];
    for (k, step) in steps.iter().enumerate() {
        assert!(
            step.abs() <= 3.0 * median,
            "area step {k} (α {} to {}) is {step} px², the median step {median}: {areas:?}",
            alphas[k],
            alphas[k + 1]
        );
    }
    // The highlight is there all along and moves across the seam.
    assert!(areas.iter().all(|&a| a > 1000.0), "{areas:?}");
}

#[test]
fn a_layer_along_the_pole_axis_is_finite_at_the_pole() {
    // A unit sphere seen from above its north pole, where N = a: the field has no direction
    // there and the patch's own frame is taken. An odd image puts a pixel centre on the pole.
    let (width, height) = (WIDTH + 1, HEIGHT + 1);
    let library = Arc::new(PatchLibrary::new(vec![NamedPatch::new(
        "ball",
        shapes::sphere(DVec3::ZERO, 1.0).unwrap(),
    )]));
    let mut renderer = Renderer::new(Arc::clone(&library));
    // Around the pole du' points up the sphere toward it, so a translation by −0.2 makes a
    // ring about the pole where sin λ = 0.2.
    let along_pole = layer(
        -0.2,
        LayerFrame::Along {
            axis: [0.0, 0.0, 1.0],
        },
    );
    let scene = scene(&library, &along_pole);
    let frame = renderer
        .render(&scene, &Settings::final_quality(width, height))
        .unwrap();
    assert!(frame.colour.iter().all(|c| c.is_finite()));
    let m = matte(&frame);
    assert!(m.iter().all(|c| c.is_finite() && (0.0..=1.0).contains(c)));
    let pole = (height as usize / 2) * width as usize + width as usize / 2;
    assert!(frame.colour[pole].w > 0.99, "the pole's pixel is drawn");
    assert!(m.iter().sum::<f32>() > 100.0, "the ring is drawn");
}
