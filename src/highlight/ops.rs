//! The basic operations on a highlight vector (Anjyo & Hiramitsu 2003, "Highlight vector field
//! for cel animation"; docs/highlights.md).
//!
//! An [`Op`] is a description with parameters of any type `P` (a number, or later an animation
//! track); [`Op::prepare`] validates an `Op<f32>` and precomputes what the per-point
//! [`PreparedOp::apply`] needs. Every operation acts on the coordinates
//! `(t_u, t_v, h_n) = ((H, du), (H, dv), (H, N))` of H in the tangent frame and ends by
//! normalizing; when the vector to normalize is (nearly) zero it returns its input H unchanged,
//! the continuous limit in the cases that occur, and never NaN.

use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};

use super::error::HighlightError;
use super::frame::TangentFrame;
use crate::math::{int_pow, normalize_or, Exponent};
use crate::param::{check, Range};

/// One operation on the highlight vector H at a surface point.
///
/// RON: `Translate(alpha: 0.2, beta: 0.0)`, `Rotate(degrees: 30.0)`,
/// `Scale(delta: 0.5, axis: U)` (axis `U`, `V` or `Angle(30.0)`, default `U`),
/// `Split(gamma_u: 0.1, gamma_v: 0.0)`, `Square(sigma: 0.2, n: 2.0, style: Tangent)` (style
/// `Tangent` or `PerAxis`, default `Tangent`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Op<P = f32> {
    /// Translation. Paper: `H' = H + α du + β dv`, `t(H) = H' / ‖H'‖`.
    ///
    /// On a convex surface the highlight moves toward `+du` for `α > 0` (its centre is where
    /// `t(H) = N`). |α|, |β| ≤ 10⁶: Anjyo & Hiramitsu 2003 warn that large values make H nearly
    /// tangent, and the bound keeps squared lengths finite in f32.
    Translate {
        /// α, the step along du.
        alpha: P,
        /// β, the step along dv.
        beta: P,
    },
    /// Rotation of the (u, v) coordinate system by θ about N. Paper: "rotating H, induced by
    /// the 2D rotation of the (u, v) coordinate system".
    ///
    /// H's tangential coordinates become its coordinates in the rotated system,
    /// `(t_u, t_v) ← R(−θ) (t_u, t_v)`, and `h_n` stays. Rotation alone leaves `(N, H)` and so the
    /// highlight unchanged; the operations after it act along axes turned by +θ (from du toward
    /// dv), so the highlight they shape turns by θ about its centre.
    Rotate {
        /// θ in degrees, counter-clockwise from du toward dv.
        degrees: P,
    },
    /// Directional scaling. Paper (Eq. 4): `H'' = H − δ (H, du) du`, `s(H) = H'' / ‖H''‖`,
    /// `0 < δ ≤ 1`.
    ///
    /// Here along any tangent axis `a` ([`Axis`]): `H'' = H − δ (H, a) a`, the same as rotating
    /// by φ, scaling along du and rotating back. δ = 0 is allowed (identity, the "off" value of
    /// an animated op). δ = 1 with H along `a` gives zero, and H is returned unchanged.
    Scale {
        /// δ ∈ [0, 1]: 0 leaves H alone, 1 removes its component along the axis.
        delta: P,
        /// The tangent axis to stretch the highlight along.
        #[serde(default = "Axis::default")]
        axis: Axis<P>,
    },
    /// Split. Paper: `H∨ = H − γ1 sgn(H, du) du − γ2 sgn(H, dv) dv`, with `sgn(0) = +1`.
    ///
    /// γ1 > 0 cuts the highlight in two along the dv axis, γ2 > 0 along the du axis, both: four
    /// pieces. `sgn(−0) = +1` too (unlike `f32::signum`). γ ≤ 10⁶, as for translation.
    Split {
        /// γ1 ≥ 0, the push along du.
        gamma_u: P,
        /// γ2 ≥ 0, the push along dv.
        gamma_v: P,
    },
    /// Squaring. Paper: `θ = min(acos(H, du), acos(H, dv))`, `sqrnorm = sin(2θ)^n`,
    /// `H^ = H − σ sqrnorm ((H, du) du + (H, dv) dv)`, σ ∈ [0, 1], integer n.
    ///
    /// Departure ([`SquareStyle::Tangent`], docs/highlights.md): θ is measured in the tangent
    /// plane. With `t = (t_u, t_v)`, `a = |t_u| / |t|`, `b = |t_v| / |t|`, θ is the angle from the
    /// nearest axis and `sin 2θ = 2ab` exactly, so `H^ = H − σ (2ab)^n (t_u du + t_v dv)`. Taken
    /// literally with the raw unit H, θ ≈ π/2 near the highlight and the op barely acts; this
    /// reading needs no `acos`, is symmetric in all four quadrants, accepts any real n > 0, and
    /// leaves H unchanged at t = 0. The diagonals are pulled toward N, so the highlight grows into
    /// its corners. The ratio of area to bounding square rises with σ up to about 0.2–0.25 (n =
    /// 1…4); beyond, the corners overshoot the square and the highlight becomes a four-pointed
    /// star.
    Square {
        /// σ ∈ [0, 1], how strongly the corners are filled.
        sigma: P,
        /// n > 0, how sharply the pull concentrates on the diagonals.
        n: P,
        /// Which reading of θ to use.
        #[serde(default)]
        style: SquareStyle,
    },
}

