//! Images encoded for 8- and 16-bit files: colour in sRGB, the matte, patch ids and flat patch
//! colours, depth, normals, (u, v) and the `N·H` heat map.

use glam::{Vec2, Vec3, Vec4};
use rayon::prelude::*;

use super::srgb::{byte, linear_to_srgb};

/// The `N·H` span the heat map shows below 1: a highlight of ε up to this is in view.
pub const HEAT_RANGE: f32 = 0.1;

/// RGBA8: sRGB-encoded colour, linear straight alpha. Cel frames are mostly runs of one
/// colour, so a pixel equal to the one before it takes its bytes without encoding them again
/// (the transfer function's power is most of a written frame's time); blocks of pixels are
/// encoded in parallel.
pub fn colour_rgba8(colour: &[Vec4]) -> Vec<u8> {
    let encode = |c: Vec4| {
        [
            byte(linear_to_srgb(c.x)),
            byte(linear_to_srgb(c.y)),
            byte(linear_to_srgb(c.z)),
            byte(c.w),
        ]
    };
    colour
        .par_chunks(PIXELS_PER_JOB)
        .flat_map_iter(|block| {
            let mut last = (Vec4::ZERO, encode(Vec4::ZERO));
            block.iter().map(move |&c| {
                if c != last.0 {
                    last = (c, encode(c));
                }
                last.1
            })
        })
        .collect::<Vec<[u8; 4]>>()
        .into_flattened()
}

/// Pixels per parallel job of the colour encoding.
const PIXELS_PER_JOB: usize = 16384;

/// Grey8: a value in [0, 1] per pixel (the highlight matte).
pub fn grey8(values: &[f32]) -> Vec<u8> {
    values.iter().map(|&v| byte(v)).collect()
}

/// A distinct flat colour for each patch index (hues spaced by the golden angle), transparent
/// where no patch is: the patch-id debug view.
pub fn patch_colours_rgba8(ids: &[u32]) -> Vec<u8> {
    ids.iter()
        .flat_map(|&id| {
            if id == u32::MAX {
                return [0, 0, 0, 0];
            }
            let [r, g, b] = patch_colour(id);
            [r, g, b, 255]
        })
        .collect()
}

/// The flat colour of patch `id` (sRGB bytes): the hue `h = fract(0.618034 · id)` of the
/// golden angle, so that consecutive indices lie far apart on the colour wheel, at full
/// saturation, each channel `c` in [0, 1] written as `0.25 + 0.7 c`.
#[must_use]
pub fn patch_colour(id: u32) -> [u8; 3] {
    let hue = (id as f32 * 0.618_034).fract() * 6.0;
    let x = 1.0 - (hue % 2.0 - 1.0).abs();
    let (r, g, b) = match hue as u32 {
        0 => (1.0, x, 0.0),
        1 => (x, 1.0, 0.0),
        2 => (0.0, 1.0, x),
        3 => (0.0, x, 1.0),
        4 => (x, 0.0, 1.0),
        _ => (1.0, 0.0, x),
    };
    [
        byte(0.25 + 0.7 * r),
        byte(0.25 + 0.7 * g),
        byte(0.25 + 0.7 * b),
    ]
}

/// Grey16 (big-endian): the patch index itself, 65535 where no patch is.
pub fn patch_ids16(ids: &[u32]) -> Vec<u8> {
    ids.iter()
        .flat_map(|&id| (id.min(65_535) as u16).to_be_bytes())
        .collect()
}

/// Grey16 (big-endian): NDC depth in [0, 1], 65535 on the background.
pub fn depth16(depth: &[f32]) -> Vec<u8> {
    depth
        .iter()
        .flat_map(|&d| ((d.clamp(0.0, 1.0) * 65_535.0).round() as u16).to_be_bytes())
        .collect()
}

