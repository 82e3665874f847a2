//! The highlight's centre: the translation that puts it on a chosen surface point.

use glam::{Vec2, Vec3};

use super::error::HighlightError;
use super::frame::TangentFrame;
use super::layer::Layer;
use super::ops::Op;
use super::stack::PreparedStack;

impl<P> Layer<P> {
    /// The index in the stack of the translation that places the highlight: the last
    /// `Translate`. `None` when the stack has none.
    ///
    /// Every operation after it (rotation, scaling, split, squaring) is odd in the tangential
    /// coordinates, `op(−t, h_n) = −op(t, h_n)`, and keeps `t = 0` at 0, so it shapes the
    /// highlight around the point where the vector leaving this translation is N: that point
    /// is the highlight's centre.
    #[must_use]
    pub fn placing_translation(&self) -> Option<usize> {
        self.stack
            .iter()
            .rposition(|op| matches!(op, Op::Translate { .. }))
    }
}

impl Layer<f32> {
    /// [`centring_translation`](Self::centring_translation) for the point whose shading frame
    /// is `frame` and whose initial unit highlight vector is `h`, in world coordinates: `h` is
    /// taken into the layer's own frame there ([`LayerFrame`](super::LayerFrame)), as every
    /// evaluation of the layer takes it. Errors also when the frame's axis is invalid.
    pub fn centring_translation_at(
        &self,
        frame: &TangentFrame,
        h: Vec3,
    ) -> Result<Vec2, HighlightError> {
        self.centring_translation(self.frame.prepare()?.local(frame, h))
    }

    /// [`centred_on`](Self::centred_on) the point whose shading frame is `frame` and whose
    /// initial unit highlight vector is `h`, in world coordinates, taken into the layer's own
    /// frame there ([`centring_translation_at`](Self::centring_translation_at)): what a pin on
    /// a surface point needs, for a layer in any [`LayerFrame`](super::LayerFrame).
    pub fn centred_at(&self, frame: &TangentFrame, h: Vec3) -> Result<Layer, HighlightError> {
        self.centred_on(self.frame.prepare()?.local(frame, h))
    }

