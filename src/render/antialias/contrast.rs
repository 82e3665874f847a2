//! The pixels of a one-sample image that more samples could change: those whose colour differs
//! from a neighbour's.

use glam::Vec4;
use rayon::prelude::*;

use crate::render::colour::premultiplied;
use crate::render::gbuffer::EMPTY;

/// Which pixels of an image the one-sample pass drew right: per pixel the slot of its texel
/// ([`EMPTY`] for none), per texel whether its pixel was drawn right, and per pixel whether it
/// was, covered or not, where more was drawn right than the texels say.
#[derive(Clone, Copy, Debug)]
pub struct DrawnRight<'a> {
    pub slot: &'a [u32],
    pub texels: &'a [bool],
    pub pixels: Option<&'a [bool]>,
}

impl DrawnRight<'_> {
    /// Whether pixel `pixel` was drawn right.
    #[inline]
    #[must_use]
    pub fn at(&self, pixel: usize) -> bool {
        let slot = self.slot[pixel];
        (slot != EMPTY && self.texels[slot as usize]) || self.pixels.is_some_and(|p| p[pixel])
    }
}

/// The largest difference in any channel of premultiplied colour (or of the highlight matte)
/// between a pixel and a neighbour that still counts as the same colour: half a step of an
/// 8-bit image.
pub const CONTRAST: f32 = 0.5 / 255.0;

/// Per pixel of a `width × height` image, whether one of its eight neighbours differs from it by
/// more than [`CONTRAST`] in premultiplied `colour` (straight alpha in, so that coverage
/// counts) or in `matte`, or `also` marks it; but never a pixel `drawn` says was drawn right at
/// one sample (its box lies inside one surface, and every edge there is clear of it or drawn
/// across it at one sample), whatever its neighbours.
///
/// A cel-shaded image is flat between edges, so this finds every edge a pixel centre on either
/// side of it sees: silhouettes (alpha), occlusion and patch edges where the tone differs,
/// highlight and tone-band edges, lines. A straight edge that crosses a pixel passes between its
/// centre and a neighbour's centre across it — the diagonal one where it only cuts a corner —
/// so both are marked. What lies wholly between the centres of neighbouring pixels (a feature
/// thinner than a pixel) is seen only where it changes a centre's colour.
#[must_use]
pub fn pixels_to_supersample(
    colour: &[Vec4],
    matte: Option<&[f32]>,
    also: Option<&[bool]>,
    drawn: Option<DrawnRight<'_>>,
    width: u32,
    height: u32,
) -> Vec<bool> {
    let (w, h) = (width as usize, height as usize);
    let is_drawn = |i: usize| drawn.is_some_and(|d| d.at(i));
    // Each pair of neighbours compared once, from the upper or left one: bit 0 its right
    // neighbour, 1 the one below, 2 below right, 3 below left.
    let mut pairs = vec![0u8; w * h];
    pairs.par_chunks_mut(w).enumerate().for_each(|(y, bits)| {
        // Sets `bit` of `bits[from + k]` for each of the `n` pixels `a + k` that differ from
        // pixel `b + k`. Most neighbours of a cel-shaded frame are the same colour to the bit:
        // that test runs in a tight loop, the rest only where it fails.
        let mut scan = |bit: u8, from: usize, a: usize, b: usize, n: usize| {
            let (ca, cb) = (&colour[a..a + n], &colour[b..b + n]);
            let bits = &mut bits[from..from + n];
            for k in 0..n {
                let same = ca[k] == cb[k] && matte.is_none_or(|m| m[a + k] == m[b + k]);
                let both_drawn = || is_drawn(a + k) && is_drawn(b + k);
                if !same && !both_drawn() && beyond_contrast(colour, matte, a + k, b + k) {
                    bits[k] |= bit;
                }
            }
        };
        let i = y * w;
        scan(1, 0, i, i + 1, w - 1);
        if y + 1 < h {
            scan(2, 0, i, i + w, w);
            scan(4, 0, i, i + w + 1, w - 1);
            scan(8, 1, i + 1, i + w, w - 1);
        }
    });
    let mut marked = vec![false; w * h];
    marked.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        let i = y * w;
        let here = &pairs[i..i + w];
        let above = (y > 0).then(|| &pairs[i - w..i]);
        let also = also.map(|also| &also[i..i + w]);
        for (x, mark) in row.iter_mut().enumerate() {
            let left = x > 0 && here[x - 1] & 1 != 0;
            let from_above = above.is_some_and(|above| {
                above[x] & 2 != 0
                    || (x > 0 && above[x - 1] & 4 != 0)
                    || (x + 1 < w && above[x + 1] & 8 != 0)
            });
            *mark = (here[x] != 0 || left || from_above || also.is_some_and(|also| also[x]))
                && !is_drawn(i + x);
        }
    });
    marked
}

