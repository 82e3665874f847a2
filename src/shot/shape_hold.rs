//! Held shapes: the map that keeps a pinned layer's highlight covering the surface about its
//! pin as it did on the frame the pin holds.

use glam::{DMat2, DVec2, Mat2, Vec2, Vec3};

use super::frame_state::FrameState;
use super::validated::Shot;
use crate::highlight::{Layer, LayerFrame, PreparedLayer, Shape, ShapeMap, TangentFrame};

/// Directions about the pin along which the held highlight's reach is looked for.
const DIRECTIONS: usize = 16;

/// How far from the centre, in gnomonic units (tan of the angle from N), the region of a
/// layer's operations is looked for: 3 is 72°.
const REACH: f32 = 3.0;

/// Steps of the search out to [`REACH`] along each direction, before bisection.
const REACH_STEPS: usize = 60;

/// The largest step from the pin the window the highlight is measured in reaches, as a
/// fraction of its patch's domain along each parameter: a view that leaves the surface about
/// the pin nearly edge-on would ask for points far off, where the surface is another.
const MAX_STEP: f64 = 0.5;

/// The window about the highlight's expected reach: this much wider than it.
const MARGIN: f64 = 1.5;

/// Samples per side of the grid the highlight is measured on.
const GRID: usize = 32;

/// The step of the differences that give the surface's first-order map at the pin, as a
/// fraction of the domain.
const DIFFERENCE: f64 = 1e-4;

/// Below this normal coordinate, a vector is too near the tangent plane for its gnomonic
/// coordinates to mean anything.
const MIN_NORMAL: f32 = 0.05;

/// Iterations of the Levenberg–Marquardt refinement; the residual that ends it early, and the
/// least fraction of its square a step must take off for another to follow.
const ITERATIONS: usize = 24;
const CLOSE_ENOUGH: f64 = 1e-4;
const SLOW: f64 = 1e-3;

/// How much the highlight's direction on the surface weighs against its area and its length
/// and width: a view can turn the directions in which the surface's normals change, which no
/// map of the tangent coordinates turns back, and size and aspect come first.
const TURN_WEIGHT: f64 = 0.1;

/// A layer centred on its pin on one frame, ready to give the gnomonic coordinates of the
/// vector leaving its placing translation at any point of the patch.
struct Placed<'a> {
    shot: &'a Shot,
    state: &'a FrameState,
    patch: usize,
    /// The layer's stack up to and with its placing translation, in the layer's frame.
    placing: PreparedLayer,
}

impl Placed<'_> {
    /// `p = t / h_n` of the vector leaving the placing translation at `uv`; None where it lies
    /// within [`MIN_NORMAL`] of the tangent plane or behind it.
    fn gnomonic(&self, uv: DVec2) -> Option<Vec2> {
        let point = self
            .shot
            .highlight_point(self.state, self.patch, (uv.x, uv.y));
        let frame = self.placing.frame_at(&point.frame);
        let g = frame.to_local(
            self.placing
                .highlight_vector(&point.frame, point.half_vector),
        );
        (g.z > MIN_NORMAL && g.is_finite()).then(|| g.truncate() / g.z)
    }
}

/// What the layer draws of a vector leaving its placing translation: its operations after it
/// and its shape, read on gnomonic coordinates.
struct Designed(PreparedLayer);

impl Designed {
    /// The operations after `layer`'s placing translation, with its ε and shape.
    fn of(layer: &Layer) -> Option<Designed> {
        let at = layer.placing_translation()?;
        let shaping = Layer {
            stack: layer.stack[at + 1..].to_vec(),
            mask: None,
            pin: None,
            frame: LayerFrame::Patch,
            shape_map: None,
            ..layer.clone()
        };
        Some(Designed(shaping.prepare().ok()?))
    }

    /// The signed inside value `s` of the vector with gnomonic coordinates `p`.
    fn signed(&self, p: Vec2) -> f32 {
        const FRAME: TangentFrame = TangentFrame::new(Vec3::X, Vec3::Y, Vec3::Z);
        self.0.signed(&FRAME, p.extend(1.0).normalize())
    }

