//! What a highlight expression covers at a point, in closed form: each layer's frame, stack
//! ([`closed_form_stack`]), ε-test, feather and mask, and the Booleans over layers, written in
//! f64 from docs/highlights.md with no call into the renderer's evaluation. The accuracy
//! reference classifies its points with it.

use std::fmt;

use glam::{DVec2, DVec3};

use super::closed_form_ops::{closed_form_stack, AnalyticFrame};
use crate::highlight::{Expr, Layer, LayerFrame, Mask, Shape};

/// The highlight at a point: coverage in [0, 1] (opacity included) and the colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClosedShade {
    /// Coverage, the carried opacity included.
    pub coverage: f64,
    /// Linear RGB of the operand the Booleans carry.
    pub colour: DVec3,
}

/// Why an expression has no closed form here.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum ClosedFormError {
    /// Layer `layer` (from 1, left to right) is a drawn outline, not the ε-disc.
    Outline { layer: usize },
    /// Layer `layer` is pinned: its translation is solved from a surface point first.
    Pinned { layer: usize },
    /// Layer `layer` holds a shape by a solved map, which the reference does not follow.
    ShapeMap { layer: usize },
}

impl fmt::Display for ClosedFormError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Outline { layer } => write!(
                f,
                "layer {layer}: a drawn outline has no closed form in the reference; use the ε-disc"
            ),
            Self::Pinned { layer } => write!(
                f,
                "layer {layer}: a pinned layer must be centred before the reference reads it"
            ),
            Self::ShapeMap { layer } => write!(
                f,
                "layer {layer}: a held shape's map has no closed form in the reference; let the pin's hold go"
            ),
        }
    }
}

impl std::error::Error for ClosedFormError {}

/// A highlight expression of ε-disc layers without pins, evaluated in closed form.
#[derive(Clone, Debug, PartialEq)]
pub struct ClosedForm {
    expr: Expr,
}

impl ClosedForm {
    /// The closed form of `expr`; an error for a drawn outline or a pin, which it does not
    /// evaluate.
    pub fn try_new(expr: &Expr) -> Result<Self, ClosedFormError> {
        for (i, layer) in expr.layers().into_iter().enumerate() {
            let number = i + 1;
            match layer.shape {
                Shape::Disc => {}
                Shape::Outline(_) | Shape::Morph(_) => {
                    return Err(ClosedFormError::Outline { layer: number })
                }
            }
            if layer.pin.is_some() {
                return Err(ClosedFormError::Pinned { layer: number });
            }
            if layer.shape_map.is_some() {
                return Err(ClosedFormError::ShapeMap { layer: number });
            }
        }
        Ok(Self { expr: expr.clone() })
    }

    /// The expression it evaluates.
    #[must_use]
    pub fn expr(&self) -> &Expr {
        &self.expr
    }

    /// The highlight at a point with the patch frame `patch`, patch parameters `uv` and unit
    /// initial highlight vector `h`: the Booleans of the layers' shape coverages
    /// (union `max(a, b)` with the paint of the larger, the left on a tie; subtraction
    /// `min(a, 1 − b)` and intersection `min(a, b)` with the left's paint), times the carried
    /// opacity.
    #[must_use]
    pub fn shade(&self, patch: AnalyticFrame, uv: DVec2, h: DVec3) -> ClosedShade {
        let (shape, layer) = shape_of(&self.expr, patch, uv, h);
        ClosedShade {
            coverage: shape * f64::from(layer.opacity),
            colour: DVec3::from_array(layer.colour.map(f64::from)),
        }
    }
}

/// Shape coverage before opacity and the layer whose paint it carries.
fn shape_of(expr: &Expr, patch: AnalyticFrame, uv: DVec2, h: DVec3) -> (f64, &Layer) {
    match expr {
        Expr::Layer(layer) => (layer_shape(layer, patch, uv, h), layer),
        Expr::Union(a, b) => {
            let (a, b) = (shape_of(a, patch, uv, h), shape_of(b, patch, uv, h));
            if b.0 > a.0 {
                b
            } else {
                a
            }
        }
        Expr::Subtract(a, b) => {
            let (a, b) = (shape_of(a, patch, uv, h), shape_of(b, patch, uv, h));
            (a.0.min(1.0 - b.0), a.1)
        }
        Expr::Intersect(a, b) => {
            let (a, b) = (shape_of(a, patch, uv, h), shape_of(b, patch, uv, h));
            (a.0.min(b.0), a.1)
        }
    }
}

