//! Designed shade: the highlight operations applied to the light vector L instead of H, after
//! Anjyo, Wemler & Baxter, "Tweakable light and shade for cartoon animation" (NPAR 2006).
//!
//! The tone of a patch reads `N·L`; a shade stack replaces L by `L'`, the same op stack the
//! highlights use ([`PreparedStack`]) run on L's coordinates `(l_u, l_v, l_n) = ((L, du), (L, dv),
//! (L, N))` in the surface frame. `Translate(α, β)` makes `L' = normalize(L + α du + β dv)`: the
//! lit region moves toward `+du` for α > 0, as a highlight does. Rotation, directional scaling,
//! split and squaring act on L as on H, so a band's edge (`N·L'` at its threshold) is moved,
//! stretched, split and squared as a highlight's edge is.
//!
//! Every operation changes only L's tangential part, so `N·L' = N·L / ‖L''‖` (L'' the vector
//! before the last normalization): the sign of `N·L` stays, and an edge at threshold 0 does not
//! move. A band edge designed this way sits above 0, on the light's side.

use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};

use super::error::HighlightError;
use super::frame::TangentFrame;
use super::layer::Mask;
use super::ops::Op;
use super::stack::PreparedStack;

/// One entry of designed shade on a patch: the operations applied to L in order, and the
/// rectangle of the patch's (u, v) where they act.
///
/// RON (in a shot's `shade` list, beside `patches`):
/// `stack: [Translate(alpha: 0.3, beta: 0.0), Square(sigma: 0.2, n: 2.0)],
///  mask: Some((u: (0.0, 0.5), v: (0.0, 1.0), feather: 0.05))`
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShadeStack<P = f32> {
    /// The operations, applied in order to L.
    pub stack: Vec<Op<P>>,
    /// Where the stack acts: its factor `m` ([`Mask`]) blends the designed light with the light
    /// it was handed, `normalize((1 − m) L + m L')`. None (the default): everywhere.
    #[serde(default)]
    pub mask: Option<Mask<P>>,
}

impl<P> ShadeStack<P> {
    /// Calls `f` with every numeric parameter, in the order of [`map`](Self::map).
    pub fn for_each_param(&self, mut f: impl FnMut(&P)) {
        let _visited: ShadeStack<()> = self.map(|p| f(p));
    }

    /// The same stack with every numeric parameter mapped through `f`.
    #[must_use]
    pub fn map<Q>(&self, mut f: impl FnMut(&P) -> Q) -> ShadeStack<Q> {
        ShadeStack {
            stack: self.stack.iter().map(|op| op.map(&mut f)).collect(),
            mask: self.mask.as_ref().map(|m| m.map(&mut f)),
        }
    }
}

impl ShadeStack<f32> {
    /// Checks every op (errors say which) and the mask.
    pub fn validate(&self) -> Result<(), HighlightError> {
        for (i, op) in self.stack.iter().enumerate() {
            op.validate()
                .map_err(|e| e.at(format!("stack[{i}] ({})", op.name())))?;
        }
        match &self.mask {
            Some(mask) => mask.validate(),
            None => Ok(()),
        }
    }

    /// Validates and precomputes the per-point form.
    pub fn prepare(&self) -> Result<PreparedShadeStack, HighlightError> {
        self.validate()?;
        Ok(PreparedShadeStack {
            stack: PreparedStack::new(
                self.stack
                    .iter()
                    .map(Op::prepare)
                    .collect::<Result<Vec<_>, _>>()?,
            ),
            mask: self.mask.clone(),
        })
    }
}

/// A validated [`ShadeStack`], ready to evaluate at many points.
#[derive(Clone, Debug, PartialEq)]
pub struct PreparedShadeStack {
    stack: PreparedStack,
    mask: Option<Mask>,
}

