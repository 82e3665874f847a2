//! Up to [`LANES`] surface points as a layer receives them: each one's shading frame and
//! initial highlight vector, in world coordinates.

use glam::Vec3;

use super::frame::TangentFrame;
use crate::math::LANES;

/// The shading frame and the initial unit highlight vector (world coordinates) of up to
/// [`LANES`] points. Each layer turns them into the coordinates of its own frame
/// ([`PreparedFrame::local`](super::PreparedFrame::local)), so no caller chooses a frame for it.
#[derive(Clone, Copy, Debug)]
pub struct PointChunk {
    frames: [TangentFrame; LANES],
    hs: [Vec3; LANES],
    len: usize,
}

impl Default for PointChunk {
    fn default() -> Self {
        Self {
            frames: [TangentFrame::new(Vec3::X, Vec3::Y, Vec3::Z); LANES],
            hs: [Vec3::Z; LANES],
            len: 0,
        }
    }
}

impl PointChunk {
    /// Replaces the contents by `frames[i]` and `hs[i]`.
    ///
    /// # Panics
    /// If the slices differ in length or are longer than [`LANES`].
    pub fn load(&mut self, frames: &[TangentFrame], hs: &[Vec3]) {
        assert!(hs.len() == frames.len(), "bad chunk");
        self.set(frames.len(), |i| (frames[i], hs[i]));
    }

    /// Replaces the contents by `point(i)`, a frame and a world highlight vector, for
    /// i < `len`.
    ///
    /// # Panics
    /// If `len` is more than [`LANES`].
    #[inline]
    pub fn set(&mut self, len: usize, point: impl Fn(usize) -> (TangentFrame, Vec3)) {
        assert!(len <= LANES, "bad chunk");
        self.len = len;
        for i in 0..len {
            (self.frames[i], self.hs[i]) = point(i);
        }
    }

    /// How many points.
    #[must_use]
    pub fn len(&self) -> usize {
        self.len
    }

    /// The shading frames, one per point.
    #[inline]
    #[must_use]
    pub fn frames(&self) -> &[TangentFrame] {
        &self.frames[..self.len]
    }

    /// The initial highlight vectors, one per point.
    #[inline]
    #[must_use]
    pub fn half_vectors(&self) -> &[Vec3] {
        &self.hs[..self.len]
    }
}