/// Whether pixels `a` and `b` differ by more than [`CONTRAST`] in premultiplied `colour` or in
/// `matte`.
#[inline(never)]
fn beyond_contrast(colour: &[Vec4], matte: Option<&[f32]>, a: usize, b: usize) -> bool {
    (premultiplied(colour[a]) - premultiplied(colour[b]))
        .abs()
        .max_element()
        > CONTRAST
        || matte.is_some_and(|m| (m[a] - m[b]).abs() > CONTRAST)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_edge_marks_the_pixels_on_both_sides_and_nothing_else() {
        // A 6 × 4 image, red on the left three columns, blue on the right three.
        let (w, h) = (6u32, 4u32);
        let colour: Vec<Vec4> = (0..w * h)
            .map(|i| {
                if i % w < 3 {
                    Vec4::new(1.0, 0.0, 0.0, 1.0)
                } else {
                    Vec4::new(0.0, 0.0, 1.0, 1.0)
                }
            })
            .collect();
        let marked = pixels_to_supersample(&colour, None, None, None, w, h);
        for (i, &m) in marked.iter().enumerate() {
            let x = i as u32 % w;
            assert_eq!(m, x == 2 || x == 3, "pixel {i}");
        }
    }

    #[test]
    fn alpha_and_the_matte_count_and_a_diagonal_neighbour_counts() {
        let (w, h) = (3u32, 3u32);
        // One covered pixel in the corner: all four pixels around the corner are marked.
        let mut colour = vec![Vec4::ZERO; 9];
        colour[0] = Vec4::new(0.0, 0.0, 0.0, 1.0);
        let marked = pixels_to_supersample(&colour, None, None, None, w, h);
        assert_eq!(
            marked,
            [true, true, false, true, true, false, false, false, false]
        );
        // The same colour everywhere but a highlight matte in the last pixel.
        let colour = vec![Vec4::ONE; 9];
        let mut matte = vec![0.0; 9];
        matte[8] = 0.5;
        let marked = pixels_to_supersample(&colour, Some(&matte), None, None, w, h);
        assert_eq!(
            marked,
            [false, false, false, false, true, true, false, true, true]
        );
        // Below the contrast, nothing.
        matte[8] = CONTRAST * 0.9;
        assert!(!pixels_to_supersample(&colour, Some(&matte), None, None, w, h).contains(&true));
    }

    #[test]
    fn each_pixel_is_marked_exactly_when_one_of_its_eight_neighbours_differs() {
        // Random blocky images against the definition, neighbour by neighbour: a pixel drawn
        // right is never marked, and one that is not is marked by any neighbour that differs.
        let (w, h) = (13usize, 9usize);
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        for _ in 0..20 {
            let colour: Vec<Vec4> = (0..w * h)
                .map(|_| match next() % 4 {
                    0 => Vec4::ZERO,
                    1 => Vec4::new(0.2, 0.3, 0.4, 1.0),
                    _ => Vec4::new(0.2, 0.3, 0.4 + CONTRAST * 0.5, 1.0),
                })
                .collect();
            let matte: Vec<f32> = (0..w * h).map(|_| (next() % 3) as f32 * 0.4).collect();
            let also: Vec<bool> = (0..w * h).map(|_| next() % 17 == 0).collect();
            // Every other image with some pixels drawn right, by their texels (numbered
            // backwards) and by the pixels themselves, covered or not.
            let with_drawn = next() % 2 == 0;
            let slot: Vec<u32> = (0..w * h)
                .map(|i| {
                    if i % 7 == 3 {
                        EMPTY
                    } else {
                        (w * h - 1 - i) as u32
                    }
                })
                .collect();
            let texels: Vec<bool> = (0..w * h).map(|_| next() % 3 != 0).collect();
            let pixels: Vec<bool> = (0..w * h).map(|_| next() % 5 == 0).collect();
            let drawn = with_drawn.then_some(DrawnRight {
                slot: &slot,
                texels: &texels,
                pixels: Some(&pixels),
            });
            let is_drawn =
                |i: usize| with_drawn && ((slot[i] != EMPTY && texels[w * h - 1 - i]) || pixels[i]);
            let marked = pixels_to_supersample(
                &colour,
                Some(&matte),
                Some(&also),
                drawn,
                w as u32,
                h as u32,
            );
            for y in 0..h {
                for x in 0..w {
                    let i = y * w + x;
                    if is_drawn(i) {
                        assert!(!marked[i], "({x}, {y}) was drawn right");
                        continue;
                    }
                    let mut expected = also[i];
                    for ny in y.saturating_sub(1)..=(y + 1).min(h - 1) {
                        for nx in x.saturating_sub(1)..=(x + 1).min(w - 1) {
                            let j = ny * w + nx;
                            let a = colour[i] * colour[i].w;
                            let b = colour[j] * colour[j].w;
                            let rgb = (a.truncate() - b.truncate()).abs().max_element();
                            let alpha = (colour[i].w - colour[j].w).abs();
                            expected |=
                                rgb.max(alpha) > CONTRAST || (matte[i] - matte[j]).abs() > CONTRAST;
                        }
                    }
                    assert_eq!(marked[i], expected, "({x}, {y})");
                }
            }
        }
    }
}
