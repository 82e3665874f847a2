//! 2D toon textures for the effect families of the X-Toon paper, painted by code so that the
//! shipped images in `textures/` can be remade (`cargo run --example toon_textures`) and edited.
//!
//! Each is drawn as a painter would, in sRGB-encoded values: a 1D toon texture on the top row
//! (D = 1) and a transformation of it down the detail axis. Across, the tone coordinate
//! `x = (n·l + 1) / 2` of each texel centre; down, its detail `D`.

/// Texture width in texels (the tone axis).
pub const WIDTH: usize = 256;
/// Texture height in texels (the detail axis).
pub const HEIGHT: usize = 64;

/// The effect families of X-Toon (Barla, Thollot & Markosian 2006), each with the detail map it
/// is made for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Family {
    /// Figure 7b, levels of abstraction (depth map; also depth of field, Figure 8a): three
    /// tones blurred more and more down the detail axis, to one flat colour at D = 0.
    Abstraction,
    /// Figure 7d, receding shadows (depth map): the shadow slides toward the dark end and
    /// lightens as detail falls, and is gone at D = 0.
    RecedingShadows,
    /// Figure 9, aerial perspective (depth map): greens converge to a blue haze, the darker
    /// tones first.
    AerialPerspective,
    /// Figure 11b, plastic highlight (highlight map): a hard white highlight over the lit tones
    /// whose width along the tone axis narrows as detail falls, gone below D = ½.
    PlasticHighlight,
    /// Figure 11c, metallic flare (highlight map): soft steel tones, and a warm glow that
    /// appears only near D = 1.
    MetalFlare,
    /// Figure 10d, backlighting (near-silhouette map): a pale rim where detail is low, thick in
    /// the light tones and thinner in the dark ones.
    Backlight,
}

/// An image of a family: RGBA8, sRGB-encoded, opaque, rows from the top (D = 1).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FamilyImage {
    pub width: usize,
    pub height: usize,
    /// `4 · width · height` bytes.
    pub rgba: Vec<u8>,
}

type Rgb = [f32; 3];

impl Family {
    /// Every family.
    pub const ALL: [Family; 6] = [
        Family::Abstraction,
        Family::RecedingShadows,
        Family::AerialPerspective,
        Family::PlasticHighlight,
        Family::MetalFlare,
        Family::Backlight,
    ];

    /// The file stem of the shipped image, e.g. `"abstraction"` for `textures/abstraction.png`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Family::Abstraction => "abstraction",
            Family::RecedingShadows => "receding_shadows",
            Family::AerialPerspective => "aerial_perspective",
            Family::PlasticHighlight => "plastic_highlight",
            Family::MetalFlare => "metal_flare",
            Family::Backlight => "backlight",
        }
    }

    /// The family's texture.
    #[must_use]
    pub fn image(self) -> FamilyImage {
        let rows: Vec<Vec<Rgb>> = (0..HEIGHT)
            .map(|j| {
                let d = 1.0 - (j as f32 + 0.5) / HEIGHT as f32;
                self.row(d)
            })
            .collect();
        let rgba = rows
            .iter()
            .flatten()
            .flat_map(|c| [byte(c[0]), byte(c[1]), byte(c[2]), 255])
            .collect();
        FamilyImage {
            width: WIDTH,
            height: HEIGHT,
            rgba,
        }
    }

    /// The row at detail `d`, from `n·l = −1`.
    fn row(self, d: f32) -> Vec<Rgb> {
        let xs = (0..WIDTH).map(|i| (i as f32 + 0.5) / WIDTH as f32);
        match self {
            Family::Abstraction => {
                let bands = [(0.5, [0.42, 0.55, 0.85]), (0.8, [0.80, 0.88, 1.0])];
                let top: Vec<Rgb> = xs
                    .map(|x| bands_at(x, [0.22, 0.26, 0.45], &bands))
                    .collect();
                let sigma = WIDTH as f32 * (1.0 - d) * (1.0 - d);
                blur(&top, sigma)
            }
            Family::RecedingShadows => {
                let (shadow, lit) = ([0.45, 0.30, 0.28], [0.96, 0.80, 0.58]);
                let edge = 0.55 * d;
                let shadow = mix(shadow, lit, 0.6 * (1.0 - d));
                xs.map(|x| if x < edge { shadow } else { lit }).collect()
            }
            Family::AerialPerspective => {
                let bands = [(0.5, [0.35, 0.60, 0.25]), (0.8, [0.78, 0.86, 0.45])];
                let haze = [0.64, 0.72, 0.86];
                xs.map(|x| {
                    let base = bands_at(x, [0.14, 0.30, 0.16], &bands);
                    let f = ((1.0 - d) * (1.0 + 0.8 * (1.0 - x))).min(1.0);
                    mix(base, haze, smoothstep(0.0, 1.0, f))
                })
                .collect()
            }
            Family::PlasticHighlight => {
                let (shadow, lit) = ([0.45, 0.08, 0.10], [0.86, 0.20, 0.22]);
                xs.map(|x| {
                    // White where D ≥ 1 − (x − ½): from D = ½ at n·l = 1 to D = 1 at n·l = 0.
                    if x >= 0.5 && d >= 1.5 - x {
                        [1.0, 1.0, 1.0]
                    } else if x >= 0.5 {
                        lit
                    } else {
                        shadow
                    }
                })
                .collect()
            }
            Family::MetalFlare => {
                let (dark, mid, light) =
                    ([0.16, 0.18, 0.24], [0.44, 0.49, 0.58], [0.72, 0.76, 0.82]);
                let glow = [1.0, 0.93, 0.72];
                xs.map(|x| {
                    let base = mix(
                        mix(dark, mid, smoothstep(0.38, 0.55, x)),
                        light,
                        smoothstep(0.7, 0.9, x),
                    );
                    let g = smoothstep(0.8, 1.0, d) * smoothstep(0.3, 0.8, x);
                    mix(base, glow, g)
                })
                .collect()
            }
            Family::Backlight => {
                let (shadow, lit, rim) =
                    ([0.28, 0.26, 0.48], [0.58, 0.56, 0.84], [1.0, 0.97, 0.86]);
                xs.map(|x| {
                    if d < 0.06 + 0.34 * x {
                        rim
                    } else if x < 0.5 {
                        shadow
                    } else {
                        lit
                    }
                })
                .collect()
            }
        }
    }
}

