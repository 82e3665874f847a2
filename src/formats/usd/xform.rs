//! A prim's local transform from its `xformOp`s, in `xformOpOrder`, at any time code.
//!
//! USD writes matrices for row vectors (`p' = p M`, the translation in the last row); here
//! every matrix is for column vectors (`p' = M p`), so a written `matrix4d` is transposed. The
//! ops listed first are outermost: `M = op₀ · op₁ ⋯`, the last op applied to points first. A
//! rotation `rotateXYZ = (a, b, c)` turns about x first, then y, then z:
//! `R = Rz(c) · Ry(b) · Rx(a)`, angles in degrees.
//!
//! A time-sampled op is interpolated as USD does by default, each in its own values: translate,
//! scale, angles and matrices componentwise, `orient` by spherical interpolation of unit
//! quaternions (the shorter way round); before its first sample and after its last it holds
//! them. Samples win over a default.

use glam::{DMat3, DMat4, DQuat, DVec3};

use super::layer::{Prim, Property, Value};
use super::track::{bracket, lerp};

/// A transform that cannot be read, and where.
pub(super) struct XformError {
    pub at: usize,
    pub message: String,
}

/// What an op does.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Translate,
    Scale,
    /// About one axis, `'X'`, `'Y'` or `'Z'`.
    Rotate(char),
    /// About three axes, the first named turning first.
    Euler([char; 3]),
    /// A quaternion `(w, x, y, z)`.
    Orient,
    /// A `matrix4d`, its 16 numbers row by row as written.
    Transform,
}

impl Kind {
    /// How many numbers its value holds.
    #[must_use]
    fn count(self) -> usize {
        match self {
            Kind::Translate | Kind::Scale | Kind::Euler(_) => 3,
            Kind::Rotate(_) => 1,
            Kind::Orient => 4,
            Kind::Transform => 16,
        }
    }
}

/// One op: its values by time (one value when it does not change).
#[derive(Clone, Debug, PartialEq)]
struct Op {
    kind: Kind,
    inverse: bool,
    /// Sorted, distinct; `[0.0]` for an op that does not change.
    times: Vec<f64>,
    values: Vec<Vec<f64>>,
}

/// A prim's transform as its ops, which may change over time.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct LocalXform {
    ops: Vec<Op>,
    /// `!resetXformStack!`: the prim ignores its parents' transforms.
    pub reset: bool,
}

/// The ops of `prim` at `path` (none when it has no `xformOpOrder`), checked: every sample's values finite; the transform at the
/// earliest time invertible; a time-sampled scale or matrix neither inverted nor passing
/// through a flat (zero-determinant) transform between its samples.
pub(super) fn read(prim: &Prim, path: &str) -> Result<LocalXform, XformError> {
    let Some(order) = prim.property("xformOpOrder") else {
        return Ok(LocalXform {
            ops: Vec::new(),
            reset: false,
        });
    };
    let err = |at: usize, message: String| XformError { at, message };
    let order_value = order
        .held_value()
        .map_err(|e| err(e.at, format!("{path}: `xformOpOrder` {}", e.message)))?;
    let names: Vec<String> = match order_value {
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
    let mut ops = Vec::new();
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
        let Some(property) = prim.property(op_name) else {
            return Err(err(
                order.at,
                format!("{path}: xformOpOrder names `{op_name}`, which the prim does not have"),
            ));
        };
        ops.push(read_op(property, op_name, inverse, path)?);
    }
    let x = LocalXform { ops, reset };
    let matrix = x.matrix_first();
    if !matrix.is_finite() || matrix.determinant() == 0.0 {
        return Err(err(
            order.at,
            format!("{path}: the transform flattens the prim (its determinant is 0)"),
        ));
    }
    Ok(x)
}

