//! Vectors side by side: up to [`LANES`] of them, one array per coordinate, so that loops over
//! them vectorize.

use glam::Vec3;

use super::lane_count::LANES;
use super::normalize::normalize_lanes;

/// Up to [`LANES`] vectors side by side, one array per coordinate: loops over the arrays
/// vectorize where a loop over `Vec3`s would not.
#[derive(Clone, Copy, Debug)]
pub struct Lanes {
    pub x: [f32; LANES],
    pub y: [f32; LANES],
    pub z: [f32; LANES],
}

impl Default for Lanes {
    /// Zero vectors.
    fn default() -> Self {
        Self {
            x: [0.0; LANES],
            y: [0.0; LANES],
            z: [0.0; LANES],
        }
    }
}

impl Lanes {
    /// Lanes holding `v` first, and zero vectors after it.
    #[must_use]
    pub fn first(v: Vec3) -> Self {
        let mut lanes = Self::default();
        lanes.set(0, v);
        lanes
    }

    /// The `k`-th vector.
    #[inline(always)]
    #[must_use]
    pub fn get(&self, k: usize) -> Vec3 {
        Vec3::new(self.x[k], self.y[k], self.z[k])
    }

    /// Sets the `k`-th vector.
    #[inline(always)]
    pub fn set(&mut self, k: usize, v: Vec3) {
        (self.x[k], self.y[k], self.z[k]) = v.into();
    }

    /// Sets the first `n` vectors to `v`.
    #[inline]
    pub fn fill(&mut self, n: usize, v: Vec3) {
        self.x[..n].fill(v.x);
        self.y[..n].fill(v.y);
        self.z[..n].fill(v.z);
    }

    /// Normalizes the first `n` vectors side by side: each one whose squared length is finite
    /// and above the zero threshold becomes `v · (1/√(v·v))` (the value glam's
    /// `try_normalize` gives it), every other one `v` becomes `exact(k, v)`.
    #[inline]
    pub fn normalize(&mut self, n: usize, exact: impl Fn(usize, Vec3) -> Vec3) {
        normalize_lanes(&mut self.x[..n], &mut self.y[..n], &mut self.z[..n], exact);
    }
}
