//! A highlight layer: an op stack, a threshold ε, a paint (colour and opacity), an optional
//! feather, an optional parameter-space mask, an optional pin, and the frame its stack acts in.

use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};

use super::error::HighlightError;
use super::footprint::Footprint;
use super::frame::TangentFrame;
use super::inside::{coverage_from_signed, signed_inside};
use super::layer_frame::{LayerFrame, PreparedFrame};
use super::ops::{Op, PreparedOp};
use super::pin::Pin;
use super::point_chunk::PointChunk;
use super::shape::{PreparedShape, Shape};
use super::shape_map::ShapeMap;
use super::stack::{LocalChunk, PreparedStack};
use crate::math::LANES;
use crate::param::{check, Range};

/// One highlight: the region `{ ‖N − H'‖² / 2 < ε }` of the vector `H'` that the op stack makes
/// from the initial H, painted with a colour.
///
/// RON:
/// ```text
/// (stack: [Translate(alpha: 0.2, beta: 0.0), Square(sigma: 0.2, n: 2.0)], epsilon: 0.05,
///  colour: (1.0, 1.0, 1.0), opacity: 1.0, feather: Some(0.005),
///  mask: Some((u: (0.0, 0.5), v: (0.0, 1.0), feather: 0.05)),
///  frame: Along(axis: (1.0, 0.0, 0.0)))
/// ```
#[derive(Clone, PartialEq, Serialize, Deserialize)]
#[serde(
    deny_unknown_fields,
    bound(deserialize = "P: Deserialize<'de> + From<f32>")
)]
pub struct Layer<P = f32> {
    /// The operations, applied in order to the initial H.
    pub stack: Vec<Op<P>>,
    /// ε ∈ (0, 2]: the highlight is `(N, H') > 1 − ε`; it covers the fraction ε/2 of a sphere.
    pub epsilon: P,
    /// Linear RGB.
    pub colour: [P; 3],
    /// Opacity ∈ [0, 1], scaling the final coverage (default 1).
    #[serde(default = "opaque")]
    pub opacity: P,
    /// Feather width ≥ 0 in units of the signed value `s = ε − ‖N − H'‖²/2` (the units of ε): the
    /// edge becomes a smoothstep over `[−w/2, w/2]` around the hard edge. None (the default): a
    /// hard edge.
    #[serde(default)]
    pub feather: Option<P>,
    /// Keeps the highlight only inside a rectangle of the patch's (u, v) parameters, Anjyo &
    /// Hiramitsu's clean-up (2003) of "an unnecessary part of a highlight". None (the default): no mask.
    #[serde(default)]
    pub mask: Option<Mask<P>>,
    /// Keeps the highlight's centre on a surface point on every frame: the stack's placing
    /// translation is solved for it ([`Pin`]). None (the default): the stack's translation as
    /// written.
    #[serde(default)]
    pub pin: Option<Pin<P>>,
    /// The tangent axes the stack acts along at each point ([`LayerFrame`]): the patch's own
    /// (the default), or one direction field over every patch the layer is drawn on.
    #[serde(default, skip_serializing_if = "LayerFrame::is_patch")]
    pub frame: LayerFrame<P>,
    /// What H' is tested against ([`Shape`]): the ε-disc (the default), or a drawn outline in
    /// the tangent coordinates `t' = ((H', du), (H', dv))`, after the stack as the disc is.
    #[serde(default, skip_serializing_if = "Shape::is_disc")]
    pub shape: Shape<P>,
    /// The map that holds a pinned layer's shape on this frame, applied right after the placing
    /// translation ([`ShapeMap`]): solved with the centring for a pin that holds
    /// ([`Pin::hold`]), never written. None: the shape as the view makes it.
    #[serde(skip)]
    pub shape_map: Option<ShapeMap>,
}

/// Every field in order, as `#[derive(Debug)]` prints them, but the frame only when it is not the
/// patch's own, the shape only when it is not the disc and the shape map only when there is
/// one: a layer in its patch's frame with the disc and no held shape prints as layers did
/// before they had frames, shapes and maps, so that what a frame's
/// fingerprint hashes of a shot without them stays the same.
impl<P: std::fmt::Debug> std::fmt::Debug for Layer<P> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut layer = f.debug_struct("Layer");
        layer
            .field("stack", &self.stack)
            .field("epsilon", &self.epsilon)
            .field("colour", &self.colour)
            .field("opacity", &self.opacity)
            .field("feather", &self.feather)
            .field("mask", &self.mask)
            .field("pin", &self.pin);
        if !self.frame.is_patch() {
            layer.field("frame", &self.frame);
        }
        if !self.shape.is_disc() {
            layer.field("shape", &self.shape);
        }
        if let Some(map) = &self.shape_map {
            layer.field("shape_map", map);
        }
        layer.finish()
    }
}

