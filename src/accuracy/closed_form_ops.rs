//! The highlight operations of Anjyo & Hiramitsu 2003 in closed form: each formula of
//! docs/highlights.md written out again in f64 on world vectors, sharing no code with the
//! renderer's evaluation (`crate::highlight` gives only the [`Op`] description read here), so
//! that the accuracy reference cannot agree with a wrong formula there.
//!
//! A rotation turns the frame the later operations act along; every other operation maps H and
//! ends by normalizing, as the paper does after every operation.

use glam::DVec3;

use crate::highlight::{Axis, Op, SquareStyle};

/// A tangent frame in f64: `du`, `dv` and the normal `n`, orthonormal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AnalyticFrame {
    /// The first tangent axis.
    pub du: DVec3,
    /// The second tangent axis, `n × du`.
    pub dv: DVec3,
    /// The outward normal N.
    pub n: DVec3,
}

impl AnalyticFrame {
    /// The frame with its tangent axes turned by θ (degrees) about N, from du toward dv:
    /// `du' = cos θ du + sin θ dv`, `dv' = −sin θ du + cos θ dv`, `N' = N`.
    #[must_use]
    pub fn turned(self, degrees: f64) -> Self {
        let (sin, cos) = degrees.to_radians().sin_cos();
        Self {
            du: cos * self.du + sin * self.dv,
            dv: -sin * self.du + cos * self.dv,
            n: self.n,
        }
    }

    /// The tangent axis of a directional scaling in this frame: du, dv, or
    /// `cos φ du + sin φ dv` for `Angle(φ)` (φ in degrees).
    #[must_use]
    pub fn axis(&self, axis: &Axis) -> DVec3 {
        match *axis {
            Axis::U => self.du,
            Axis::V => self.dv,
            Axis::Angle(phi) => self.turned(f64::from(phi)).du,
        }
    }
}

/// `v / ‖v‖`, or the operation's unit input `h` where v vanishes: `‖v‖² ≤ 10⁻¹² ‖h‖²`
/// (docs/highlights.md, Normalization).
#[must_use]
fn normalized_or_input(v: DVec3, h: DVec3) -> DVec3 {
    let length_squared = v.length_squared();
    if length_squared > 1e-12 * h.length_squared() {
        v / length_squared.sqrt()
    } else {
        h
    }
}