/// Hard bands: `base` below the first threshold, else the colour of the last threshold ≤ x.
fn bands_at(x: f32, base: Rgb, bands: &[(f32, Rgb)]) -> Rgb {
    bands
        .iter()
        .take_while(|(t, _)| x >= *t)
        .last()
        .map_or(base, |b| b.1)
}

/// `a + t (b − a)` per channel.
fn mix(a: Rgb, b: Rgb, t: f32) -> Rgb {
    [0, 1, 2].map(|k| a[k] + t * (b[k] - a[k]))
}

/// `3s² − 2s³` of `s = (x − a)/(b − a)` clamped to [0, 1].
fn smoothstep(a: f32, b: f32, x: f32) -> f32 {
    let s = ((x - a) / (b - a)).clamp(0.0, 1.0);
    s * s * (3.0 - 2.0 * s)
}

/// A Gaussian blur of standard deviation `sigma` texels along the row, mirrored at its ends (so
/// that a wide blur tends to the row's mean colour).
fn blur(row: &[Rgb], sigma: f32) -> Vec<Rgb> {
    if sigma < 0.05 {
        return row.to_vec();
    }
    let radius = (3.0 * sigma).ceil() as isize;
    let weights: Vec<f32> = (-radius..=radius)
        .map(|k| (-0.5 * (k as f32 / sigma).powi(2)).exp())
        .collect();
    let total: f32 = weights.iter().sum();
    let n = row.len() as isize;
    let mirrored = |i: isize| {
        let m = i.rem_euclid(2 * n);
        (if m < n { m } else { 2 * n - 1 - m }) as usize
    };
    (0..n)
        .map(|i| {
            let mut sum = [0.0; 3];
            for (k, w) in (-radius..=radius).zip(&weights) {
                let c = row[mirrored(i + k)];
                for (s, c) in sum.iter_mut().zip(c) {
                    *s += w * c;
                }
            }
            sum.map(|s| s / total)
        })
        .collect()
}

/// An sRGB-encoded value in [0, 1] as a byte.
fn byte(v: f32) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texel(image: &FamilyImage, x: usize, y: usize) -> [u8; 3] {
        let k = 4 * (y * image.width + x);
        [image.rgba[k], image.rgba[k + 1], image.rgba[k + 2]]
    }

    #[test]
    fn abstraction_is_hard_on_top_and_flat_at_the_bottom() {
        let image = Family::Abstraction.image();
        assert_eq!(image.rgba.len(), 4 * WIDTH * HEIGHT);
        // Top row: three flat bands with hard steps.
        assert_eq!(texel(&image, 0, 0), texel(&image, 127, 0));
        assert_ne!(texel(&image, 127, 0), texel(&image, 128, 0));
        // Bottom row: nearly one colour.
        let (a, b) = (
            texel(&image, 0, HEIGHT - 1),
            texel(&image, WIDTH - 1, HEIGHT - 1),
        );
        assert!(
            a.iter().zip(b).all(|(a, b)| a.abs_diff(b) < 40),
            "{a:?} {b:?}"
        );
        assert!(image.rgba.chunks(4).all(|p| p[3] == 255));
    }

    #[test]
    fn plastic_highlight_narrows_down_the_detail_axis() {
        let image = Family::PlasticHighlight.image();
        let white = |y: usize| {
            (0..WIDTH)
                .filter(|&x| texel(&image, x, y) == [255; 3])
                .count()
        };
        assert!(white(0) > white(HEIGHT / 4));
        assert!(white(HEIGHT / 4) > 0);
        assert_eq!(white(HEIGHT - 1), 0);
    }

    #[test]
    fn blur_keeps_a_constant_row() {
        let row = vec![[0.3, 0.5, 0.7]; 10];
        for c in blur(&row, 4.0) {
            assert!(c
                .iter()
                .zip([0.3, 0.5, 0.7])
                .all(|(a, b)| (a - b).abs() < 1e-6));
        }
    }
}