/// The tangent axis of a directional [`Op::Scale`].
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Axis<P = f32> {
    /// du.
    U,
    /// dv.
    V,
    /// `cos φ du + sin φ dv`, φ in degrees from du toward dv.
    Angle(P),
}

// A derive would require `P: Default`, which an animation track need not implement.
#[allow(clippy::derivable_impls)]
impl<P> Default for Axis<P> {
    fn default() -> Self {
        Axis::U
    }
}

/// How [`Op::Square`] measures the angle θ.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum SquareStyle {
    /// θ of the tangent-plane direction of H: one factor `(2ab)^n` (docs/highlights.md).
    #[default]
    Tangent,
    /// A published port's per-axis form with its `sin(pow(2θ, n))` corrected: each tangent
    /// component has its own angle `θ_u = acos(H, du)`, `θ_v = acos(H, dv)` of the raw unit H and
    /// its own factor, `H^ = H − σ (|sin 2θ_u|^n t_u du + |sin 2θ_v|^n t_v dv)`. The absolute
    /// value keeps non-integer n finite and pulls all four quadrants the same way. Offered for
    /// comparison: near the highlight `|sin 2θ_u| ≈ 2|t_u|` is small, so it acts weakly.
    PerAxis,
}

impl<P> Op<P> {
    /// Calls `f` with every numeric parameter, in the order of [`map`](Self::map), which
    /// it is built on: a parameter `map` reaches is visited, with no second list to keep.
    pub fn for_each_param(&self, mut f: impl FnMut(&P)) {
        let _visited: Op<()> = self.map(|p| f(p));
    }

    /// The same operation with every numeric parameter mapped through `f`, in declaration order.
    #[must_use]
    pub fn map<Q>(&self, mut f: impl FnMut(&P) -> Q) -> Op<Q> {
        match self {
            Op::Translate { alpha, beta } => Op::Translate {
                alpha: f(alpha),
                beta: f(beta),
            },
            Op::Rotate { degrees } => Op::Rotate {
                degrees: f(degrees),
            },
            Op::Scale { delta, axis } => Op::Scale {
                delta: f(delta),
                axis: match axis {
                    Axis::U => Axis::U,
                    Axis::V => Axis::V,
                    Axis::Angle(phi) => Axis::Angle(f(phi)),
                },
            },
            Op::Split { gamma_u, gamma_v } => Op::Split {
                gamma_u: f(gamma_u),
                gamma_v: f(gamma_v),
            },
            Op::Square { sigma, n, style } => Op::Square {
                sigma: f(sigma),
                n: f(n),
                style: *style,
            },
        }
    }

    /// The variant's name, for messages.
    #[must_use]
    pub fn name(&self) -> &'static str {
        match self {
            Op::Translate { .. } => "Translate",
            Op::Rotate { .. } => "Rotate",
            Op::Scale { .. } => "Scale",
            Op::Split { .. } => "Split",
            Op::Square { .. } => "Square",
        }
    }
}

