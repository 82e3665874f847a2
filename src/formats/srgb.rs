//! The sRGB transfer function and its inverse: linear colour to the encoded values images
//! store, and back.

/// The sRGB transfer function of a linear value in [0, 1]:
/// `12.92 c` below 0.0031308, `1.055 c^(1/2.4) − 0.055` above.
#[must_use]
pub fn linear_to_srgb(c: f32) -> f32 {
    let c = c.clamp(0.0, 1.0);
    if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// A value in [0, 1] as a byte, rounded: `round(255 clamp(v, 0, 1))`.
#[must_use]
pub(crate) fn byte(v: f32) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// The inverse sRGB transfer function of an encoded value in [0, 1]:
/// `c / 12.92` up to 0.04045, `((c + 0.055) / 1.055)^2.4` above.
#[must_use]
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.040_45 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    // Reference points of IEC 61966-2-1 (sRGB): linear 0.5 is encoded 0.735357, encoded 0.5
    // is linear 0.214041, and the two pieces meet at encoded 0.04045, linear 0.0031308.

    #[test]
    fn srgb_encoding_matches_its_reference_points() {
        assert_eq!(linear_to_srgb(0.0), 0.0);
        assert!((linear_to_srgb(1.0) - 1.0).abs() < 1e-6);
        assert!((linear_to_srgb(0.5) - 0.735_357).abs() < 1e-5);
        assert!((linear_to_srgb(0.003_130_8) - 0.040_45).abs() < 1e-6);
        // Linear 0.2159 is sRGB 0.502, 128 of 255.
        assert_eq!(byte(linear_to_srgb(0.2159)), 128);
    }

    #[test]
    fn srgb_decoding_matches_its_reference_points() {
        assert_eq!(srgb_to_linear(0.0), 0.0);
        assert!((srgb_to_linear(1.0) - 1.0).abs() < 1e-6);
        assert!((srgb_to_linear(0.5) - 0.214_041).abs() < 1e-5);
        // Both pieces meet at the threshold: no step between it and the next value above.
        let t = 0.040_45_f32;
        assert!((srgb_to_linear(t) - 0.003_130_8).abs() < 1e-7);
        assert!((srgb_to_linear(t.next_up()) - srgb_to_linear(t)).abs() < 1e-7);
    }

    #[test]
    fn decoding_then_encoding_gives_every_byte_back() {
        for k in 0..=255u8 {
            let c = f32::from(k) / 255.0;
            assert_eq!(byte(linear_to_srgb(srgb_to_linear(c))), k);
        }
    }
}
