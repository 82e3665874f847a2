//! Behaviour of the highlight operations on the analytic unit sphere.
//!
//! The sphere's frame at latitude φ, longitude λ is (east, north, outward): with
//! `N = (cos φ sin λ, sin φ, cos φ cos λ)`, `east = (cos λ, 0, −sin λ)` and `north = N × east`.
//! Images are orthographic views along −z (x right, y up), where the frame at the centre is
//! `(x, y, z)`, so du points right and dv up.

use glam::{DVec3, Vec2, Vec3};
use glint::highlight::{
    Axis, Expr, Footprint, Layer, Op, PreparedLayer, SquareStyle, TangentFrame,
};
use rand::{Rng, SeedableRng};

/// The sphere's frame and (u, v) = (λ, φ) at unit normal `n` (not a pole).
fn sphere_frame(n: DVec3) -> (TangentFrame, Vec2) {
    let east = DVec3::new(n.z, 0.0, -n.x).normalize();
    let north = n.cross(east);
    let uv = Vec2::new(n.x.atan2(n.z) as f32, n.y.asin() as f32);
    (
        TangentFrame::new(east.as_vec3(), north.as_vec3(), n.as_vec3()),
        uv,
    )
}

fn layer(stack: Vec<Op>, epsilon: f32) -> Layer {
    Layer::new(stack, epsilon, [1.0, 1.0, 1.0])
}

fn prepared(stack: Vec<Op>, epsilon: f32) -> PreparedLayer {
    layer(stack, epsilon).prepare().unwrap()
}

/// A square boolean image of the visible hemisphere, `half` the half-width of the window.
struct Grid {
    res: usize,
    px: Vec<bool>,
}

impl Grid {
    /// Pixel centres `x = (2i + 1 − res) / res · half` are exactly antisymmetric in i.
    fn render(
        res: usize,
        half: f64,
        mut inside: impl FnMut(&TangentFrame, Vec2, DVec3) -> bool,
    ) -> Self {
        let mut px = vec![false; res * res];
        for j in 0..res {
            for i in 0..res {
                let x = (2 * i + 1) as f64 - res as f64;
                let y = res as f64 - (2 * j + 1) as f64;
                let (x, y) = (x / res as f64 * half, y / res as f64 * half);
                let r2 = x * x + y * y;
                if r2 < 1.0 {
                    let n = DVec3::new(x, y, (1.0 - r2).sqrt());
                    let (frame, uv) = sphere_frame(n);
                    px[j * res + i] = inside(&frame, uv, n);
                }
            }
        }
        Self { res, px }
    }

    fn of(res: usize, half: f64, l: &PreparedLayer, h: Vec3) -> Self {
        Self::render(res, half, |f, _, _| l.signed(f, h) > 0.0)
    }

    fn at(&self, i: usize, j: usize) -> bool {
        self.px[j * self.res + i]
    }

    fn count(&self) -> usize {
        self.px.iter().filter(|&&b| b).count()
    }

    /// The image reflected left-right (`x → −x`) or top-bottom (`y → −y`).
    fn mirrored(&self, left_right: bool) -> Self {
        let n = self.res;
        let mut px = vec![false; n * n];
        for j in 0..n {
            for i in 0..n {
                let (si, sj) = if left_right {
                    (n - 1 - i, j)
                } else {
                    (i, n - 1 - j)
                };
                px[j * n + i] = self.at(si, sj);
            }
        }
        Self { res: n, px }
    }

    /// 4-connected components, each as its list of pixels `(i, j)`.
    fn components(&self) -> Vec<Vec<(usize, usize)>> {
        let n = self.res;
        let mut seen = vec![false; n * n];
        let mut out = Vec::new();
        for start in 0..n * n {
            if !self.px[start] || seen[start] {
                continue;
            }
            seen[start] = true;
            let mut stack = vec![start];
            let mut comp = Vec::new();
            while let Some(k) = stack.pop() {
                let (i, j) = (k % n, k / n);
                comp.push((i, j));
                let mut push = |k2: usize| {
                    if self.px[k2] && !seen[k2] {
                        seen[k2] = true;
                        stack.push(k2);
                    }
                };
                if i > 0 {
                    push(k - 1);
                }
                if i + 1 < n {
                    push(k + 1);
                }
                if j > 0 {
                    push(k - n);
                }
                if j + 1 < n {
                    push(k + n);
                }
            }
            out.push(comp);
        }
        out
    }

