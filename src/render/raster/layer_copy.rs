//! What a buffer drawn over a layer still holds of it, tile by tile.

use super::layer::Layer;
use super::viewport::Viewport;

/// The record a buffer keeps of its last draw over a [`Layer`]
/// ([`Rasterizer::rasterize_over_keeping`]): the layer's stamp and the viewport, and per tile
/// whether the tile is the layer's pixels as they were copied (depth clamped) with the pixels
/// it covers, or had triangles drawn over it. A later draw over the same layer, into the same
/// buffer unchanged since, leaves the copied tiles it would copy again as they are: they hold
/// what copying would write, so the buffer is the same byte for byte.
///
/// [`Rasterizer::rasterize_over_keeping`]: super::Rasterizer::rasterize_over_keeping
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct LayerCopy {
    /// The layer's stamp and the viewport the tiles are of; `None`: nothing is known of the
    /// buffer.
    of: Option<(u64, Viewport)>,
    /// Per tile, the pixels covered where the tile is the layer's copy; `None` where triangles
    /// were drawn over it.
    tiles: Vec<Option<u64>>,
}

impl LayerCopy {
    /// Knows nothing of the buffer: the next draw writes every tile.
    pub fn forget(&mut self) {
        self.of = None;
        self.tiles.clear();
    }

    /// The pixels covered in tile `index` where the buffer already holds `layer`'s copy there
    /// for `viewport`, or `None` where the tile is to be written.
    #[must_use]
    pub(super) fn copied(&self, layer: &Layer, viewport: Viewport, index: usize) -> Option<u64> {
        let of = self.of?;
        (of == (layer.stamp(), viewport) && layer.stamp() != 0)
            .then(|| self.tiles.get(index).copied().flatten())
            .flatten()
    }

    /// Records a draw over `layer` for `viewport` that left `tiles` (per tile, as
    /// [`LayerCopy::copied`] reads them).
    pub(super) fn record(&mut self, layer: &Layer, viewport: Viewport, tiles: Vec<Option<u64>>) {
        self.of = Some((layer.stamp(), viewport));
        self.tiles = tiles;
    }

    /// How many tiles the record holds as the layer's copy.
    #[cfg(test)]
    pub(super) fn copied_tiles(&self) -> usize {
        self.tiles.iter().flatten().count()
    }
}