/// The paper's sign: `+1` for `x ≥ 0` (so `sgn(0) = sgn(−0) = +1`), `−1` below.
#[must_use]
fn paper_sign(x: f64) -> f64 {
    if x >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

/// The tangent squaring's factor `sin 2θ` for θ the angle of the tangent part
/// `t = (t_u, t_v)` from its nearest axis, `θ = min(atan2(|t_v|, |t_u|), π/2 − atan2(|t_v|, |t_u|))`;
/// 0 where `t = 0`.
#[must_use]
fn tangent_sin_twice_theta(t_u: f64, t_v: f64) -> f64 {
    if t_u == 0.0 && t_v == 0.0 {
        return 0.0;
    }
    let from_u = t_v.abs().atan2(t_u.abs());
    let theta = from_u.min(std::f64::consts::FRAC_PI_2 - from_u);
    (2.0 * theta).sin()
}

/// The per-axis squaring's factor `|sin 2θ|` for `θ = acos c`, c a component of the unit H.
#[must_use]
fn per_axis_sin_twice_theta(c: f64) -> f64 {
    (2.0 * c.clamp(-1.0, 1.0).acos()).sin().abs()
}

/// One operation on the unit highlight vector `h` in `frame`: the frame the operations after it
/// act in, and the unit vector it makes (docs/highlights.md, Operations):
///
/// - translation `H' = H + α du + β dv`;
/// - rotation: the frame turned by θ from du toward dv ([`AnalyticFrame::turned`]), H kept;
/// - directional scaling `H' = H − δ (H, a) a`, a the axis ([`AnalyticFrame::axis`]);
/// - split `H' = H − γ1 sgn(H, du) du − γ2 sgn(H, dv) dv`, `sgn(0) = +1`;
/// - squaring, tangent style: `H' = H − σ (sin 2θ)^n ((H, du) du + (H, dv) dv)` with θ the angle
///   of the tangent part from its nearest axis; per-axis style:
///   `H' = H − σ (|sin 2θ_u|^n (H, du) du + |sin 2θ_v|^n (H, dv) dv)`, `θ_u = acos(H, du)`,
///   `θ_v = acos(H, dv)`;
///
/// each H' normalized, or `h` returned where it vanishes.
#[must_use]
pub fn closed_form_op(op: &Op, frame: AnalyticFrame, h: DVec3) -> (AnalyticFrame, DVec3) {
    let AnalyticFrame { du, dv, .. } = frame;
    let (t_u, t_v) = (h.dot(du), h.dot(dv));
    let mapped = match *op {
        Op::Translate { alpha, beta } => h + f64::from(alpha) * du + f64::from(beta) * dv,
        Op::Rotate { degrees } => return (frame.turned(f64::from(degrees)), h),
        Op::Scale { delta, ref axis } => {
            let a = frame.axis(axis);
            h - f64::from(delta) * h.dot(a) * a
        }
        Op::Split { gamma_u, gamma_v } => {
            h - f64::from(gamma_u) * paper_sign(t_u) * du
                - f64::from(gamma_v) * paper_sign(t_v) * dv
        }
        Op::Square { sigma, n, style } => {
            let (sigma, n) = (f64::from(sigma), f64::from(n));
            match style {
                SquareStyle::Tangent => {
                    let k = sigma * tangent_sin_twice_theta(t_u, t_v).powf(n);
                    h - k * (t_u * du + t_v * dv)
                }
                SquareStyle::PerAxis => {
                    let k_u = sigma * per_axis_sin_twice_theta(t_u).powf(n);
                    let k_v = sigma * per_axis_sin_twice_theta(t_v).powf(n);
                    h - k_u * t_u * du - k_v * t_v * dv
                }
            }
        }
    };
    (frame, normalized_or_input(mapped, h))
}

/// A stack of operations applied in order to the unit `h` in `frame`, normalizing after every
/// one ([`closed_form_op`]): the last frame and the unit H' it makes.
#[must_use]
pub fn closed_form_stack(stack: &[Op], frame: AnalyticFrame, h: DVec3) -> (AnalyticFrame, DVec3) {
    stack
        .iter()
        .fold((frame, h), |(frame, h), op| closed_form_op(op, frame, h))
}

#[cfg(test)]
mod tests {
    use super::*;

    const WORLD: AnalyticFrame = AnalyticFrame {
        du: DVec3::X,
        dv: DVec3::Y,
        n: DVec3::Z,
    };

    fn unit(x: f64, y: f64) -> DVec3 {
        DVec3::new(x, y, (1.0 - x * x - y * y).sqrt())
    }

    #[test]
    fn translation_puts_the_centre_of_the_equator_at_sin_lambda_alpha() {
        // At longitude λ on the equator N = (sin λ, 0, cos λ), du = (cos λ, 0, −sin λ); H = z.
        // H + α du ∥ N iff sin λ = α.
        for alpha in [-0.4_f32, 0.3] {
            let lambda = f64::from(alpha).asin();
            let frame = AnalyticFrame {
                du: DVec3::new(lambda.cos(), 0.0, -lambda.sin()),
                dv: DVec3::Y,
                n: DVec3::new(lambda.sin(), 0.0, lambda.cos()),
            };
            let (_, h) = closed_form_op(&Op::Translate { alpha, beta: 0.0 }, frame, DVec3::Z);
            assert!((h - frame.n).length() < 1e-12, "{h}");
        }
    }

    #[test]
    fn rotation_turns_the_axes_the_scaling_acts_along() {
        // Turned by 90°, the scaling along U removes the dv part: (0.3, 0.4, z) → (0.3, 0, z).
        let h = unit(0.3, 0.4);
        let scale = Op::Scale {
            delta: 1.0,
            axis: Axis::U,
        };
        let (frame, _) = closed_form_op(&Op::Rotate { degrees: 90.0 }, WORLD, h);
        let (_, got) = closed_form_op(&scale, frame, h);
        let want = DVec3::new(0.3, 0.0, h.z).normalize();
        assert!((got - want).length() < 1e-12, "{got} vs {want}");
    }

    #[test]
    fn scaling_along_an_angle_removes_that_component() {
        let h = unit(0.2, 0.3);
        let phi = 30f64.to_radians();
        let a = DVec3::new(phi.cos(), phi.sin(), 0.0);
        let (_, got) = closed_form_op(
            &Op::Scale {
                delta: 0.5,
                axis: Axis::Angle(30.0),
            },
            WORLD,
            h,
        );
        let want = (h - 0.5 * h.dot(a) * a).normalize();
        assert!((got - want).length() < 1e-12);
        assert!(((got.dot(a) / got.z) - 0.5 * h.dot(a) / h.z).abs() < 1e-12);
    }

    #[test]
    fn split_pushes_away_from_each_axis_with_the_sign_of_zero_positive() {
        let split = Op::Split {
            gamma_u: 0.5,
            gamma_v: 0.25,
        };
        let (_, at_zero) = closed_form_op(&split, WORLD, DVec3::Z);
        assert!((at_zero - DVec3::new(-0.5, -0.25, 1.0).normalize()).length() < 1e-12);
        let (_, negative) = closed_form_op(&split, WORLD, unit(-0.1, -0.2));
        let want = DVec3::new(-0.1 + 0.5, -0.2 + 0.25, unit(-0.1, -0.2).z).normalize();
        assert!((negative - want).length() < 1e-12);
    }

    #[test]
    fn tangent_squaring_shrinks_the_diagonal_by_one_minus_sigma_and_spares_the_axes() {
        let square = Op::Square {
            sigma: 0.5,
            n: 2.0,
            style: SquareStyle::Tangent,
        };
        let d = unit(0.2, 0.2);
        let (_, got) = closed_form_op(&square, WORLD, d);
        assert!((got - DVec3::new(0.1, 0.1, d.z).normalize()).length() < 1e-12);
        let on_axis = unit(0.0, 0.3);
        assert!((closed_form_op(&square, WORLD, on_axis).1 - on_axis).length() < 1e-15);
        // t = (0.3, 0.1): sin 2θ = 2·0.3·0.1/0.1 = 0.6.
        let h = unit(0.3, 0.1);
        let (_, got) = closed_form_op(&square, WORLD, h);
        let k = 1.0 - 0.5 * 0.36;
        let want = DVec3::new(k * 0.3, k * 0.1, h.z).normalize();
        assert!((got - want).length() < 1e-12, "{got} vs {want}");
    }

    #[test]
    fn per_axis_squaring_uses_each_component_s_own_angle() {
        // c = 0.6: |sin 2 acos c| = 2 · 0.6 · 0.8 = 0.96; c = 0: sin π = 0.
        let h = unit(0.6, 0.0);
        let square = Op::Square {
            sigma: 0.5,
            n: 1.0,
            style: SquareStyle::PerAxis,
        };
        let (_, got) = closed_form_op(&square, WORLD, h);
        let want = DVec3::new(0.6 * (1.0 - 0.5 * 0.96), 0.0, h.z).normalize();
        assert!((got - want).length() < 1e-12, "{got} vs {want}");
    }

    #[test]
    fn a_vanishing_result_returns_the_input() {
        let scale = Op::Scale {
            delta: 1.0,
            axis: Axis::U,
        };
        assert_eq!(closed_form_op(&scale, WORLD, DVec3::X).1, DVec3::X);
    }

    #[test]
    fn the_stack_applies_in_order() {
        // Translate then scale fully along du: the du part is gone whatever the translation.
        let stack = [
            Op::Translate {
                alpha: 0.3,
                beta: 0.1,
            },
            Op::Scale {
                delta: 1.0,
                axis: Axis::U,
            },
        ];
        let (_, got) = closed_form_stack(&stack, WORLD, DVec3::Z);
        assert!(got.x.abs() < 1e-15 && got.y > 0.0, "{got}");
        let (_, reversed) =
            closed_form_stack(&[stack[1].clone(), stack[0].clone()], WORLD, DVec3::Z);
        assert!(reversed.x > 0.0, "{reversed}");
    }
}