    /// Inside pixel count over the area of the axis-aligned bounding box of the inside pixels.
    fn fill_of_bounding_box(&self) -> f64 {
        let (mut i0, mut i1, mut j0, mut j1) = (usize::MAX, 0, usize::MAX, 0);
        for j in 0..self.res {
            for i in 0..self.res {
                if self.at(i, j) {
                    (i0, i1, j0, j1) = (i0.min(i), i1.max(i), j0.min(j), j1.max(j));
                }
            }
        }
        self.count() as f64 / ((i1 - i0 + 1) * (j1 - j0 + 1)) as f64
    }

    /// Second moments `(⟨x²⟩, ⟨y²⟩, ⟨xy⟩)` of the inside pixels about their mean, in pixels.
    fn moments(&self) -> (f64, f64, f64) {
        let pts: Vec<(f64, f64)> = (0..self.res * self.res)
            .filter(|&k| self.px[k])
            .map(|k| ((k % self.res) as f64, -((k / self.res) as f64)))
            .collect();
        let n = pts.len() as f64;
        let (mx, my) = pts
            .iter()
            .fold((0.0, 0.0), |(a, b), p| (a + p.0 / n, b + p.1 / n));
        pts.iter().fold((0.0, 0.0, 0.0), |(xx, yy, xy), p| {
            let (dx, dy) = (p.0 - mx, p.1 - my);
            (xx + dx * dx / n, yy + dy * dy / n, xy + dx * dy / n)
        })
    }
}

/// A uniformly distributed point of the unit sphere.
fn uniform_sphere(rng: &mut impl Rng) -> DVec3 {
    let z: f64 = rng.random_range(-1.0..1.0);
    let a: f64 = rng.random_range(0.0..std::f64::consts::TAU);
    let r = (1.0 - z * z).sqrt();
    DVec3::new(r * a.cos(), z, r * a.sin())
}

#[test]
fn identity_stack_covers_fraction_half_epsilon_of_sphere() {
    const SAMPLES: usize = 1_000_000;
    let h = Vec3::new(0.3, -0.5, 0.8).normalize();
    for eps in [1e-4_f32, 1e-3, 1e-2, 0.1, 0.25, 0.5] {
        let l = prepared(vec![], eps);
        let mut rng = rand::rngs::StdRng::seed_from_u64(eps.to_bits().into());
        let hits = (0..SAMPLES)
            .filter(|_| {
                let (frame, _) = sphere_frame(uniform_sphere(&mut rng));
                l.signed(&frame, h) > 0.0
            })
            .count() as f64;
        // A cap {(N, H) > 1 − ε} has area 2π ε: the fraction ε/2 of the sphere.
        let p = f64::from(eps) / 2.0;
        let mean = SAMPLES as f64 * p;
        let sigma = (mean * (1.0 - p)).sqrt();
        assert!(
            (hits - mean).abs() < 4.0 * sigma,
            "ε = {eps}: {hits} hits, expected {mean} ± {sigma}"
        );
    }
}

/// The longitude (or latitude) of the maximum of the signed value along the equator (or the
/// central meridian), searched on a grid of step `step` over (−π/2, π/2).
fn argmax_along(l: &PreparedLayer, h: Vec3, along_equator: bool, step: f64) -> (f64, f32) {
    let mut best = (0.0, f32::NEG_INFINITY);
    let steps = (std::f64::consts::PI / step) as i64;
    for k in -steps / 2 + 1..steps / 2 {
        let a = k as f64 * step;
        let n = if along_equator {
            DVec3::new(a.sin(), 0.0, a.cos())
        } else {
            DVec3::new(0.0, a.sin(), a.cos())
        };
        let s = l.signed(&sphere_frame(n).0, h);
        if s > best.1 {
            best = (a, s);
        }
    }
    best
}