/// The frame a layer's stack acts in: the patch's, or for `Along(a)` with â = a/|a|,
/// `du' = normalize(â − (â·N) N)`, `dv' = N × du'` — the patch's where `|â − (â·N) N| < 10⁻³`.
#[must_use]
pub fn layer_frame(frame: &LayerFrame, patch: AnalyticFrame) -> AnalyticFrame {
    match frame {
        LayerFrame::Patch => patch,
        LayerFrame::Along { axis } => {
            let a = DVec3::from_array(axis.map(f64::from)).normalize_or_zero();
            let tangential = a - a.dot(patch.n) * patch.n;
            if tangential.length() < 1e-3 {
                return patch;
            }
            let du = tangential.normalize();
            AnalyticFrame {
                du,
                dv: patch.n.cross(du),
                n: patch.n,
            }
        }
    }
}

/// The layer's signed inside value at the point: `s = ε − (1 − (N, H'))`, positive where
/// `(N, H') > 1 − ε`, with H' its stack's output in its frame.
#[must_use]
pub fn layer_signed(layer: &Layer, patch: AnalyticFrame, h: DVec3) -> f64 {
    let (_, h) = closed_form_stack(&layer.stack, layer_frame(&layer.frame, patch), h);
    f64::from(layer.epsilon) - (1.0 - patch.n.dot(h))
}

/// `x²(3 − 2x)` of `x = clamp(s/w + ½, 0, 1)`: the smoothstep over the band `[−w/2, w/2]`;
/// for `w ≤ 0` the hard step, 1 where `s > 0`.
#[must_use]
fn band(s: f64, w: f64) -> f64 {
    if w > 0.0 {
        let x = (s / w + 0.5).clamp(0.0, 1.0);
        x * x * (3.0 - 2.0 * x)
    } else if s > 0.0 {
        1.0
    } else {
        0.0
    }
}

/// The mask factor at `uv`: `smoothstep(0, f, d)` of the inward distance d to the nearest side
/// of the rectangle (1 strictly inside for `f = 0`).
#[must_use]
pub fn mask_factor(mask: &Mask, uv: DVec2) -> f64 {
    let d = (uv.x - f64::from(mask.u.0))
        .min(f64::from(mask.u.1) - uv.x)
        .min(uv.y - f64::from(mask.v.0))
        .min(f64::from(mask.v.1) - uv.y);
    let f = f64::from(mask.feather);
    if f > 0.0 {
        let x = (d / f).clamp(0.0, 1.0);
        x * x * (3.0 - 2.0 * x)
    } else if d > 0.0 {
        1.0
    } else {
        0.0
    }
}

