//! A layer: what some of a list's triangles show, kept to draw the others over it.

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
}

impl Layer {
    /// The layer's pixels: depth unclamped, `f32::INFINITY` where empty.
    #[must_use]
    pub fn buffer(&self) -> &VisibilityBuffer {
        &self.buffer
    }

    pub(super) fn buffer_mut(&mut self) -> &mut VisibilityBuffer {
        &mut self.buffer
    }
}