#[test]
fn translation_moves_centre_by_predicted_angle() {
    // On the equator at longitude λ: du = (cos λ, 0, −sin λ), N = (sin λ, 0, cos λ). With H = z,
    // H + α du = (α cos λ, 0, 1 − α sin λ) is parallel to N iff α cos²λ = sin λ (1 − α sin λ),
    // i.e. sin λ = α: the centre moves toward +du by λ = asin α. Likewise along dv on the
    // central meridian, by φ = asin β.
    let eps = 0.01;
    let step = 1e-4;
    for alpha in [-0.4_f32, 0.1, 0.3, 0.6] {
        let l = prepared(vec![Op::Translate { alpha, beta: 0.0 }], eps);
        let (lambda, s) = argmax_along(&l, Vec3::Z, true, step);
        let want = f64::from(alpha).asin();
        assert!(
            (lambda - want).abs() <= step,
            "α = {alpha}: centre at {lambda}, want {want}"
        );
        // There the translated H equals N, so s reaches ε.
        assert!((s - eps).abs() < 1e-6, "α = {alpha}: s = {s}");
    }
    for beta in [-0.2_f32, 0.5] {
        let l = prepared(vec![Op::Translate { alpha: 0.0, beta }], eps);
        let (phi, _) = argmax_along(&l, Vec3::Z, false, step);
        assert!(
            (phi - f64::from(beta).asin()).abs() <= step,
            "β = {beta}: centre at {phi}"
        );
    }
}

/// The angle of the long axis of the inside pixels, in degrees from +x toward +y.
fn long_axis_degrees(g: &Grid) -> f64 {
    let (xx, yy, xy) = g.moments();
    0.5 * (2.0 * xy).atan2(xx - yy).to_degrees()
}

#[test]
fn rotation_turns_stretched_highlight() {
    let stretch = Op::Scale {
        delta: 0.6,
        axis: Axis::U,
    };
    let g = |stack: Vec<Op>| Grid::of(301, 0.6, &prepared(stack, 0.005), Vec3::Z);
    let along_u = g(vec![stretch.clone()]);
    let (xx, yy, _) = along_u.moments();
    assert!(
        xx > 3.0 * yy,
        "δ-stretched highlight not long along du: {xx} vs {yy}"
    );
    let turned = g(vec![Op::Rotate { degrees: 90.0 }, stretch.clone()]);
    let (xx, yy, _) = turned.moments();
    assert!(
        yy > 3.0 * xx,
        "rotated highlight not long along dv: {xx} vs {yy}"
    );
    for degrees in [30.0_f32, -60.0] {
        let a = long_axis_degrees(&g(vec![Op::Rotate { degrees }, stretch.clone()]));
        assert!(
            (a - f64::from(degrees)).abs() < 2.0,
            "rotate {degrees}°: axis at {a}°"
        );
    }
    // Rotation alone preserves (N, H): the round highlight is unchanged.
    let round = g(vec![]);
    assert_eq!(g(vec![Op::Rotate { degrees: 37.0 }]).count(), round.count());
}

#[test]
fn split_in_two_and_in_four() {
    let res = 201;
    let centre = res / 2;
    let g = |gamma_u: f32, gamma_v: f32| {
        Grid::of(
            res,
            0.7,
            &prepared(vec![Op::Split { gamma_u, gamma_v }], 0.02),
            Vec3::Z,
        )
    };
    let whole = g(0.0, 0.0);
    assert!(whole.at(centre, centre));
    assert_eq!(whole.components().len(), 1);

    let two = g(0.3, 0.0);
    assert!(!two.at(centre, centre), "centre point not removed");
    let comps = two.components();
    assert_eq!(comps.len(), 2);
    // One piece on each side of the dv axis, mirror images of each other.
    for c in &comps {
        assert!(c.iter().all(|&(i, _)| i < centre) || c.iter().all(|&(i, _)| i > centre));
    }
    assert!(
        two.px == two.mirrored(true).px,
        "two pieces not mirror-symmetric about dv"
    );

    let four = g(0.3, 0.3);
    assert!(!four.at(centre, centre));
    let comps = four.components();
    assert_eq!(comps.len(), 4);
    let quadrants: std::collections::HashSet<(bool, bool)> = comps
        .iter()
        .map(|c| (c[0].0 > centre, c[0].1 > centre))
        .collect();
    assert_eq!(quadrants.len(), 4, "pieces not one per quadrant");
    assert!(four.px == four.mirrored(true).px && four.px == four.mirrored(false).px);
}

