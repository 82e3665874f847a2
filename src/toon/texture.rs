//! The 2D toon texture of X-Toon (Barla et al. 2006, §3): a stack of 1D toon textures, one per
//! detail level.

use glam::Vec3;

use super::error::XToonError;
use super::grid::Grid;

/// A 2D toon texture in linear RGB, indexed by tone (`n·l`, across) and detail D (down).
///
/// Column 0 is `n·l = −1` and the last column `n·l = 1`; the top row is D = 1 (full detail) and
/// the bottom row D = 0 (most abstract). Texel centres sit at `(i + ½) / width` and
/// `(j + ½) / height` of the axes; lookups are bilinear between them and clamp to the edge.
#[derive(Clone, Debug, PartialEq)]
pub struct ToonTexture {
    /// Rows from the top (D = 1), each from `n·l = −1`.
    texels: Grid,
    /// The lookup's affine maps to grid coordinates: column `n·l · width/2 + (width − 1)/2`,
    /// row `(height − ½) − D · height`.
    half_width: f32,
    column_offset: f32,
    height_f: f32,
    row_offset: f32,
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
            texels: Grid::new(&texels, width),
            half_width: 0.5 * width as f32,
            column_offset: 0.5 * (width as f32 - 1.0),
            height_f: height as f32,
            row_offset: height as f32 - 0.5,
        })
    }

    /// Width in texels (the tone axis).
    #[must_use]
    pub fn width(&self) -> usize {
        self.texels.columns()
    }

    /// Height in texels (the detail axis).
    #[must_use]
    pub fn height(&self) -> usize {
        self.texels.rows()
    }

    /// The texel in column `x` (from `n·l = −1`) of row `y` (from D = 1), clamped to the edge.
    #[must_use]
    pub fn texel(&self, x: usize, y: usize) -> Vec3 {
        self.texels.sample(y, x)
    }

    /// The colour at tone `n_dot_l` and detail `detail`: bilinear between the texel centres
    /// around `s = (n·l + 1)/2 · width − ½` and `t = (1 − D) · height − ½`, both clamped to the
    /// edge texels. NaN coordinates read the first column or the top row, never NaN.
    #[must_use]
    pub fn sample(&self, n_dot_l: f32, detail: f32) -> Vec3 {
        let mut colour = [Vec3::ZERO];
        self.sample_run(&[n_dot_l], &[detail], &mut colour);
        colour[0]
    }

    /// [`sample`](Self::sample) at each `(n_dot_l[k], detail[k])` into `out[k]`, for up to
    /// [`LANES`](crate::math::LANES) lookups side by side.
    ///
    /// # Panics
    /// If the three slices differ in length or are longer than [`LANES`](crate::math::LANES).
    #[inline(always)]
    pub fn sample_run(&self, n_dot_l: &[f32], detail: &[f32], out: &mut [Vec3]) {
        let n = out.len();
        assert!(n_dot_l.len() == n && detail.len() == n, "bad run");
        self.texels.bilinear(
            n,
            |k| self.row_offset - detail[k] * self.height_f,
            |k| n_dot_l[k] * self.half_width + self.column_offset,
            |k, colour| out[k] = colour,
        );
    }
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