impl PreparedShadeStack {
    /// The stack applied to the unit light `l` in frame coordinates at `uv`: `L'` where the mask
    /// keeps all of it, `l` where it keeps none, and between, `normalize((1 − m) l + m L')`
    /// (`l` where that sum vanishes: L' opposite l at m = ½). Unit, in frame coordinates.
    #[must_use]
    pub fn apply_local(&self, uv: Vec2, l: Vec3) -> Vec3 {
        let Some(mask) = &self.mask else {
            return self.stack.apply_local(l);
        };
        let m = mask.factor(uv);
        if m <= 0.0 {
            return l;
        }
        let designed = self.stack.apply_local(l);
        if m >= 1.0 {
            return designed;
        }
        let blend = l.lerp(designed, m);
        let len2 = blend.length_squared();
        if len2 >= f32::MIN_POSITIVE {
            blend * len2.sqrt().recip()
        } else {
            l
        }
    }
}

/// Which light a patch's highlight reads: the scene's light L, as Anjyo & Hiramitsu's
/// highlights do, or the designed light `L'` its tone reads.
///
/// RON (on a highlight entry, beside `patches` and `expr`): `light: Designed`. With `Designed`
/// the highlight vector starts from `H = normalize(L' + V)`, so that a highlight moves with a
/// shadow pushed by the patch's shade stacks; on a patch no shade entry picks, `L' = L`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum HighlightLight {
    /// The scene's light: designed shade leaves the highlight where it is (the default).
    #[default]
    Plain,
    /// The patch's designed light `L'`, the one its tone reads.
    Designed,
}

/// The designed light of one patch: the shade stacks of the entries that pick it, in the order
/// they are written (includes first). Each acts on what the one before it made:
/// `L' = s_k(… s_2(s_1(L)))`. The tone reads it; the highlight reads it too where its entry
/// asks ([`HighlightLight::Designed`]).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct DesignedLight {
    stacks: Vec<PreparedShadeStack>,
    highlight: HighlightLight,
}

impl DesignedLight {
    /// The light designed by `stacks`, applied in order, which the highlight does not read.
    #[must_use]
    pub fn new(stacks: Vec<PreparedShadeStack>) -> Self {
        Self {
            stacks,
            highlight: HighlightLight::Plain,
        }
    }

    /// The same light, read by the patch's highlight as `highlight` says.
    #[must_use]
    pub fn read_by_highlight(self, highlight: HighlightLight) -> Self {
        Self { highlight, ..self }
    }

    /// Which light the patch's highlight reads.
    #[must_use]
    pub fn highlight_reads(&self) -> HighlightLight {
        self.highlight
    }

    /// The unit light direction the patch's highlight reads at a point lit from `l`: `L'`
    /// ([`light`](Self::light)) when it reads the designed light, else `l`.
    #[must_use]
    pub fn highlight_light(&self, frame: &TangentFrame, uv: Vec2, l: Vec3) -> Vec3 {
        match self.highlight {
            HighlightLight::Plain => l,
            HighlightLight::Designed => self.light(frame, uv, l),
        }
    }

