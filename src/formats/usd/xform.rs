//! A prim's local transform from its `xformOp`s, in `xformOpOrder`.
//!
//! USD writes matrices for row vectors (`p' = p M`, the translation in the last row); here
//! every matrix is for column vectors (`p' = M p`), so a written `matrix4d` is transposed. The
//! ops listed first are outermost: `M = op₀ · op₁ ⋯`, the last op applied to points first. A
//! rotation `rotateXYZ = (a, b, c)` turns about x first, then y, then z:
//! `R = Rz(c) · Ry(b) · Rx(a)`, angles in degrees.

use glam::{DMat4, DQuat, DVec3};

use super::layer::{Prim, Value};

/// A transform that cannot be read, and where.
pub(super) struct XformError {
    pub at: usize,
    pub message: String,
}

/// The local transform of `prim` (identity when it has no `xformOpOrder`), and whether the
/// order starts with `!resetXformStack!` (the prim ignores its parents' transforms).
pub(super) fn local_transform(prim: &Prim, path: &str) -> Result<(DMat4, bool), XformError> {
    let Some(order) = prim.property("xformOpOrder") else {
        return Ok((DMat4::IDENTITY, false));
    };
    let err = |at: usize, message: String| XformError { at, message };
    let names: Vec<String> = match &order.value {
        Some(Value::List(items)) => items
            .iter()
            .map(|v| match v {
                Value::Str(s) => Ok(s.clone()),
                _ => Err(err(
                    order.at,
                    format!("{path}: xformOpOrder must list op names in quotes"),
                )),
            })
            .collect::<Result<_, _>>()?,
        _ => {
            return Err(err(
                order.at,
                format!("{path}: xformOpOrder must be a list of op names"),
            ))
        }
    };
    let mut matrix = DMat4::IDENTITY;
    let mut reset = false;
    for (k, name) in names.iter().enumerate() {
        if name == "!resetXformStack!" {
            if k != 0 {
                return Err(err(
                    order.at,
                    format!("{path}: !resetXformStack! must come first in xformOpOrder"),
                ));
            }
            reset = true;
            continue;
        }
        let (inverse, op_name) = match name.strip_prefix("!invert!") {
            Some(rest) => (true, rest),
            None => (false, name.as_str()),
        };
        let Some(op) = prim.property(op_name) else {
            return Err(err(
                order.at,
                format!("{path}: xformOpOrder names `{op_name}`, which the prim does not have"),
            ));
        };
        let kind = op_name
            .strip_prefix("xformOp:")
            .map(|rest| rest.split(':').next().unwrap_or(rest))
            .unwrap_or("");
        let numbers = |n: usize| -> Result<Vec<f64>, XformError> {
            let values = match &op.value {
                Some(Value::Tuple(items)) if n > 1 => items.clone(),
                Some(v @ Value::Number(_)) if n == 1 => vec![v.clone()],
                _ => Vec::new(),
            };
            let out: Vec<f64> = values
                .iter()
                .filter_map(|v| match v {
                    Value::Number(x) if x.is_finite() => Some(*x),
                    _ => None,
                })
                .collect();
            if out.len() == n && values.len() == n {
                Ok(out)
            } else {
                Err(err(
                    op.at,
                    format!(
                        "{path}: `{op_name}` must be {n} finite number{}",
                        if n > 1 { "s" } else { "" }
                    ),
                ))
            }
        };
        let degrees = |x: f64| x.to_radians();
        let axis_rotation = |axis: char, angle: f64| match axis {
            'X' => DMat4::from_rotation_x(degrees(angle)),
            'Y' => DMat4::from_rotation_y(degrees(angle)),
            _ => DMat4::from_rotation_z(degrees(angle)),
        };
        let op_matrix = match kind {
            "translate" => {
                let t = numbers(3)?;
                DMat4::from_translation(DVec3::new(t[0], t[1], t[2]))
            }
            "scale" => {
                let s = numbers(3)?;
                DMat4::from_scale(DVec3::new(s[0], s[1], s[2]))
            }
            "rotateX" | "rotateY" | "rotateZ" => {
                let a = numbers(1)?;
                axis_rotation(kind.chars().last().unwrap_or('Z'), a[0])
            }
            "rotateXYZ" | "rotateXZY" | "rotateYXZ" | "rotateYZX" | "rotateZXY" | "rotateZYX" => {
                let a = numbers(3)?;
                // The first named axis turns first: it is the rightmost factor.
                let axes: Vec<char> = kind["rotate".len()..].chars().collect();
                let angle = |axis: char| match axis {
                    'X' => a[0],
                    'Y' => a[1],
                    _ => a[2],
                };
                axes.iter()
                    .fold(DMat4::IDENTITY, |m, &axis| axis_rotation(axis, angle(axis)) * m)
            }
            "orient" => {
                // (w, x, y, z), normalized.
                let q = numbers(4)?;
                let quat = DQuat::from_xyzw(q[1], q[2], q[3], q[0]);
                if quat.length() == 0.0 {
                    return Err(err(op.at, format!("{path}: `{op_name}` is a quaternion of no length")));
                }
                DMat4::from_quat(quat.normalize())
            }
            "transform" => {
                let rows = match &op.value {
                    Some(Value::Tuple(rows)) if rows.len() == 4 => rows,
                    _ => return Err(err(op.at, format!("{path}: `{op_name}` must be a 4 × 4 matrix ((…), (…), (…), (…))"))),
                };
                let mut m = [0.0; 16];
                for (r, row) in rows.iter().enumerate() {
                    let Value::Tuple(items) = row else {
                        return Err(err(op.at, format!("{path}: `{op_name}` must be a 4 × 4 matrix")));
                    };
                    if items.len() != 4 {
                        return Err(err(op.at, format!("{path}: `{op_name}` must be a 4 × 4 matrix")));
                    }
                    for (c, item) in items.iter().enumerate() {
                        match item {
                            Value::Number(x) if x.is_finite() => m[r * 4 + c] = *x,
                            _ => return Err(err(op.at, format!("{path}: `{op_name}` must hold finite numbers"))),
                        }
                    }
                }
                // Written row by row for row vectors: as columns, it is the column-vector matrix.
                DMat4::from_cols_array(&m)
            }
            _ => {
                return Err(err(
                    op.at,
                    format!("{path}: `{op_name}` is not an op glint reads (translate, scale, rotateX/Y/Z, rotateXYZ and the other orders, orient, transform)"),
                ))
            }
        };
        let op_matrix = if inverse {
            let det = op_matrix.determinant();
            if det == 0.0 || !det.is_finite() {
                return Err(err(
                    op.at,
                    format!("{path}: `{op_name}` cannot be inverted"),
                ));
            }
            op_matrix.inverse()
        } else {
            op_matrix
        };
        matrix *= op_matrix;
    }
    if !matrix.is_finite() || matrix.determinant() == 0.0 {
        return Err(err(
            order.at,
            format!("{path}: the transform flattens the prim (its determinant is 0)"),
        ));
    }
    Ok((matrix, reset))
}