impl Op<f32> {
    /// Checks every parameter: all finite, δ ∈ [0, 1], γ ≥ 0, σ ∈ [0, 1], n > 0.
    pub fn validate(&self) -> Result<(), HighlightError> {
        let checked = match *self {
            Op::Translate { alpha, beta } => {
                let hint = "; beyond that H is tangent to the surface and the highlight gone";
                check("translate alpha (α)", alpha, Range::Step, hint)?;
                check("translate beta (β)", beta, Range::Step, hint)
            }
            Op::Rotate { degrees } => check("rotate degrees", degrees, Range::Finite, ""),
            Op::Scale { delta, ref axis } => {
                check(
                    "scale delta (δ)",
                    delta,
                    Range::Unit,
                    "; 0 leaves the highlight alone, 1 stretches it fully along the axis",
                )?;
                match *axis {
                    Axis::Angle(phi) => check("scale axis angle", phi, Range::Finite, ""),
                    Axis::U | Axis::V => Ok(()),
                }
            }
            Op::Split { gamma_u, gamma_v } => {
                let hint = "; 0 does not split, larger values push the pieces further apart";
                check("split gamma_u (γ1)", gamma_u, Range::NonNegativeStep, hint)?;
                check("split gamma_v (γ2)", gamma_v, Range::NonNegativeStep, hint)
            }
            Op::Square { sigma, n, .. } => {
                check(
                    "square sigma (σ)",
                    sigma,
                    Range::Unit,
                    "; 0 leaves the highlight round, larger values fill its corners",
                )?;
                check(
                    "square exponent n",
                    n,
                    Range::Positive,
                    "; larger values sharpen the corners",
                )
            }
        };
        Ok(checked?)
    }

    /// Validates and precomputes the per-point form (cosines and sines of angles).
    pub fn prepare(&self) -> Result<PreparedOp, HighlightError> {
        self.validate()?;
        Ok(match *self {
            Op::Translate { alpha, beta } => PreparedOp::Translate(Vec2::new(alpha, beta)),
            Op::Rotate { degrees } => {
                let (s, c) = degrees.to_radians().sin_cos();
                PreparedOp::Rotate { cos: c, sin: s }
            }
            Op::Scale { delta, ref axis } => {
                let axis = match *axis {
                    Axis::U => Vec2::X,
                    Axis::V => Vec2::Y,
                    Axis::Angle(phi) => {
                        let (s, c) = phi.to_radians().sin_cos();
                        Vec2::new(c, s)
                    }
                };
                PreparedOp::Scale { axis, delta }
            }
            Op::Split { gamma_u, gamma_v } => PreparedOp::Split(Vec2::new(gamma_u, gamma_v)),
            Op::Square { sigma, n, style } => PreparedOp::Square {
                sigma,
                n: Exponent::new(n),
                style,
            },
        })
    }
}

/// A validated operation, ready to apply at many points. Made by [`Op::prepare`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PreparedOp {
    /// `(α, β)`.
    Translate(Vec2),
    /// cos θ and sin θ.
    Rotate {
        /// cos θ.
        cos: f32,
        /// sin θ.
        sin: f32,
    },
    /// Unit tangent axis `(cos φ, sin φ)` and δ.
    Scale {
        /// The axis in frame coordinates.
        axis: Vec2,
        /// δ.
        delta: f32,
    },
    /// `(γ1, γ2)`.
    Split(Vec2),
    /// σ, n and the style.
    Square {
        /// σ.
        sigma: f32,
        /// n.
        n: Exponent,
        /// The style.
        style: SquareStyle,
    },
    /// `t ← M t`: the map a pin that holds its layer's shape solves on each frame
    /// ([`ShapeMap`](super::ShapeMap)); no file writes it. Linear, so homogeneous and odd.
    Linear(glam::Mat2),
}

/// The `sgn` of Anjyo & Hiramitsu 2003, with `sgn(0) = sgn(−0) = +1`.
#[inline]
fn sgn(x: f32) -> f32 {
    if x < 0.0 {
        -1.0
    } else {
        1.0
    }
}

/// `|sin 2θ|` for `cos θ = c`: `2 |c| √(1 − c²)`.
#[inline]
fn abs_sin_twice_acos(c: f32) -> f32 {
    2.0 * c.abs() * (1.0 - c * c).max(0.0).sqrt()
}

