//! Strokes: capsules (segments widened by a radius, with round ends) drawn into a coverage
//! image with analytic anti-aliasing.

use glam::Vec2;
use rayon::prelude::*;

/// A segment from `a` to `b` (in pixels), widened on every side by a radius that runs from
/// `radii[0]` at `a` to `radii[1]` at `b`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Capsule {
    pub a: Vec2,
    pub b: Vec2,
    pub radii: [f32; 2],
    /// The coverage inside, in [0, 1].
    pub opacity: f32,
    /// Its colour's index in the line image's palette.
    pub colour: u32,
}

impl Capsule {
    /// The coverage of the pixel centred at `c`: `opacity · clamp(r(t) + ½ − d, 0, 1)` with
    /// `t ∈ [0, 1]` the nearest point of the segment to `c`, `d` the distance to it and
    /// `r(t) = (1 − t) r₀ + t r₁`. Across a straight stroke of one radius this sums to its width
    /// `2r` (for `r ≥ ½`), and the half-pixel ramp at each side is the box filter of an edge
    /// met head on. Where the radius changes (a taper, over many pixels) the nearest point
    /// stands in for the point of tangency, which differs from it by a fraction of the slope.
    #[inline]
    #[must_use]
    pub fn coverage(&self, c: Vec2) -> f32 {
        let ab = self.b - self.a;
        let along = ab.length_squared();
        let t = if along > 0.0 {
            ((c - self.a).dot(ab) / along).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let d = (c - (self.a + ab * t)).length();
        let radius = self.radii[0] + (self.radii[1] - self.radii[0]) * t;
        self.opacity * (radius + 0.5 - d).clamp(0.0, 1.0)
    }
}

/// Rows of the image drawn by one job.
pub(crate) const BAND: usize = 16;

/// Draws `capsules` into `alpha` (a `width × height` image): each pixel keeps the largest
/// coverage any capsule gives it, so that where strokes overlap (a join) the ink is not
/// doubled. When `colour` is not empty (one per pixel), each pixel takes the colour of the
/// capsule that gave it that coverage (the first of equals). Returns, per band of [`BAND`]
/// rows from the top, how many of its pixels are inked (coverage above 0).
pub(crate) fn draw(
    capsules: &[Capsule],
    (width, height): (u32, u32),
    alpha: &mut [f32],
    colour: &mut [u32],
) -> Vec<u32> {
    let (w, h) = (width as usize, height as usize);
    assert_eq!(alpha.len(), w * h, "one coverage per pixel");
    let coloured = !colour.is_empty();
    assert!(!coloured || colour.len() == w * h, "one colour per pixel");
    if w == 0 {
        return Vec::new();
    }
    // The pixel rectangle each capsule can cover: [x0, x1) × [y0, y1).
    let bounds: Vec<[usize; 4]> = capsules
        .iter()
        .map(|c| {
            let reach = c.radii[0].max(c.radii[1]) + 0.5;
            let (lo, hi) = (c.a.min(c.b) - reach, c.a.max(c.b) + reach);
            let clamp = |v: f32, n: usize| (v.max(0.0) as usize).min(n);
            [
                clamp(lo.x.floor(), w),
                clamp(hi.x.ceil() + 1.0, w),
                clamp(lo.y.floor(), h),
                clamp(hi.y.ceil() + 1.0, h),
            ]
        })
        .collect();
    // Per band, the capsules that reach it, in their order.
    let bands = alpha.len().div_ceil(w * BAND);
    let mut reaching: Vec<Vec<u32>> = vec![Vec::new(); bands];
    for (k, &[_, _, y0, y1]) in (0..).zip(&bounds) {
        for band in reaching.iter_mut().take(y1.div_ceil(BAND)).skip(y0 / BAND) {
            band.push(k);
        }
    }
    // With one colour the colour image is empty: split it as if it had no rows.
    let colour_band = if coloured { w * BAND } else { 1 };
    let mut colour_bands: Vec<&mut [u32]> = colour.chunks_mut(colour_band).collect();
    colour_bands.resize_with(bands, Default::default);
    alpha
        .par_chunks_mut(w * BAND)
        .zip(colour_bands)
        .zip(&reaching)
        .enumerate()
        .map(|(band, ((rows, colours), reaching))| {
            let (top, bottom) = (band * BAND, band * BAND + rows.len() / w);
            for &k in reaching {
                let (c, &[x0, x1, y0, y1]) = (&capsules[k as usize], &bounds[k as usize]);
                for y in y0.max(top)..y1.min(bottom) {
                    let row = (y - top) * w;
                    for x in x0..x1 {
                        let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                        let coverage = c.coverage(centre);
                        if coverage > rows[row + x] {
                            rows[row + x] = coverage;
                            if coloured {
                                colours[row + x] = c.colour;
                            }
                        }
                    }
                }
            }
            rows.iter().filter(|&&a| a > 0.0).count() as u32
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_straight_stroke_covers_its_width_across_and_ends_round() {
        // A horizontal stroke 3 px wide through y = 20.3, from x = 10 to 50.
        let capsule = Capsule {
            a: Vec2::new(10.0, 20.3),
            b: Vec2::new(50.0, 20.3),
            radii: [1.5; 2],
            opacity: 1.0,
            colour: 0,
        };
        let (w, h) = (64, 40);
        let mut alpha = vec![0.0; w * h];
        draw(&[capsule], (w as u32, h as u32), &mut alpha, &mut []);
        let column = |x: usize| (0..h).map(|y| alpha[y * w + x]).collect::<Vec<f32>>();
        let across = column(30);
        let sum: f32 = across.iter().sum();
        assert!((sum - 3.0).abs() < 1e-4, "coverage across {sum}");
        let centre: f32 = across
            .iter()
            .enumerate()
            .map(|(y, a)| (y as f32 + 0.5) * a)
            .sum::<f32>()
            / sum;
        assert!((centre - 20.3).abs() < 1e-3, "centred at {centre}");
        // Beyond the end by more than the radius and half a pixel: nothing; along the end's
        // axis the cap reaches as far as the sides do.
        assert_eq!(alpha[20 * w + 52], 0.0);
        assert!(alpha[20 * w + 51] > 0.0);
        assert_eq!(column(5).iter().sum::<f32>(), 0.0);
    }

    #[test]
    fn overlapping_strokes_do_not_double_the_ink() {
        let stroke = |a: Vec2, b: Vec2| Capsule {
            a,
            b,
            radii: [1.0; 2],
            opacity: 0.6,
            colour: 0,
        };
        let (w, h) = (32, 32);
        let mut alpha = vec![0.0; w * h];
        let crossing = [
            stroke(Vec2::new(2.0, 16.0), Vec2::new(30.0, 16.0)),
            stroke(Vec2::new(16.0, 2.0), Vec2::new(16.0, 30.0)),
            stroke(Vec2::new(2.0, 16.0), Vec2::new(30.0, 16.0)),
        ];
        draw(&crossing, (w as u32, h as u32), &mut alpha, &mut []);
        let most = alpha.iter().copied().fold(0.0f32, f32::max);
        assert!((most - 0.6).abs() < 1e-6, "{most}");
    }

    #[test]
    fn a_tapered_stroke_narrows_linearly_and_each_pixel_takes_the_colour_of_its_ink() {
        // A stroke along y = 20.5 whose radius runs from 0 at x = 10 to 3 at x = 70, and a
        // 1 px stroke of another colour crossing it at x = 40.
        let (w, h) = (80usize, 40usize);
        let taper = Capsule {
            a: Vec2::new(10.0, 20.5),
            b: Vec2::new(70.0, 20.5),
            radii: [0.0, 3.0],
            opacity: 1.0,
            colour: 7,
        };
        let crossing = Capsule {
            a: Vec2::new(40.5, 2.0),
            b: Vec2::new(40.5, 38.0),
            radii: [0.5, 0.5],
            opacity: 1.0,
            colour: 9,
        };
        let mut alpha = vec![0.0; w * h];
        let mut colour = vec![u32::MAX; w * h];
        draw(
            &[taper, crossing],
            (w as u32, h as u32),
            &mut alpha,
            &mut colour,
        );
        // Across the stroke at x (away from the crossing), the coverage sums to the width there
        // (for a radius of ½ or more).
        for x in [25usize, 33, 50, 60] {
            let sum: f32 = (0..h).map(|y| alpha[y * w + x]).sum();
            let width = 2.0 * 3.0 * (x as f32 + 0.5 - 10.0) / 60.0;
            assert!(
                (sum - width).abs() < 0.02,
                "at x = {x}: {sum} against {width}"
            );
        }
        for p in 0..w * h {
            match colour[p] {
                u32::MAX => assert_eq!(alpha[p], 0.0),
                c => {
                    assert!(alpha[p] > 0.0);
                    let (x, y) = ((p % w) as f32 + 0.5, (p / w) as f32 + 0.5);
                    let expected =
                        if taper.coverage(Vec2::new(x, y)) >= crossing.coverage(Vec2::new(x, y)) {
                            7
                        } else {
                            9
                        };
                    assert_eq!(c, expected, "pixel {p}");
                }
            }
        }
        // Beside the taper the crossing's colour shows; where both ink a pixel fully, the
        // first drawn keeps it.
        assert_eq!(colour[23 * w + 40], 9);
        assert_eq!(colour[20 * w + 40], 7);
        assert_eq!(colour[20 * w + 65], 7);
    }
}
