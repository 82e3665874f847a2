//! Every centre of a highlight layer: each local minimum of `‖N − H'‖` on each patch it is
//! drawn on, where the highlight shows — one per blob of highlight, so that a layer that shows
//! twice on a patch (on a lid whose normals repeat along a radius, on an S-bend) is reported
//! twice.

use glam::Vec2;

use super::pixel_of::PointInImage;
use crate::geom::Domain;
use crate::highlight::{Footprint, HighlightError, Layer, Shape};
use crate::shot::{FrameState, Shot};

/// A centre of a layer's highlight on one patch.
#[derive(Clone, Debug, PartialEq)]
pub struct Centre {
    /// The patch (index into the shot's library).
    pub patch: usize,
    /// Where on the patch.
    pub uv: (f64, f64),
    /// `‖N − H'‖² / 2` there: 0 where `N = H'`.
    pub nearest: f32,
    /// Whether the eye sees the patch's back there: shading turns the frame toward the eye,
    /// so the layer has a centre of its own on each side of a two-sided surface.
    pub back: bool,
    /// Where it lands in the frame, and whether the frame shows it.
    pub pixel: Option<PointInImage>,
}

/// A least point found on a patch, before centres at one point are merged.
struct Found {
    patch: usize,
    uv: (f64, f64),
    /// `‖N − H'‖² / 2` there.
    value: f32,
    /// Where it is in space.
    point: glam::DVec3,
    /// Whether it lies on its patch's domain's edge.
    edge: bool,
    /// Whether it is the point the layer was placed on.
    placed: bool,
}

/// Samples per side of the grid each patch is searched on.
pub(super) const GRID: usize = 33;

/// Steps of the compass search that refines each minimum of the grid.
const REFINE_STEPS: usize = 60;

/// Samples along the segment between two minima of one patch that tell whether the highlight
/// joins them.
const JOIN_SAMPLES: usize = 24;

/// Two centres closer than this, relative to the model's extent, are one point (the same
/// centre found from both sides of a seam, or at both ends of a closed patch's domain).
const SAME_POINT: f64 = 1e-6;

/// A refined uv this close to its domain's edge (relative to the domain's size) lies on it.
const ON_EDGE: f64 = 1e-9;

