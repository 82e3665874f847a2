//! A layer: what some of a list's triangles show, kept to draw the others over it.

use std::sync::atomic::{AtomicU64, Ordering};

use super::visibility::VisibilityBuffer;

/// The visibility of some triangles of a list ([`Rasterizer::rasterize_layer_into`]), with
/// depth as computed (not clamped to [0, 1]), so that triangles drawn over it
/// ([`Rasterizer::rasterize_over_into`]) meet it in the depth test exactly as they would meet
/// its triangles drawn with them.
///
/// [`Rasterizer::rasterize_layer_into`]: super::Rasterizer::rasterize_layer_into
/// [`Rasterizer::rasterize_over_into`]: super::Rasterizer::rasterize_over_into
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Layer {
    buffer: VisibilityBuffer,
    /// Which drawing of a layer this is, unique in the process (0: never drawn), so that a
    /// [`LayerCopy`](super::LayerCopy) knows the pixels it recorded.
    stamp: u64,
}

/// The stamps given to layers drawn, counted across the process.
static STAMPS: AtomicU64 = AtomicU64::new(0);

impl Layer {
    /// The layer's pixels: depth unclamped, `f32::INFINITY` where empty.
    #[must_use]
    pub fn buffer(&self) -> &VisibilityBuffer {
        &self.buffer
    }

    /// Which drawing of a layer this is: a layer drawn again has a new stamp.
    #[must_use]
    pub(super) fn stamp(&self) -> u64 {
        self.stamp
    }

    /// The buffer, to be drawn again: the layer takes a new stamp.
    pub(super) fn buffer_mut(&mut self) -> &mut VisibilityBuffer {
        self.stamp = STAMPS.fetch_add(1, Ordering::Relaxed) + 1;
        &mut self.buffer
    }
}