/// The op `property`, named `op_name` in the order, at `path`.
fn read_op(
    property: &Property,
    op_name: &str,
    inverse: bool,
    path: &str,
) -> Result<Op, XformError> {
    let err = |at: usize, message: String| XformError {
        at,
        message: format!("{path}: `{op_name}` {message}"),
    };
    let kind_name = op_name
        .strip_prefix("xformOp:")
        .map(|rest| rest.split(':').next().unwrap_or(rest))
        .unwrap_or("");
    let axis = |c: char| match c {
        'X' | 'Y' | 'Z' => Some(c),
        _ => None,
    };
    let kind = match kind_name {
        "translate" => Kind::Translate,
        "scale" => Kind::Scale,
        "rotateX" | "rotateY" | "rotateZ" => Kind::Rotate(kind_name.chars().last().unwrap_or('Z')),
        "rotateXYZ" | "rotateXZY" | "rotateYXZ" | "rotateYZX" | "rotateZXY" | "rotateZYX" => {
            let axes: Vec<char> = kind_name["rotate".len()..].chars().filter_map(axis).collect();
            Kind::Euler([axes[0], axes[1], axes[2]])
        }
        "orient" => Kind::Orient,
        "transform" => Kind::Transform,
        _ => {
            return Err(err(
                property.at,
                "is not an op glint reads (translate, scale, rotateX/Y/Z, rotateXYZ and the other orders, orient, transform)".to_string(),
            ))
        }
    };
    let sampled = property.varies();
    let written: Vec<(f64, Option<&Value>, usize)> = if sampled {
        property
            .samples
            .iter()
            .map(|s| (s.time, Some(&s.value), s.at))
            .collect()
    } else {
        vec![(0.0, property.first_value(), property.at)]
    };
    let mut times = Vec::with_capacity(written.len());
    let mut values = Vec::with_capacity(written.len());
    for (time, value, at) in written {
        let numbers = op_numbers(kind, value).map_err(|m| err(at, m))?;
        if kind == Kind::Orient && quaternion(&numbers).length() == 0.0 {
            return Err(err(at, "is a quaternion of no length".to_string()));
        }
        if inverse && !sampled {
            let det = op_matrix(kind, &numbers).determinant();
            if det == 0.0 || !det.is_finite() {
                return Err(err(at, "cannot be inverted".to_string()));
            }
        }
        times.push(time);
        values.push(numbers);
    }
    if sampled {
        let at = property.samples[0].at;
        if inverse && matches!(kind, Kind::Scale | Kind::Transform) {
            return Err(err(at, "is time-sampled and inverted (!invert!); glint inverts a time-sampled translate, rotation or orient only".to_string()));
        }
        for (k, pair) in values.windows(2).enumerate() {
            let flat = match kind {
                Kind::Scale => (0..3).any(|c| pair[0][c] * pair[1][c] <= 0.0),
                Kind::Transform => determinant_reaches_zero(
                    DMat3::from_mat4(op_matrix(kind, &pair[0])),
                    DMat3::from_mat4(op_matrix(kind, &pair[1])),
                ),
                Kind::Translate | Kind::Rotate(_) | Kind::Euler(_) | Kind::Orient => false,
            };
            if flat {
                return Err(err(
                    property.samples[k + 1].at,
                    format!(
                        "flattens the prim between time codes {} and {} (its determinant reaches 0)",
                        times[k],
                        times[k + 1]
                    ),
                ));
            }
        }
    }
    Ok(Op {
        kind,
        inverse,
        times,
        values,
    })
}

/// The numbers of one value of an op of `kind`: a number, a tuple, or a matrix's four rows.
fn op_numbers(kind: Kind, value: Option<&Value>) -> Result<Vec<f64>, String> {
    let n = kind.count();
    let finite = |items: &[Value]| -> Option<Vec<f64>> {
        items
            .iter()
            .map(|v| match v {
                Value::Number(x) if x.is_finite() => Some(*x),
                _ => None,
            })
            .collect()
    };
    if kind == Kind::Transform {
        let Some(Value::Tuple(rows)) = value else {
            return Err("must be a 4 × 4 matrix ((…), (…), (…), (…))".to_string());
        };
        let mut m = Vec::with_capacity(16);
        for row in rows {
            let Value::Tuple(items) = row else {
                return Err("must be a 4 × 4 matrix".to_string());
            };
            if items.len() != 4 {
                return Err("must be a 4 × 4 matrix".to_string());
            }
            m.extend(finite(items).ok_or("must hold finite numbers")?);
        }
        if m.len() != 16 {
            return Err("must be a 4 × 4 matrix ((…), (…), (…), (…))".to_string());
        }
        return Ok(m);
    }
    let out = match value {
        Some(Value::Tuple(items)) if n > 1 && items.len() == n => finite(items),
        Some(Value::Number(x)) if n == 1 && x.is_finite() => Some(vec![*x]),
        _ => None,
    };
    out.ok_or_else(|| format!("must be {n} finite number{}", if n > 1 { "s" } else { "" }))
}

/// The unit quaternion of `orient` numbers `(w, x, y, z)` (not normalized).
#[must_use]
fn quaternion(q: &[f64]) -> DQuat {
    DQuat::from_xyzw(q[1], q[2], q[3], q[0])
}

