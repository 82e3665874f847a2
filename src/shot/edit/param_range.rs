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
            LayerParam::Colour(_) => Range::Colour,
            LayerParam::MaskU(_) | LayerParam::MaskV(_) | LayerParam::PinU | LayerParam::PinV => {
                Range::Finite
            }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::highlight::{Axis, Layer, Mask, Op, SquareStyle};

    fn layer() -> Layer {
        let mut layer = Layer::new(
            vec![
                Op::Translate {
                    alpha: 0.1,
                    beta: 0.1,
                },
                Op::Rotate { degrees: 10.0 },
                Op::Scale {
                    delta: 0.5,
                    axis: Axis::Angle(30.0),
                },
                Op::Split {
                    gamma_u: 0.1,
                    gamma_v: 0.1,
                },
                Op::Square {
                    sigma: 0.2,
                    n: 2.0,
                    style: SquareStyle::Tangent,
                },
            ],
            0.05,
            [1.0, 1.0, 1.0],
        );
        layer.mask = Some(Mask {
            u: (0.0, 1.0),
            v: (0.0, 1.0),
            feather: 0.1,
        });
        layer
    }

    /// The number `param` names in `layer`, to set.
    fn number(layer: &mut Layer, param: LayerParam) -> &mut f32 {
        match param {
            LayerParam::Epsilon => &mut layer.epsilon,
            LayerParam::Colour(c) => &mut layer.colour[c.unwrap_or(0)],
            LayerParam::Opacity => &mut layer.opacity,
            LayerParam::Feather => layer.feather.insert(0.0),
            LayerParam::MaskFeather => &mut layer.mask.as_mut().unwrap().feather,
            LayerParam::MaskU(_) | LayerParam::MaskV(_) | LayerParam::PinU | LayerParam::PinV => {
                unreachable!("checked with the order or domain they must also keep")
            }
            LayerParam::Op { index, param } => match (&mut layer.stack[index], param) {
                (Op::Translate { alpha, .. }, OpParam::Alpha) => alpha,
                (Op::Translate { beta, .. }, OpParam::Beta) => beta,
                (Op::Rotate { degrees }, OpParam::Degrees) => degrees,
                (Op::Scale { delta, .. }, OpParam::Delta) => delta,
                (
                    Op::Scale {
                        axis: Axis::Angle(phi),
                        ..
                    },
                    OpParam::Axis,
                ) => phi,
                (Op::Split { gamma_u, .. }, OpParam::GammaU) => gamma_u,
                (Op::Split { gamma_v, .. }, OpParam::GammaV) => gamma_v,
                (Op::Square { sigma, .. }, OpParam::Sigma) => sigma,
                (Op::Square { n, .. }, OpParam::N) => n,
                (op, param) => unreachable!("{op:?} has no {param:?}"),
            },
        }
    }

    #[test]
    fn every_range_is_the_one_validation_checks() {
        let op = |index, param| LayerParam::Op { index, param };
        let params = [
            LayerParam::Epsilon,
            LayerParam::Colour(Some(1)),
            LayerParam::Opacity,
            LayerParam::Feather,
            LayerParam::MaskFeather,
            op(0, OpParam::Alpha),
            op(0, OpParam::Beta),
            op(1, OpParam::Degrees),
            op(2, OpParam::Delta),
            op(2, OpParam::Axis),
            op(3, OpParam::GammaU),
            op(3, OpParam::GammaV),
            op(4, OpParam::Sigma),
            op(4, OpParam::N),
        ];
        let probes = [
            f32::NEG_INFINITY,
            -2e6,
            -1e6,
            -1.0,
            -1e-9,
            0.0,
            1e-9,
            0.5,
            1.0,
            1.5,
            2.0,
            2.5,
            1e6,
            2e6,
            f32::INFINITY,
            f32::NAN,
        ];
        for param in params {
            for x in probes {
                let mut layer = layer();
                *number(&mut layer, param) = x;
                assert_eq!(
                    layer.validate().is_ok(),
                    param.bounds().contains(x),
                    "{param:?} = {x}"
                );
            }
        }
    }
}
