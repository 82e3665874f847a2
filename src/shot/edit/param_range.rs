//! The range each highlight layer or shade entry parameter must lie in, as its validation
//! checks it (`Op::validate`, `Layer::validate`, `ShadeStack::validate`): what an editor's slider
//! and number field allow.

use super::param_path::{LayerParam, OpParam, ShadeParam};
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
            LayerParam::Op { param, .. } => return param.bounds(),
        };
        range.bounds()
    }
}

impl ShadeParam {
    /// The values the parameter may take at any frame. A mask's bounds must also lie in order,
    /// which no range of one number says.
    #[must_use]
    pub fn bounds(self) -> Bounds {
        match self {
            ShadeParam::MaskU(_) | ShadeParam::MaskV(_) => Range::Finite.bounds(),
            ShadeParam::MaskFeather => Range::NonNegative.bounds(),
            ShadeParam::Op { param, .. } => param.bounds(),
        }
    }
}

impl OpParam {
    /// The values the operation's number may take at any frame ([`Op::validate`]).
    ///
    /// [`Op::validate`]: crate::highlight::Op::validate
    #[must_use]
    pub fn bounds(self) -> Bounds {
        match self {
            OpParam::Alpha | OpParam::Beta => Range::Step,
            OpParam::Degrees | OpParam::Axis => Range::Finite,
            OpParam::Delta | OpParam::Sigma => Range::Unit,
            OpParam::GammaU | OpParam::GammaV => Range::NonNegativeStep,
            OpParam::N => Range::Positive,
        }
        .bounds()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::highlight::{Axis, Layer, Mask, Op, ShadeStack, SquareStyle};

    /// One operation of each kind, every number valid.
    fn ops() -> Vec<Op> {
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
        ]
    }

    fn mask() -> Mask {
        Mask {
            u: (0.0, 1.0),
            v: (0.0, 1.0),
            feather: 0.1,
        }
    }

    fn layer() -> Layer {
        let mut layer = Layer::new(ops(), 0.05, [1.0, 1.0, 1.0]);
        layer.mask = Some(mask());
        layer
    }

    fn shade() -> ShadeStack {
        ShadeStack {
            stack: ops(),
            mask: Some(mask()),
        }
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
            LayerParam::Op { index, param } => op_number(&mut layer.stack[index], param),
        }
    }

    /// The number `param` names in `shade`, to set.
    fn shade_number(shade: &mut ShadeStack, param: ShadeParam) -> &mut f32 {
        match param {
            ShadeParam::MaskFeather => &mut shade.mask.as_mut().unwrap().feather,
            ShadeParam::MaskU(_) | ShadeParam::MaskV(_) => {
                unreachable!("checked with the order they must also keep")
            }
            ShadeParam::Op { index, param } => op_number(&mut shade.stack[index], param),
        }
    }

    /// The number `param` names in `op`, to set.
    fn op_number(op: &mut Op, param: OpParam) -> &mut f32 {
        match (op, param) {
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
        }
    }

    /// Every operation number, with the index of the operation of [`ops`] that has it.
    const OP_NUMBERS: [(usize, OpParam); 9] = [
        (0, OpParam::Alpha),
        (0, OpParam::Beta),
        (1, OpParam::Degrees),
        (2, OpParam::Delta),
        (2, OpParam::Axis),
        (3, OpParam::GammaU),
        (3, OpParam::GammaV),
        (4, OpParam::Sigma),
        (4, OpParam::N),
    ];

    const PROBES: [f32; 16] = [
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

    #[test]
    fn every_shade_range_is_the_one_validation_checks() {
        let params = OP_NUMBERS
            .iter()
            .map(|&(index, param)| ShadeParam::Op { index, param })
            .chain([ShadeParam::MaskFeather]);
        for param in params {
            for x in PROBES {
                let mut shade = shade();
                *shade_number(&mut shade, param) = x;
                assert_eq!(
                    shade.validate().is_ok(),
                    param.bounds().contains(x),
                    "{param:?} = {x}"
                );
            }
        }
    }

    #[test]
    fn every_range_is_the_one_validation_checks() {
        let params = [
            LayerParam::Epsilon,
            LayerParam::Colour(Some(1)),
            LayerParam::Opacity,
            LayerParam::Feather,
            LayerParam::MaskFeather,
        ]
        .into_iter()
        .chain(
            OP_NUMBERS
                .iter()
                .map(|&(index, param)| LayerParam::Op { index, param }),
        );
        for param in params {
            for x in PROBES {
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