/// The default opacity of a layer as written in a file: 1.
fn opaque<P: From<f32>>() -> P {
    P::from(1.0)
}

/// A rectangle `[u.0, u.1] × [v.0, v.1]` in patch parameters with an inward feather.
///
/// The mask factor is `smoothstep(0, f, d)` of the distance `d` from (u, v) to the nearest side,
/// measured inward: 1 deep inside, 0 on and outside the rectangle's boundary when `f > 0`;
/// `f = 0` is a hard rectangle.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mask<P = f32> {
    /// u range, first < second.
    pub u: (P, P),
    /// v range, first < second.
    pub v: (P, P),
    /// Feather width f ≥ 0 in parameter units.
    pub feather: P,
}

impl Layer {
    /// The highlight of Anjyo & Hiramitsu 2003: the stack's region `(N, H') > 1 − ε` in one
    /// opaque colour, with a hard edge and no mask.
    #[must_use]
    pub fn new(stack: Vec<Op>, epsilon: f32, colour: [f32; 3]) -> Self {
        Self {
            stack,
            epsilon,
            colour,
            opacity: 1.0,
            feather: None,
            mask: None,
            pin: None,
            frame: LayerFrame::Patch,
            shape: Shape::Disc,
            shape_map: None,
        }
    }
}

impl<P: Clone> Layer<P> {
    /// The layer's own parameters (ε, colour, opacity, feather, mask, pin, frame, shape) with an empty
    /// stack:
    /// what is checked apart from the operations.
    #[must_use]
    pub fn without_stack(&self) -> Layer<P> {
        Layer {
            stack: Vec::new(),
            epsilon: self.epsilon.clone(),
            colour: self.colour.clone(),
            opacity: self.opacity.clone(),
            feather: self.feather.clone(),
            mask: self.mask.clone(),
            pin: self.pin.clone(),
            frame: self.frame.clone(),
            shape: self.shape.clone(),
            shape_map: self.shape_map,
        }
    }
}

impl<P> Layer<P> {
    /// Calls `f` with every numeric parameter, in the order of [`map`](Self::map).
    pub fn for_each_param(&self, mut f: impl FnMut(&P)) {
        let _visited: Layer<()> = self.map(|p| f(p));
    }

    /// The same layer with every numeric parameter mapped through `f`.
    #[must_use]
    pub fn map<Q>(&self, mut f: impl FnMut(&P) -> Q) -> Layer<Q> {
        Layer {
            stack: self.stack.iter().map(|op| op.map(&mut f)).collect(),
            epsilon: f(&self.epsilon),
            colour: [f(&self.colour[0]), f(&self.colour[1]), f(&self.colour[2])],
            opacity: f(&self.opacity),
            feather: self.feather.as_ref().map(&mut f),
            mask: self.mask.as_ref().map(|m| m.map(&mut f)),
            pin: self.pin.as_ref().map(|p| p.map(&mut f)),
            frame: self.frame.map(&mut f),
            shape: self.shape.map(&mut f),
            shape_map: self.shape_map,
        }
    }
}

impl<P> Mask<P> {
    /// The same mask with every numeric parameter mapped through `f`.
    #[must_use]
    pub fn map<Q>(&self, mut f: impl FnMut(&P) -> Q) -> Mask<Q> {
        Mask {
            u: (f(&self.u.0), f(&self.u.1)),
            v: (f(&self.v.0), f(&self.v.1)),
            feather: f(&self.feather),
        }
    }
}

impl Mask<f32> {
    /// Checks the bounds finite and ordered and the feather not negative.
    pub(super) fn validate(&self) -> Result<(), HighlightError> {
        for (axis, (min, max)) in [("u", self.u), ("v", self.v)] {
            check("mask bound", min, Range::Finite, "")?;
            check("mask bound", max, Range::Finite, "")?;
            if min >= max {
                return Err(HighlightError::MaskUnordered { axis, min, max });
            }
        }
        check(
            "mask feather",
            self.feather,
            Range::NonNegative,
            "; 0 is a hard rectangle",
        )?;
        Ok(())
    }