    /// How far from the centre, in gnomonic units, the region reaches along `direction`: where
    /// it first ends, searched out to [`REACH`] and refined by bisection; the ε-disc's radius
    /// `tan(acos(1 − ε))` where the region does not hold the centre (a split's) or does not
    /// end.
    fn reach(&self, direction: Vec2, epsilon: f32) -> f32 {
        let cos = 1.0 - epsilon;
        let disc = ((1.0 - cos * cos).max(0.0).sqrt() / cos.max(MIN_NORMAL)).min(REACH);
        let inside = |r: f32| self.signed(direction * r) > 0.0;
        if !inside(0.0) {
            return disc;
        }
        let step = REACH / REACH_STEPS as f32;
        let Some(k) = (1..=REACH_STEPS).find(|&k| !inside(step * k as f32)) else {
            return disc;
        };
        let (mut lo, mut hi) = (step * (k - 1) as f32, step * k as f32);
        for _ in 0..20 {
            let mid = 0.5 * (lo + hi);
            if inside(mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }
}

/// The grid the highlight is measured on: each sample's (u, v) in units of the domain about
/// the pin, and the gnomonic coordinates of the vector leaving the placing translation there
/// on the frame drawn and on the held frame.
struct Samples {
    uv: Vec<DVec2>,
    now: Vec<Option<Vec2>>,
    then: Vec<Option<Vec2>>,
}

/// The zeroth and second moments of a weighted set of points: the weight, and the covariance
/// `(xx, xy, yy)` about the weighted mean.
fn moments(uv: &[DVec2], weight: impl Fn(usize) -> f64) -> (f64, [f64; 3]) {
    let (mut total, mut mean) = (0.0, DVec2::ZERO);
    for (i, p) in uv.iter().enumerate() {
        let w = weight(i);
        total += w;
        mean += w * *p;
    }
    if total <= 0.0 {
        return (0.0, [0.0; 3]);
    }
    mean /= total;
    let mut c = [0.0; 3];
    for (i, p) in uv.iter().enumerate() {
        let (w, d) = (weight(i), *p - mean);
        c[0] += w * d.x * d.x;
        c[1] += w * d.x * d.y;
        c[2] += w * d.y * d.y;
    }
    (total, c.map(|x| x / total))
}

impl Shot {
    /// The map that holds the shape of `held`, the layer centred on its pin at `uv` of patch
    /// `patch` on the held frame (`held_state`), on `centred`, the same layer centred there on
    /// the frame `state` ([`ShapeMap`]). None when the held frame shows no highlight about the
    /// pin on the patch, or an operation does not prepare (which drawing the frame reports);
    /// the shape then follows the view.
    ///
    /// The highlight is measured on a 48 × 48 grid of the patch's (u, v) about the pin: a window
    /// half as wide again as where the held highlight reaches (in each of 16 directions, where
    /// the operations after the placing translation end, taken onto the surface through the
    /// inverse of the held frame's first-order map at the pin), at most half the domain each
    /// way. The map starts from the least-squares fit of the held frame's gnomonic coordinates
    /// on the drawn frame's over the held highlight, and is refined by Levenberg–Marquardt
    /// until the drawn highlight's area in (u, v) and the covariance of its (u, v) — its size,
    /// aspect and direction — are the held one's, each sample weighed by a ramp of its signed
    /// value one grid step wide so that both change smoothly with the map.
    pub(super) fn shape_map(
        &self,
        (centred, state): (&Layer, &FrameState),
        (held, held_state): (&Layer, &FrameState),
        patch: usize,
        uv: (f64, f64),
    ) -> Option<ShapeMap> {
        let placed = |layer: &Layer, state| {
            let at = layer.placing_translation()?;
            let placing = Layer {
                stack: layer.stack[..=at].to_vec(),
                mask: None,
                pin: None,
                shape: Shape::Disc,
                shape_map: None,
                ..layer.clone()
            }
            .prepare()
            .ok()?;
            Some(Placed {
                shot: self,
                state,
                patch,
                placing,
            })
        };
        let (now, then) = (placed(centred, state)?, placed(held, held_state)?);
        // A frame that sees the other side of the surface at the pin draws another highlight
        // there (shading turns the frame toward the eye), with no shape of the held one's.
        let side = |state: &FrameState| {
            let surface = &state.library.patches[patch].surface;
            let frame = surface.frame(uv.0, uv.1);
            let point = self.highlight_point(state, patch, uv);
            point.frame.n.as_dvec3().dot(frame.normal) > 0.0
        };
        if side(state) != side(held_state) {
            return None;
        }
        let designed = Designed::of(held)?;
        let samples = self.samples(&now, &then, &designed, held.epsilon, uv)?;
        fit(&samples, &designed)
    }

    /// The grid of [`Samples`] about the pin at `uv`.
    fn samples(
        &self,
        now: &Placed,
        then: &Placed,
        designed: &Designed,
        epsilon: f32,
        uv: (f64, f64),
    ) -> Option<Samples> {
        let domain = then.state.library.patches[then.patch].surface.domain();
        let span = DVec2::new(domain.u.1 - domain.u.0, domain.v.1 - domain.v.0);
        let low = DVec2::new(domain.u.0, domain.v.0);
        let clamp = |p: DVec2| p.clamp(low, low + span);
        let pin = clamp(DVec2::new(uv.0, uv.1));
        // Where the held highlight reaches, in units of the domain about the pin.
        let inverse = first_order_inverse(then, pin, span, clamp);
        let mut half = DVec2::ZERO;
        for i in 0..DIRECTIONS {
            let direction = Vec2::from_angle(i as f32 * std::f32::consts::TAU / DIRECTIONS as f32);
            let target = (direction * designed.reach(direction, epsilon)).as_dvec2();
            let step = match inverse {
                Some(inverse) => (inverse * target) / span,
                None => DVec2::splat(MAX_STEP),
            };
            half = half.max(step.abs());
        }
        let mut half = (half * MARGIN).clamp(DVec2::splat(1e-6), DVec2::splat(MAX_STEP));
        loop {
            let corner = (pin - low) / span - half;
            let mut samples = Samples {
                uv: Vec::with_capacity(GRID * GRID),
                now: Vec::with_capacity(GRID * GRID),
                then: Vec::with_capacity(GRID * GRID),
            };
            // Whether the held highlight reaches the window's sides, along u and along v.
            let mut reaches = (false, false);
            for i in 0..GRID {
                for j in 0..GRID {
                    let at = corner
                        + 2.0 * half * DVec2::new(i as f64 + 0.5, j as f64 + 0.5) / GRID as f64;
                    // Samples off the patch are not its surface.
                    if at.cmplt(DVec2::ZERO).any() || at.cmpgt(DVec2::ONE).any() {
                        continue;
                    }
                    let x = low + at * span;
                    let held = then.gnomonic(x);
                    if held.is_some_and(|p| designed.signed(p) > 0.0) {
                        reaches.0 |= i == 0 || i == GRID - 1;
                        reaches.1 |= j == 0 || j == GRID - 1;
                    }
                    samples.uv.push(at);
                    samples.now.push(now.gnomonic(x));
                    samples.then.push(held);
                }
            }
            // A window the held highlight overflows is widened while it can be.
            let wider = DVec2::new(
                if reaches.0 { 2.0 } else { 1.0 },
                if reaches.1 { 2.0 } else { 1.0 },
            );
            let widened = (half * wider).min(DVec2::splat(MAX_STEP));
            if widened == half {
                return Some(samples);
            }
            half = widened;
        }
    }
}

/// The map whose highlight over `samples` has the held highlight's area and (u, v) covariance.
fn fit(samples: &Samples, designed: &Designed) -> Option<ShapeMap> {
    let signed = |p: Option<Vec2>| p.map_or(f64::NEG_INFINITY, |p| f64::from(designed.signed(p)));
    let held: Vec<f64> = samples.then.iter().map(|&p| signed(p)).collect();
    // The ramp's half width: the mean change of the held signed value across the edge between
    // neighbouring samples.
    let (mut sum, mut count) = (0.0, 0usize);
    for k in 1..held.len() {
        let (a, b) = (held[k - 1], held[k]);
        if a.is_finite() && b.is_finite() && (a > 0.0) != (b > 0.0) {
            sum += (a - b).abs();
            count += 1;
        }
    }
    if count == 0 {
        return None;
    }
    let ramp = 2.0 * sum / count as f64;
    let weigh = |s: f64| (0.5 + 0.5 * s / ramp).clamp(0.0, 1.0);
    let (area, covariance) = moments(&samples.uv, |i| weigh(held[i]));
    // The held covariance's inverse square root, which turns it into the identity: the drawn
    // one is compared in its frame, so that a narrow highlight's width counts as much as its
    // length.
    let held_covariance = DMat2::from_cols(
        DVec2::new(covariance[0], covariance[1]),
        DVec2::new(covariance[1], covariance[2]),
    );
    let whiten = inverse_square_root(held_covariance)?;
    let held_principal = principal(covariance);
    if !(area > 0.0 && held_principal.1 > 0.0) {
        return None;
    }
    // The drawn highlight's moments under the map `m`, less the held ones.
    let residual = |m: &[f64; 4]| -> [f64; 4] {
        let map = Mat2::from_cols(
            Vec2::new(m[0] as f32, m[1] as f32),
            Vec2::new(m[2] as f32, m[3] as f32),
        );
        let (a, c) = moments(&samples.uv, |i| {
            samples.now[i].map_or(0.0, |p| weigh(f64::from(designed.signed(map * p))))
        });
        let drawn = DMat2::from_cols(DVec2::new(c[0], c[1]), DVec2::new(c[1], c[2]));
        let relative = whiten * drawn * whiten;
        let (long, wide) = principal(c);
        [
            a / area - 1.0,
            long / held_principal.0 - 1.0,
            wide / held_principal.1 - 1.0,
            TURN_WEIGHT * relative.x_axis.y,
        ]
    };
    // The start: least squares over the held highlight and its edge.
    let pairs: Vec<(Vec2, Vec2)> = (0..samples.uv.len())
        .filter(|&i| held[i] > -ramp)
        .filter_map(|i| Some((samples.now[i]?, samples.then[i]?)))
        .collect();
    let start = ShapeMap::try_fit(&pairs)
        .unwrap_or(ShapeMap::IDENTITY)
        .matrix;
    let mut m = [
        f64::from(start.x_axis.x),
        f64::from(start.x_axis.y),
        f64::from(start.y_axis.x),
        f64::from(start.y_axis.y),
    ];
    let norm = |r: &[f64; 4]| r.iter().map(|x| x * x).sum::<f64>();
    let mut r = residual(&m);
    let mut lambda = 1e-3;
    for _ in 0..ITERATIONS {
        if norm(&r).sqrt() < CLOSE_ENOUGH {
            break;
        }
        // The Jacobian by forward differences.
        let scale = m.iter().map(|x| x.abs()).fold(0.0, f64::max).max(1e-3);
        let h = 1e-2 * scale;
        let mut jacobian = [[0.0; 4]; 4];
        for p in 0..4 {
            let mut moved = m;
            moved[p] += h;
            let rp = residual(&moved);
            for q in 0..4 {
                jacobian[q][p] = (rp[q] - r[q]) / h;
            }
        }
        let j = nalgebra::Matrix4::from_fn(|q, p| jacobian[q][p]);
        let rv = nalgebra::Vector4::from_column_slice(&r);
        let jtj = j.transpose() * j;
        let gradient = j.transpose() * rv;
        let mut improved = false;
        for _ in 0..8 {
            let damped = jtj
                + nalgebra::Matrix4::from_diagonal(&(jtj.diagonal() * lambda))
                + nalgebra::Matrix4::identity() * (1e-12 * jtj.trace().max(1e-300));
            let Some(step) = damped.lu().solve(&(-gradient)) else {
                lambda *= 10.0;
                continue;
            };
            let trial = [
                m[0] + step[0],
                m[1] + step[1],
                m[2] + step[2],
                m[3] + step[3],
            ];
            let rt = residual(&trial);
            if trial.iter().all(|x| x.is_finite()) && norm(&rt) < norm(&r) {
                // A step that gains little ends the search once it is taken.
                improved = norm(&rt) < (1.0 - SLOW) * norm(&r);
                m = trial;
                r = rt;
                lambda = (lambda * 0.3).max(1e-9);
                break;
            }
            lambda *= 10.0;
        }
        if !improved {
            break;
        }
    }
    ShapeMap::try_new(nalgebra::Matrix2::new(m[0], m[2], m[1], m[3]))
}

/// The principal values of the covariance `(xx, xy, yy)`, the larger first.
fn principal(c: [f64; 3]) -> (f64, f64) {
    let half_trace = 0.5 * (c[0] + c[2]);
    let root = (0.25 * (c[0] - c[2]) * (c[0] - c[2]) + c[1] * c[1]).sqrt();
    (half_trace + root, half_trace - root)
}

/// `C^(−1/2)` of a symmetric positive definite 2 × 2 matrix, from its eigenvalues; None when it
/// is not positive definite.
fn inverse_square_root(c: DMat2) -> Option<DMat2> {
    let (a, b, d) = (c.x_axis.x, c.x_axis.y, c.y_axis.y);
    let half_trace = 0.5 * (a + d);
    let root = (0.25 * (a - d) * (a - d) + b * b).sqrt();
    let (high, low) = (half_trace + root, half_trace - root);
    if low.is_nan() || low <= 1e-18 * high {
        return None;
    }
    // The eigenvector of the larger eigenvalue.
    let e = if b.abs() > 1e-300 || a >= d {
        DVec2::new(high - d, b).try_normalize().unwrap_or(DVec2::X)
    } else {
        DVec2::Y
    };
    let f = e.perp();
    let outer = |v: DVec2| DMat2::from_cols(v * v.x, v * v.y);
    Some(outer(e) / high.sqrt() + outer(f) / low.sqrt())
}

/// The inverse of the first-order map `(u, v) ↦ p` of `placed` at `pin` (central differences,
/// one-sided at the domain's edge): the step in (u, v) that moves p by a given amount. None
/// where the map is singular or cannot be evaluated.
fn first_order_inverse(
    placed: &Placed,
    pin: DVec2,
    span: DVec2,
    clamp: impl Fn(DVec2) -> DVec2,
) -> Option<glam::DMat2> {
    let column = |axis: DVec2| {
        let (ahead, behind) = (clamp(pin + axis), clamp(pin - axis));
        let length = (ahead - behind).length();
        let change = placed.gnomonic(ahead)? - placed.gnomonic(behind)?;
        (length > 0.0).then(|| change.as_dvec2() / length)
    };
    let du = column(DVec2::new(span.x * DIFFERENCE, 0.0))?;
    let dv = column(DVec2::new(0.0, span.y * DIFFERENCE))?;
    // The map in units of the domain, so that u and v weigh alike in telling it singular.
    let map = glam::DMat2::from_cols(du * span.x, dv * span.y);
    let scale = map.x_axis.length_squared() + map.y_axis.length_squared();
    if scale.is_nan() || scale <= 0.0 || map.determinant().abs() <= 1e-8 * scale {
        return None;
    }
    let inverse = glam::DMat2::from_cols(du, dv).inverse();
    inverse.is_finite().then_some(inverse)
}
