//! A highlight layer's parts as a shot file writes them: an operation of its stack, its mask.

use crate::highlight::{Axis, Mask, Op, SquareStyle};

/// An operation as a file writes it, each number written by `number` ([`number_text`](crate::shot::number_text) to read
/// back exactly, `rounded_number_text` for people): `Translate(alpha: 0.2, beta: 0.0)`,
/// `Scale(delta: 0.5, axis: Angle(30.0))`, `Square(sigma: 0.2, n: 2.0, style: PerAxis)`.
#[must_use]
pub fn op_text(op: &Op<f32>, number: fn(f32) -> String) -> String {
    let n = number;
    match op {
        Op::Translate { alpha, beta } => {
            format!("Translate(alpha: {}, beta: {})", n(*alpha), n(*beta))
        }
        Op::Rotate { degrees } => format!("Rotate(degrees: {})", n(*degrees)),
        Op::Scale { delta, axis } => {
            let axis = match axis {
                Axis::U => "U".to_string(),
                Axis::V => "V".to_string(),
                Axis::Angle(phi) => format!("Angle({})", n(*phi)),
            };
            format!("Scale(delta: {}, axis: {axis})", n(*delta))
        }
        Op::Split { gamma_u, gamma_v } => {
            format!("Split(gamma_u: {}, gamma_v: {})", n(*gamma_u), n(*gamma_v))
        }
        Op::Square {
            sigma,
            n: exponent,
            style,
        } => {
            let style = match style {
                SquareStyle::Tangent => "Tangent",
                SquareStyle::PerAxis => "PerAxis",
            };
            format!(
                "Square(sigma: {}, n: {}, style: {style})",
                n(*sigma),
                n(*exponent)
            )
        }
    }
}

/// A mask as a layer's field, each number written by `number` (as in [`op_text`]):
/// `mask: (u: (0.0, 1.0), v: (0.0, 1.0), feather: 0.0)`.
#[must_use]
pub fn mask_text(mask: &Mask<f32>, number: fn(f32) -> String) -> String {
    let n = number;
    format!(
        "mask: (u: ({}, {}), v: ({}, {}), feather: {})",
        n(mask.u.0),
        n(mask.u.1),
        n(mask.v.0),
        n(mask.v.1),
        n(mask.feather)
    )
}
