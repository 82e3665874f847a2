//! The 2D toon texture of X-Toon (Barla et al. 2006, §3): a stack of 1D toon textures, one per
//! detail level.

use glam::Vec3;

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
    /// Rows from the top (D = 1), each `width` texels from `n·l = −1`.
    texels: Vec<Vec3>,
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
            texels,
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

    /// The texel in column `x` (from `n·l = −1`) of row `y` (from D = 1).
    #[must_use]
    pub fn texel(&self, x: usize, y: usize) -> Vec3 {
        self.texels[y.min(self.height - 1) * self.width + x.min(self.width - 1)]
    }

    /// The colour at tone `n_dot_l` and detail `detail`: bilinear between the texel centres
    /// around `s = (n·l + 1)/2 · width − ½` and `t = (1 − D) · height − ½`, both clamped to the
    /// edge texels. NaN coordinates read the first column or the top row, never NaN.
    #[inline]
    #[must_use]
    pub fn sample(&self, n_dot_l: f32, detail: f32) -> Vec3 {
        let (x0, x1, fx) = axis((n_dot_l + 1.0) * 0.5, self.width);
        let (y0, y1, fy) = axis(1.0 - detail, self.height);
        let row0 = &self.texels[y0 * self.width..][..self.width];
        let row1 = &self.texels[y1 * self.width..][..self.width];
        let top = row0[x0].lerp(row0[x1], fx);
        let bottom = row1[x0].lerp(row1[x1], fx);
        top.lerp(bottom, fy)
    }
}

/// The two texel indices around coordinate `c ∈ [0, 1]` of an axis of `n` texels and the weight
/// of the second: `c n − ½` clamped to `[0, n − 1]` (NaN clamps to 0).
#[inline]
fn axis(c: f32, n: usize) -> (usize, usize, f32) {
    let last = (n - 1) as f32;
    let s = (c * n as f32 - 0.5).max(0.0).min(last);
    let i = s as usize;
    let next = (i + 1).min(n - 1);
    (i, next, s - i as f32)
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