    /// `(α, β)` for the placing translation ([`placing_translation`](Self::placing_translation))
    /// that puts the highlight's centre on the point whose initial highlight vector has
    /// coordinates `h = (t_u, t_v, h_n)` in the layer's own frame there (for
    /// [`LayerFrame::Patch`](super::LayerFrame::Patch), the patch's frame; from world
    /// coordinates, [`centring_translation_at`](Self::centring_translation_at)): with `g` the unit output of the operations before it
    /// applied to `h`, the translation maps `g` to `g + (α, β, 0)`, which is `(0, 0, g_n)`, a
    /// positive multiple of N, for `(α, β) = −(g_u, g_v)`.
    ///
    /// Closed form, no iteration; `|(α, β)| ≤ 1`, so the result is always a valid
    /// translation. `h` must be a unit vector; a zero one is taken as N (no step). Errors when
    /// the stack has no translation or an operation before it is invalid.
    pub fn centring_translation(&self, h: Vec3) -> Result<Vec2, HighlightError> {
        let Some(at) = self.placing_translation() else {
            return Err(HighlightError::NoTranslation);
        };
        let before = self.stack[..at]
            .iter()
            .enumerate()
            .map(|(i, op)| {
                op.prepare()
                    .map_err(|e| e.at(format!("stack[{i}] ({})", op.name())))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let g = PreparedStack::new(before).apply_local(h);
        let g = g.try_normalize().unwrap_or(Vec3::Z);
        Ok(-g.truncate())
    }

    /// The layer with its highlight centred on the point whose initial highlight vector has
    /// coordinates `h` in the layer's own frame there
    /// ([`centring_translation`](Self::centring_translation); from world coordinates,
    /// [`centred_at`](Self::centred_at)), and no pin. A stack without a translation gets one at
    /// its start.
    pub fn centred_on(&self, h: Vec3) -> Result<Layer, HighlightError> {
        let mut layer = self.clone();
        layer.pin = None;
        if layer.placing_translation().is_none() {
            let none = Op::Translate {
                alpha: 0.0,
                beta: 0.0,
            };
            layer.stack.insert(0, none);
        }
        let step = layer.centring_translation(h)?;
        let at = layer
            .placing_translation()
            .ok_or(HighlightError::NoTranslation)?;
        layer.stack[at] = Op::Translate {
            alpha: step.x,
            beta: step.y,
        };
        Ok(layer)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::highlight::{Axis, SquareStyle};

    fn unit(x: f32, y: f32) -> Vec3 {
        Vec3::new(x, y, (1.0 - x * x - y * y).sqrt())
    }

    fn layer(stack: Vec<Op>) -> Layer {
        Layer::new(stack, 0.01, [1.0; 3])
    }

    /// The stack's output at `h` is N: no tangential part left.
    fn centred_at(layer: &Layer, h: Vec3) -> f32 {
        let prepared = layer.prepare().unwrap();
        let frame = crate::highlight::TangentFrame::new(Vec3::X, Vec3::Y, Vec3::Z);
        prepared.highlight_vector(&frame, h).truncate().length()
    }

    #[test]
    fn a_lone_translation_cancels_the_tangential_part() {
        let h = unit(0.3, -0.2);
        let step = layer(vec![Op::Translate {
            alpha: 5.0,
            beta: 5.0,
        }])
        .centring_translation(h)
        .unwrap();
        assert!((step - Vec2::new(-0.3, 0.2)).length() < 1e-6, "{step}");
    }

    #[test]
    fn operations_before_and_after_the_translation_are_taken_into_account() {
        let h = unit(0.25, 0.4);
        let shaped = layer(vec![
            Op::Rotate { degrees: 40.0 },
            Op::Scale {
                delta: 0.6,
                axis: Axis::Angle(20.0),
            },
            Op::Translate {
                alpha: 0.0,
                beta: 0.0,
            },
            Op::Square {
                sigma: 0.2,
                n: 2.0,
                style: SquareStyle::Tangent,
            },
            Op::Split {
                gamma_u: 0.0,
                gamma_v: 0.0,
            },
            Op::Scale {
                delta: 0.5,
                axis: Axis::V,
            },
        ]);
        let before = centred_at(&shaped, h);
        assert!(before > 0.1, "the point starts off centre: {before}");
        let centred = shaped.centred_on(h).unwrap();
        assert!(centred_at(&centred, h) < 1e-6);
        // Only the placing translation changed.
        let changed: Vec<usize> = (0..shaped.stack.len())
            .filter(|&i| shaped.stack[i] != centred.stack[i])
            .collect();
        assert_eq!(changed, vec![2]);
    }

    #[test]
    fn the_last_translation_places_and_a_stack_without_one_gets_one() {
        let h = unit(-0.1, 0.35);
        let two = layer(vec![
            Op::Translate {
                alpha: 0.2,
                beta: 0.0,
            },
            Op::Translate {
                alpha: 0.0,
                beta: 0.0,
            },
        ]);
        assert_eq!(two.placing_translation(), Some(1));
        let centred = two.centred_on(h).unwrap();
        assert_eq!(centred.stack[0], two.stack[0]);
        assert!(centred_at(&centred, h) < 1e-6);

        let bare = layer(vec![Op::Square {
            sigma: 0.3,
            n: 2.0,
            style: SquareStyle::Tangent,
        }]);
        assert_eq!(
            bare.centring_translation(h),
            Err(HighlightError::NoTranslation)
        );
        let centred = bare.centred_on(h).unwrap();
        assert_eq!(centred.placing_translation(), Some(0));
        assert!(centred_at(&centred, h) < 1e-6);
    }

    #[test]
    fn a_layer_along_an_axis_is_centred_in_its_own_frame() {
        use crate::highlight::LayerFrame;
        // A patch frame with u reversed and v along −y, and a layer whose du follows +x.
        let patch = TangentFrame::new(-Vec3::X, -Vec3::Y, Vec3::Z);
        let mut along = layer(vec![
            Op::Translate {
                alpha: 0.0,
                beta: 0.0,
            },
            Op::Scale {
                delta: 0.5,
                axis: Axis::U,
            },
        ]);
        along.frame = LayerFrame::Along {
            axis: [2.0, 0.0, 0.0],
        };
        let h = Vec3::new(0.3, -0.2, (1.0 - 0.13_f32).sqrt());
        // In the layer's frame (+x, +y, +z) the step cancels h's tangential part.
        let step = along.centring_translation_at(&patch, h).unwrap();
        assert!((step - Vec2::new(-0.3, 0.2)).length() < 1e-6, "{step}");
        let centred = along.centred_at(&patch, h).unwrap();
        let prepared = centred.prepare().unwrap();
        assert!(prepared.highlight_vector(&patch, h).truncate().length() < 1e-6);
        // The patch frame's coordinates would put it elsewhere: the step is not the same.
        let naive = along
            .centred_on(patch.to_local(h))
            .unwrap()
            .prepare()
            .unwrap();
        assert!(naive.highlight_vector(&patch, h).truncate().length() > 0.1);
        // A patch-framed layer is centred the same either way.
        let plain = layer(vec![Op::Translate {
            alpha: 0.0,
            beta: 0.0,
        }]);
        assert_eq!(
            plain.centred_at(&patch, h).unwrap(),
            plain.centred_on(patch.to_local(h)).unwrap()
        );
    }

    #[test]
    fn extreme_points_give_bounded_steps() {
        // Grazing H, H opposite N, and a zero vector: finite steps within the unit disc.
        for h in [Vec3::X, -Vec3::Z, Vec3::ZERO, Vec3::new(0.6, 0.8, 0.0)] {
            let step = layer(vec![Op::Translate {
                alpha: 0.0,
                beta: 0.0,
            }])
            .centring_translation(h)
            .unwrap();
            assert!(
                step.is_finite() && step.length() <= 1.0 + 1e-6,
                "{h}: {step}"
            );
        }
    }
}