fn square(sigma: f32, n: f32, style: SquareStyle) -> Op {
    Op::Square { sigma, n, style }
}

#[test]
fn squaring_fills_bounding_square_monotonically() {
    let fill = |sigma: f32| {
        let l = prepared(vec![square(sigma, 2.0, SquareStyle::Tangent)], 0.002);
        Grid::of(401, 0.15, &l, Vec3::Z).fill_of_bounding_box()
    };
    let fills: Vec<f64> = [0.0, 0.05, 0.1, 0.15, 0.2].into_iter().map(fill).collect();
    // A disc fills π/4 of its bounding square.
    assert!(
        (fills[0] - std::f64::consts::FRAC_PI_4).abs() < 0.01,
        "{fills:?}"
    );
    assert!(fills.windows(2).all(|w| w[1] > w[0] + 0.01), "{fills:?}");
    assert!(fills[4] > 0.9, "σ = 0.2 not square: {fills:?}");
    // Beyond σ ≈ 0.2 the corners overshoot the square (a four-pointed star) and the ratio falls,
    // as the documentation of `Op::Square` states.
    assert!(fill(0.4) < fills[4] - 0.05, "no overshoot at σ = 0.4");
}

#[test]
fn squaring_is_symmetric_under_quadrant_reflections() {
    for (sigma, n, style) in [
        (0.2, 2.0, SquareStyle::Tangent),
        (0.6, 0.7, SquareStyle::Tangent),
        (1.0, 5.0, SquareStyle::Tangent),
        (1.0, 1.0, SquareStyle::PerAxis),
        (0.8, 2.5, SquareStyle::PerAxis),
    ] {
        let l = prepared(vec![square(sigma, n, style)], 0.01);
        let g = Grid::of(201, 0.4, &l, Vec3::Z);
        assert!(g.count() > 100);
        assert!(
            g.px == g.mirrored(true).px,
            "{style:?} σ={sigma} n={n}: not left-right symmetric"
        );
        assert!(
            g.px == g.mirrored(false).px,
            "{style:?} σ={sigma} n={n}: not top-bottom symmetric"
        );
    }
}

/// The squaring as published in a shader port: `θ = min(acos(H, du), acos(H, dv))` of the raw
/// unit H and `sqrnorm = sin(pow(2θ, n))`, in frame coordinates.
fn published_square(l: Vec3, sigma: f32, n: f32) -> Vec3 {
    let theta = l.x.acos().min(l.y.acos());
    let sqrnorm = (2.0 * theta).powf(n).sin();
    (l - sigma * sqrnorm * Vec3::new(l.x, l.y, 0.0)).normalize()
}

/// The same port's per-axis variant, `sin(pow(2θ_u, n))` and `sin(pow(2θ_v, n))`.
fn published_per_axis(l: Vec3, sigma: f32, n: f32) -> Vec3 {
    let k = |c: f32| (2.0 * c.acos()).powf(n).sin();
    (l - sigma * Vec3::new(k(l.x) * l.x, k(l.y) * l.y, 0.0)).normalize()
}

#[test]
fn published_squaring_forms_break_quadrant_symmetry() {
    for form in [published_square, published_per_axis] {
        let g = Grid::render(201, 0.4, |f, _, n| {
            let l = form(f.to_local(Vec3::Z), 1.0, 2.0);
            // (N, H') > 1 − ε with N = z in frame coordinates.
            f64::from(l.z) > 1.0 - 0.01 && n.z > 0.0
        });
        assert!(g.count() > 100);
        let asymmetric = g.px != g.mirrored(true).px || g.px != g.mirrored(false).px;
        assert!(asymmetric, "published form unexpectedly symmetric");
    }
    // Near the highlight's centre θ → π/2, so for n = 2 the published factor tends to
    // sin(π²) < 0: it pushes H away from N instead of pulling it in.
    let near = Vec3::new(0.005, 0.005, (1.0_f32 - 5e-5).sqrt());
    assert!((2.0 * near.x.acos()).powf(2.0).sin() < 0.0);
}