    /// The mask factor at `uv`, in [0, 1].
    #[inline]
    #[must_use]
    pub(super) fn factor(&self, uv: Vec2) -> f32 {
        let d = (uv.x - self.u.0)
            .min(self.u.1 - uv.x)
            .min(uv.y - self.v.0)
            .min(self.v.1 - uv.y);
        // A band [0, f] is the centred band of width f shifted inward by f/2.
        coverage_from_signed(d - 0.5 * self.feather, self.feather)
    }
}

impl Layer<f32> {
    /// Checks ε ∈ (0, 2], colour components in [0, 1e4], opacity ∈ [0, 1], feather ≥ 0, the mask
    /// ordered, the frame's axis a direction, the shape as drawn ([`Shape::validate`]: a
    /// drawn outline simple), and every op; errors say which op.
    pub fn validate(&self) -> Result<(), HighlightError> {
        self.validate_but_shape()?;
        self.shape.validate()
    }

    /// [`validate`](Self::validate) but for the shape.
    fn validate_but_shape(&self) -> Result<(), HighlightError> {
        for (i, op) in self.stack.iter().enumerate() {
            op.validate()
                .map_err(|e| e.at(format!("stack[{i}] ({})", op.name())))?;
        }
        check(
            "epsilon (ε)",
            self.epsilon,
            Range::Epsilon,
            "; the highlight covers the fraction ε/2 of a sphere, so 0.01 is a small spot and 2 the whole sphere",
        )?;
        for c in self.colour {
            check(
                "colour component",
                c,
                Range::Colour,
                "; colours are linear RGB, 1 the display's white",
            )?;
        }
        check(
            "opacity",
            self.opacity,
            Range::Unit,
            "; 0 is invisible, 1 opaque",
        )?;
        if let Some(f) = self.feather {
            check("feather", f, Range::NonNegative, "; 0 is a hard edge")?;
        }
        if let Some(m) = &self.mask {
            m.validate()?;
        }
        self.frame.validate()
    }

    /// Validates and precomputes the per-point form, with the shape map, where there is one,
    /// right after the placing translation. A pinned layer is first centred on its
    /// point ([`centred_on`](Self::centred_on)) by whoever knows the point; with its pin still
    /// set it is an error, never a translation silently left as written. A drawn outline is
    /// checked for its values but not for crossing itself ([`Outline::prepare`]): a frame
    /// between two keys of a morph may cross itself; [`validate`](Self::validate) checks keys.
    ///
    /// [`Outline::prepare`]: super::Outline::prepare
    pub fn prepare(&self) -> Result<PreparedLayer, HighlightError> {
        self.validate_but_shape()?;
        if let Some(pin) = &self.pin {
            return Err(HighlightError::Unresolved {
                patch: pin.patch.clone(),
            });
        }
        let mut ops = self
            .stack
            .iter()
            .map(Op::prepare)
            .collect::<Result<Vec<_>, _>>()?;
        if let Some(map) = self.shape_map {
            let after = self.placing_translation().map_or(0, |at| at + 1);
            ops.insert(after, PreparedOp::Linear(map.matrix));
        }
        Ok(PreparedLayer {
            stack: PreparedStack::new(ops),
            epsilon: self.epsilon,
            paint: Paint {
                colour: Vec3::from_array(self.colour),
                opacity: self.opacity,
            },
            feather: self.feather.unwrap_or(0.0),
            mask: self.mask.clone(),
            frame: self.frame.prepare()?,
            shape: self.shape.prepare()?,
        })
    }
}

/// What a layer paints with: colour (linear RGB) and opacity.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Paint {
    /// Linear RGB.
    pub colour: Vec3,
    /// Opacity in [0, 1].
    pub opacity: f32,
}

/// A validated layer, ready to evaluate at many points. Made by [`Layer::prepare`].
#[derive(Clone, Debug, PartialEq)]
pub struct PreparedLayer {
    stack: PreparedStack,
    epsilon: f32,
    paint: Paint,
    feather: f32,
    mask: Option<Mask>,
    frame: PreparedFrame,
    shape: PreparedShape,
}

