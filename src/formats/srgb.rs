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

    #[test]
    fn srgb_encoding_matches_its_reference_points() {
        assert_eq!(linear_to_srgb(0.0), 0.0);
        assert!((linear_to_srgb(1.0) - 1.0).abs() < 1e-6);
        // Linear 0.2159 is sRGB 0.502, 128 of 255.
        assert_eq!(byte(linear_to_srgb(0.2159)), 128);
    }

    #[test]
    fn srgb_decoding_matches_its_reference_points() {
        assert_eq!(srgb_to_linear(0.0), 0.0);
        assert!((srgb_to_linear(1.0) - 1.0).abs() < 1e-6);
        // sRGB 128/255 is linear 0.2159.
        assert!((srgb_to_linear(128.0 / 255.0) - 0.2159).abs() < 1e-4);
        // Both branches meet at the threshold.
        let t = 0.040_45;
        assert!((t / 12.92 - ((t + 0.055) / 1.055_f32).powf(2.4)).abs() < 1e-6);
    }
}
