//! How the patches of a USD layer move: each patch's control points at any time code, from its
//! time-sampled `points` and the time-sampled xformOps of its prim and its ancestors.
//!
//! A patch's world transform at time t is `N(t) · S`: `S` the product of the unchanging
//! transforms below its nearest changing ancestor, `N(t)` that ancestor's world transform,
//! `N(t) = N_parent(t) · F · L(t)` with `F` the unchanging transforms between the two and
//! `L(t)` its own ops at t. Its control points at t are `N(t) · S · P(t)`, `P(t)` the points
//! interpolated componentwise between the samples around t (held outside them).

use glam::{DMat3, DMat4, DVec3};

use super::track::{bracket, lerp};
use super::xform::LocalXform;

/// How a layer's time codes run, from its metadata.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TimeCodes {
    /// `timeCodesPerSecond`: time codes in a second, 24 when not written (USD's default).
    pub per_second: f64,
    /// `framesPerSecond`, when written.
    pub frames_per_second: Option<f64>,
    /// `startTimeCode`, when written.
    pub start: Option<f64>,
    /// `endTimeCode`, when written.
    pub end: Option<f64>,
}

/// USD's `timeCodesPerSecond` when a layer does not write it.
pub const DEFAULT_TIME_CODES_PER_SECOND: f64 = 24.0;

/// A transform that changes over time, under its nearest changing ancestor.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Node {
    /// The nearest changing ancestor; None when there is none (or the prim resets the
    /// transform stack).
    pub parent: Option<usize>,
    /// The unchanging transforms between that ancestor and this prim (from the root, with
    /// the layer's up-axis turn, when there is no such ancestor).
    pub prefix: DMat4,
    pub local: LocalXform,
    /// `(a, b)` with `|N(t)·p| ≤ a·|p| + b` at every time.
    pub reach: (f64, f64),
}

/// How one patch's control points are found at a time.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct PatchMotion {
    /// Its nearest changing transform.
    pub node: Option<usize>,
    /// The unchanging transforms below that node, to the patch.
    pub since: DMat4,
    /// The times of its points' samples, sorted; `[0.0]` when its points do not change.
    pub times: Vec<f64>,
    /// Its points at those times, in the order of `NurbsSurface::control_points`, before any
    /// transform.
    pub points: Vec<Vec<DVec3>>,
}

impl PatchMotion {
    /// Whether its control points change over time.
    #[must_use]
    pub fn moves(&self) -> bool {
        self.node.is_some() || self.points.len() > 1
    }
}

/// How the patches of a USD layer move when the layer animates them.
#[derive(Clone, Debug, PartialEq)]
pub struct UsdMotion {
    time_codes: TimeCodes,
    nodes: Vec<Node>,
    patches: Vec<PatchMotion>,
    moving: Vec<usize>,
    sample_times: Vec<f64>,
}

/// `(a, b)` with `|M·p| ≤ a·|p| + b` for the affine `m`: the Frobenius norm of its linear part
/// and the length of its translation.
#[must_use]
pub(super) fn reach_of(m: DMat4) -> (f64, f64) {
    let linear = DMat3::from_mat4(m)
        .to_cols_array()
        .iter()
        .map(|x| x * x)
        .sum::<f64>()
        .sqrt();
    (linear, m.w_axis.truncate().length())
}

/// The bound of `M₁ · M₂` from the bounds `(a₁, b₁)` of M₁ and `(a₂, b₂)` of M₂:
/// `(a₁a₂, a₁b₂ + b₁)`.
#[must_use]
pub(super) fn compose_reach(outer: (f64, f64), inner: (f64, f64)) -> (f64, f64) {
    (outer.0 * inner.0, outer.0 * inner.1 + outer.1)
}

impl UsdMotion {
    /// The motion of `patches` (one per patch of the library, in its order) under `nodes`;
    /// None when no patch moves.
    pub(super) fn try_new(
        time_codes: TimeCodes,
        nodes: Vec<Node>,
        patches: Vec<PatchMotion>,
    ) -> Option<Self> {
        let moving: Vec<usize> = (0..patches.len()).filter(|&k| patches[k].moves()).collect();
        if moving.is_empty() {
            return None;
        }
        let mut times = Vec::new();
        let mut seen = vec![false; nodes.len()];
        for &k in &moving {
            let patch = &patches[k];
            if patch.points.len() > 1 {
                times.extend_from_slice(&patch.times);
            }
            let mut node = patch.node;
            while let Some(n) = node {
                if seen[n] {
                    break;
                }
                seen[n] = true;
                times.extend(nodes[n].local.sample_times());
                node = nodes[n].parent;
            }
        }
        times.sort_by(f64::total_cmp);
        times.dedup();
        Some(Self {
            time_codes,
            nodes,
            patches,
            moving,
            sample_times: times,
        })
    }

    /// How the layer's time codes run.
    #[must_use]
    pub fn time_codes(&self) -> TimeCodes {
        self.time_codes
    }

    /// The patches (indices into the library) whose control points change over time.
    #[must_use]
    pub fn moving(&self) -> &[usize] {
        &self.moving
    }

    /// Every time code at which some value of a moving patch is sampled, sorted, once: the
    /// samples of its `points` and of its and its ancestors' xformOps that change.
    #[must_use]
    pub fn sample_times(&self) -> &[f64] {
        &self.sample_times
    }

    /// The control points of `patch` at `time_code`, in the order of
    /// `NurbsSurface::control_points` (use `NurbsSurface::try_with_points` to make the
    /// surface): `N(t) · S · P(t)` (see the module's documentation), every value interpolated
    /// linearly between the samples around `time_code` and held before the first and after
    /// the last (a NaN time code holds the first). Empty when the library has no patch
    /// `patch`.
    #[must_use]
    pub fn points_at(&self, patch: usize, time_code: f64) -> Vec<DVec3> {
        let Some(motion) = self.patches.get(patch) else {
            return Vec::new();
        };
        let world = self.node_world(motion.node, time_code) * motion.since;
        let (i, j, s) = bracket(&motion.times, time_code);
        let (a, b) = (&motion.points[i], &motion.points[j]);
        // At a sample, or held before the first or after the last (where `i == j`).
        if s == 0.0 {
            return a.iter().map(|&p| world.transform_point3(p)).collect();
        }
        a.iter()
            .zip(b)
            .map(|(p, q)| {
                let mixed = DVec3::new(lerp(p.x, q.x, s), lerp(p.y, q.y, s), lerp(p.z, q.z, s));
                world.transform_point3(mixed)
            })
            .collect()
    }

    /// The world transform of `node` at `time`: `N(t) = N_parent(t) · F · L(t)`; identity for
    /// no node.
    #[must_use]
    fn node_world(&self, node: Option<usize>, time: f64) -> DMat4 {
        let mut chain = Vec::new();
        let mut at = node;
        while let Some(n) = at {
            chain.push(n);
            at = self.nodes[n].parent;
        }
        chain.iter().rev().fold(DMat4::IDENTITY, |world, &n| {
            let node = &self.nodes[n];
            world * node.prefix * node.local.matrix_at(time)
        })
    }
}
