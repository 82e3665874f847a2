//! Accuracy and output settings, with the `preview` and `final` presets (docs/accuracy.md).

use std::fmt;

use serde::Deserialize;

use super::tessellate::Density;
use super::RenderError;

/// Where shading frames come from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
pub enum FrameMode {
    /// The vertex frames, interpolated across each triangle (perspective-correct) and
    /// re-orthonormalized.
    Interpolated,
    /// The exact NURBS frame, evaluated at each pixel's perspective-correct (u, v).
    #[default]
    Exact,
    /// The exact frame after Newton steps move (u, v) so that the surface point lies on the
    /// pixel's ray: the frame of the point the pixel really sees, not of the flat triangle's.
    Refined,
}

/// Edge anti-aliasing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
pub enum Antialias {
    /// One sample per pixel: hard edges, the look of Anjyo & Hiramitsu's stylized highlights
    /// (2003).
    #[default]
    None,
    /// One sample per pixel; highlight edges smoothed over the pixel's footprint of the signed
    /// inside value (its screen-space derivatives), and cel band edges that cross a pixel
    /// straight inside one patch covering it as straight edges of `N·L`. Silhouettes stay
    /// hard.
    Analytic,
    /// K × K samples per pixel, box-filtered (K from 2 to 8).
    Supersample(u32),
    /// One sample per pixel with analytic band edges and the highlight edges that cross a
    /// pixel smoothly drawn from the quadratic of their signed value, then K × K samples (K
    /// from 2 to 8), each with analytic highlight edges at its own footprint, in just the
    /// pixels the one sample did not draw right and whose colour differs from a neighbour's:
    /// silhouettes, edges that bend sharply or meet another patch, two edges in one pixel,
    /// lines. A pixel whose eight neighbours agree with it is shaded once. Memory is that of
    /// one sample per pixel plus a small tile per worker.
    Adaptive(u32),
}

impl fmt::Display for FrameMode {
    /// The mode as benchmarks, tables and `--stats` name it: `interpolated`, `exact`, `refined`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            FrameMode::Interpolated => "interpolated",
            FrameMode::Exact => "exact",
            FrameMode::Refined => "refined",
        })
    }
}

impl fmt::Display for Antialias {
    /// `none`, `analytic`, `ssaa K` for K × K samples, or `adaptive K`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Antialias::None => f.write_str("none"),
            Antialias::Analytic => f.write_str("analytic"),
            Antialias::Supersample(k) => write!(f, "ssaa {k}"),
            Antialias::Adaptive(k) => write!(f, "adaptive {k}"),
        }
    }
}

/// How to render a frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    pub width: u32,
    pub height: u32,
    pub density: Density,
    pub frames: FrameMode,
    pub antialias: Antialias,
    /// Worker threads; 0 uses one per core.
    pub threads: usize,
}

/// The most worker threads a frame may ask for: far beyond the cores of any machine, and few
/// enough that starting them is quick.
pub const MAX_THREADS: usize = 1024;

/// The largest image side glint renders (samples included under supersampling).
pub const MAX_SIDE: u32 = 16384;

impl Settings {
    /// Fast feedback: coarse adaptive tessellation, interpolated frames, no anti-aliasing.
    pub fn preview(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            density: Density::ScreenTolerance { pixels: 1.0 },
            frames: FrameMode::Interpolated,
            antialias: Antialias::None,
            threads: 0,
        }
    }

    /// Finished frames: fine adaptive tessellation (0.05 px), refined frames, adaptive 4 × 4
    /// anti-aliasing — the cheapest measured setting whose highlight mattes reach soft IoU
    /// ≥ 0.995 against the analytic sphere at 256 × 256 on every view of the hard ladder, with
    /// anti-aliased silhouettes (docs/accuracy.md).
    pub fn final_quality(width: u32, height: u32) -> Self {
        Self {
            width,
            height,
            density: Density::ScreenTolerance { pixels: 0.05 },
            frames: FrameMode::Refined,
            antialias: Antialias::Adaptive(4),
            threads: 0,
        }
    }

    /// Samples per pixel side of the whole-image buffers: K under supersampling, otherwise 1
    /// (adaptive anti-aliasing takes its K × K samples tile by tile).
    pub fn samples_per_side(&self) -> u32 {
        match self.antialias {
            Antialias::None | Antialias::Analytic | Antialias::Adaptive(_) => 1,
            Antialias::Supersample(k) => k,
        }
    }

    /// Checks the image size, the supersampling factor, the density and the thread count.
    pub fn validate(&self) -> Result<(), RenderError> {
        let bad = |what: String| Err(RenderError::Settings(what));
        if self.threads > MAX_THREADS {
            return bad(format!(
                "{} worker threads is more than the {MAX_THREADS} a frame may use (0 uses one per core)",
                self.threads
            ));
        }
        if let Antialias::Supersample(k) | Antialias::Adaptive(k) = self.antialias {
            if !(2..=8).contains(&k) {
                return bad(format!(
                    "supersampling takes 2 to 8 samples per side, got {k}"
                ));
            }
        }
        let k = u64::from(match self.antialias {
            Antialias::None | Antialias::Analytic => 1,
            Antialias::Supersample(k) | Antialias::Adaptive(k) => k,
        });
        let fits = |side: u32| side > 0 && u64::from(side) * k <= u64::from(MAX_SIDE);
        if !fits(self.width) || !fits(self.height) {
            return bad(format!(
                "image size {}×{} (× {k} samples per side) must be between 1 and {MAX_SIDE} per side",
                self.width, self.height
            ));
        }
        match self.density {
            Density::PerSpan { u, v } if u == 0 || v == 0 || u > 256 || v > 256 => bad(format!(
                "segments per span must be 1 to 256, got ({u}, {v})"
            )),
            Density::ScreenTolerance { pixels } if !(pixels.is_finite() && pixels >= 0.01) => bad(
                format!("the screen tolerance must be at least 0.01 pixels, got {pixels}"),
            ),
            _ => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn out_of_range_settings_are_errors_not_panics() {
        assert!(Settings::preview(640, 480).validate().is_ok());
        assert!(Settings::final_quality(640, 480).validate().is_ok());
        for bad in [
            Settings::preview(0, 480),
            Settings::preview(u32::MAX, 480),
            Settings::final_quality(MAX_SIDE, 16),
            Settings {
                threads: MAX_THREADS + 1,
                ..Settings::preview(64, 64)
            },
            Settings {
                antialias: Antialias::Supersample(9),
                ..Settings::preview(64, 64)
            },
            Settings {
                antialias: Antialias::Adaptive(1),
                ..Settings::preview(64, 64)
            },
            Settings {
                density: Density::PerSpan { u: 0, v: 4 },
                ..Settings::preview(64, 64)
            },
            Settings {
                density: Density::ScreenTolerance { pixels: f32::NAN },
                ..Settings::preview(64, 64)
            },
        ] {
            assert!(
                matches!(bad.validate(), Err(RenderError::Settings(_))),
                "{bad:?}"
            );
        }
    }
}
