//! The AOVs: the images beside the colour a scene asks for, at output resolution.

use glam::{Vec2, Vec3, Vec4};

use super::colour::box_filter;
use super::gbuffer::GBuffer;
use super::lines::LineImage;
use super::scene::Scene;
use super::settings::Settings;
use super::shade::Shaded;

/// The AOVs a scene asked for (`None` for the others). Under supersampling the matte is the
/// average of a pixel's samples; the others are taken from its central sample.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AovImages {
    pub matte: Option<Vec<f32>>,
    /// Patch index per pixel, `u32::MAX` on the background.
    pub patch_id: Option<Vec<u32>>,
    /// NDC depth per pixel, `f32::INFINITY` on the background.
    pub depth: Option<Vec<f32>>,
    pub normal: Option<Vec<Vec3>>,
    pub uv: Option<Vec<Vec2>>,
    /// `N·H` of the initial half vector, 0 on the background.
    pub n_dot_h: Option<Vec<f32>>,
    /// `N·L'` the tone reads, 0 on the background.
    pub n_dot_l: Option<Vec<f32>>,
    /// The lines alone: linear RGB, straight alpha their coverage.
    pub outline: Option<Vec<Vec4>>,
}

impl AovImages {
    /// How many AOV images there are.
    #[must_use]
    pub fn count(&self) -> usize {
        [
            self.matte.is_some(),
            self.patch_id.is_some(),
            self.depth.is_some(),
            self.normal.is_some(),
            self.uv.is_some(),
            self.n_dot_h.is_some(),
            self.n_dot_l.is_some(),
            self.outline.is_some(),
        ]
        .iter()
        .filter(|&&on| on)
        .count()
    }
}

/// The AOVs the scene asked for, at output resolution.
#[must_use]
pub(super) fn collect_aovs(
    scene: &Scene,
    gbuffer: &GBuffer,
    lines: Option<&LineImage>,
    shaded: &mut Shaded,
    settings: &Settings,
) -> AovImages {
    let (width, height, k) = (settings.width, settings.height, settings.samples_per_side());
    let centre = |x: u32, y: u32| gbuffer.at(x * k + k / 2, y * k + k / 2);
    let pixels = || (0..height).flat_map(move |y| (0..width).map(move |x| (x, y)));
    let a = scene.aovs;
    AovImages {
        matte: shaded
            .matte
            .take()
            .map(|samples| box_filter(&samples, width, height, k)),
        n_dot_h: shaded
            .n_dot_h
            .take()
            .map(|samples| box_filter(&samples, width, height, k)),
        n_dot_l: shaded
            .n_dot_l
            .take()
            .map(|samples| box_filter(&samples, width, height, k)),
        patch_id: a.patch_id.then(|| {
            pixels()
                .map(|(x, y)| centre(x, y).map_or(u32::MAX, |t| t.patch))
                .collect()
        }),
        depth: a.depth.then(|| {
            pixels()
                .map(|(x, y)| centre(x, y).map_or(f32::INFINITY, |t| t.depth))
                .collect()
        }),
        normal: a.normal.then(|| {
            pixels()
                .map(|(x, y)| centre(x, y).map_or(Vec3::ZERO, |t| t.frame.n))
                .collect()
        }),
        uv: a.uv.then(|| {
            pixels()
                .map(|(x, y)| centre(x, y).map_or(Vec2::ZERO, |t| t.uv))
                .collect()
        }),
        outline: a.outline.then(|| {
            lines.map_or_else(
                || vec![Vec4::ZERO; width as usize * height as usize],
                LineImage::alone,
            )
        }),
    }
}
