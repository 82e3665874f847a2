//! Cel ramps: a few flat bands of colour over `n·l` (docs/xtoon.md).

use glam::Vec3;
use serde::Deserialize;
use thiserror::Error;

use crate::math::box_coverage;
use crate::param::is_colour_component;

/// Flat colour bands over `n·l ∈ [−1, 1]`: the colour of the band with the highest threshold not
/// above `n·l`, or `base` below every threshold. For the classic two-tone look, a shadow colour
/// as `base` and one band `(0.0, lit colour)`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CelRamp {
    /// Linear RGB below every threshold (the deepest shadow).
    pub base: Vec3,
    /// `(threshold, linear RGB)` in increasing threshold order.
    #[serde(default)]
    pub bands: Vec<(f32, Vec3)>,
}

/// A cel ramp that cannot be used.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum ToneError {
    #[error("band thresholds must increase: {threshold} follows {previous}")]
    ThresholdOrder { threshold: f32, previous: f32 },
    #[error("band threshold {threshold} is outside [-1, 1], the range of n·l")]
    ThresholdRange { threshold: f32 },
    #[error(
        "colour {colour:?} must have components from 0 to 1e4 (linear RGB, 1 the display's white)"
    )]
    Colour { colour: [f32; 3] },
}

impl CelRamp {
    /// Two tones: `shadow` where `n·l < threshold`, `lit` from there on.
    pub fn two_tone(shadow: Vec3, lit: Vec3, threshold: f32) -> Self {
        Self {
            base: shadow,
            bands: vec![(threshold, lit)],
        }
    }

    /// Checks thresholds (in [−1, 1], increasing) and colours (each component in
    /// `[0, MAX_COLOUR]`).
    pub fn validate(&self) -> Result<(), ToneError> {
        let colours = std::iter::once(self.base).chain(self.bands.iter().map(|b| b.1));
        for colour in colours {
            if !colour.to_array().into_iter().all(is_colour_component) {
                return Err(ToneError::Colour {
                    colour: colour.to_array(),
                });
            }
        }
        let mut previous = f32::NEG_INFINITY;
        for &(threshold, _) in &self.bands {
            if !(-1.0..=1.0).contains(&threshold) {
                return Err(ToneError::ThresholdRange { threshold });
            }
            if threshold <= previous {
                return Err(ToneError::ThresholdOrder {
                    threshold,
                    previous,
                });
            }
            previous = threshold;
        }
        Ok(())
    }

    /// The colour at `n_dot_l`.
    #[must_use]
    pub fn shade(&self, n_dot_l: f32) -> Vec3 {
        match self.band(n_dot_l) {
            0 => self.base,
            k => self.bands[k - 1].1,
        }
    }

    /// The mean colour over a pixel's box across which `n·l` is linear, `n_dot_l` at its centre
    /// and changing by `g_x`, `g_y` from one pixel to the next: each band's edge covers the box
    /// as a straight edge would ([`box_coverage`]), and the bands are nested (a point past a
    /// threshold is past every lower one), so
    /// `base + Σ_k box_coverage(n·l − t_k, g_x, g_y) (c_k − c_{k−1})`, with `c_0` the base.
    /// With `g_x = g_y = 0`, [`shade`](Self::shade) but for a point exactly on a threshold.
    #[must_use]
    pub fn shade_over_box(&self, n_dot_l: f32, gx: f32, gy: f32) -> Vec3 {
        let mut colour = self.base;
        let mut below = self.base;
        for &(threshold, band) in &self.bands {
            // Wholly past a threshold is wholly past every lower one: the band's own colour.
            match box_coverage(n_dot_l - threshold, gx, gy) {
                c if c >= 1.0 => colour = band,
                c => colour += c * (band - below),
            }
            below = band;
        }
        colour
    }

    /// The colour of every `n·l` in `[low, high]` when they all fall in one band, else `None`.
    #[must_use]
    pub fn uniform_between(&self, low: f32, high: f32) -> Option<Vec3> {
        (low <= high && self.band(low) == self.band(high)).then(|| self.shade(low))
    }

