//! A `NurbsPatch` prim as a [`NurbsSurface`]: `uVertexCount × vVertexCount` control points,
//! row-major with u varying fastest (`points[v · uVertexCount + u]`), orders (degree + 1),
//! knot vectors of `count + order` knots — or `count + order − 2`, Maya's own count without the
//! end knots, which are then repeated — optional `pointWeights`, and ranges that must be the
//! knots' whole domain. Its `points` may be time-sampled, each sample a whole net; the other
//! attributes may be time-sampled only with one value in every sample (and `pointWeights` not).

use glam::DVec3;

use super::layer::{Prim, Property, Value};
use crate::geom::{NurbsSurface, MAX_DEGREE};

/// A patch that cannot be built, and where.
pub(super) struct PatchError {
    pub at: usize,
    pub message: String,
}

/// A `NurbsPatch` as read.
pub(super) struct PatchRead {
    /// The surface, its points at their earliest sample.
    pub surface: NurbsSurface,
    /// When the patch is left-handed (its v reversed to make it right-handed), the first and
    /// last of its v knots, about whose middle v was mirrored.
    pub mirrored: Option<(f64, f64)>,
    /// The time samples of its points, each in the order of `NurbsSurface::control_points`,
    /// when they hold more than one value; else empty.
    pub samples: Vec<(f64, Vec<DVec3>)>,
}

