//! The visibility buffer: per pixel the nearest triangle, its depth and where on it the pixel
//! centre lies.

use rayon::prelude::*;

use super::viewport::Viewport;

/// Per pixel (row-major, top row first): the nearest triangle and where on it the pixel centre
/// lies.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VisibilityBuffer {
    pub width: u32,
    pub height: u32,
    /// NDC depth z/w in [0, 1] of the nearest surface, `f32::INFINITY` where empty.
    pub depth: Vec<f32>,
    /// Index into the input triangle list, `u32::MAX` where empty.
    pub triangle: Vec<u32>,
    /// Perspective-correct `(b1, b2)` of the pixel centre relative to the original triangle's
    /// vertices 1 and 2 (`b0 = 1 − b1 − b2`), also after clipping; `[0, 0]` where empty.
    pub barycentric: Vec<[f32; 2]>,
}

/// What one pixel of a [`VisibilityBuffer`] holds when a triangle covers it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    pub triangle: u32,
    pub barycentric: [f32; 2],
    pub depth: f32,
}

impl VisibilityBuffer {
    /// Sizes the buffer for `viewport`. The tiles write every pixel they own, so a buffer of
    /// that size is left as it is; one of another size is replaced by an empty one, filled in
    /// parallel.
    pub(super) fn resize(&mut self, viewport: Viewport) {
        let pixels = viewport.width as usize * viewport.height as usize;
        (self.width, self.height) = (viewport.width, viewport.height);
        if self.triangle.len() != pixels {
            self.depth = filled(pixels, f32::INFINITY);
            self.triangle = filled(pixels, u32::MAX);
            self.barycentric = filled(pixels, [0.0; 2]);
        }
    }

    /// The triangle covering pixel `(x, y)`, or `None` where empty or outside the buffer.
    #[must_use]
    pub fn hit(&self, x: u32, y: u32) -> Option<Hit> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = y as usize * self.width as usize + x as usize;
        (self.triangle[i] != u32::MAX).then(|| Hit {
            triangle: self.triangle[i],
            barycentric: self.barycentric[i],
            depth: self.depth[i],
        })
    }
}

/// `len` copies of `value`, written in parallel.
fn filled<T: Copy + Send + Sync>(len: usize, value: T) -> Vec<T> {
    (0..len).into_par_iter().map(|_| value).collect()
}
