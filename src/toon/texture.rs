//! The 2D toon texture of X-Toon (Barla et al. 2006, §3): a stack of 1D toon textures, one per
//! detail level.

use glam::{Vec3, Vec3A};

use super::error::XToonError;

/// A 2D toon texture in linear RGB, indexed by tone (`n·l`, across) and detail D (down).
///
/// Column 0 is `n·l = −1` and the last column `n·l = 1`; the top row is D = 1 (full detail) and
/// the bottom row D = 0 (most abstract). Texel centres sit at `(i + ½) / width` and
/// `(j + ½) / height` of the axes; lookups are bilinear between them and clamp to the edge.
#[derive(Clone, Debug, PartialEq)]
pub struct ToonTexture {
    width: usize,
    height: usize,
    /// Rows from the top (D = 1), each `width` texels from `n·l = −1` and a copy of its last
    /// texel, and a copy of the last row at the bottom: a lookup's four texels are then always
    /// at `k`, `k + 1`, `k + width + 1` and `k + width + 2`.
    texels: Vec<Vec3A>,
    /// The lookup's affine maps: `s = n·l · width/2 + (width − 1)/2`,
    /// `t = (height − ½) − D · height`, and their upper clamps.
    half_width: f32,
    s_offset: f32,
    height_f: f32,
    t_offset: f32,
    last_s: f32,
    last_t: f32,
}

/// The largest texture side accepted.
pub const MAX_TEXTURE_SIDE: usize = 4096;

impl ToonTexture {
    /// A texture of `width × height` texels given row by row from the top (D = 1), each row
    /// from `n·l = −1`. Both sides between 1 and [`MAX_TEXTURE_SIDE`]; colours finite and ≥ 0.
    pub fn new(width: usize, height: usize, texels: Vec<Vec3>) -> Result<Self, XToonError> {
        let bad = |reason: String| Err(XToonError::Texture(reason));
        if !(1..=MAX_TEXTURE_SIDE).contains(&width) || !(1..=MAX_TEXTURE_SIDE).contains(&height) {
            return bad(format!(
                "size {width}×{height} must be between 1 and {MAX_TEXTURE_SIDE} per side"
            ));
        }
        if texels.len() != width * height {
            return bad(format!(
                "{} texels for a {width}×{height} texture, which needs {}",
                texels.len(),
                width * height
            ));
        }
        if let Some(k) = texels
            .iter()
            .position(|c| !(c.is_finite() && c.min_element() >= 0.0))
        {
            return bad(format!(
                "texel ({}, {}) is {:?}; colours must be finite and at least 0",
                k % width,
                k / width,
                texels[k].to_array()
            ));
        }
        Ok(Self {
            width,
            height,
            texels: padded(&texels, width),
            half_width: 0.5 * width as f32,
            s_offset: 0.5 * (width as f32 - 1.0),
            height_f: height as f32,
            t_offset: height as f32 - 0.5,
            last_s: (width - 1) as f32,
            last_t: (height - 1) as f32,
        })
    }

    /// Width in texels (the tone axis).
    #[must_use]
    pub fn width(&self) -> usize {
        self.width
    }

    /// Height in texels (the detail axis).
    #[must_use]
    pub fn height(&self) -> usize {
        self.height
    }

    /// The texel in column `x` (from `n·l = −1`) of row `y` (from D = 1), clamped to the edge.
    #[must_use]
    pub fn texel(&self, x: usize, y: usize) -> Vec3 {
        self.texels[y.min(self.height - 1) * (self.width + 1) + x.min(self.width - 1)].into()
    }

    /// The colour at tone `n_dot_l` and detail `detail`: bilinear between the texel centres
    /// around `s = (n·l + 1)/2 · width − ½` and `t = (1 − D) · height − ½`, both clamped to the
    /// edge texels. NaN coordinates read the first column or the top row, never NaN.
    #[inline(always)]
    #[must_use]
    pub fn sample(&self, n_dot_l: f32, detail: f32) -> Vec3 {
        // `max` then `min` clamps, and takes NaN to 0.
        let s = (n_dot_l * self.half_width + self.s_offset)
            .max(0.0)
            .min(self.last_s);
        let t = (self.t_offset - detail * self.height_f)
            .max(0.0)
            .min(self.last_t);
        // Through u32, which converts to and from f32 in one instruction each (usize does not).
        let (x, y) = (s as u32, t as u32);
        let (fx, fy) = (s - x as f32, t - y as f32);
        // The next column and row are the padding copies at the last ones (their weight is 0).
        let stride = self.width + 1;
        let k = y as usize * stride + x as usize;
        let (top, bottom) = (
            &self.texels[k..k + 2],
            &self.texels[k + stride..k + stride + 2],
        );
        let top = top[0].lerp(top[1], fx);
        let bottom = bottom[0].lerp(bottom[1], fx);
        top.lerp(bottom, fy).into()
    }
}

/// A grid of `values` in rows of `width`, with the last value of each row repeated after it
/// and the last row so extended repeated below: a bilinear lookup clamped to the grid then
/// always reads the entries `k`, `k + 1`, `k + width + 1` and `k + width + 2`.
pub(super) fn padded(values: &[Vec3], width: usize) -> Vec<Vec3A> {
    let rows = values.chunks(width).chain(values.rchunks(width).take(1));
    rows.flat_map(|row| row.iter().chain(row.last()).map(|&c| Vec3A::from(c)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_textures_are_refused() {
        assert!(ToonTexture::new(0, 1, vec![]).is_err());
        assert!(ToonTexture::new(2, 1, vec![Vec3::ONE]).is_err());
        let e = ToonTexture::new(2, 1, vec![Vec3::ONE, Vec3::new(0.0, f32::NAN, 0.0)]).unwrap_err();
        assert!(e.to_string().contains("texel (1, 0)"), "{e}");
        assert!(ToonTexture::new(1, 1, vec![Vec3::splat(-0.1)]).is_err());
    }

    #[test]
    fn one_texel_is_constant() {
        let t = ToonTexture::new(1, 1, vec![Vec3::new(0.1, 0.2, 0.3)]).unwrap();
        for (nl, d) in [(-1.0, 0.0), (0.3, 0.7), (1.0, 1.0), (f32::NAN, 2.0)] {
            assert_eq!(t.sample(nl, d), Vec3::new(0.1, 0.2, 0.3));
        }
    }
}
