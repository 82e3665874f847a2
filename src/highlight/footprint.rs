//! A pixel's footprint of the highlight's signed inside value, and the coverage of the pixel by
//! the edge it gives.

use super::inside::coverage_from_signed;
use crate::math::box_coverage;

/// How much the signed inside value `s` changes from one pixel to the next along x and along
/// y: what the renderer knows of the pixel's box for analytic anti-aliasing. Zero: a hard edge
/// at the pixel's centre, as in Anjyo & Hiramitsu 2003.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Footprint {
    /// `|∂s/∂x|` over one pixel.
    pub x: f32,
    /// `|∂s/∂y|` over one pixel.
    pub y: f32,
}

impl Footprint {
    /// No footprint: the hard edge.
    pub const HARD: Footprint = Footprint { x: 0.0, y: 0.0 };

    /// The larger of two footprints, component by component.
    #[must_use]
    pub fn max(self, other: Footprint) -> Footprint {
        Footprint {
            x: self.x.max(other.x),
            y: self.y.max(other.y),
        }
    }

    /// The edge's coverage of the pixel from the signed value `s` at its centre, for a layer
    /// with feather `feather`: without feather the exact box coverage of a straight edge
    /// ([`box_coverage`](crate::math::box_coverage)); with one, a smoothstep over the feather widened by the footprint
    /// `x + y` ([`coverage_from_signed`]).
    #[inline]
    #[must_use]
    pub fn coverage(self, s: f32, feather: f32) -> f32 {
        if feather > 0.0 {
            coverage_from_signed(s, feather + self.x + self.y)
        } else {
            box_coverage(s, self.x, self.y)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_box_coverage_is_exact_where_a_smoothstep_is_a_tenth_off() {
        // A quarter into a vertical edge: where a smoothstep over the footprint is a tenth off: a quarter into a vertical edge.
        let quarter = box_coverage(-0.25, 1.0, 0.0);
        assert!((quarter - 0.25).abs() < 1e-6, "{quarter}");
        assert!((coverage_from_signed(-0.25, 1.0) - 0.25).abs() > 0.09);
    }

    #[test]
    fn a_footprint_widens_a_feather_and_is_exact_without_one() {
        let f = Footprint { x: 1.0, y: 0.0 };
        assert_eq!(f.coverage(-0.25, 0.0), box_coverage(-0.25, 1.0, 0.0));
        assert_eq!(f.coverage(-0.25, 0.5), coverage_from_signed(-0.25, 1.5));
        assert_eq!(Footprint::HARD.coverage(1e-9, 0.0), 1.0);
        assert_eq!(Footprint::HARD.coverage(-1e-9, 0.0), 0.0);
    }
}