/// The matrix of an op of `kind` with the numbers `v`, not inverted.
#[must_use]
fn op_matrix(kind: Kind, v: &[f64]) -> DMat4 {
    let axis_rotation = |axis: char, angle: f64| match axis {
        'X' => DMat4::from_rotation_x(angle.to_radians()),
        'Y' => DMat4::from_rotation_y(angle.to_radians()),
        _ => DMat4::from_rotation_z(angle.to_radians()),
    };
    match kind {
        Kind::Translate => DMat4::from_translation(DVec3::new(v[0], v[1], v[2])),
        Kind::Scale => DMat4::from_scale(DVec3::new(v[0], v[1], v[2])),
        Kind::Rotate(axis) => axis_rotation(axis, v[0]),
        Kind::Euler(axes) => {
            // The first named axis turns first: it is the rightmost factor.
            let angle = |axis: char| match axis {
                'X' => v[0],
                'Y' => v[1],
                _ => v[2],
            };
            axes.iter().fold(DMat4::IDENTITY, |m, &axis| {
                axis_rotation(axis, angle(axis)) * m
            })
        }
        Kind::Orient => DMat4::from_quat(quaternion(v).normalize()),
        // Written row by row for row vectors: as columns, it is the column-vector matrix.
        Kind::Transform => {
            let mut m = [0.0; 16];
            m.copy_from_slice(&v[..16]);
            DMat4::from_cols_array(&m)
        }
    }
}

impl Op {
    /// Its numbers at `time`: interpolated between the samples around it, componentwise, or
    /// by spherical interpolation for `orient`; the end samples held outside them.
    #[must_use]
    fn numbers_at(&self, time: f64) -> Vec<f64> {
        let (i, j, s) = bracket(&self.times, time);
        let (a, b) = (&self.values[i], &self.values[j]);
        if i == j || s == 0.0 {
            return a.clone();
        }
        match self.kind {
            Kind::Orient => {
                let q = quaternion(a)
                    .normalize()
                    .slerp(quaternion(b).normalize(), s)
                    .normalize();
                vec![q.w, q.x, q.y, q.z]
            }
            Kind::Translate | Kind::Scale | Kind::Rotate(_) | Kind::Euler(_) | Kind::Transform => {
                a.iter().zip(b).map(|(&x, &y)| lerp(x, y, s)).collect()
            }
        }
    }

    /// Its matrix for the numbers `v`, inverted when the order says `!invert!`.
    #[must_use]
    fn matrix(&self, v: &[f64]) -> DMat4 {
        let m = op_matrix(self.kind, v);
        if self.inverse {
            m.inverse()
        } else {
            m
        }
    }

    /// `(a, b)` with `|M(t)·p| ≤ a·|p| + b` (Euclidean lengths) at every time t.
    #[must_use]
    fn reach(&self) -> (f64, f64) {
        let most = |f: &dyn Fn(&[f64]) -> f64| self.values.iter().map(|v| f(v)).fold(0.0, f64::max);
        match self.kind {
            // Rotations keep lengths, and so do their inverses.
            Kind::Rotate(_) | Kind::Euler(_) | Kind::Orient => (1.0, 0.0),
            // Componentwise interpolation stays within the largest sample (a convex mix).
            Kind::Translate => (1.0, most(&|v| DVec3::new(v[0], v[1], v[2]).length())),
            Kind::Scale | Kind::Transform if self.inverse => {
                // Inverted, these do not change (refused otherwise): their exact matrix.
                let m = self.matrix(&self.values[0]);
                (
                    DMat3::from_mat4(m)
                        .to_cols_array()
                        .iter()
                        .map(|x| x * x)
                        .sum::<f64>()
                        .sqrt(),
                    m.w_axis.truncate().length(),
                )
            }
            Kind::Scale => (most(&|v| v[0].abs().max(v[1].abs()).max(v[2].abs())), 0.0),
            Kind::Transform => {
                // The Frobenius norm bounds the linear part's stretch, and is convex.
                let m = |v: &[f64]| op_matrix(Kind::Transform, v);
                (
                    most(&|v| {
                        DMat3::from_mat4(m(v))
                            .to_cols_array()
                            .iter()
                            .map(|x| x * x)
                            .sum::<f64>()
                            .sqrt()
                    }),
                    most(&|v| m(v).w_axis.truncate().length()),
                )
            }
        }
    }
}

impl LocalXform {
    /// The transform with every op at its earliest sample.
    #[must_use]
    pub fn matrix_first(&self) -> DMat4 {
        let mut matrix = DMat4::IDENTITY;
        for op in &self.ops {
            matrix *= op.matrix(&op.values[0]);
        }
        matrix
    }

    /// The transform at `time`: `op₀(t) · op₁(t) ⋯`.
    #[must_use]
    pub fn matrix_at(&self, time: f64) -> DMat4 {
        let mut matrix = DMat4::IDENTITY;
        for op in &self.ops {
            matrix *= op.matrix(&op.numbers_at(time));
        }
        matrix
    }