/// RGBA8: a unit normal as `0.5 n + 0.5`, transparent where it is zero (background).
pub fn normal_rgba8(normals: &[Vec3]) -> Vec<u8> {
    normals
        .iter()
        .flat_map(|n| {
            let c = *n * 0.5 + 0.5;
            let alpha = if *n == Vec3::ZERO { 0 } else { 255 };
            [byte(c.x), byte(c.y), byte(c.z), alpha]
        })
        .collect()
}

/// RGBA8: a heat map of `N·H` over [1 − 2 `range`, 1]: blue far from the highlight through green
/// and yellow to red at `N·H = 1`; values below the range are blue. `alpha` per pixel (the
/// colour's coverage) keeps the background transparent.
pub fn heat_rgba8(n_dot_h: &[f32], alpha: &[f32], range: f32) -> Vec<u8> {
    n_dot_h
        .iter()
        .zip(alpha)
        .flat_map(|(&x, &a)| {
            let t = ((x - (1.0 - 2.0 * range)) / (2.0 * range)).clamp(0.0, 1.0);
            // Blue (0) → cyan → green → yellow → red (1).
            let (r, g, b) = match (t * 4.0) as u32 {
                0 => (0.0, 4.0 * t, 1.0),
                1 => (0.0, 1.0, 2.0 - 4.0 * t),
                2 => (4.0 * t - 2.0, 1.0, 0.0),
                _ => (1.0, (4.0 - 4.0 * t).max(0.0), 0.0),
            };
            [byte(r), byte(g), byte(b), byte(a)]
        })
        .collect()
}

/// RGBA8: (u, v) as red and green.
pub fn uv_rgba8(uvs: &[Vec2]) -> Vec<u8> {
    uvs.iter()
        .flat_map(|uv| [byte(uv.x), byte(uv.y), 0, 255])
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colour_is_srgb_encoded_with_linear_alpha() {
        assert_eq!(
            colour_rgba8(&[Vec4::new(1.0, 0.0, 2.0, 0.5)]),
            [255, 0, 255, 128]
        );
    }

    #[test]
    fn runs_of_one_colour_encode_as_each_pixel_alone() {
        // Runs, changes, the background and NaN, across the blocks encoded in parallel.
        let colours = [
            Vec4::ZERO,
            Vec4::new(0.2, 0.3, 0.4, 1.0),
            Vec4::new(0.2, 0.3, 0.4, 1.0),
            Vec4::new(0.9, 0.001, 0.5, 1.0),
            Vec4::new(f32::NAN, 0.5, 0.5, 1.0),
        ];
        let image: Vec<Vec4> = (0..3 * PIXELS_PER_JOB + 7)
            .map(|i| colours[(i / 3 + i / 1000) % colours.len()])
            .collect();
        let alone: Vec<u8> = image.iter().flat_map(|&c| colour_rgba8(&[c])).collect();
        assert_eq!(colour_rgba8(&image), alone);
        assert_eq!(colour_rgba8(&colours[1..2]), [124, 149, 170, 255]);
    }

    #[test]
    fn heat_map_runs_from_blue_to_red_over_its_range() {
        let values = [1.0, 1.0 - 2.0 * HEAT_RANGE, -1.0, 1.0 - HEAT_RANGE];
        let c = heat_rgba8(&values, &[1.0, 1.0, 0.0, 1.0], HEAT_RANGE);
        assert_eq!(c[0..4], [255, 0, 0, 255]);
        assert_eq!(c[4..8], [0, 0, 255, 255]);
        assert_eq!(c[8..12], [0, 0, 255, 0]);
        assert_eq!(c[12..16], [0, 255, 0, 255]);
    }

    #[test]
    fn patch_colours_differ_between_neighbouring_ids() {
        let c = patch_colours_rgba8(&[0, 1, 2, u32::MAX]);
        assert_ne!(c[0..4], c[4..8]);
        assert_ne!(c[4..8], c[8..12]);
        assert_eq!(c[12..16], [0, 0, 0, 0]);
    }
}
