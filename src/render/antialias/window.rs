//! A window of an image drawn as an image of its own: the projection that maps the window onto
//! a whole viewport, so the rasterizer and the G-buffer need not know they draw a part.

use glam::{Mat4, Vec4};

use crate::render::raster::Viewport;

/// The pixels `[x, x + width) × [y, y + height)` of an image `full` pixels in size.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Window {
    pub x: u32,
    pub y: u32,
    pub width: u32,
    pub height: u32,
    /// The image the window is part of.
    pub full: Viewport,
}

impl Window {
    /// The window's own viewport.
    #[must_use]
    pub fn viewport(&self) -> Viewport {
        Viewport {
            width: self.width,
            height: self.height,
        }
    }

    /// The map from the image's clip space to the window's: a pixel centre at `(px, py)` of the
    /// image lands at `(px − x, py − y)` of the window.
    ///
    /// With `W, H` the image's size and `w, h` the window's, NDC x scales by `W/w` and moves by
    /// `(W − 2x)/w − 1`, NDC y (up) scales by `H/h` and moves by `1 − (H − 2y)/h`; in clip space
    /// the move is multiplied by the vertex's w, so the map is linear: `clip' = M clip`. Depth
    /// and w are unchanged, so are depth and perspective-correct barycentrics.
    #[must_use]
    pub fn clip_from_image(&self) -> Mat4 {
        let (full_w, full_h) = (self.full.width as f32, self.full.height as f32);
        let (w, h) = (self.width as f32, self.height as f32);
        let sx = full_w / w;
        let tx = (full_w - 2.0 * self.x as f32) / w - 1.0;
        let sy = full_h / h;
        let ty = 1.0 - (full_h - 2.0 * self.y as f32) / h;
        Mat4::from_cols(
            Vec4::new(sx, 0.0, 0.0, 0.0),
            Vec4::new(0.0, sy, 0.0, 0.0),
            Vec4::new(0.0, 0.0, 1.0, 0.0),
            Vec4::new(tx, ty, 0.0, 1.0),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

    /// Pixel coordinates (x right, y down) of an NDC point in a viewport.
    fn pixel(ndc: Vec2, viewport: Viewport) -> Vec2 {
        Vec2::new(
            (ndc.x + 1.0) / 2.0 * viewport.width as f32,
            (1.0 - ndc.y) / 2.0 * viewport.height as f32,
        )
    }

    #[test]
    fn a_point_lands_at_its_pixel_less_the_windows_corner() {
        let full = Viewport {
            width: 640,
            height: 360,
        };
        let window = Window {
            x: 96,
            y: 200,
            width: 70,
            height: 34,
            full,
        };
        let m = window.clip_from_image();
        for (clip, w) in [
            (Vec4::new(0.3, -0.2, 0.4, 1.0), 1.0),
            (Vec4::new(-1.5, 2.0, 1.0, 2.5), 2.5),
            (Vec4::new(0.0, 0.0, 0.1, 0.5), 0.5),
        ] {
            let image = pixel(Vec2::new(clip.x, clip.y) / w, full);
            let moved = m * clip;
            assert_eq!((moved.z, moved.w), (clip.z, clip.w));
            let inside = pixel(Vec2::new(moved.x, moved.y) / moved.w, window.viewport());
            let expected = image - Vec2::new(96.0, 200.0);
            assert!(
                (inside - expected).length() < 1e-3,
                "{inside} vs {expected}"
            );
        }
    }
}