/// Working memory of a layer evaluated on a [`PointChunk`]: the initial vectors in the layer's
/// frame, and the running vectors of its stack.
#[derive(Clone, Copy, Debug, Default)]
pub struct LayerScratch {
    initial: LocalChunk,
    vectors: LocalChunk,
}

impl PreparedLayer {
    /// The frame the layer's operations act in at a point whose shading frame is `frame`
    /// ([`PreparedFrame::at`]): `frame` itself for [`LayerFrame::Patch`].
    #[must_use]
    pub fn frame_at(&self, frame: &TangentFrame) -> TangentFrame {
        self.frame.at(frame)
    }

    /// The stack's output `H'` for the initial unit vector `h` at a point whose shading frame
    /// is `frame`, in world coordinates.
    #[must_use]
    pub fn highlight_vector(&self, frame: &TangentFrame, h: Vec3) -> Vec3 {
        let own = self.frame.at(frame);
        own.to_world(self.local_vector(own.to_local(h)))
    }

    #[inline]
    fn local_vector(&self, l: Vec3) -> Vec3 {
        self.stack.apply_local(l)
    }

    /// `s` of the stack's output given in frame coordinates, where N is +z: the disc's
    /// `ε − ‖N − H'‖²/2`, or a drawn outline's signed distance in the same units
    /// ([`PreparedOutline::signed`](super::PreparedOutline::signed)).
    #[inline]
    fn signed_local(&self, l: Vec3) -> f32 {
        match &self.shape {
            PreparedShape::Disc => signed_inside(Vec3::Z, l, self.epsilon),
            PreparedShape::Outline(outline) => outline.signed(l),
            PreparedShape::Morph(morph) => morph.signed(l),
        }
    }

    /// The signed inside value of the stack's output (positive inside), `s = ε − ‖N − H'‖² / 2`
    /// for the disc (a drawn outline's in the same units: [`PreparedShape`]),
    /// for the initial unit vector `h` at a point whose shading frame is `frame`.
    #[inline]
    #[must_use]
    pub fn signed(&self, frame: &TangentFrame, h: Vec3) -> f32 {
        self.signed_local(self.local_vector(self.frame.local(frame, h)))
    }

    /// [`signed`](Self::signed) at many points: `out[i]` for `frames[i]` and `hs[i]`. Faster per
    /// point than single calls (see [`LANES`]).
    ///
    /// # Panics
    /// If the slices differ in length.
    pub fn signed_many(&self, frames: &[TangentFrame], hs: &[Vec3], out: &mut [f32]) {
        assert!(
            frames.len() == hs.len() && hs.len() == out.len(),
            "slice lengths differ"
        );
        let (mut points, mut scratch) = (PointChunk::default(), LayerScratch::default());
        for ((f, h), o) in frames
            .chunks(LANES)
            .zip(hs.chunks(LANES))
            .zip(out.chunks_mut(LANES))
        {
            points.load(f, h);
            self.signed_chunk(&points, &mut scratch, o);
        }
    }

    /// `s` at each point of a chunk, into `out`; `scratch` is overwritten.
    pub(crate) fn signed_chunk(
        &self,
        points: &PointChunk,
        scratch: &mut LayerScratch,
        out: &mut [f32],
    ) {
        let LayerScratch { initial, vectors } = scratch;
        initial.load_in(self.frame, points);
        *vectors = *initial;
        self.stack.apply_chunk(initial, vectors);
        let (x, y, z) = vectors.lanes();
        for (o, ((x, y), z)) in out.iter_mut().zip(x.iter().zip(y).zip(z)) {
            *o = self.signed_local(Vec3::new(*x, *y, *z));
        }
    }

    /// Shape coverage before opacity at each point of a chunk, with (u, v) `uvs`, into `out`.
    pub(crate) fn shape_chunk(
        &self,
        points: &PointChunk,
        scratch: &mut LayerScratch,
        uvs: &[Vec2],
        footprint: Footprint,
        out: &mut [f32],
    ) {
        self.signed_chunk(points, scratch, out);
        for (o, uv) in out.iter_mut().zip(uvs) {
            *o = self.shape_from_signed(*o, *uv, footprint);
        }
    }