/// Below this ratio of squared lengths an operation's output counts as zero.
const MIN_LENGTH_RATIO_SQUARED: f32 = 1e-12;

/// Runs an operation's formula on the tangential part `t` of H; every operation leaves the normal
/// coordinate `h_n` alone.
trait Formula {
    fn run(self, f: impl Fn(Vec2) -> Vec2);
}

/// `f(t)`, and whether `(f(t), h_n)` is not (nearly) zero relative to `(t, h_n)`.
#[inline(always)]
fn guarded(t: Vec2, h_n: f32, f: impl Fn(Vec2) -> Vec2) -> (Vec2, bool) {
    let v = f(t);
    let z2 = h_n * h_n;
    let keep = v.length_squared() + z2 > MIN_LENGTH_RATIO_SQUARED * (t.length_squared() + z2);
    (v, keep)
}

/// One vector.
struct One<'a>(&'a mut Vec3);

impl Formula for One<'_> {
    #[inline(always)]
    fn run(self, f: impl Fn(Vec2) -> Vec2) {
        let l = *self.0;
        // A branch: one vector's chain of operations is latency-bound, and a well-predicted
        // branch keeps the comparison off it.
        if let (v, true) = guarded(l.truncate(), l.z, f) {
            *self.0 = v.extend(l.z);
        }
    }
}

/// Many vectors, one array per coordinate.
struct Columns<'a>(&'a mut [f32], &'a mut [f32], &'a [f32]);

impl Formula for Columns<'_> {
    #[inline(always)]
    fn run(self, f: impl Fn(Vec2) -> Vec2) {
        for ((x, y), z) in self.0.iter_mut().zip(self.1.iter_mut()).zip(self.2) {
            // Selects, so the loop vectorizes.
            let (v, keep) = guarded(Vec2::new(*x, *y), *z, &f);
            *x = select(keep, v.x, *x);
            *y = select(keep, v.y, *y);
        }
    }
}

/// `if keep { a } else { b }` by bit masks. Written as a plain `if`, storing it back where `b`
/// came from becomes a store only where `keep` holds, which SSE2 does lane by lane, each with a
/// branch.
#[inline(always)]
fn select(keep: bool, a: f32, b: f32) -> f32 {
    let mask = u32::from(keep).wrapping_neg();
    f32::from_bits((a.to_bits() & mask) | (b.to_bits() & !mask))
}

/// Tangent squaring of the tangential part t: `t (1 − σ (2ab)^n)` with `2ab = 2|t_u||t_v|/|t|²`
/// (0 at t = 0).
#[inline(always)]
fn square_tangent(t: Vec2, sigma: f32, pow: impl Fn(f32) -> f32) -> Vec2 {
    let t2 = t.length_squared();
    let sin2theta = if t2 > 0.0 {
        (2.0 * t.x.abs() * t.y.abs() / t2).min(1.0)
    } else {
        0.0
    };
    t * (1.0 - sigma * pow(sin2theta))
}

/// Per-axis squaring of the tangential part t of a unit H:
/// `t − σ (|sin 2θ_u|^n t_u, |sin 2θ_v|^n t_v)`.
#[inline(always)]
fn square_per_axis(t: Vec2, sigma: f32, pow: impl Fn(f32) -> f32) -> Vec2 {
    let k = Vec2::new(pow(abs_sin_twice_acos(t.x)), pow(abs_sin_twice_acos(t.y)));
    t - sigma * k * t
}

/// Hands the squaring of `style` with σ = `sigma` and the power `pow` to `target`.
#[inline(always)]
fn square(target: impl Formula, style: SquareStyle, sigma: f32, pow: impl Fn(f32) -> f32) {
    match style {
        SquareStyle::Tangent => target.run(|t| square_tangent(t, sigma, &pow)),
        SquareStyle::PerAxis => target.run(|t| square_per_axis(t, sigma, &pow)),
    }
}