/// A layer's shape coverage before opacity: the hard edge of s (or its smoothstep over the
/// feather's band), times the mask at `uv`.
#[must_use]
pub fn layer_shape(layer: &Layer, patch: AnalyticFrame, uv: DVec2, h: DVec3) -> f64 {
    let edge = band(
        layer_signed(layer, patch, h),
        layer.feather.map_or(0.0, f64::from),
    );
    layer
        .mask
        .as_ref()
        .map_or(edge, |mask| edge * mask_factor(mask, uv))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::highlight::Op;

    const WORLD: AnalyticFrame = AnalyticFrame {
        du: DVec3::X,
        dv: DVec3::Y,
        n: DVec3::Z,
    };

    fn cap(stack: Vec<Op>, epsilon: f32, colour: [f32; 3]) -> Box<Expr> {
        Box::new(Expr::Layer(Layer::new(stack, epsilon, colour)))
    }

    #[test]
    fn the_disc_is_one_minus_cos_below_epsilon() {
        let layer = Layer::new(vec![], 0.2, [1.0; 3]);
        // (N, H) = 0.85: inside ε = 0.2 by 0.05.
        let h = DVec3::new((1.0f64 - 0.85 * 0.85).sqrt(), 0.0, 0.85);
        // ε is an f32: 0.2 to about 3·10⁻⁹.
        assert!((layer_signed(&layer, WORLD, h) - 0.05).abs() < 1e-8);
    }

    #[test]
    fn the_feather_is_a_smoothstep_centred_on_the_edge() {
        let layer = Layer {
            feather: Some(0.1),
            ..Layer::new(vec![], 0.2, [1.0; 3])
        };
        let at = |cos: f64| {
            let h = DVec3::new((1.0 - cos * cos).sqrt(), 0.0, cos);
            layer_shape(&layer, WORLD, DVec2::ZERO, h)
        };
        assert!((at(0.8) - 0.5).abs() < 1e-7);
        // s = 0.025: x = 0.75, 0.75²(3 − 1.5) = 0.84375.
        assert!((at(0.825) - 0.84375).abs() < 1e-7);
        assert_eq!(at(0.9), 1.0);
        assert_eq!(at(0.7), 0.0);
    }

    #[test]
    fn the_mask_rises_over_its_feather_inside_the_rectangle() {
        let mask = Mask {
            u: (0.0, 1.0),
            v: (0.0, 0.5),
            feather: 0.2,
        };
        assert_eq!(mask_factor(&mask, DVec2::new(0.5, 0.25)), 1.0);
        assert_eq!(mask_factor(&mask, DVec2::new(0.5, 0.6)), 0.0);
        // d = 0.1, half the feather: ½.
        assert!((mask_factor(&mask, DVec2::new(0.1, 0.25)) - 0.5).abs() < 1e-7);
    }

    #[test]
    fn booleans_combine_coverage_and_carry_paint() {
        let (red, blue) = ([1.0, 0.0, 0.0], [0.0, 0.0, 1.0]);
        let a = cap(vec![], 0.1, red);
        let b = cap(
            vec![Op::Translate {
                alpha: 0.3,
                beta: 0.0,
            }],
            0.1,
            blue,
        );
        // H = N: in a; H + 0.3 du is 1 − 1/√1.09 ≈ 0.042 from N, in b too.
        let at = |expr: Expr, h: DVec3| {
            ClosedForm::try_new(&expr)
                .unwrap()
                .shade(WORLD, DVec2::ZERO, h)
        };
        let both = DVec3::Z;
        let union = at(Expr::Union(a.clone(), b.clone()), both);
        assert_eq!((union.coverage, union.colour), (1.0, DVec3::X));
        assert_eq!(at(Expr::Subtract(a.clone(), b.clone()), both).coverage, 0.0);
        assert_eq!(
            at(Expr::Intersect(a.clone(), b.clone()), both).coverage,
            1.0
        );
        // H = (0.4, 0, √0.84): in a (1 − √0.84 ≈ 0.083); b's H' = (0.7, 0, √0.84)/1.153 has
        // 1 − cos ≈ 0.205, out.
        let a_only = DVec3::new(0.4, 0.0, 0.84f64.sqrt());
        let union = at(Expr::Union(a.clone(), b.clone()), a_only);
        assert_eq!((union.coverage, union.colour), (1.0, DVec3::X));
        let minus = at(Expr::Subtract(a.clone(), b.clone()), a_only);
        assert_eq!((minus.coverage, minus.colour), (1.0, DVec3::X));
        assert_eq!(
            at(Expr::Intersect(a.clone(), b.clone()), a_only).coverage,
            0.0
        );
        // H = (−0.55, 0, √0.6975): out of a (≈ 0.165); b's H' = (−0.25, 0, 0.835)/0.872 has
        // 1 − cos ≈ 0.042, in: the union is b's, blue.
        let b_only = DVec3::new(-0.55, 0.0, 0.6975f64.sqrt());
        let union = at(Expr::Union(a.clone(), b.clone()), b_only);
        assert_eq!((union.coverage, union.colour), (1.0, DVec3::Z));
        assert_eq!(
            at(Expr::Subtract(a.clone(), b.clone()), b_only).coverage,
            0.0
        );
        // Opacity scales the carried coverage; a subtracted operand cuts whatever its own.
        let faint = Box::new(Expr::Layer(Layer {
            opacity: 0.25,
            ..Layer::new(vec![], 0.1, red)
        }));
        assert_eq!(
            at(Expr::Union(faint.clone(), b.clone()), a_only).coverage,
            0.25
        );
        let faint_b = Box::new(Expr::Layer(Layer {
            opacity: 0.0,
            ..Layer::new(
                vec![Op::Translate {
                    alpha: 0.3,
                    beta: 0.0,
                }],
                0.1,
                blue,
            )
        }));
        assert_eq!(at(Expr::Subtract(a, faint_b), both).coverage, 0.0);
    }

    #[test]
    fn a_drawn_outline_or_a_pin_is_refused() {
        let mut layer = Layer::new(vec![], 0.1, [1.0; 3]);
        layer.pin = Some(crate::highlight::Pin {
            patch: "p".into(),
            member: 0,
            u: 0.5,
            v: 0.5,
            hold: None,
        });
        let expr = Expr::Union(cap(vec![], 0.1, [1.0; 3]), Box::new(Expr::Layer(layer)));
        assert_eq!(
            ClosedForm::try_new(&expr),
            Err(ClosedFormError::Pinned { layer: 2 })
        );
        let mut held = Layer::new(vec![], 0.1, [1.0; 3]);
        held.shape_map = Some(crate::highlight::ShapeMap::IDENTITY);
        assert_eq!(
            ClosedForm::try_new(&Expr::Layer(held)),
            Err(ClosedFormError::ShapeMap { layer: 1 })
        );
    }

    #[test]
    fn an_along_frame_projects_its_axis() {
        let patch = WORLD;
        let along = LayerFrame::Along {
            axis: [1.0, 0.0, 1.0],
        };
        let f = layer_frame(&along, patch);
        assert!((f.du - DVec3::X).length() < 1e-12 && (f.dv - DVec3::Y).length() < 1e-12);
        let normal = LayerFrame::Along {
            axis: [0.0, 0.0, 2.0],
        };
        assert_eq!(layer_frame(&normal, patch), patch);
    }
}
