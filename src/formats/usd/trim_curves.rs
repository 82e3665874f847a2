//! A `NurbsPatch` prim's `trimCurve:*` attributes as a [`Trim`]: loops of rational B-spline
//! curves in (u, v), each loop closed head to tail, followed by polylines.

use std::sync::Arc;

use glam::{DVec2, DVec3};

use super::layer::{Prim, Property, Value};
use super::nurbs_patch::{first_decrease, numbers, repeat_end_knots, vectors, PatchError};
use crate::geom::{Domain, Trim, TrimCurve, MAX_DEGREE, MAX_TRIM_SEGMENTS};

/// How closely a polyline follows its trim curve, as a fraction of the domain's larger side: a
/// thousandth of a pixel on a patch 100 pixels across.
const FOLLOW: f64 = 1e-5;

/// How near one curve's end must be to the next one's start, as a fraction of the domain's
/// larger side.
const JOIN: f64 = 1e-6;

/// The most trim curves a patch may have.
const MAX_CURVES: usize = 100_000;

/// The trim of the `NurbsPatch` prim `prim` at `path` over `domain`, or None when it writes no
/// trim curves (or only empty ones). `flip_v` is the patch's v range when v was reversed to
/// make a left-handed patch right-handed: the curves' v is reversed with it, and their loops'
/// directions, so the trim keeps what it kept.
pub(super) fn trim(
    prim: &Prim,
    path: &str,
    domain: Domain,
    flip_v: Option<(f64, f64)>,
) -> Result<Option<Arc<Trim>>, PatchError> {
    let err = |at: usize, message: String| PatchError {
        at,
        message: format!("{path}: {message}"),
    };
    let written = |name: &str| {
        prim.property(name)
            .filter(|p| !matches!(p.first_value(), Some(Value::List(items)) if items.is_empty()))
    };
    let counts_property = match written("trimCurve:counts") {
        Some(p) => p,
        None => {
            let other = [
                "trimCurve:orders",
                "trimCurve:vertexCounts",
                "trimCurve:knots",
                "trimCurve:ranges",
                "trimCurve:points",
            ]
            .into_iter()
            .find_map(written);
            return match other {
                Some(p) => Err(err(
                    p.at,
                    format!(
                        "`{}` is written but `trimCurve:counts` is not: the trim has no loops",
                        p.name
                    ),
                )),
                None => Ok(None),
            };
        }
    };
    let required = |name: &str| -> Result<&Property, PatchError> {
        written(name).ok_or_else(|| {
            err(
                counts_property.at,
                format!("the patch is trimmed but has no `{name}`"),
            )
        })
    };
    let whole = |p: &Property, least: usize| -> Result<Vec<usize>, PatchError> {
        let values = numbers(p).map_err(|m| err(p.at, format!("`{}` {m}", p.name)))?;
        values
            .iter()
            .map(|&x| {
                if x.fract() == 0.0 && x >= least as f64 && x <= MAX_TRIM_SEGMENTS as f64 {
                    Ok(x as usize)
                } else {
                    Err(err(
                        p.at,
                        format!(
                            "`{}` holds {x}; each must be a whole number from {least} to {MAX_TRIM_SEGMENTS}",
                            p.name
                        ),
                    ))
                }
            })
            .collect()
    };
    let counts = whole(counts_property, 1)?;
    let curves: usize = counts.iter().sum();
    if curves > MAX_CURVES {
        return Err(err(
            counts_property.at,
            format!("the trim has {curves} curves, more than the {MAX_CURVES} glint reads"),
        ));
    }
    let per_curve = |p: &Property, values: usize| -> Result<(), PatchError> {
        if values == curves {
            Ok(())
        } else {
            Err(err(
                p.at,
                format!(
                    "`{}` has {values} entries; `trimCurve:counts` makes {curves} curves",
                    p.name
                ),
            ))
        }
    };
    let orders_property = required("trimCurve:orders")?;
    let orders = whole(orders_property, 1)?;
    per_curve(orders_property, orders.len())?;
    if let Some(&o) = orders.iter().find(|&&o| !(2..=MAX_DEGREE + 1).contains(&o)) {
        return Err(err(
            orders_property.at,
            format!(
                "a trim curve has order {o}; glint evaluates orders 2 to {}",
                MAX_DEGREE + 1
            ),
        ));
    }
    let vertex_property = required("trimCurve:vertexCounts")?;
    let vertex_counts = whole(vertex_property, 1)?;
    per_curve(vertex_property, vertex_counts.len())?;
    if let Some(c) = (0..curves).find(|&c| vertex_counts[c] < orders[c]) {
        return Err(err(
            vertex_property.at,
            format!(
                "trim curve {c} has {} vertices, fewer than its order {}",
                vertex_counts[c], orders[c]
            ),
        ));
    }
    let knots_property = required("trimCurve:knots")?;
    let knots = numbers(knots_property)
        .map_err(|m| err(knots_property.at, format!("`trimCurve:knots` {m}")))?;
    let full: usize = (0..curves).map(|c| vertex_counts[c] + orders[c]).sum();
    // Maya's count leaves out each curve's two end knots.
    let maya = knots.len() + 2 * curves == full;
    if knots.len() != full && !maya {
        return Err(err(
            knots_property.at,
            format!(
                "`trimCurve:knots` has {} knots; the curves' vertices and orders take {full} (or {}, without the end knots)",
                knots.len(),
                full - 2 * curves
            ),
        ));
    }
    let points_property = required("trimCurve:points")?;
    let points = vectors(points_property)
        .map_err(|m| err(points_property.at, format!("`trimCurve:points` {m}")))?;
    let vertices: usize = vertex_counts.iter().sum();
    if points.len() != vertices {
        return Err(err(
            points_property.at,
            format!(
                "`trimCurve:points` has {} points; `trimCurve:vertexCounts` adds up to {vertices}",
                points.len()
            ),
        ));
    }
    let ranges = match written("trimCurve:ranges") {
        None => None,
        Some(p) => {
            let r = numbers_of_pairs(p).map_err(|m| err(p.at, m))?;
            per_curve(p, r.len())?;
            Some((p, r))
        }
    };

    let side = (domain.u.1 - domain.u.0).max(domain.v.1 - domain.v.0);
    let (mut next_knot, mut next_point) = (0, 0);
    let mut built = Vec::with_capacity(curves);
    for c in 0..curves {
        let (n, order) = (vertex_counts[c], orders[c]);
        let take = if maya { n + order - 2 } else { n + order };
        let mut k = knots[next_knot..next_knot + take].to_vec();
        next_knot += take;
        if maya {
            repeat_end_knots(&mut k);
        }
        if let Some(at) = first_decrease(&k) {
            return Err(err(
                knots_property.at,
                format!("the knots of trim curve {c} decrease {at}"),
            ));
        }
        let homogeneous: Vec<DVec3> = points[next_point..next_point + n]
            .iter()
            .map(|&p| match flip_v {
                Some((lo, hi)) => DVec3::new(p.x, (lo + hi) * p.z - p.y, p.z),
                None => p,
            })
            .collect();
        next_point += n;
        let domain_of_knots = (k[order - 1], k[n]);
        let range = match &ranges {
            None => domain_of_knots,
            Some((p, r)) => {
                let (lo, hi) = r[c];
                let slack = 1e-9 * (1.0 + domain_of_knots.0.abs().max(domain_of_knots.1.abs()));
                if lo < domain_of_knots.0 - slack || hi > domain_of_knots.1 + slack || lo >= hi {
                    return Err(err(
                        p.at,
                        format!(
                            "trim curve {c} has the range ({lo}, {hi}), which is not within its knots' domain ({}, {})",
                            domain_of_knots.0, domain_of_knots.1
                        ),
                    ));
                }
                (lo.max(domain_of_knots.0), hi.min(domain_of_knots.1))
            }
        };
        let curve = TrimCurve::new(order, k, homogeneous, range)
            .map_err(|e| err(points_property.at, format!("trim curve {c}: {e}")))?;
        built.push(curve);
    }

    let mut loops = Vec::with_capacity(counts.len());
    let mut first = 0;
    for (l, &count) in counts.iter().enumerate() {
        let curves = &built[first..first + count];
        first += count;
        let mut polyline = vec![curves[0].ends()[0]];
        for (c, curve) in curves.iter().enumerate() {
            let [start, _] = curve.ends();
            let here = *polyline.last().unwrap_or(&start);
            if (start - here).length() > JOIN * side {
                return Err(err(
                    points_property.at,
                    format!(
                        "trim loop {l} is not closed: its curve {} ends at {} but the next begins at {}",
                        c - 1,
                        show(here),
                        show(start)
                    ),
                ));
            }
            curve.follow(FOLLOW * side, &mut polyline);
            if polyline.len() > MAX_TRIM_SEGMENTS {
                return Err(err(
                    points_property.at,
                    format!("the trim's loops need more than {MAX_TRIM_SEGMENTS} segments"),
                ));
            }
        }
        let (start, end) = (polyline[0], polyline[polyline.len() - 1]);
        if (start - end).length() > JOIN * side {
            return Err(err(
                points_property.at,
                format!(
                    "trim loop {l} is not closed: it ends at {} but begins at {}; each loop must return to where it starts",
                    show(end),
                    show(start)
                ),
            ));
        }
        let last = polyline.len() - 1;
        polyline[last] = start;
        if flip_v.is_some() {
            polyline.reverse();
        }
        loops.push(polyline);
    }
    Trim::new(loops, domain)
        .map(|t| Some(Arc::new(t)))
        .map_err(|e| err(points_property.at, e.to_string()))
}

/// `(u, v)` with the digits that tell points apart.
fn show(p: DVec2) -> String {
    format!("({:.6}, {:.6})", p.x, p.y)
}

/// The pairs of a list of `(a, b)`.
fn numbers_of_pairs(p: &Property) -> Result<Vec<(f64, f64)>, String> {
    let bad = || {
        format!(
            "`{}` must be a list of (min, max) pairs of finite numbers",
            p.name
        )
    };
    let Some(Value::List(items)) = p
        .held_value()
        .map_err(|e| format!("`{}` {}", p.name, e.message))?
    else {
        return Err(bad());
    };
    items
        .iter()
        .map(|v| match v {
            Value::Tuple(c) => match c.as_slice() {
                [Value::Number(a), Value::Number(b)] if a.is_finite() && b.is_finite() => {
                    Ok((*a, *b))
                }
                _ => Err(bad()),
            },
            _ => Err(bad()),
        })
        .collect()
}