/// glint's squaring against the published forms it departs from, in f64 on random unit H:
/// the tangent style is the published `θ = min(acos(H, du), acos(H, dv))` with θ measured in the
/// tangent plane and the sine, not its argument, raised to n; the per-axis style is the published
/// per-axis form with `|sin 2θ|^n`, which is the published form itself for n = 1 where both
/// tangent components are positive.
#[test]
fn squaring_styles_are_the_published_forms_with_their_stated_departures() {
    let mut rng = rand::rngs::StdRng::seed_from_u64(23);
    let mut first_quadrant = 0;
    for _ in 0..2000 {
        let z: f64 = rng.random_range(0.3..1.0);
        let a: f64 = rng.random_range(0.0..std::f64::consts::TAU);
        let r = (1.0 - z * z).sqrt();
        let h = DVec3::new(r * a.cos(), r * a.sin(), z);
        let sigma: f32 = rng.random_range(0.0..1.0);
        let n: f32 = [1.0, 2.0, 3.0, 4.5][rng.random_range(0..4)];
        let (s, p) = (f64::from(sigma), f64::from(n));
        let apply = |style| {
            Op::Square { sigma, n, style }
                .prepare()
                .unwrap()
                .apply_local(h.as_vec3())
                .as_dvec3()
        };
        // Tangent: the angle from the nearest axis in the tangent plane.
        let from_u = h.y.abs().atan2(h.x.abs());
        let theta = from_u.min(std::f64::consts::FRAC_PI_2 - from_u);
        let k = (2.0 * theta).sin().powf(p);
        let want = (h - s * k * DVec3::new(h.x, h.y, 0.0)).normalize();
        let got = apply(SquareStyle::Tangent);
        assert!(
            (got - want).length() < 2e-6,
            "tangent at {h}: {got} vs {want}"
        );
        // Per axis: each component's own angle to its axis, of the raw unit H.
        let k = |c: f64| (2.0 * c.acos()).sin().abs().powf(p);
        let want = (h - s * DVec3::new(k(h.x) * h.x, k(h.y) * h.y, 0.0)).normalize();
        let got = apply(SquareStyle::PerAxis);
        assert!(
            (got - want).length() < 2e-6,
            "per axis at {h}: {got} vs {want}"
        );
        if n == 1.0 && h.x > 0.0 && h.y > 0.0 {
            let published = published_per_axis(h.as_vec3(), sigma, 1.0).as_dvec3();
            assert!(
                (got - published).length() < 2e-6,
                "published at {h}: {got} vs {published}"
            );
            first_quadrant += 1;
        }
    }
    assert!(first_quadrant > 50, "{first_quadrant}");
}

#[test]
fn booleans_match_set_algebra_and_make_a_crescent() {
    let eps = 0.05_f32;
    let alpha = 0.15_f32;
    let red = Layer {
        colour: [1.0, 0.0, 0.0],
        ..layer(vec![], eps)
    };
    let blue = Layer {
        colour: [0.0, 0.0, 1.0],
        ..layer(vec![Op::Translate { alpha, beta: 0.0 }], eps)
    };
    let (a, b) = (Box::new(Expr::Layer(red)), Box::new(Expr::Layer(blue)));
    let union = Expr::Union(a.clone(), b.clone()).prepare().unwrap();
    let minus = Expr::Subtract(a.clone(), b.clone()).prepare().unwrap();
    let both = Expr::Intersect(a, b).prepare().unwrap();

    // Independent f64 reference of the two caps, and the margin around their edges.
    let reference = |n: DVec3, frame: &TangentFrame| {
        let h = DVec3::Z;
        let hb = (h + f64::from(alpha) * frame.du.as_dvec3()).normalize();
        let sa = f64::from(eps) - (1.0 - n.dot(h));
        let sb = f64::from(eps) - (1.0 - n.dot(hb));
        let clear = sa.abs() > 1e-4 && sb.abs() > 1e-4;
        (sa > 0.0, sb > 0.0, clear)
    };
    let mut counts = [0usize; 3];
    let crescent = Grid::render(201, 0.6, |frame, uv, n| {
        let (in_a, in_b, clear) = reference(n, frame);
        let u = union.eval(frame, uv, Vec3::Z, Footprint::HARD);
        let m = minus.eval(frame, uv, Vec3::Z, Footprint::HARD);
        let i = both.eval(frame, uv, Vec3::Z, Footprint::HARD);
        if clear {
            assert_eq!(u.coverage == 1.0, in_a || in_b);
            assert_eq!(m.coverage == 1.0, in_a && !in_b);
            assert_eq!(i.coverage == 1.0, in_a && in_b);
            for (k, c) in [u, m, i].iter().enumerate() {
                assert!(c.coverage == 0.0 || c.coverage == 1.0);
                counts[k] += usize::from(c.coverage == 1.0);
            }
            // Union paints with the covering operand: blue only where A is absent.
            if u.coverage == 1.0 {
                assert_eq!(u.colour.z == 1.0, !in_a);
            }
            if m.coverage == 1.0 {
                assert_eq!(m.colour, Vec3::X);
            }
        }
        m.coverage == 1.0
    });
    let [n_union, n_minus, n_both] = counts;
    assert!(n_both > 0 && n_minus > 0 && n_union > n_minus + n_both);
    // The crescent: one piece, symmetric about the equator, without B's centre (λ = asin α on
    // the equator), keeping A's far (−du) side.
    assert_eq!(crescent.components().len(), 1);
    assert!(crescent.px == crescent.mirrored(false).px);
    let centre_b = f64::from(alpha).asin().sin();
    let pixel = |x: f64| ((x / 0.6 + 1.0) * 0.5 * 201.0) as usize;
    assert!(!crescent.at(pixel(centre_b), 100));
    assert!(!crescent.at(100, 100));
    let far_side = -(1.0 - (1.0 - f64::from(eps)).powi(2)).sqrt() * 0.95;
    assert!(crescent.at(pixel(far_side), 100));
}

