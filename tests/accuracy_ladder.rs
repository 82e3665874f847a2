//! A reduced accuracy sweep (`glint::accuracy::sweep`) on small images: the facts the ladder
//! rests on, measured against the analytic sphere. No timings are checked.

use glint::accuracy::case::{Case, Pose};
use glint::accuracy::sweep::{Measurement, Rung, Stack, Sweep};
use glint::render::tessellate::Density;
use glint::render::{Antialias, FrameMode};

const SIZE: u32 = 128;

fn span(n: u32) -> Density {
    Density::PerSpan { u: n, v: n }
}

/// Each rung on each stack in the front pose.
fn measure(stacks: &[Stack], rungs: Vec<Rung>) -> Vec<Measurement> {
    let cases: Vec<Case> = stacks
        .iter()
        .map(|&stack| Case {
            pose: Pose::Front,
            stack,
        })
        .collect();
    measure_cases(&cases, rungs)
}

fn rung(density: Density, frames: FrameMode, antialias: Antialias) -> Rung {
    Rung {
        density,
        frames,
        antialias,
    }
}

#[test]
fn exact_frames_beat_interpolated_frames_at_equal_tessellation() {
    for n in [2, 4] {
        let m = measure(
            &[Stack::Identity, Stack::TranslateScale],
            vec![
                rung(span(n), FrameMode::Interpolated, Antialias::None),
                rung(span(n), FrameMode::Exact, Antialias::None),
            ],
        );
        for pair in m.chunks(2) {
            let (interpolated, exact) = (&pair[0].errors, &pair[1].errors);
            assert!(
                exact.one_minus_iou < interpolated.one_minus_iou
                    && exact.mean_normal_degrees < interpolated.mean_normal_degrees,
                "{n} segments, {:?}: exact {exact:?} vs interpolated {interpolated:?}",
                pair[0].case.stack
            );
        }
    }
}

#[test]
fn finer_tessellation_never_raises_the_error_beyond_noise() {
    let densities = [2, 4, 8, 16, 32];
    for frames in [FrameMode::Interpolated, FrameMode::Exact] {
        let m = measure(
            &[Stack::Identity, Stack::Crescent],
            densities
                .iter()
                .map(|&n| rung(span(n), frames, Antialias::None))
                .collect(),
        );
        for per_stack in m.chunks(densities.len()) {
            let errors: Vec<f64> = per_stack.iter().map(|m| m.errors.one_minus_iou).collect();
            // Noise: where hard edges happen to fall on pixel centres, a tenth of the error.
            for w in errors.windows(2) {
                assert!(w[1] <= 1.1 * w[0] + 1e-3, "{frames:?}: {errors:?}");
            }
            assert!(
                errors[errors.len() - 1] < 0.8 * errors[0],
                "{frames:?}: {errors:?}"
            );
            // At 32 segments per span the mesh is within 1e-3 of the sphere (below), 0.03 px at
            // this size, and its normals within 0.1°: what is left of the boundary's
            // displacement is hard-edge sampling, a quarter pixel on average (the mean of
            // |x| for x uniform in [−½, ½]).
            let boundary = per_stack[per_stack.len() - 1].errors.boundary_pixels;
            assert!(
                boundary < 0.25 + 0.03 + 0.02,
                "{frames:?} {:?}: {boundary} px",
                per_stack[0].case.stack
            );
        }
    }
}

