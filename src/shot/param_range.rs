//! The range each highlight layer parameter must lie in, as the layer's validation checks it
//! (`Op::validate`, `Layer::validate`): what an editor's slider and number field allow.

use super::param_path::{LayerParam, OpParam};
use crate::param::{Bounds, Range};

impl LayerParam {
    /// The values the parameter may take at any frame. A pin's (u, v) must also lie in its
    /// patch's domain and a mask's bounds in order, which no range of one number says.
    #[must_use]
    pub fn bounds(self) -> Bounds {
        let range = match self {
            LayerParam::Epsilon => Range::Epsilon,
            LayerParam::Colour(_)
            | LayerParam::MaskU(_)
            | LayerParam::MaskV(_)
            | LayerParam::PinU
            | LayerParam::PinV => Range::Finite,
            LayerParam::Opacity => Range::Unit,
            LayerParam::Feather | LayerParam::MaskFeather => Range::NonNegative,
            LayerParam::Op { param, .. } => match param {
                OpParam::Alpha | OpParam::Beta => Range::Step,
                OpParam::Degrees | OpParam::Axis => Range::Finite,
                OpParam::Delta | OpParam::Sigma => Range::Unit,
                OpParam::GammaU | OpParam::GammaV => Range::NonNegativeStep,
                OpParam::N => Range::Positive,
            },
        };
        range.bounds()
    }
}