/// The `NurbsPatch` prim `prim` at `path`, read.
pub(super) fn surface(prim: &Prim, path: &str) -> Result<PatchRead, PatchError> {
    let err = |at: usize, message: String| PatchError {
        at,
        message: format!("{path}: {message}"),
    };
    let required = |name: &str| -> Result<&Property, PatchError> {
        prim.property(name)
            .ok_or_else(|| err(prim.at, format!("the NurbsPatch has no `{name}`")))
    };
    for p in &prim.properties {
        if p.type_name.ends_with(".connect") && is_read(&p.name) {
            return Err(err(
                p.at,
                format!(
                    "`{}` is connected to another attribute; glint reads written values only",
                    p.name
                ),
            ));
        }
    }
    // Time samples of an attribute read as one value must agree: refused at the first that
    // differs.
    let held = |p: &Property| -> Result<(), PatchError> {
        p.held_value()
            .map(|_| ())
            .map_err(|e| err(e.at, format!("`{}` {}", p.name, e.message)))
    };
    let count = |name: &str| -> Result<usize, PatchError> {
        let p = required(name)?;
        match p
            .held_value()
            .map_err(|e| err(e.at, format!("`{name}` {}", e.message)))?
        {
            Some(&Value::Number(n)) if n.fract() == 0.0 && (1.0..=1e6).contains(&n) => {
                Ok(n as usize)
            }
            _ => Err(err(
                p.at,
                format!("`{name}` must be a whole number from 1 to 10⁶"),
            )),
        }
    };
    let (nu, nv) = (count("uVertexCount")?, count("vVertexCount")?);
    let order = |name: &str, vertices: usize| -> Result<usize, PatchError> {
        let p = required(name)?;
        let o = count(name)?;
        if !(2..=MAX_DEGREE + 1).contains(&o) {
            return Err(err(
                p.at,
                format!("`{name}` {o} is outside the orders glint evaluates, 2 to {} (degree 1 to {MAX_DEGREE})", MAX_DEGREE + 1),
            ));
        }
        if o > vertices {
            return Err(err(
                p.at,
                format!("`{name}` {o} is more than the {vertices} vertices along it"),
            ));
        }
        Ok(o)
    };
    let (ou, ov) = (order("uOrder", nu)?, order("vOrder", nv)?);
    let knots = |name: &str, vertices: usize, order: usize| -> Result<Vec<f64>, PatchError> {
        let p = required(name)?;
        held(p)?;
        let mut k = numbers(p).map_err(|m| err(p.at, format!("`{name}` {m}")))?;
        if k.len() + 2 == vertices + order && !k.is_empty() {
            repeat_end_knots(&mut k);
        }
        if k.len() != vertices + order {
            return Err(err(
                p.at,
                format!("`{name}` has {} knots; {vertices} vertices of order {order} take {} (or {}, without the end knots)", k.len(), vertices + order, vertices + order - 2),
            ));
        }
        if let Some(at) = first_decrease(&k) {
            return Err(err(p.at, format!("`{name}` decreases {at}")));
        }
        if k[order - 1] >= k[vertices] {
            return Err(err(
                p.at,
                format!(
                    "`{name}` spans no parameter range (knots {} to {} are equal)",
                    order - 1,
                    vertices
                ),
            ));
        }
        Ok(k)
    };
    let (ku, kv) = (knots("uKnots", nu, ou)?, knots("vKnots", nv, ov)?);
    for (name, k, vertices, order) in [("uRange", &ku, nu, ou), ("vRange", &kv, nv, ov)] {
        if let Some(p) = prim.property(name) {
            held(p)?;
            let r = numbers(p).map_err(|m| err(p.at, format!("`{name}` {m}")))?;
            let (lo, hi) = (k[order - 1], k[vertices]);
            let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * (1.0 + lo.abs().max(hi.abs()));
            if r.len() != 2 || !close(r[0], lo) || !close(r[1], hi) {
                return Err(err(
                    p.at,
                    format!("`{name}` {r:?} is not the knots' domain ({lo}, {hi}); glint draws a patch over its knots' whole domain — re-knot the patch to its range, or trim it with `trimCurve:*`"),
                ));
            }
        }
    }
    let points_property = required("points")?;
    let net_of = |value: Option<&Value>, at: usize| -> Result<Vec<DVec3>, PatchError> {
        let points = vectors_of(value).map_err(|m| err(at, format!("`points` {m}")))?;
        if points.len() != nu * nv {
            return Err(err(
                at,
                format!(
                    "`points` has {} points; uVertexCount × vVertexCount is {nu} × {nv} = {}",
                    points.len(),
                    nu * nv
                ),
            ));
        }
        Ok(points)
    };
    let points = match points_property.samples.first() {
        None => net_of(points_property.default.as_ref(), points_property.at)?,
        Some(first) => net_of(Some(&first.value), first.at)?,
    };
    let mut sampled = Vec::new();
    if points_property.varies() {
        for s in &points_property.samples {
            sampled.push((s.time, net_of(Some(&s.value), s.at)?));
        }
    }
    let weights = match prim.property("pointWeights") {
        None => None,
        Some(p) if !p.samples.is_empty() => {
            return Err(err(
                p.at,
                "`pointWeights` is time-sampled; glint animates `points` only, with weights that do not change".to_string(),
            ))
        }
        Some(p) => {
            let w = numbers(p).map_err(|m| err(p.at, format!("`pointWeights` {m}")))?;
            if w.is_empty() {
                None
            } else if w.len() != nu * nv {
                return Err(err(
                    p.at,
                    format!(
                        "`pointWeights` has {} weights for {} points",
                        w.len(),
                        nu * nv
                    ),
                ));
            } else {
                Some(w)
            }
        }
    };
    let orientation = match prim.property("orientation") {
        None => None,
        Some(p) => p
            .held_value()
            .map_err(|e| err(e.at, format!("`orientation` {}", e.message)))?,
    };
    let left_handed = matches!(orientation, Some(Value::Str(s)) if s == "leftHanded");
    // glint's net is rows along u, each running along v.
    let net: Vec<Vec<DVec3>> = (0..nu)
        .map(|i| (0..nv).map(|j| points[j * nu + i]).collect())
        .collect();
    let weight_net: Option<Vec<Vec<f64>>> = weights.as_ref().map(|w| {
        (0..nu)
            .map(|i| (0..nv).map(|j| w[j * nu + i]).collect())
            .collect()
    });
    let mirrored = left_handed.then(|| (kv[0], kv[kv.len() - 1]));
    let (net, weight_net, kv) = if let Some((lo, hi)) = mirrored {
        // The other side is the front: v runs the other way.
        let flipped: Vec<f64> = kv.iter().rev().map(|&k| lo + hi - k).collect();
        let reverse = |rows: Vec<Vec<DVec3>>| {
            rows.into_iter()
                .map(|r| r.into_iter().rev().collect())
                .collect()
        };
        let reverse_w = |rows: Vec<Vec<f64>>| {
            rows.into_iter()
                .map(|r| r.into_iter().rev().collect())
                .collect()
        };
        (reverse(net), weight_net.map(reverse_w), flipped)
    } else {
        (net, weight_net, kv)
    };
    let surface = NurbsSurface::new(ou - 1, ov - 1, ku, kv, &net, weight_net.as_deref())
        .map_err(|e| err(points_property.at, e.to_string()))?;
    let samples = sampled
        .into_iter()
        .map(|(time, points)| {
            (
                time,
                control_point_order(&points, nu, nv, mirrored.is_some()),
            )
        })
        .collect();
    Ok(PatchRead {
        surface,
        mirrored,
        samples,
    })
}