/// The centres of `layer` (of highlight entry `entry`) at the frame `state` poses, on every
/// patch the entry is drawn on, the deepest first. On each patch: every sample of a 33 × 33 grid
/// over its domain no higher than its eight neighbours, refined by a compass search, where the
/// highlight shows (`‖N − H'‖²/2 < ε`, measured as the disc's for a drawn shape, whose own
/// outline must cover it) and the layer's mask keeps it; minima the highlight joins — in one
/// blob of the grid's samples where it shows, or showing all along the straight (u, v) segment
/// between them — are one centre, the deeper. A minimum on the edge of
/// its patch's domain is a centre only where the patch closes on itself there and a minimum
/// from its other end lies at the same point (the seam of a sphere): otherwise it is the
/// highlight spilling over from a neighbouring patch, whose own frame places its centre, or a
/// highlight whose centre is off the surface. Centres at one point are one. Pixels are left to
/// the caller. `placed`, the point the layer was placed on (a centre by construction), stands
/// for its blob and is listed first; the others follow, the deepest first.
pub(crate) fn centres(
    shot: &Shot,
    (entry, layer): (usize, &Layer),
    state: &FrameState,
    placed: Option<(usize, (f64, f64))>,
) -> Result<Vec<Centre>, HighlightError> {
    let prepared = layer.prepare()?;
    let disc = Layer {
        shape: Shape::Disc,
        ..layer.clone()
    }
    .prepare()?;
    let mut found: Vec<Found> = Vec::new();
    for (patch, named) in state.library.patches.iter().enumerate() {
        if shot.highlight_of(patch) != Some(entry) {
            continue;
        }
        let domain = named.surface.domain();
        let distance = |uv: (f64, f64)| {
            let point = shot.highlight_point(state, patch, uv);
            layer.epsilon - disc.signed(&point.frame, point.half_vector)
        };
        // Where the layer paints: inside its shape, and where its mask keeps it.
        let shows = |uv: (f64, f64)| {
            let point = shot.highlight_point(state, patch, uv);
            let at = Vec2::new(uv.0 as f32, uv.1 as f32);
            prepared.shape(&point.frame, at, point.half_vector, Footprint::HARD) > 0.0
        };
        let last = (GRID - 1) as f64;
        let values: Vec<f32> = (0..GRID * GRID)
            .map(|k| distance(domain.lerp((k / GRID) as f64 / last, (k % GRID) as f64 / last)))
            .collect();
        // The grid's blobs: samples where the highlight's disc shows, 8-connected.
        let blob = grid_blobs(&values, layer.epsilon);
        // The blob of the sample nearest `uv`, or of sample `fallback` when that one is outside.
        let blob_of = |uv: (f64, f64), fallback: Option<usize>| {
            let (x, y) = domain.unlerp(uv);
            let nearest = (x * last).round().clamp(0.0, last) as usize * GRID
                + (y * last).round().clamp(0.0, last) as usize;
            blob[nearest].or(fallback.and_then(|k| blob[k]))
        };
        let mut minima: Vec<((f64, f64), f32, Option<usize>)> = Vec::new();
        for i in 0..GRID {
            for j in 0..GRID {
                let value = values[i * GRID + j];
                if !value.is_finite() {
                    continue;
                }
                let lowest = (-1i64..=1).all(|di| {
                    (-1i64..=1).all(|dj| {
                        let (a, b) = (i as i64 + di, j as i64 + dj);
                        !(0..GRID as i64).contains(&a)
                            || !(0..GRID as i64).contains(&b)
                            || values[a as usize * GRID + b as usize] >= value
                    })
                });
                if lowest {
                    // A highlight narrower than the grid's step may show between its samples:
                    // every minimum of the grid is refined, and kept where it shows.
                    let uv = domain.lerp(i as f64 / last, j as f64 / last);
                    let refined = refine(&distance, domain, (uv, value));
                    if refined.1 < layer.epsilon {
                        minima.push((refined.0, refined.1, blob_of(refined.0, Some(i * GRID + j))));
                    }
                }
            }
        }
        minima.sort_by(|a, b| a.1.total_cmp(&b.1));
        let mut kept: Vec<((f64, f64), f32, Option<usize>)> = Vec::new();
        // The placed point first: the minima its blob holds are joined to it.
        let placed_here = placed.filter(|&(p, _)| p == patch).map(|(_, uv)| uv);
        if let Some(uv) = placed_here {
            minima.insert(0, (uv, distance(uv), blob_of(uv, None)));
        }
        for (uv, value, blob) in minima {
            // Joined: in one blob of the grid, or, for a highlight narrower than the grid's
            // step, showing all along the straight (u, v) segment between them.
            let joined = kept.iter().any(|&(other, _, other_blob)| {
                (blob.is_some() && blob == other_blob)
                    || (0..=JOIN_SAMPLES).all(|k| {
                        let t = k as f64 / JOIN_SAMPLES as f64;
                        let at = (uv.0 + (other.0 - uv.0) * t, uv.1 + (other.1 - uv.1) * t);
                        distance(at) < layer.epsilon
                    })
            });
            if !joined && shows(uv) {
                kept.push((uv, value, blob));
            }
        }
        for (uv, value, _) in kept {
            let point = named.surface.point(uv.0, uv.1);
            let (du, dv) = (domain.u.1 - domain.u.0, domain.v.1 - domain.v.0);
            let edge = uv.0 - domain.u.0 <= ON_EDGE * du
                || domain.u.1 - uv.0 <= ON_EDGE * du
                || uv.1 - domain.v.0 <= ON_EDGE * dv
                || domain.v.1 - uv.1 <= ON_EDGE * dv;
            let first = placed_here == Some(uv);
            found.push(Found {
                patch,
                uv,
                value,
                point,
                edge: edge && !first,
                placed: first,
            });
        }
    }
    let extent = found
        .iter()
        .fold(1.0f64, |m, f| m.max(f.point.abs().max_element()));
    let same = |a: glam::DVec3, b: glam::DVec3| a.distance(b) <= SAME_POINT * extent;
    found.sort_by(|a, b| b.placed.cmp(&a.placed).then(a.value.total_cmp(&b.value)));
    let mut out: Vec<Centre> = Vec::new();
    let mut points: Vec<glam::DVec3> = Vec::new();
    for (k, f) in found.iter().enumerate() {
        let (patch, uv, value, point, edge) = (f.patch, f.uv, f.value, f.point, f.edge);
        if points.iter().any(|&p| same(p, point)) {
            continue;
        }
        let met_across = found
            .iter()
            .enumerate()
            .any(|(m, other)| m != k && other.patch == patch && same(other.point, point));
        if edge && !met_across {
            continue;
        }
        points.push(point);
        let raw = state.library.patches[patch]
            .surface
            .frame(uv.0, uv.1)
            .normal;
        let seen = shot.highlight_point(state, patch, uv).frame.n;
        out.push(Centre {
            patch,
            uv,
            nearest: value.max(0.0),
            back: raw.dot(seen.as_dvec3()) < 0.0,
            pixel: None,
        });
    }
    Ok(out)
}

