//! A supersampled pixel: the mean of its samples' colour, matte, `N·H` and `N·L'`.

use glam::Vec4;

use crate::render::colour::{premultiplied, straight};
use crate::render::shade::Shaded;

/// One pixel's average over its samples.
pub(in crate::render) struct Resolved {
    pub pixel: u32,
    pub colour: Vec4,
    pub matte: f32,
    pub n_dot_h: f32,
    pub n_dot_l: f32,
}

impl Resolved {
    /// Pixel `pixel` as the mean of `samples`, indices into `shaded`'s images: premultiplied
    /// colour `α = mean(α_s)`, `rgb = mean(α_s rgb_s)/α`, and the mean matte, `N·H` and `N·L'`
    /// (0 where `shaded` has none).
    #[must_use]
    pub(in crate::render) fn average(
        pixel: u32,
        shaded: &Shaded,
        samples: impl ExactSizeIterator<Item = usize>,
    ) -> Self {
        let weight = 1.0 / samples.len() as f32;
        let (mut colour, mut matte, mut n_dot_h, mut n_dot_l) = (Vec4::ZERO, 0.0, 0.0, 0.0);
        for s in samples {
            colour += premultiplied(shaded.colour[s]);
            matte += shaded.matte.as_ref().map_or(0.0, |m| m[s]);
            n_dot_h += shaded.n_dot_h.as_ref().map_or(0.0, |n| n[s]);
            n_dot_l += shaded.n_dot_l.as_ref().map_or(0.0, |n| n[s]);
        }
        Self {
            pixel,
            colour: straight(colour * weight),
            matte: matte * weight,
            n_dot_h: n_dot_h * weight,
            n_dot_l: n_dot_l * weight,
        }
    }
}