/// USD's `points` (`points[v · nu + u]`, u varying fastest) in the order of
/// `NurbsSurface::control_points`: `(i, j)` at `i · nv + j`, i along u, j along v — with j
/// running backwards when the patch was `mirrored` in v.
#[must_use]
fn control_point_order(points: &[DVec3], nu: usize, nv: usize, mirrored: bool) -> Vec<DVec3> {
    let mut out = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            let row = if mirrored { nv - 1 - j } else { j };
            out.push(points[row * nu + i]);
        }
    }
    out
}

/// Maya's knot vector, which leaves out the end knots, made whole: its first and last knots
/// repeated once more.
pub(super) fn repeat_end_knots(knots: &mut Vec<f64>) {
    if let (Some(&first), Some(&last)) = (knots.first(), knots.last()) {
        knots.insert(0, first);
        knots.push(last);
    }
}

/// Where `knots` first decrease, as `at knot i: kᵢ after kᵢ₋₁`; None when they never do.
pub(super) fn first_decrease(knots: &[f64]) -> Option<String> {
    let w = knots.windows(2).position(|w| w[1] < w[0])?;
    Some(format!(
        "at knot {}: {} after {}",
        w + 1,
        knots[w + 1],
        knots[w]
    ))
}

/// Whether glint reads the attribute `name` of a NurbsPatch.
fn is_read(name: &str) -> bool {
    matches!(
        name,
        "uVertexCount"
            | "vVertexCount"
            | "uOrder"
            | "vOrder"
            | "uKnots"
            | "vKnots"
            | "uRange"
            | "vRange"
            | "points"
            | "pointWeights"
            | "orientation"
    ) || name.starts_with("xformOp")
        || name.starts_with("trimCurve:")
}

/// The numbers of a list or tuple of numbers, the property's value at every time.
pub(super) fn numbers(p: &Property) -> Result<Vec<f64>, String> {
    let items = match p.held_value().map_err(|e| e.message)? {
        Some(Value::List(items) | Value::Tuple(items)) => items,
        _ => return Err("must be a list of numbers".to_string()),
    };
    items
        .iter()
        .map(|v| match v {
            Value::Number(x) if x.is_finite() => Ok(*x),
            Value::Number(_) => Err("must hold finite numbers".to_string()),
            _ => Err("must be a list of numbers".to_string()),
        })
        .collect()
}

/// The points of a list of `(x, y, z)`, the property's value at every time.
pub(super) fn vectors(p: &Property) -> Result<Vec<DVec3>, String> {
    vectors_of(p.held_value().map_err(|e| e.message)?)
}

/// The points of `value`, a list of `(x, y, z)`.
fn vectors_of(value: Option<&Value>) -> Result<Vec<DVec3>, String> {
    let Some(Value::List(items)) = value else {
        return Err("must be a list of (x, y, z) points".to_string());
    };
    items
        .iter()
        .map(|v| match v {
            Value::Tuple(c) if c.len() == 3 => {
                let mut xyz = [0.0; 3];
                for (k, value) in c.iter().enumerate() {
                    match value {
                        Value::Number(x) if x.is_finite() => xyz[k] = *x,
                        _ => return Err("must hold finite numbers".to_string()),
                    }
                }
                Ok(DVec3::from_array(xyz))
            }
            _ => Err("must be a list of (x, y, z) points".to_string()),
        })
        .collect()
}