    /// Shape coverage in [0, 1] before opacity from the signed value `s` at `uv`: the edge's
    /// coverage of the pixel ([`Footprint::coverage`]) times the mask.
    #[inline]
    pub(crate) fn shape_from_signed(&self, s: f32, uv: Vec2, footprint: Footprint) -> f32 {
        self.masked(footprint.coverage(s, self.feather), uv)
    }

    /// The edge's coverage `c` of the pixel times the mask at `uv`.
    #[inline]
    fn masked(&self, c: f32, uv: Vec2) -> f32 {
        match &self.mask {
            Some(m) if c > 0.0 => c * m.factor(uv),
            _ => c,
        }
    }

    /// Shape coverage in [0, 1] before opacity where the edge covers `edge(s)` of the pixel,
    /// from the signed value `s` at the point, times the mask at `uv`: for a pixel whose cover
    /// the renderer finds otherwise than from a footprint (the feather is the caller's to
    /// heed).
    #[inline]
    #[must_use]
    pub fn shape_by(
        &self,
        frame: &TangentFrame,
        uv: Vec2,
        h: Vec3,
        edge: &dyn Fn(f32) -> f32,
    ) -> f32 {
        self.masked(edge(self.signed(frame, h)).clamp(0.0, 1.0), uv)
    }

    /// Shape coverage in [0, 1] before opacity: the edge's coverage of the pixel whose
    /// `footprint` of `s` the renderer gives ([`Footprint::HARD`]: the hard edge), times the mask
    /// at `uv`.
    #[inline]
    #[must_use]
    pub fn shape(&self, frame: &TangentFrame, uv: Vec2, h: Vec3, footprint: Footprint) -> f32 {
        self.shape_from_signed(self.signed(frame, h), uv, footprint)
    }

    /// [`shape`](Self::shape) at many points, into `out`.
    ///
    /// # Panics
    /// If the slices differ in length.
    pub fn shape_many(
        &self,
        frames: &[TangentFrame],
        uvs: &[Vec2],
        hs: &[Vec3],
        footprint: Footprint,
        out: &mut [f32],
    ) {
        assert!(
            frames.len() == uvs.len() && uvs.len() == hs.len() && hs.len() == out.len(),
            "slice lengths differ"
        );
        let (mut points, mut scratch) = (PointChunk::default(), LayerScratch::default());
        for (k, o) in out.chunks_mut(LANES).enumerate() {
            let r = k * LANES..k * LANES + o.len();
            points.load(&frames[r.clone()], &hs[r.clone()]);
            self.shape_chunk(&points, &mut scratch, &uvs[r], footprint, o);
        }
    }

    /// The layer's colour and opacity.
    #[must_use]
    pub fn paint(&self) -> Paint {
        self.paint
    }

    /// The width in `s` over which the edge fades (0: a hard edge): its coverage rises from 0
    /// at `s = −feather/2` to 1 at `s = feather/2`.
    #[must_use]
    pub fn feather(&self) -> f32 {
        self.feather
    }

