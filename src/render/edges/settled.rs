//! The texels whose edges the one-sample pass draws straight, their frames evaluated again in
//! the settings' mode where the G-buffer's are interpolated.

use glam::Mat4;

use crate::render::gbuffer::{Evaluate, GBuffer, Texel};
use crate::render::scene::Scene;
use crate::render::settings::FrameMode;

/// Copies of some texels of a G-buffer, by slot, with frames better than the G-buffer's.
#[derive(Clone, Debug, Default)]
pub(in crate::render) struct SettledTexels {
    /// The texels' slots in the G-buffer, increasing.
    slots: Vec<u32>,
    texels: Vec<Texel>,
}

impl SettledTexels {
    /// The texels of `gbuffer` that `picked` marks (per slot), their frames evaluated in `mode`
    /// ([`GBuffer::evaluate_frames`]), and the frames evaluated. A pixel an edge crosses at one
    /// sample takes its colour from where the edge is, which an interpolated frame misplaces by
    /// a small part of a pixel.
    pub(in crate::render) fn evaluate(
        gbuffer: &GBuffer,
        scene: &Scene,
        view_projection: Mat4,
        mode: FrameMode,
        picked: &[bool],
    ) -> (Self, u64) {
        let slots: Vec<u32> = (0..gbuffer.texels.len())
            .filter(|&k| picked[k])
            .map(|k| k as u32)
            .collect();
        let mut texels: Vec<Texel> = slots.iter().map(|&k| gbuffer.texels[k as usize]).collect();
        let frames = GBuffer::evaluate_frames(
            &mut texels,
            scene.library,
            &scene.camera,
            view_projection,
            (gbuffer.width, gbuffer.height),
            mode,
            Evaluate::Full,
        );
        (Self { slots, texels }, frames)
    }

    /// The settled copy of the texel in slot `slot`, if it was settled.
    #[must_use]
    pub(in crate::render) fn get(&self, slot: usize) -> Option<&Texel> {
        let slot = u32::try_from(slot).ok()?;
        self.slots
            .binary_search(&slot)
            .ok()
            .map(|i| &self.texels[i])
    }

    /// The settled texels with their slots, in slot order.
    pub(in crate::render) fn iter(&self) -> impl Iterator<Item = (usize, &Texel)> {
        self.slots.iter().map(|&k| k as usize).zip(&self.texels)
    }
}