/// The 8-connected blobs of the grid samples (row `i` along u, column `j` along v) whose
/// `‖N − H'‖²/2` is below `epsilon`: each sample's blob, None outside.
fn grid_blobs(values: &[f32], epsilon: f32) -> Vec<Option<usize>> {
    let mut blob = vec![None; values.len()];
    let mut count = 0;
    for start in 0..values.len() {
        if values[start] >= epsilon || blob[start].is_some() {
            continue;
        }
        blob[start] = Some(count);
        let mut stack = vec![start];
        while let Some(k) = stack.pop() {
            let (i, j) = ((k / GRID) as i64, (k % GRID) as i64);
            for (di, dj) in [
                (-1, -1),
                (-1, 0),
                (-1, 1),
                (0, -1),
                (0, 1),
                (1, -1),
                (1, 0),
                (1, 1),
            ] {
                let (a, b) = (i + di, j + dj);
                if !(0..GRID as i64).contains(&a) || !(0..GRID as i64).contains(&b) {
                    continue;
                }
                let m = a as usize * GRID + b as usize;
                if values[m] < epsilon && blob[m].is_none() {
                    blob[m] = Some(count);
                    stack.push(m);
                }
            }
        }
        count += 1;
    }
    blob
}

/// A compass search down `distance` from `(uv, value)` over `domain`, from a step of a 32nd of
/// the domain: a step along ±u or ±v that lowers it is taken, and the step halves when none
/// does, 60 times.
pub(super) fn refine(
    distance: &dyn Fn((f64, f64)) -> f32,
    domain: Domain,
    mut best: ((f64, f64), f32),
) -> ((f64, f64), f32) {
    let last = (GRID - 1) as f64;
    let mut step = (
        (domain.u.1 - domain.u.0) / last,
        (domain.v.1 - domain.v.0) / last,
    );
    for _ in 0..REFINE_STEPS {
        let (u, v) = best.0;
        let better = [(step.0, 0.0), (-step.0, 0.0), (0.0, step.1), (0.0, -step.1)]
            .into_iter()
            .map(|(du, dv)| {
                let uv = (
                    (u + du).clamp(domain.u.0, domain.u.1),
                    (v + dv).clamp(domain.v.0, domain.v.1),
                );
                (uv, distance(uv))
            })
            .find(|candidate| candidate.1 < best.1);
        match better {
            Some(candidate) => best = candidate,
            None => step = (step.0 / 2.0, step.1 / 2.0),
        }
    }
    best
}