    /// The threshold nearest `n_dot_l`, if the ramp has bands (and `n_dot_l` is not NaN).
    #[must_use]
    pub fn nearest_threshold(&self, n_dot_l: f32) -> Option<f32> {
        self.bands
            .iter()
            .map(|&(threshold, _)| threshold)
            .filter(|_| !n_dot_l.is_nan())
            .min_by(|a, b| (a - n_dot_l).abs().total_cmp(&(b - n_dot_l).abs()))
    }

    /// How many thresholds `n_dot_l` reaches: 0 below the first (the base colour) or for NaN,
    /// k in the k-th band.
    #[inline]
    fn band(&self, n_dot_l: f32) -> usize {
        self.bands
            .iter()
            .take_while(|(threshold, _)| n_dot_l >= *threshold)
            .count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bands_switch_at_their_thresholds() {
        let ramp = CelRamp {
            base: Vec3::splat(0.1),
            bands: vec![(-0.2, Vec3::splat(0.4)), (0.5, Vec3::splat(0.9))],
        };
        assert!(ramp.validate().is_ok());
        assert_eq!(ramp.shade(-1.0), Vec3::splat(0.1));
        assert_eq!(ramp.shade(-0.2), Vec3::splat(0.4));
        assert_eq!(ramp.shade(0.49), Vec3::splat(0.4));
        assert_eq!(ramp.shade(0.5), Vec3::splat(0.9));
        assert_eq!(ramp.shade(f32::NAN), Vec3::splat(0.1));
        assert_eq!(ramp.uniform_between(-0.2, 0.49), Some(Vec3::splat(0.4)));
        assert_eq!(ramp.uniform_between(0.5, 1.0), Some(Vec3::splat(0.9)));
        assert_eq!(ramp.uniform_between(-0.21, 0.0), None);
        assert_eq!(ramp.uniform_between(0.4, 0.5), None);
        assert_eq!(ramp.uniform_between(f32::NAN, 0.0), None);
    }

    #[test]
    fn a_box_takes_the_mean_of_its_points_colours() {
        // Two bands whose edges both cross the box: against the mean of `shade` over a
        // 400 × 400 grid of points of the linear n·l.
        let ramp = CelRamp {
            base: Vec3::new(0.1, 0.2, 0.3),
            bands: vec![
                (0.0, Vec3::new(0.5, 0.4, 0.9)),
                (0.08, Vec3::new(1.0, 0.9, 0.2)),
            ],
        };
        let n = 400;
        for (centre, gx, gy) in [
            (0.04f32, 0.1f32, 0.03f32),
            (0.01, -0.05, 0.2),
            (0.2, 0.1, 0.1),
        ] {
            let mut mean = Vec3::ZERO;
            for i in 0..n * n {
                let x = ((i % n) as f32 + 0.5) / n as f32 - 0.5;
                let y = ((i / n) as f32 + 0.5) / n as f32 - 0.5;
                mean += ramp.shade(centre + gx * x + gy * y);
            }
            mean /= (n * n) as f32;
            let boxed = ramp.shade_over_box(centre, gx, gy);
            assert!(
                (boxed - mean).abs().max_element() < 5e-3,
                "{centre} ({gx}, {gy}): {boxed} vs {mean}"
            );
        }
        // Far from every threshold, and without a footprint, the point's colour.
        assert_eq!(ramp.shade_over_box(0.5, 0.1, 0.1), ramp.shade(0.5));
        assert_eq!(ramp.shade_over_box(0.03, 0.0, 0.0), ramp.shade(0.03));
    }

    #[test]
    fn invalid_ramps_say_what_is_wrong() {
        let mut ramp = CelRamp::two_tone(Vec3::ZERO, Vec3::ONE, 0.0);
        ramp.bands.push((-0.5, Vec3::ONE));
        assert!(matches!(
            ramp.validate(),
            Err(ToneError::ThresholdOrder { .. })
        ));
        let ramp = CelRamp::two_tone(Vec3::ZERO, Vec3::ONE, 1.5);
        assert!(matches!(
            ramp.validate(),
            Err(ToneError::ThresholdRange { .. })
        ));
        let ramp = CelRamp::two_tone(Vec3::new(0.0, -1.0, 0.0), Vec3::ONE, 0.0);
        assert!(ramp.validate().unwrap_err().to_string().contains("colour"));
    }
}