impl PreparedOp {
    /// Whether the formula needs a unit H: translation and split add fixed amounts, the per-axis
    /// square reads the unit H's components. The others are homogeneous (`op(cH) = c op(H)`
    /// for c > 0), so normalizing before or after them gives the same direction.
    #[inline]
    #[must_use]
    pub fn needs_unit_input(&self) -> bool {
        match self {
            PreparedOp::Translate(_) | PreparedOp::Split(_) => true,
            PreparedOp::Square { style, .. } => match style {
                SquareStyle::PerAxis => true,
                SquareStyle::Tangent => false,
            },
            PreparedOp::Rotate { .. } | PreparedOp::Scale { .. } | PreparedOp::Linear(_) => false,
        }
    }

    /// The operation's formula without the final normalization, on H in frame coordinates
    /// `l = (t_u, t_v, h_n)`; when the result is (nearly) zero relative to `l`, `l` itself.
    #[inline]
    #[must_use]
    pub fn step(&self, l: Vec3) -> Vec3 {
        let mut l = l;
        self.run(One(&mut l));
        l
    }

    /// [`step`](Self::step) in place on many vectors given one array per coordinate (the normal
    /// coordinate `z` never changes). The match on the operation is outside the loop over them,
    /// so the loop is straight-line arithmetic the compiler can vectorize.
    #[inline]
    pub fn step_all(&self, x: &mut [f32], y: &mut [f32], z: &[f32]) {
        self.run(Columns(x, y, z));
    }

    /// Hands the operation's tangential formula (see [`Op`]) to `target`.
    #[inline(always)]
    fn run(&self, target: impl Formula) {
        match *self {
            PreparedOp::Translate(ab) => target.run(|t| t + ab),
            PreparedOp::Rotate { cos, sin } => {
                target.run(|t| Vec2::new(cos * t.x + sin * t.y, cos * t.y - sin * t.x))
            }
            PreparedOp::Scale { axis, delta } => target.run(|t| t - delta * t.dot(axis) * axis),
            PreparedOp::Split(g) => target.run(|t| t - g * Vec2::new(sgn(t.x), sgn(t.y))),
            PreparedOp::Square { sigma, n, style } => match n {
                // Anjyo & Hiramitsu's n = 2 (2003), and 1 and 3: two bits.
                Exponent::Integer(k) if k < 4 => {
                    square(target, style, sigma, |x| int_pow::<2>(x, k))
                }
                Exponent::Integer(k) => square(target, style, sigma, |x| {
                    int_pow::<{ Exponent::INTEGER_BITS }>(x, k)
                }),
                Exponent::Real(r) => square(target, style, sigma, |x| x.powf(r)),
            },
            PreparedOp::Linear(m) => target.run(|t| m * t),
        }
    }

    /// Applies the operation to unit H given in frame coordinates `l = (t_u, t_v, h_n)` (so N is
    /// `+z`), returning unit frame coordinates: [`step`](Self::step), then normalize. See [`Op`]
    /// for each formula.
    #[inline]
    #[must_use]
    pub fn apply_local(&self, l: Vec3) -> Vec3 {
        normalize_or(self.step(l), l)
    }