    /// Whether no stack acts: `L' = L` everywhere.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.stacks.is_empty()
    }

    /// `L'` at a point with surface frame `frame` and patch parameters `uv`, lit from the unit
    /// direction `l` (world): each stack in turn on l's frame coordinates
    /// ([`PreparedShadeStack::apply_local`]), back to the world. Unit.
    #[must_use]
    pub fn light(&self, frame: &TangentFrame, uv: Vec2, l: Vec3) -> Vec3 {
        frame.to_world(self.light_local(frame, uv, l))
    }

    /// `N·L'` at a point: what a cel ramp or an X-Toon texture reads there
    /// ([`light`](Self::light)'s normal coordinate).
    #[must_use]
    pub fn n_dot_l(&self, frame: &TangentFrame, uv: Vec2, l: Vec3) -> f32 {
        self.light_local(frame, uv, l).z
    }

    /// `L'` in frame coordinates.
    fn light_local(&self, frame: &TangentFrame, uv: Vec2, l: Vec3) -> Vec3 {
        self.stacks
            .iter()
            .fold(frame.to_local(l), |local, s| s.apply_local(uv, local))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::highlight::{Axis, SquareStyle};

    fn frame() -> TangentFrame {
        TangentFrame::new(Vec3::X, Vec3::Y, Vec3::Z)
    }

    fn stack(ops: Vec<Op>, mask: Option<Mask>) -> PreparedShadeStack {
        ShadeStack { stack: ops, mask }.prepare().unwrap()
    }

    #[test]
    fn translation_adds_the_tangents_to_the_light_and_normalizes() {
        let (alpha, beta) = (0.4, -0.25);
        let light = DesignedLight::new(vec![stack(vec![Op::Translate { alpha, beta }], None)]);
        let l = Vec3::new(0.3, -0.2, 0.5).normalize();
        let expected = (l + Vec3::new(alpha, beta, 0.0)).normalize();
        let got = light.light(&frame(), Vec2::ZERO, l);
        assert!((got - expected).length() < 1e-6, "{got} vs {expected}");
        assert!((light.n_dot_l(&frame(), Vec2::ZERO, l) - expected.z).abs() < 1e-6);
    }

    #[test]
    fn later_stacks_act_on_what_earlier_ones_made() {
        let t = |alpha| stack(vec![Op::Translate { alpha, beta: 0.0 }], None);
        let two = DesignedLight::new(vec![t(0.3), t(0.2)]);
        let l = Vec3::new(0.1, 0.2, 0.9).normalize();
        let once = (l + Vec3::new(0.3, 0.0, 0.0)).normalize();
        let expected = (once + Vec3::new(0.2, 0.0, 0.0)).normalize();
        assert!((two.light(&frame(), Vec2::ZERO, l) - expected).length() < 1e-6);
    }

    #[test]
    fn the_mask_blends_between_the_plain_and_the_designed_light() {
        let mask = Mask {
            u: (0.0, 0.5),
            v: (0.0, 1.0),
            feather: 0.2,
        };
        let light = DesignedLight::new(vec![stack(
            vec![Op::Translate {
                alpha: 1.0,
                beta: 0.0,
            }],
            Some(mask),
        )]);
        let l = Vec3::new(0.0, 0.0, 1.0);
        let designed = Vec3::new(1.0, 0.0, 1.0).normalize();
        let at = |u: f32| light.light(&frame(), Vec2::new(u, 0.5), l);
        assert!((at(0.7) - l).length() < 1e-7, "outside: plain");
        assert!(
            (at(0.25) - designed).length() < 1e-6,
            "deep inside: designed"
        );
        // Halfway through the feather (0.1 in from the side): m = ½.
        let half = at(0.4);
        let expected = (l + designed).normalize();
        assert!((half - expected).length() < 1e-5, "{half} vs {expected}");
    }

    #[test]
    fn every_operation_keeps_the_light_a_finite_unit_vector() {
        let ops = vec![
            Op::Translate {
                alpha: 1e6,
                beta: -1e6,
            },
            Op::Rotate { degrees: 30.0 },
            Op::Scale {
                delta: 1.0,
                axis: Axis::U,
            },
            Op::Split {
                gamma_u: 1e6,
                gamma_v: 0.0,
            },
            Op::Square {
                sigma: 1.0,
                n: 4.0,
                style: SquareStyle::PerAxis,
            },
        ];
        let light = DesignedLight::new(vec![stack(ops, None)]);
        for l in [
            Vec3::X,
            Vec3::Z,
            -Vec3::Z,
            Vec3::new(1.0, 1.0, 0.0).normalize(),
        ] {
            let got = light.light(&frame(), Vec2::ZERO, l);
            assert!(
                got.is_finite() && (got.length() - 1.0).abs() < 1e-5,
                "{l} → {got}"
            );
        }
    }
}