    /// Whether a parameter-space mask cuts the layer.
    #[must_use]
    pub fn is_masked(&self) -> bool {
        self.mask.is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn layer(stack: Vec<Op>) -> Layer {
        Layer {
            stack,
            epsilon: 0.1,
            colour: [1.0, 0.5, 0.25],
            opacity: 0.8,
            feather: None,
            mask: None,
            pin: None,
            frame: LayerFrame::Patch,
            shape: Shape::Disc,
            shape_map: None,
        }
    }

    const FRAME: TangentFrame = TangentFrame::new(Vec3::X, Vec3::Y, Vec3::Z);

    #[test]
    fn signed_value_of_identity_stack() {
        let l = layer(vec![]).prepare().unwrap();
        assert!((l.signed(&FRAME, Vec3::Z) - 0.1).abs() < 1e-7);
        let h = Vec3::new(0.6, 0.0, 0.8);
        assert!((l.signed(&FRAME, h) - (0.1 - 0.2)).abs() < 1e-6);
        assert_eq!(l.shape(&FRAME, Vec2::ZERO, h, Footprint::HARD), 0.0);
        assert_eq!(l.shape(&FRAME, Vec2::ZERO, Vec3::Z, Footprint::HARD), 1.0);
    }

    #[test]
    fn batch_equals_single_calls() {
        let mut l = layer(vec![
            Op::Translate {
                alpha: 0.1,
                beta: 0.2,
            },
            Op::Square {
                sigma: 0.3,
                n: 1.5,
                style: crate::highlight::SquareStyle::Tangent,
            },
        ]);
        l.mask = Some(Mask {
            u: (0.0, 0.5),
            v: (0.0, 1.0),
            feather: 0.1,
        });
        let p = l.prepare().unwrap();
        let count = 2 * LANES + 7;
        let frames = vec![FRAME; count];
        let hs: Vec<Vec3> = (0..count)
            .map(|i| Vec3::new(0.3 * (i as f32 * 0.1).sin(), 0.2, 1.0).normalize())
            .collect();
        let uvs: Vec<Vec2> = (0..count)
            .map(|i| Vec2::new(i as f32 / 100.0, 0.5))
            .collect();
        let mut out = vec![0.0; count];
        p.shape_many(&frames, &uvs, &hs, Footprint { x: 0.01, y: 0.0 }, &mut out);
        for i in 0..count {
            assert_eq!(
                out[i],
                p.shape(&FRAME, uvs[i], hs[i], Footprint { x: 0.01, y: 0.0 })
            );
        }
        assert!(out.contains(&0.0) && out.iter().any(|&c| c > 0.5));
    }

    #[test]
    fn mask_cuts_and_feathers_inward() {
        let mut l = layer(vec![]);
        l.mask = Some(Mask {
            u: (0.2, 0.6),
            v: (0.0, 1.0),
            feather: 0.1,
        });
        let p = l.prepare().unwrap();
        let at = |u: f32| p.shape(&FRAME, Vec2::new(u, 0.5), Vec3::Z, Footprint::HARD);
        assert_eq!(at(0.1), 0.0);
        assert_eq!(at(0.2), 0.0);
        assert!((at(0.25) - 0.5).abs() < 1e-5);
        assert_eq!(at(0.4), 1.0);
        assert_eq!(at(0.7), 0.0);
    }

    #[test]
    fn feather_softens_edge_symmetrically() {
        let mut l = layer(vec![]);
        l.feather = Some(0.02);
        let p = l.prepare().unwrap();
        // On the hard edge (1 − cos = ε) coverage is one half.
        let c = 0.9_f32;
        let h = Vec3::new((1.0 - c * c).sqrt(), 0.0, c);
        assert!((p.shape(&FRAME, Vec2::ZERO, h, Footprint::HARD) - 0.5).abs() < 1e-3);
    }

    #[test]
    fn validation_names_the_op() {
        let l = layer(vec![
            Op::Rotate { degrees: 10.0 },
            Op::Split {
                gamma_u: -1.0,
                gamma_v: 0.0,
            },
        ]);
        let msg = l.prepare().unwrap_err().to_string();
        assert!(msg.starts_with("stack[1] (Split): split gamma_u"), "{msg}");
        let mut bad = layer(vec![]);
        bad.epsilon = 0.0;
        assert!(bad.validate().unwrap_err().to_string().contains("(0, 2]"));
        bad.epsilon = 0.1;
        bad.opacity = 1.5;
        assert!(bad.validate().is_err());
        bad.opacity = 1.0;
        bad.feather = Some(-0.1);
        assert!(bad.validate().is_err());
        bad.feather = None;
        bad.colour[1] = f32::NAN;
        assert!(bad.validate().is_err());
        bad.colour[1] = 0.0;
        bad.mask = Some(Mask {
            u: (0.5, 0.5),
            v: (0.0, 1.0),
            feather: 0.0,
        });
        let msg = bad.validate().unwrap_err().to_string();
        assert!(msg.contains("mask u range is (0.5, 0.5)"), "{msg}");
    }

    #[test]
    fn map_covers_all_fields() {
        let mut l = layer(vec![Op::Translate {
            alpha: 0.1,
            beta: 0.2,
        }]);
        l.feather = Some(0.3);
        l.mask = Some(Mask {
            u: (0.0, 1.0),
            v: (0.0, 1.0),
            feather: 0.0,
        });
        let mut count = 0;
        let doubled = l.map(|x| {
            count += 1;
            2.0 * x
        });
        assert_eq!(count, 2 + 1 + 3 + 1 + 1 + 5);
        assert_eq!(doubled.epsilon, 0.2);
        assert_eq!(doubled.feather, Some(0.6));
    }

    #[test]
    fn for_each_param_visits_every_parameter_in_order() {
        let mut l = layer(vec![Op::Rotate { degrees: 7.0 }]);
        l.feather = Some(0.3);
        l.mask = Some(Mask {
            u: (0.0, 1.0),
            v: (0.25, 0.75),
            feather: 0.5,
        });
        let mut seen = Vec::new();
        l.for_each_param(|p| seen.push(*p));
        assert_eq!(
            seen,
            [7.0, 0.1, 1.0, 0.5, 0.25, 0.8, 0.3, 0.0, 1.0, 0.25, 0.75, 0.5]
        );
    }

    #[test]
    fn mask_cuts_and_feathers_inward_along_v() {
        let mut l = layer(vec![]);
        l.mask = Some(Mask {
            u: (0.0, 1.0),
            v: (0.2, 0.6),
            feather: 0.1,
        });
        let p = l.prepare().unwrap();
        let at = |v: f32| p.shape(&FRAME, Vec2::new(0.5, v), Vec3::Z, Footprint::HARD);
        assert_eq!(at(0.1), 0.0);
        assert_eq!(at(0.2), 0.0);
        assert!((at(0.25) - 0.5).abs() < 1e-5);
        assert_eq!(at(0.4), 1.0);
        assert!((at(0.55) - 0.5).abs() < 1e-5);
        assert_eq!(at(0.7), 0.0);
    }

    #[test]
    fn pixel_width_widens_the_feather_band() {
        let mut l = layer(vec![]);
        l.feather = Some(0.02);
        let p = l.prepare().unwrap();
        // At cos = 0.91, s = ε − (1 − cos) = 0.01. Over the band 0.02 + 0.02 the smoothstep is at
        // x = 0.01 / 0.04 + 0.5 = 0.75: 0.75² (3 − 1.5) = 0.84375; over the feather alone, x = 1.
        let c = 0.91_f32;
        let h = Vec3::new((1.0 - c * c).sqrt(), 0.0, c);
        assert!(
            (p.shape(&FRAME, Vec2::ZERO, h, Footprint { x: 0.02, y: 0.0 }) - 0.84375).abs() < 1e-4
        );
        assert!((p.shape(&FRAME, Vec2::ZERO, h, Footprint::HARD) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn along_evaluates_in_the_projected_axis_frame_one_point_or_many() {
        let mut l = layer(vec![
            Op::Translate {
                alpha: 0.3,
                beta: -0.1,
            },
            Op::Scale {
                delta: 0.6,
                axis: crate::highlight::Axis::U,
            },
        ]);
        l.frame = LayerFrame::Along {
            axis: [1.0, 0.2, 0.5],
        };
        let along = l.prepare().unwrap();
        l.frame = LayerFrame::Patch;
        let plain = l.prepare().unwrap();
        let count = LANES + 5;
        // Frames about several normals, each du turned a different way about N; the
        // highlight vectors near N.
        let (mut frames, mut hs, mut own) = (Vec::new(), Vec::new(), Vec::new());
        for i in 0..count {
            let t = i as f32 * 0.37;
            let n = Vec3::new(0.3 * t.sin(), 0.3 * t.cos(), 1.0).normalize();
            let du = n.any_orthonormal_vector();
            let (c, s) = (t.cos(), t.sin());
            let du = c * du + s * n.cross(du);
            let f = TangentFrame::new(du, n.cross(du), n);
            // Independently: the axis's component in the tangent plane.
            let a = Vec3::new(1.0, 0.2, 0.5).normalize();
            let du2 = (a - a.dot(n) * n).normalize();
            own.push(TangentFrame::new(du2, n.cross(du2), n));
            frames.push(f);
            hs.push((n + Vec3::new(0.1 * s, -0.05, 0.02 * c)).normalize());
        }
        let mut out = vec![0.0; count];
        along.signed_many(&frames, &hs, &mut out);
        for i in 0..count {
            // The same as the patch-framed layer at a point whose frame is the field's.
            let want = plain.signed(&own[i], hs[i]);
            assert!((along.signed(&frames[i], hs[i]) - want).abs() < 1e-5, "{i}");
            assert_eq!(out[i], along.signed(&frames[i], hs[i]), "{i}");
            let world = along.highlight_vector(&frames[i], hs[i]);
            assert!((world - plain.highlight_vector(&own[i], hs[i])).length() < 1e-5);
            assert_eq!(along.frame_at(&frames[i]).n, frames[i].n);
        }
        // The patch frames differ, so the patch-framed layer differs somewhere.
        assert!((0..count).any(|i| (plain.signed(&frames[i], hs[i]) - out[i]).abs() > 1e-3));
    }

    #[test]
    fn a_layer_reads_its_frame_from_ron_patch_by_default() {
        let text = "(stack: [], epsilon: 0.1, colour: (1.0, 1.0, 1.0))";
        let l: Layer = ron::from_str(text).unwrap();
        assert_eq!(l.frame, LayerFrame::Patch);
        let text = "(stack: [], epsilon: 0.1, colour: (1.0, 1.0, 1.0), \
                    frame: Along(axis: (1, 0, 0)))";
        let l: Layer = ron::from_str(text).unwrap();
        assert_eq!(
            l.frame,
            LayerFrame::Along {
                axis: [1.0, 0.0, 0.0]
            }
        );
        let text = "(stack: [], epsilon: 0.1, colour: (1.0, 1.0, 1.0), \
                    frame: Along(axis: (0, 0, 0)))";
        let l: Layer = ron::from_str(text).unwrap();
        let msg = l.prepare().unwrap_err().to_string();
        assert!(msg.contains("frame axis is (0, 0, 0)"), "{msg}");
        let text = "(stack: [], epsilon: 0.1, colour: (1.0, 1.0, 1.0), \
                    frame: Along(axis: (1, 0, 0), spin: 2.0))";
        assert!(ron::from_str::<Layer>(text).is_err());
        // The axis is three parameters, after every other.
        let mut seen = Vec::new();
        l.map(|p| *p + 1.0).for_each_param(|p| seen.push(*p));
        assert_eq!(seen, [1.1, 2.0, 2.0, 2.0, 2.0, 1.0, 1.0, 1.0]);
    }

    #[test]
    fn a_shape_map_acts_right_after_the_placing_translation() {
        // The map R(−30°) is the rotation op's: a layer with it after its translation is the
        // layer with Rotate(30) there, and not the one with Rotate(30) at the end.
        let translate = Op::Translate {
            alpha: 0.05,
            beta: -0.02,
        };
        let scale = Op::Scale {
            delta: 0.7,
            axis: crate::highlight::Axis::U,
        };
        let mut held = layer(vec![translate.clone(), scale.clone()]);
        let (s, c) = 30f32.to_radians().sin_cos();
        held.shape_map = Some(ShapeMap {
            matrix: glam::Mat2::from_cols(Vec2::new(c, -s), Vec2::new(s, c)),
        });
        let rotate = Op::Rotate { degrees: 30.0 };
        let turned = layer(vec![translate.clone(), rotate.clone(), scale.clone()]);
        let last = layer(vec![translate, scale, rotate]);
        let (held, turned, last) = (
            held.prepare().unwrap(),
            turned.prepare().unwrap(),
            last.prepare().unwrap(),
        );
        let mut apart = 0.0_f32;
        for i in 0..40 {
            let t = i as f32 * 0.157;
            let h = Vec3::new(0.2 * t.cos(), 0.2 * t.sin(), 1.0).normalize();
            let s = held.signed(&FRAME, h);
            assert!((s - turned.signed(&FRAME, h)).abs() < 1e-6, "{i}");
            apart = apart.max((s - last.signed(&FRAME, h)).abs());
        }
        assert!(apart > 1e-3, "{apart}");
        // The map prints only when there is one.
        assert!(!format!("{:?}", layer(vec![])).contains("shape_map"));
    }

    #[test]
    fn signed_many_is_epsilon_minus_one_minus_cosine_at_each_point() {
        let p = layer(vec![]).prepare().unwrap();
        let count = LANES + 3;
        let angle = |i: usize| i as f32 * 0.05;
        let hs: Vec<Vec3> = (0..count)
            .map(|i| Vec3::new(angle(i).sin(), 0.0, angle(i).cos()))
            .collect();
        let mut out = vec![f32::NAN; count];
        p.signed_many(&vec![FRAME; count], &hs, &mut out);
        for (i, s) in out.iter().enumerate() {
            let want = 0.1 - (1.0 - f64::from(angle(i)).cos());
            assert!((f64::from(*s) - want).abs() < 1e-6, "{i}: {s} vs {want}");
        }
    }
}