/// The expressions every operation's closed form is checked on: each operation alone at
/// intermediate strength, stacks of several, and each layer feature and Boolean.
fn closed_form_cases() -> Vec<(&'static str, Expr)> {
    let one = |stack: Vec<Op>| Expr::Layer(layer(stack, 0.04));
    let scale = |delta: f32, axis: Axis| Op::Scale { delta, axis };
    let split = |gamma_u: f32, gamma_v: f32| Op::Split { gamma_u, gamma_v };
    let shift = |alpha: f32, beta: f32| Op::Translate { alpha, beta };
    let tinted = |stack: Vec<Op>, epsilon: f32, colour: [f32; 3], opacity: f32| {
        Box::new(Expr::Layer(Layer {
            opacity,
            ..Layer::new(stack, epsilon, colour)
        }))
    };
    let (red, blue) = ([1.0, 0.2, 0.1], [0.1, 0.3, 1.0]);
    vec![
        ("translate", one(vec![shift(0.25, -0.15)])),
        (
            "rotate then scale along U",
            one(vec![Op::Rotate { degrees: 35.0 }, scale(0.6, Axis::U)]),
        ),
        ("scale U δ 0.3", one(vec![scale(0.3, Axis::U)])),
        ("scale V δ 0.7", one(vec![scale(0.7, Axis::V)])),
        (
            "scale Angle(25°) δ 0.5",
            one(vec![scale(0.5, Axis::Angle(25.0))]),
        ),
        ("split γu", one(vec![split(0.12, 0.0)])),
        ("split γv", one(vec![split(0.0, 0.09)])),
        ("split both", one(vec![split(0.1, 0.07)])),
        (
            "square tangent n 2",
            one(vec![square(0.25, 2.0, SquareStyle::Tangent)]),
        ),
        (
            "square tangent n 1.5",
            one(vec![square(0.6, 1.5, SquareStyle::Tangent)]),
        ),
        (
            "square per axis n 1",
            one(vec![square(0.8, 1.0, SquareStyle::PerAxis)]),
        ),
        (
            "square per axis n 2.5",
            one(vec![square(1.0, 2.5, SquareStyle::PerAxis)]),
        ),
        (
            "translate, rotate, scale, split, square",
            one(vec![
                shift(0.1, 0.05),
                Op::Rotate { degrees: -20.0 },
                scale(0.4, Axis::V),
                split(0.05, 0.03),
                square(0.2, 2.0, SquareStyle::Tangent),
            ]),
        ),
        (
            "split, translate, square per axis, scale along an angle",
            one(vec![
                split(0.06, 0.0),
                shift(-0.08, 0.12),
                square(0.5, 3.0, SquareStyle::PerAxis),
                scale(0.8, Axis::Angle(-50.0)),
            ]),
        ),
        (
            "feathered",
            Expr::Layer(Layer {
                feather: Some(0.01),
                ..layer(vec![shift(0.05, 0.1)], 0.05)
            }),
        ),
        (
            "masked, feathered mask",
            Expr::Layer(Layer {
                mask: Some(glint::highlight::Mask {
                    u: (-0.1, 0.3),
                    v: (-0.2, 0.15),
                    feather: 0.05,
                }),
                ..layer(vec![], 0.08)
            }),
        ),
        (
            "along an axis",
            Expr::Layer(Layer {
                frame: glint::highlight::LayerFrame::Along {
                    axis: [1.0, 1.0, 0.2],
                },
                ..layer(vec![scale(0.7, Axis::U), shift(0.1, 0.0)], 0.04)
            }),
        ),
        (
            "union",
            Expr::Union(
                tinted(vec![], 0.05, red, 0.8),
                tinted(vec![shift(0.2, 0.05)], 0.04, blue, 0.5),
            ),
        ),
        (
            "subtract",
            Expr::Subtract(
                tinted(vec![], 0.06, red, 0.9),
                tinted(vec![shift(0.12, 0.05)], 0.05, blue, 0.3),
            ),
        ),
        (
            "intersect of a split and a square",
            Expr::Intersect(
                tinted(vec![split(0.08, 0.0)], 0.07, red, 1.0),
                tinted(
                    vec![square(0.3, 2.0, SquareStyle::Tangent), shift(0.0, 0.05)],
                    0.05,
                    blue,
                    1.0,
                ),
            ),
        ),
    ]
}