    /// Applies the operation to the unit world vector `h` at a point with frame `frame`.
    #[inline]
    #[must_use]
    pub fn apply(&self, frame: &TangentFrame, h: Vec3) -> Vec3 {
        frame.to_world(self.apply_local(frame.to_local(h)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn local(x: f32, y: f32) -> Vec3 {
        Vec3::new(x, y, (1.0 - x * x - y * y).sqrt())
    }

    fn prep(op: Op) -> PreparedOp {
        op.prepare().unwrap()
    }

    /// A frame turned away from the world axes, as f32 and as f64 columns.
    fn turned_frame() -> (TangentFrame, [glam::DVec3; 3]) {
        let q = glam::DQuat::from_euler(glam::EulerRot::ZXY, 0.7, -0.4, 1.9);
        let axes = [q * glam::DVec3::X, q * glam::DVec3::Y, q * glam::DVec3::Z];
        let frame = TangentFrame::new(axes[0].as_vec3(), axes[1].as_vec3(), axes[2].as_vec3());
        (frame, axes)
    }

    #[test]
    fn translate_moves_h_along_the_frame_in_world_space() {
        // H' = H + α du + β dv of Anjyo & Hiramitsu 2003, normalized, in f64 on the world
        // vectors.
        let (frame, [du, dv, n]) = turned_frame();
        let h = (0.1 * du - 0.2 * dv + 0.97 * n).normalize();
        let got = prep(Op::Translate {
            alpha: 0.3,
            beta: 0.05,
        })
        .apply(&frame, h.as_vec3());
        let want = (h + 0.3 * du + 0.05 * dv).normalize();
        assert!((got.as_dvec3() - want).length() < 1e-6, "{got} vs {want}");
    }

    #[test]
    fn rotate_turns_coordinates_by_minus_theta_and_keeps_normal_part() {
        let l = local(0.3, 0.0);
        let got = prep(Op::Rotate { degrees: 90.0 }).apply_local(l);
        assert!((got - Vec3::new(0.0, -0.3, l.z)).length() < 1e-6);
    }

    #[test]
    fn scale_along_angle_equals_rotate_scale_rotate_back() {
        let l = local(0.2, 0.3);
        let direct = prep(Op::Scale {
            delta: 0.7,
            axis: Axis::Angle(30.0),
        })
        .apply_local(l);
        let composed = [
            Op::Rotate { degrees: 30.0 },
            Op::Scale {
                delta: 0.7,
                axis: Axis::U,
            },
            Op::Rotate { degrees: -30.0 },
        ]
        .iter()
        .fold(l, |h, op| prep(op.clone()).apply_local(h));
        assert!((direct - composed).length() < 1e-6);
    }

    #[test]
    fn scale_to_zero_returns_input() {
        let op = prep(Op::Scale {
            delta: 1.0,
            axis: Axis::V,
        });
        assert_eq!(op.apply_local(Vec3::Y), Vec3::Y);
        assert!((op.apply_local(local(0.0, 0.6)) - Vec3::Z).length() < 1e-6);
    }

    #[test]
    fn split_sign_of_zero_is_plus_one() {
        let op = prep(Op::Split {
            gamma_u: 0.5,
            gamma_v: 0.0,
        });
        let want = Vec3::new(-0.5, 0.0, 1.0).normalize();
        assert!((op.apply_local(Vec3::Z) - want).length() < 1e-6);
        assert!((op.apply_local(Vec3::new(-0.0, 0.0, 1.0)) - want).length() < 1e-6);
        assert_eq!(sgn(-0.0), 1.0);
        assert_eq!(sgn(-1e-30), -1.0);
    }

    #[test]
    fn square_tangent_pulls_diagonal_not_axes() {
        let op = prep(Op::Square {
            sigma: 0.5,
            n: 2.0,
            style: SquareStyle::Tangent,
        });
        // On an axis 2ab = 0: unchanged.
        let on_axis = local(0.2, 0.0);
        assert!((op.apply_local(on_axis) - on_axis).length() < 1e-6);
        // On the diagonal 2ab = 1: tangential part times (1 − σ).
        let d = local(0.2, 0.2);
        let want = Vec3::new(0.1, 0.1, d.z).normalize();
        assert!((op.apply_local(d) - want).length() < 1e-6);
        // t = 0 is left alone.
        assert_eq!(op.apply_local(Vec3::Z), Vec3::Z);
    }

    #[test]
    fn square_per_axis_matches_its_formula() {
        // θ_u and θ_v are the angles between the unit H and du, dv, measured in f64 from the
        // world vectors with atan2; each tangent component shrinks by σ |sin 2θ|^n.
        let (frame, [du, dv, n]) = turned_frame();
        let h = (-0.3 * du + 0.4 * dv + 0.75_f64.sqrt() * n).normalize();
        let got = prep(Op::Square {
            sigma: 0.5,
            n: 1.5,
            style: SquareStyle::PerAxis,
        })
        .apply(&frame, h.as_vec3());
        let angle = |a: glam::DVec3| h.cross(a).length().atan2(h.dot(a));
        let k = |theta: f64| (2.0 * theta).sin().abs().powf(1.5);
        let (tu, tv) = (h.dot(du), h.dot(dv));
        let want = (h - 0.5 * k(angle(du)) * tu * du - 0.5 * k(angle(dv)) * tv * dv).normalize();
        assert!((got.as_dvec3() - want).length() < 1e-6, "{got} vs {want}");
    }

    #[test]
    fn validation_rejects_out_of_range() {
        let bad = [
            Op::Scale {
                delta: 1.01,
                axis: Axis::U,
            },
            Op::Scale {
                delta: 0.5,
                axis: Axis::Angle(f32::INFINITY),
            },
            Op::Split {
                gamma_u: -0.1,
                gamma_v: 0.0,
            },
            Op::Square {
                sigma: 0.5,
                n: 0.0,
                style: SquareStyle::Tangent,
            },
            Op::Square {
                sigma: -0.1,
                n: 1.0,
                style: SquareStyle::Tangent,
            },
            Op::Translate {
                alpha: f32::NAN,
                beta: 0.0,
            },
            Op::Rotate {
                degrees: f32::NEG_INFINITY,
            },
        ];
        for op in bad {
            assert!(op.prepare().is_err(), "{op:?} accepted");
        }
        let msg = Op::Scale {
            delta: 1.5,
            axis: Axis::U,
        }
        .validate()
        .unwrap_err()
        .to_string();
        assert!(msg.contains("delta") && msg.contains("1.5") && msg.contains("[0, 1]"));
    }

    #[test]
    fn map_visits_every_parameter() {
        let op: Op<u32> = Op::Scale {
            delta: 1,
            axis: Axis::Angle(2),
        };
        assert_eq!(
            op.map(|x| f64::from(*x) * 0.5),
            Op::Scale {
                delta: 0.5,
                axis: Axis::Angle(1.0)
            }
        );
        let sq: Op<u32> = Op::Square {
            sigma: 3,
            n: 4,
            style: SquareStyle::PerAxis,
        };
        let mut seen = Vec::new();
        let _ = sq.map(|x| seen.push(*x));
        assert_eq!(seen, [3, 4]);
    }

    #[test]
    fn for_each_param_visits_every_parameter_in_order() {
        let ops: [Op<u32>; 5] = [
            Op::Translate { alpha: 1, beta: 2 },
            Op::Rotate { degrees: 3 },
            Op::Scale {
                delta: 4,
                axis: Axis::Angle(5),
            },
            Op::Split {
                gamma_u: 6,
                gamma_v: 7,
            },
            Op::Square {
                sigma: 8,
                n: 9,
                style: SquareStyle::Tangent,
            },
        ];
        let mut seen = Vec::new();
        for op in &ops {
            op.for_each_param(|p| seen.push(*p));
        }
        assert_eq!(seen, (1..=9).collect::<Vec<u32>>());
    }

    #[test]
    fn square_tangent_off_the_diagonal_for_small_and_large_exponents() {
        // t = (0.3, 0.1): 2ab = 2·0.3·0.1 / 0.1 = 0.6, so t shrinks by 1 − σ 0.6ⁿ.
        let (x, y) = (0.3_f64, 0.1_f64);
        let z = (1.0 - x * x - y * y).sqrt();
        for n in [1.0_f64, 2.0, 3.0, 4.0, 5.0, 6.0, 2.5] {
            let got = prep(Op::Square {
                sigma: 0.5,
                n: n as f32,
                style: SquareStyle::Tangent,
            })
            .apply_local(Vec3::new(x as f32, y as f32, z as f32));
            let k = 1.0 - 0.5 * 0.6_f64.powf(n);
            let want = glam::DVec3::new(k * x, k * y, z).normalize();
            assert!(
                (got.as_dvec3() - want).length() < 1e-6,
                "n = {n}: {got} vs {want}"
            );
        }
    }

    #[test]
    fn output_counts_as_zero_below_a_millionth_of_the_input_length() {
        // Scaling fully along du leaves (0, 0, h_n): kept when |h_n| > 1e-6 ‖H‖, else H itself
        // is returned, whatever the length of H.
        let op = prep(Op::Scale {
            delta: 1.0,
            axis: Axis::U,
        });
        for length in [1.0_f32, 1e3, 1e-3] {
            let below = Vec3::new(length, 0.0, 1e-7 * length);
            assert_eq!(op.step(below), below, "{length}");
            let above = Vec3::new(length, 0.0, 1e-5 * length);
            assert_eq!(op.step(above), Vec3::new(0.0, 0.0, above.z), "{length}");
        }
        // Below the tangent plane the normal part keeps its sign.
        assert!((op.apply_local(Vec3::new(0.6, 0.0, -0.8)) + Vec3::Z).length() < 1e-6);
    }
}