/// The least-squares slope of `log y` against `log x`.
fn log_slope(points: &[(f64, f64)]) -> f64 {
    let logs: Vec<(f64, f64)> = points.iter().map(|(x, y)| (x.ln(), y.ln())).collect();
    let n = logs.len() as f64;
    let (mx, my) = (
        logs.iter().map(|p| p.0).sum::<f64>() / n,
        logs.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxy: f64 = logs.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = logs.iter().map(|(x, _)| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

#[test]
fn the_mesh_converges_to_the_sphere_as_n_to_the_minus_two() {
    let segments = [4, 8, 16, 32];
    let errors = glint::accuracy::geometry::mesh_errors(&segments, 1);
    let position: Vec<(f64, f64)> = errors
        .iter()
        .map(|e| (f64::from(e.segments), e.max_position_error))
        .collect();
    let normal: Vec<(f64, f64)> = errors
        .iter()
        .map(|e| (f64::from(e.segments), e.max_normal_degrees))
        .collect();
    println!("{position:?} {normal:?}");
    // A chord of angle θ stays within 1 − cos(θ/2) ≈ θ²/8 of the unit sphere: second order.
    for (what, points) in [("position", &position), ("normal", &normal)] {
        let slope = log_slope(points);
        assert!(
            (-2.2..=-1.8).contains(&slope),
            "{what}: slope {slope}, {points:?}"
        );
    }
    // At 32 segments per quarter circle the longest triangle edge, a quad's diagonal, spans at
    // most √2 · 1.2 · (π/2)/32 ≈ 0.083 rad (the rational quadratic's speed varies by less than
    // 1.2 along a span), whose sagitta is 1 − cos(0.042) ≈ 8.7e-4.
    let last = errors[errors.len() - 1];
    assert!(last.max_position_error < 8.7e-4, "{last:?}");
    assert!(last.max_normal_degrees < 0.1, "{last:?}");
}

#[test]
fn anti_aliasing_lowers_the_boundary_error() {
    let m = measure(
        &[Stack::Identity, Stack::Crescent],
        [
            Antialias::None,
            Antialias::Analytic,
            Antialias::Supersample(2),
            Antialias::Supersample(4),
        ]
        .into_iter()
        .map(|aa| rung(span(16), FrameMode::Exact, aa))
        .collect(),
    );
    for per_stack in m.chunks(4) {
        let b: Vec<f64> = per_stack.iter().map(|m| m.errors.boundary_pixels).collect();
        let stack = per_stack[0].case.stack;
        assert!(b[1] < 0.8 * b[0], "{stack:?} analytic vs none: {b:?}");
        assert!(b[2] < 0.8 * b[0], "{stack:?} 2x2 vs none: {b:?}");
        assert!(b[3] < b[2], "{stack:?} 4x4 vs 2x2: {b:?}");
    }
}

/// Each rung on each of `cases`.
fn measure_cases(cases: &[Case], rungs: Vec<Rung>) -> Vec<Measurement> {
    measure_at(SIZE, cases, rungs)
}

/// Each rung on each of `cases` at `size` × `size`.
fn measure_at(size: u32, cases: &[Case], rungs: Vec<Rung>) -> Vec<Measurement> {
    let sweep = Sweep {
        sizes: vec![size],
        cases: cases.to_vec(),
        rungs,
        repeats: 1,
        threads: 0,
    };
    sweep.run(|_| {}).unwrap()
}

#[test]
fn off_centre_highlights_need_the_point_on_the_pixel_s_ray() {
    // Exact frames are exact at the flat triangle's (u, v); toward the limb that point is far
    // from the one the pixel sees, and refined frames, which move it onto the ray, do better.
    let cases: Vec<Case> = [50, 70]
        .into_iter()
        .map(|degrees| Case {
            pose: Pose::OffCentre { degrees },
            stack: Stack::Identity,
        })
        .collect();
    let m = measure_cases(
        &cases,
        vec![
            rung(span(4), FrameMode::Exact, Antialias::Supersample(2)),
            rung(span(4), FrameMode::Refined, Antialias::Supersample(2)),
        ],
    );
    for pair in m.chunks(2) {
        let (exact, refined) = (&pair[0].errors, &pair[1].errors);
        assert!(
            refined.boundary_pixels < 0.7 * exact.boundary_pixels,
            "{}: exact {exact:?} vs refined {refined:?}",
            pair[0].case
        );
    }
}

#[test]
fn the_silhouette_closes_on_the_disc_with_tessellation_and_samples() {
    let front = [Case {
        pose: Pose::Front,
        stack: Stack::Identity,
    }];
    let m = measure_cases(
        &front,
        vec![
            rung(span(2), FrameMode::Interpolated, Antialias::None),
            rung(span(16), FrameMode::Interpolated, Antialias::None),
            rung(span(16), FrameMode::Interpolated, Antialias::Supersample(4)),
        ],
    );
    let px: Vec<f64> = m.iter().map(|m| m.errors.silhouette_pixels).collect();
    // The disc's radius in pixels: the sphere subtends asin(1/5) from 5 units, and the image's
    // half height is tan 15°.
    let r = f64::from(SIZE) / 2.0 * (0.2f64.asin().tan() / 15f64.to_radians().tan());
    // Two segments per span: chords of a quarter circle sag by up to 1 − cos(22.5°) ≈ 0.076 of
    // the radius, about 3.7 px here; at 16 by 0.06 px, and what is left is the quarter pixel
    // of hard sampling, which 4 × 4 samples cut.
    assert!(px[0] > 1.0, "{px:?}");
    assert!(px[1] < 0.35, "{px:?}");
    assert!(px[2] < 0.5 * px[1], "{px:?}");
    // The silhouette's IoU follows: about 2·d/r for a disc of radius r displaced by d.
    for m in &m {
        let e = m.errors;
        assert!(
            (e.silhouette_one_minus_iou - 2.0 * e.silhouette_pixels / r).abs()
                < 0.3 * e.silhouette_one_minus_iou,
            "{e:?}"
        );
    }
}

#[test]
fn analytic_edges_on_the_pixel_s_own_point_are_within_a_hundredth_of_a_pixel() {
    // Refined frames put each pixel's point on its ray; the exact box coverage of a straight
    // edge, with central differences for the footprint, then leaves only the edge's curvature
    // over a pixel. A smoothstep over the footprint is a quarter pixel off on average at a
    // vertical edge, 0.026 px of displacement measured on these views.
    let cases: Vec<Case> = [Stack::Identity, Stack::SplitFour, Stack::Square]
        .into_iter()
        .map(|stack| Case {
            pose: Pose::Front,
            stack,
        })
        .collect();
    let m = measure_cases(
        &cases,
        vec![rung(span(16), FrameMode::Refined, Antialias::Analytic)],
    );
    for m in &m {
        assert!(
            m.errors.boundary_pixels < 0.012,
            "{}: {:?}",
            m.case,
            m.errors
        );
    }
}

#[test]
fn final_frames_hold_on_the_hard_views() {
    // The preset's promise at 256²: soft IoU ≥ 0.995 of the highlight matte on every view of
    // the hard ladder (here the hardest of each kind), and ≥ 0.999 of the silhouette's alpha.
    let hard = [
        (Pose::OffCentre { degrees: 70 }, Stack::Identity),
        (Pose::OffCentre { degrees: 50 }, Stack::Square),
        (Pose::Pole, Stack::Identity),
        (Pose::WideAngle, Stack::Identity),
        (Pose::Front, Stack::ThinCrescent),
        (Pose::OffCentre { degrees: 30 }, Stack::Tiny),
        (Pose::OffCentre { degrees: 30 }, Stack::Keyed { frame: 2.5 }),
    ];
    let cases: Vec<Case> = hard
        .into_iter()
        .map(|(pose, stack)| Case { pose, stack })
        .collect();
    let all = Case::all();
    assert!(cases.iter().all(|c| all.contains(c)), "views of the ladder");
    let final_quality = Rung::of(&glint::render::Settings::final_quality(1, 1));
    for m in measure_at(256, &cases, vec![final_quality]) {
        let e = m.errors;
        assert!(e.one_minus_iou <= 0.005, "{}: {e:?}", m.case);
        assert!(e.silhouette_one_minus_iou <= 0.001, "{}: {e:?}", m.case);
    }
}

#[test]
fn the_closed_form_reference_and_the_renderer_s_formulas_agree_on_every_view() {
    // The reference evaluates each view's highlight in closed form; the renderer's own
    // evaluation of the same description, run on the same samples, differs only where f32 and
    // f64 round a sample within a hair of the edge to different sides: at 256² with the
    // ladder's samples, at most two of the 1024 samples of an edge pixel. A wrong formula in
    // either moves whole arcs of the boundary.
    use glint::accuracy::sweep::{REFERENCE_EDGE_SAMPLES, REFERENCE_SAMPLES};
    let size = SIZE;
    for case in Case::all() {
        let sphere = case.pose.sphere();
        let closed = case.stack.reference_expression();
        let renderer = closed.expr().prepare().unwrap();
        let a = sphere.mattes(&closed, size, REFERENCE_SAMPLES, REFERENCE_EDGE_SAMPLES);
        let b = sphere.mattes(&renderer, size, REFERENCE_SAMPLES, REFERENCE_EDGE_SAMPLES);
        let moved: f64 = a
            .highlight
            .iter()
            .zip(&b.highlight)
            .map(|(x, y)| f64::from((x - y).abs()))
            .sum();
        let iou = glint::accuracy::metrics::iou(&a.highlight, &b.highlight).unwrap();
        // Four samples of an edge pixel's 32 × 32.
        assert!(moved <= 4.0 / 1024.0, "{case}: {moved} px of area differ");
        assert!(1.0 - iou < 1e-5, "{case}: 1 − IoU {}", 1.0 - iou);
        assert_eq!(a.silhouette, b.silhouette, "{case}");
    }
}
