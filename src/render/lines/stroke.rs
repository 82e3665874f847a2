//! Strokes: capsules (segments widened by a radius, with round ends) drawn into a coverage
//! image with analytic anti-aliasing.

use glam::Vec2;
use rayon::prelude::*;

/// A segment from `a` to `b` (in pixels), widened by `radius` on every side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Capsule {
    pub a: Vec2,
    pub b: Vec2,
    pub radius: f32,
    /// The coverage inside, in [0, 1].
    pub opacity: f32,
}

impl Capsule {
    /// The coverage of the pixel centred at `c`: `opacity · clamp(r + ½ − d, 0, 1)` with `d`
    /// the distance from `c` to the segment. Across a straight stroke this sums to its width
    /// `2r` (for `r ≥ ½`), and the half-pixel ramp at each side is the box filter of an edge
    /// met head on.
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
        self.opacity * (self.radius + 0.5 - d).clamp(0.0, 1.0)
    }
}

/// Rows of the image drawn by one job.
const BAND: usize = 16;

/// Draws `capsules` into `alpha` (a `width × height` image): each pixel keeps the largest
/// coverage any capsule gives it, so that where strokes overlap (a join) the ink is not
/// doubled.
pub(crate) fn draw(capsules: &[Capsule], (width, height): (u32, u32), alpha: &mut [f32]) {
    let (w, h) = (width as usize, height as usize);
    assert_eq!(alpha.len(), w * h, "one coverage per pixel");
    if w == 0 {
        return;
    }
    // The pixel rectangle each capsule can cover: [x0, x1) × [y0, y1).
    let bounds: Vec<[usize; 4]> = capsules
        .iter()
        .map(|c| {
            let reach = c.radius + 0.5;
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
    alpha
        .par_chunks_mut(w * BAND)
        .enumerate()
        .for_each(|(band, rows)| {
            let (top, bottom) = (band * BAND, band * BAND + rows.len() / w);
            for (c, &[x0, x1, y0, y1]) in capsules.iter().zip(&bounds) {
                for y in y0.max(top)..y1.min(bottom) {
                    let row = &mut rows[(y - top) * w..][..w];
                    for (x, a) in row.iter_mut().enumerate().take(x1).skip(x0) {
                        let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
                        *a = a.max(c.coverage(centre));
                    }
                }
            }
        });
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
            radius: 1.5,
            opacity: 1.0,
        };
        let (w, h) = (64, 40);
        let mut alpha = vec![0.0; w * h];
        draw(&[capsule], (w as u32, h as u32), &mut alpha);
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
            radius: 1.0,
            opacity: 0.6,
        };
        let (w, h) = (32, 32);
        let mut alpha = vec![0.0; w * h];
        let crossing = [
            stroke(Vec2::new(2.0, 16.0), Vec2::new(30.0, 16.0)),
            stroke(Vec2::new(16.0, 2.0), Vec2::new(16.0, 30.0)),
            stroke(Vec2::new(2.0, 16.0), Vec2::new(30.0, 16.0)),
        ];
        draw(&crossing, (w as u32, h as u32), &mut alpha);
        let most = alpha.iter().copied().fold(0.0f32, f32::max);
        assert!((most - 0.6).abs() < 1e-6, "{most}");
    }
}
