//! The highlight stacks the ladder renders on the sphere.

use std::fmt;

use super::closed_form::ClosedForm;
use crate::anim::{Key, Track};
use crate::highlight::{Expr, Layer, Op, PreparedExpr, SquareStyle};

/// A highlight the sweep renders.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Stack {
    /// The plain Blinn highlight.
    Identity,
    /// Moved toward du and −dv, then stretched along du.
    TranslateScale,
    /// Cut in two along dv.
    Split,
    /// Squared (tangent style).
    Square,
    /// A Boolean crescent: a plain highlight minus a moved one.
    Crescent,
    /// A crescent a few pixels wide: a plain highlight minus one moved by a tenth of its radius.
    ThinCrescent,
    /// The plain highlight at ε = 10⁻³: a few pixels across.
    Tiny,
    /// Cut into four, along du and along dv.
    SplitFour,
    /// Moved along du by a keyed track ([`Stack::KEYS`]), read at a fractional frame.
    Keyed { frame: f32 },
}

impl Stack {
    /// The five stacks of the centred view.
    pub const CENTRED: [Stack; 5] = [
        Stack::Identity,
        Stack::TranslateScale,
        Stack::Split,
        Stack::Square,
        Stack::Crescent,
    ];

    /// The keys of [`Stack::Keyed`]'s translation α along du: (frame, α).
    pub const KEYS: [(f64, f32); 3] = [(1.0, -0.2), (4.0, 0.1), (9.0, 0.3)];

    /// The highlight as the renderer gets it: a keyed value is read from its [`Track`] at the
    /// frame.
    pub fn expression(self) -> PreparedExpr {
        self.with_keyed(keyed_by_track)
            .prepare()
            .expect("the sweep's highlight parameters are in range")
    }

    /// The highlight as the analytic reference gets it: a keyed value is interpolated between
    /// the keys around the frame, `α = α_k + (f − f_k)(α_{k+1} − α_k)/(f_{k+1} − f_k)`,
    /// independently of [`Track::at`], evaluated in closed form ([`ClosedForm`]).
    pub fn reference_expression(self) -> ClosedForm {
        ClosedForm::try_new(&self.with_keyed(keyed_by_hand))
            .expect("the sweep's highlights are ε-discs without pins")
    }

    /// The expression, ε = 0.04 unless said otherwise, with `keyed` giving the keyed
    /// translation at a frame.
    fn with_keyed(self, keyed: impl Fn(f32) -> f32) -> Expr {
        let layer = |stack: Vec<Op>, epsilon: f32| {
            Box::new(Expr::Layer(Layer::new(stack, epsilon, [1.0, 1.0, 1.0])))
        };
        match self {
            Stack::Identity => *layer(vec![], 0.04),
            Stack::TranslateScale => *layer(
                vec![
                    Op::Translate {
                        alpha: 0.15,
                        beta: -0.1,
                    },
                    Op::Scale {
                        delta: 0.6,
                        axis: Default::default(),
                    },
                ],
                0.04,
            ),
            Stack::Split => *layer(
                vec![Op::Split {
                    gamma_u: 0.08,
                    gamma_v: 0.0,
                }],
                0.04,
            ),
            Stack::Square => *layer(
                vec![Op::Square {
                    sigma: 0.2,
                    n: 2.0,
                    style: SquareStyle::Tangent,
                }],
                0.04,
            ),
            Stack::Crescent => Expr::Subtract(
                layer(vec![], 0.06),
                layer(
                    vec![Op::Translate {
                        alpha: 0.12,
                        beta: 0.05,
                    }],
                    0.05,
                ),
            ),
            // Radius √(2ε) ≈ 0.32 in H; moved by 0.035 the crescent is about a ninth as wide.
            Stack::ThinCrescent => Expr::Subtract(
                layer(vec![], 0.05),
                layer(
                    vec![Op::Translate {
                        alpha: 0.03,
                        beta: 0.018,
                    }],
                    0.05,
                ),
            ),
            Stack::Tiny => *layer(vec![], 1e-3),
            Stack::SplitFour => *layer(
                vec![Op::Split {
                    gamma_u: 0.08,
                    gamma_v: 0.08,
                }],
                0.06,
            ),
            Stack::Keyed { frame } => *layer(
                vec![Op::Translate {
                    alpha: keyed(frame),
                    beta: 0.05,
                }],
                0.04,
            ),
        }
    }
}

/// [`Stack::KEYS`] as a [`Track`], read at `frame`.
fn keyed_by_track(frame: f32) -> f32 {
    let keys = Stack::KEYS
        .iter()
        .map(|&(frame, value)| Key { frame, value });
    Track::Keys(keys.collect()).at(f64::from(frame))
}

/// [`Stack::KEYS`] read at `f`: `α = α_k + (f − f_k)(α_{k+1} − α_k)/(f_{k+1} − f_k)` between
/// the keys around `f`, the first value before them and the last after.
fn keyed_by_hand(frame: f32) -> f32 {
    let f = f64::from(frame);
    let [first, .., last] = Stack::KEYS;
    if f <= first.0 {
        return first.1;
    }
    Stack::KEYS
        .windows(2)
        .find(|pair| f <= pair[1].0)
        .map_or(last.1, |pair| {
            let ((f0, a0), (f1, a1)) = (pair[0], pair[1]);
            (f64::from(a0) + (f - f0) * f64::from(a1 - a0) / (f1 - f0)) as f32
        })
}

impl fmt::Display for Stack {
    /// `identity`, `translate+scale`, …, `keyed @2.5` for the keyed translation at frame 2.5.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Stack::Identity => f.write_str("identity"),
            Stack::TranslateScale => f.write_str("translate+scale"),
            Stack::Split => f.write_str("split"),
            Stack::Square => f.write_str("square"),
            Stack::Crescent => f.write_str("crescent"),
            Stack::ThinCrescent => f.write_str("thin crescent"),
            Stack::Tiny => f.write_str("ε 0.001"),
            Stack::SplitFour => f.write_str("split in four"),
            Stack::Keyed { frame } => write!(f, "keyed @{frame}"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_keyed_translation_is_read_alike_by_the_track_and_by_hand() {
        // Before the first key, at keys, between them and after the last.
        let expected = [
            (0.0, -0.2),
            (1.0, -0.2),
            (2.5, -0.05),
            (4.0, 0.1),
            (6.25, 0.19),
            (12.0, 0.3),
        ];
        for (frame, alpha) in expected {
            let (track, hand) = (keyed_by_track(frame), keyed_by_hand(frame));
            assert!(
                (track - alpha).abs() < 1e-6 && (hand - alpha).abs() < 1e-6,
                "frame {frame}: track {track}, by hand {hand}, expected {alpha}"
            );
        }
    }
}
