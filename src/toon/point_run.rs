//! Points of one patch side by side, as the X-Toon tone shades them.

use glam::{Vec2, Vec3};

use crate::math::{Lanes, LANES};

/// Up to [`LANES`] points of one patch side by side, one array per coordinate, as
/// [`ViewXToon::shade_run`](super::ViewXToon::shade_run) reads them.
#[derive(Clone, Debug)]
pub struct PointRun {
    /// How many points: the first `len` of each array.
    pub len: usize,
    /// The patch they lie on.
    pub patch: usize,
    /// World positions.
    pub position: Lanes,
    /// Unit normals, facing the viewer.
    pub normal: Lanes,
    /// Patch parameters.
    pub u: [f32; LANES],
    pub v: [f32; LANES],
}

impl Default for PointRun {
    /// No points.
    fn default() -> Self {
        Self {
            len: 0,
            patch: 0,
            position: Lanes::default(),
            normal: Lanes::default(),
            u: [0.0; LANES],
            v: [0.0; LANES],
        }
    }
}

impl PointRun {
    /// The run of the one point at `position` with unit normal `normal`, on patch `patch` at
    /// `uv`.
    #[must_use]
    pub fn one(position: Vec3, normal: Vec3, patch: usize, uv: Vec2) -> Self {
        let mut run = Self {
            len: 1,
            patch,
            ..Self::default()
        };
        run.set(0, position, normal, uv);
        run
    }

    /// Sets the `k`-th point.
    #[inline(always)]
    pub fn set(&mut self, k: usize, position: Vec3, normal: Vec3, uv: Vec2) {
        self.position.set(k, position);
        self.normal.set(k, normal);
        (self.u[k], self.v[k]) = uv.into();
    }
}