/// Every operation, layer feature and Boolean as the renderer evaluates it
/// (`PreparedExpr::eval`, f32) against its closed form written out independently in f64
/// (`glint::accuracy::ClosedForm`), on the sphere's frame at the pixels of an orthographic view
/// and for three initial highlight vectors: the coverages and colours agree, but within 10⁻⁴ of
/// a layer's hard edge (where f32 rounding may decide either way).
#[test]
fn every_operation_agrees_with_its_closed_form_over_the_sphere() {
    use glint::accuracy::closed_form::layer_signed;
    use glint::accuracy::closed_form_ops::AnalyticFrame;
    use glint::accuracy::ClosedForm;
    let hs = [
        DVec3::Z,
        DVec3::new(0.25, -0.1, 1.0).normalize(),
        DVec3::new(-0.4, 0.3, 0.85).normalize(),
    ];
    for (name, expr) in closed_form_cases() {
        let renderer = expr.prepare().unwrap();
        let closed = ClosedForm::try_new(&expr).unwrap();
        let (mut inside, mut outside, mut partial) = (0, 0, 0);
        for h in hs {
            Grid::render(161, 0.9, |frame, uv, n| {
                let analytic = AnalyticFrame {
                    du: frame.du.as_dvec3(),
                    dv: frame.dv.as_dvec3(),
                    n,
                };
                let near_edge = expr
                    .layers()
                    .iter()
                    .any(|l| l.feather.is_none() && layer_signed(l, analytic, h).abs() < 1e-4);
                let got = renderer.eval(frame, uv, h.as_vec3(), Footprint::HARD);
                let want = closed.shade(analytic, uv.as_dvec2(), h);
                if !near_edge {
                    assert!(
                        (f64::from(got.coverage) - want.coverage).abs() < 1e-3,
                        "{name}, H = {h}, N = {n}: {} vs {}",
                        got.coverage,
                        want.coverage
                    );
                    if want.coverage > 0.0 {
                        assert!(
                            (got.colour.as_dvec3() - want.colour).length() < 1e-6,
                            "{name}, N = {n}: {} vs {}",
                            got.colour,
                            want.colour
                        );
                    }
                    let c = want.coverage;
                    outside += usize::from(c == 0.0);
                    inside += usize::from(c > 0.0);
                    partial += usize::from(c > 0.0 && c < 0.999);
                }
                false
            });
        }
        assert!(
            inside > 200 && outside > 200,
            "{name}: {inside} in, {outside} out"
        );
        if name.starts_with("feathered") || name.starts_with("masked") {
            assert!(partial > 20, "{name}: {partial} soft");
        }
    }
}