    /// Whether an op changes over time.
    #[must_use]
    pub fn varies(&self) -> bool {
        self.ops.iter().any(|op| op.values.len() > 1)
    }

    /// The time codes of the samples of its ops that change.
    pub fn sample_times(&self) -> impl Iterator<Item = f64> + '_ {
        self.ops
            .iter()
            .filter(|op| op.values.len() > 1)
            .flat_map(|op| op.times.iter().copied())
    }

    /// `(a, b)` with `|M(t)·p| ≤ a·|p| + b` at every time t: the ops' bounds composed.
    #[must_use]
    pub fn reach(&self) -> (f64, f64) {
        self.ops.iter().fold((1.0, 0.0), |(a, b), op| {
            let (c, d) = op.reach();
            // |A(C p + d) + b| ≤ a(c|p| + d) + b.
            (a * c, a * d + b)
        })
    }
}

/// Whether `det((1 − s)·a + s·b)` is zero for some s in [0, 1]. The determinant is a cubic in
/// s: from its values at s = 0, ⅓, ⅔, 1 its extremes on [0, 1] are at the ends or where its
/// derivative vanishes, and it reaches zero when they are not all of one strict sign (within
/// 10⁻⁹ of the ends' size).
#[must_use]
fn determinant_reaches_zero(a: DMat3, b: DMat3) -> bool {
    let f = |s: f64| (a * (1.0 - s) + b * s).determinant();
    let (f0, f1, f2, f3) = (f(0.0), f(1.0 / 3.0), f(2.0 / 3.0), f(1.0));
    // The cubic c₀ + c₁s + c₂s² + c₃s³ through those four values (Newton's divided differences
    // on s = 0, ⅓, ⅔, 1).
    let c3 = 4.5 * (f3 - 3.0 * f2 + 3.0 * f1 - f0);
    let c2 = 4.5 * (f2 - 2.0 * f1 + f0) - c3;
    let c1 = 3.0 * (f1 - f0) - c2 / 3.0 - c3 / 9.0;
    let cubic = |s: f64| f0 + s * (c1 + s * (c2 + s * c3));
    // Critical points: c₁ + 2c₂s + 3c₃s² = 0, solved without cancellation:
    // q = −(b + sign(b)·√(b² − 4ac))/2, s = q/a and s = c/q.
    let mut at = vec![0.0, 1.0];
    let (qa, qb, qc) = (3.0 * c3, 2.0 * c2, c1);
    let disc = qb * qb - 4.0 * qa * qc;
    if disc >= 0.0 {
        let q = -0.5 * (qb + qb.signum() * disc.sqrt());
        if q != 0.0 {
            at.push(qc / q);
            if qa != 0.0 {
                at.push(q / qa);
            }
        }
    }
    let values: Vec<f64> = at
        .into_iter()
        .filter(|s| (0.0..=1.0).contains(s))
        .map(cubic)
        .collect();
    // Within rounding of zero, relative to the ends, counts as zero.
    let zero = 1e-9 * f0.abs().max(f3.abs());
    !(values.iter().all(|&v| v > zero) || values.iter().all(|&v| v < -zero))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_matrix_turning_through_a_mirror_reaches_zero_and_a_rotation_does_not() {
        let identity = DMat3::IDENTITY;
        let mirror = DMat3::from_diagonal(DVec3::new(-1.0, 1.0, 1.0));
        assert!(determinant_reaches_zero(identity, mirror));
        // det((1−s)I + s·R₁₈₀) about z: (1−2s)² ≥ 0 touches 0 at s = ½.
        let half_turn = DMat3::from_rotation_z(std::f64::consts::PI);
        assert!(determinant_reaches_zero(identity, half_turn));
        let quarter = DMat3::from_rotation_z(std::f64::consts::FRAC_PI_2);
        assert!(!determinant_reaches_zero(identity, quarter));
        assert!(!determinant_reaches_zero(identity, identity * 3.0));
    }

    #[test]
    fn orient_samples_turn_by_slerp_the_short_way() {
        // A quarter turn about z, then its negative quaternion (the same rotation): halfway is
        // an eighth turn, not the long way round.
        let q1 = DQuat::from_rotation_z(std::f64::consts::FRAC_PI_2);
        let op = Op {
            kind: Kind::Orient,
            inverse: false,
            times: vec![0.0, 10.0],
            values: vec![vec![1.0, 0.0, 0.0, 0.0], vec![-q1.w, -q1.x, -q1.y, -q1.z]],
        };
        let m = op.matrix(&op.numbers_at(5.0));
        let p = m.transform_point3(DVec3::X);
        let angle = p.y.atan2(p.x);
        assert!(
            (angle - std::f64::consts::FRAC_PI_4).abs() < 1e-12,
            "{angle}"
        );
    }
}
