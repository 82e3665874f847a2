//! The Boolean post-operations of Anjyo & Hiramitsu 2003: a patch's highlight as an expression
//! over layers.

use glam::{Vec2, Vec3};
use serde::{Deserialize, Serialize};

use super::error::HighlightError;
use super::footprint::Footprint;
use super::frame::TangentFrame;
use super::layer::{Layer, LayerScratch, Paint, PreparedLayer};
use super::point_chunk::PointChunk;
use crate::math::LANES;

/// A Boolean expression over highlight layers, on soft coverage `a, b ∈ [0, 1]`
/// (docs/highlights.md): union `max(a, b)`, subtraction `A \ B = min(a, 1 − b)`, intersection
/// `min(a, b)`.
///
/// Colour rule: the Booleans combine *shape* coverage; each result carries one operand's paint
/// (colour and opacity). Union takes the paint of the operand with the larger coverage (the left
/// one on a tie); subtraction and intersection take the left operand's. The final coverage is the
/// shape coverage times the carried opacity, so a subtracted operand cuts fully whatever its own
/// opacity.
///
/// RON: `Subtract(Layer((stack: [], epsilon: 0.05, …)), Layer((stack: [Translate(…)], …)))`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(bound(deserialize = "P: Deserialize<'de> + From<f32>"))]
pub enum Expr<P = f32> {
    /// A single layer.
    Layer(Layer<P>),
    /// `A ∪ B`, coverage `max(a, b)`.
    Union(Box<Expr<P>>, Box<Expr<P>>),
    /// `A \ B`, coverage `min(a, 1 − b)`.
    Subtract(Box<Expr<P>>, Box<Expr<P>>),
    /// `A ∩ B`, coverage `min(a, b)`.
    Intersect(Box<Expr<P>>, Box<Expr<P>>),
}

/// The result of evaluating a highlight at a point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Shade {
    /// Coverage in [0, 1], opacity included: composite `colour` over the base with this weight.
    pub coverage: f32,
    /// Linear RGB.
    pub colour: Vec3,
}

impl<P> Expr<P> {
    /// Calls `f` with every numeric parameter, in the order of [`map`](Self::map), which
    /// it is built on: a parameter `map` reaches is visited, with no second list to keep.
    pub fn for_each_param(&self, mut f: impl FnMut(&P)) {
        let _visited: Expr<()> = self.map(|p| f(p));
    }

    /// The same expression with every numeric parameter mapped through `f`, left to right.
    #[must_use]
    pub fn map<Q>(&self, mut f: impl FnMut(&P) -> Q) -> Expr<Q> {
        self.map_dyn(&mut f)
    }

    /// The layers, left to right as written (the numbering of error messages, from 0 here).
    #[must_use]
    pub fn layers(&self) -> Vec<&Layer<P>> {
        match self {
            Expr::Layer(l) => vec![l],
            Expr::Union(a, b) | Expr::Subtract(a, b) | Expr::Intersect(a, b) => {
                let mut layers = a.layers();
                layers.extend(b.layers());
                layers
            }
        }
    }

    /// The layers, left to right as written, to change in place.
    pub fn layers_mut(&mut self) -> Vec<&mut Layer<P>> {
        match self {
            Expr::Layer(l) => vec![l],
            Expr::Union(a, b) | Expr::Subtract(a, b) | Expr::Intersect(a, b) => {
                let mut layers = a.layers_mut();
                layers.extend(b.layers_mut());
                layers
            }
        }
    }

    /// Where layer `k` (left to right, from 0) is written inside the expression: the operand
    /// index of each Boolean on the way (`Subtract(a, b)`: 0 for `a`, 1 for `b`), then 0 for
    /// the layer's own parentheses (`Layer((…))`). `None` when there are not that many layers.
    #[must_use]
    pub fn layer_route(&self, k: usize) -> Option<Vec<usize>> {
        match self {
            Expr::Layer(_) => (k == 0).then(|| vec![0]),
            Expr::Union(a, b) | Expr::Subtract(a, b) | Expr::Intersect(a, b) => {
                let left = a.layers().len();
                let (side, operand, k) = if k < left {
                    (0, a, k)
                } else {
                    (1, b, k - left)
                };
                let mut route = vec![side];
                route.extend(operand.layer_route(k)?);
                Some(route)
            }
        }
    }

    fn map_dyn<Q>(&self, f: &mut dyn FnMut(&P) -> Q) -> Expr<Q> {
        let pair = |a: &Self, b: &Self, f: &mut dyn FnMut(&P) -> Q| {
            let a = Box::new(a.map_dyn(f));
            (a, Box::new(b.map_dyn(f)))
        };
        match self {
            Expr::Layer(l) => Expr::Layer(l.map(f)),
            Expr::Union(a, b) => {
                let (a, b) = pair(a, b, f);
                Expr::Union(a, b)
            }
            Expr::Subtract(a, b) => {
                let (a, b) = pair(a, b, f);
                Expr::Subtract(a, b)
            }
            Expr::Intersect(a, b) => {
                let (a, b) = pair(a, b, f);
                Expr::Intersect(a, b)
            }
        }
    }
}

impl Expr<f32> {
    /// Validates every layer; errors say which layer (numbered left to right from 1).
    pub fn validate(&self) -> Result<(), HighlightError> {
        self.prepare().map(|_| ())
    }

    /// Validates and precomputes the per-point form.
    pub fn prepare(&self) -> Result<PreparedExpr, HighlightError> {
        let mut count = 0;
        self.prepare_numbered(&mut count)
    }

    fn prepare_numbered(&self, count: &mut usize) -> Result<PreparedExpr, HighlightError> {
        let mut pair = |a: &Self, b: &Self| -> Result<_, HighlightError> {
            let a = Box::new(a.prepare_numbered(count)?);
            Ok((a, Box::new(b.prepare_numbered(count)?)))
        };
        Ok(match self {
            Expr::Layer(l) => {
                let index = *count;
                *count += 1;
                PreparedExpr::Layer(l.prepare().map_err(|e| e.at(format!("layers[{index}]")))?)
            }
            Expr::Union(a, b) => {
                let (a, b) = pair(a, b)?;
                PreparedExpr::Combine(Boolean::Union, a, b)
            }
            Expr::Subtract(a, b) => {
                let (a, b) = pair(a, b)?;
                PreparedExpr::Combine(Boolean::Subtract, a, b)
            }
            Expr::Intersect(a, b) => {
                let (a, b) = pair(a, b)?;
                PreparedExpr::Combine(Boolean::Intersect, a, b)
            }
        })
    }
}

/// A Boolean post-operation on shape coverage.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Boolean {
    /// `max(a, b)`, paint of the larger (left on a tie).
    Union,
    /// `min(a, 1 − b)`, paint of the left.
    Subtract,
    /// `min(a, b)`, paint of the left.
    Intersect,
}

impl Boolean {
    /// Combines two (shape coverage, paint) pairs by the rule documented on [`Expr`].
    #[inline]
    #[must_use]
    pub fn combine(self, a: (f32, Paint), b: (f32, Paint)) -> (f32, Paint) {
        match self {
            Boolean::Union if b.0 > a.0 => b,
            Boolean::Union => a,
            Boolean::Subtract => (a.0.min(1.0 - b.0), a.1),
            Boolean::Intersect => (a.0.min(b.0), a.1),
        }
    }
}

/// A validated expression, ready to evaluate at many points. Made by [`Expr::prepare`].
#[derive(Clone, Debug, PartialEq)]
pub enum PreparedExpr {
    /// A single layer.
    Layer(PreparedLayer),
    /// A Boolean of two subexpressions.
    Combine(Boolean, Box<PreparedExpr>, Box<PreparedExpr>),
}

impl PreparedExpr {
    /// The highlight at a point with frame `frame`, patch parameters `uv` and initial unit
    /// highlight vector `h`. `footprint` is the pixel's footprint of the signed value
    /// ([`Footprint::HARD`]: the hard edge of Anjyo & Hiramitsu 2003; the renderer's for
    /// analytic anti-aliasing),
    /// which each layer's edge covers ([`Footprint::coverage`]).
    #[must_use]
    pub fn eval(&self, frame: &TangentFrame, uv: Vec2, h: Vec3, footprint: Footprint) -> Shade {
        let (shape, paint) = self.shape(frame, uv, h, footprint);
        Shade {
            coverage: shape * paint.opacity,
            colour: paint.colour,
        }
    }

    /// [`eval`](Self::eval) at many points, into `out`; faster per point than single calls.
    ///
    /// # Panics
    /// If the slices differ in length.
    pub fn eval_many(
        &self,
        frames: &[TangentFrame],
        uvs: &[Vec2],
        hs: &[Vec3],
        footprint: Footprint,
        out: &mut [Shade],
    ) {
        assert!(
            frames.len() == uvs.len() && uvs.len() == hs.len() && hs.len() == out.len(),
            "slice lengths differ"
        );
        let (mut points, mut scratch) = (PointChunk::default(), ChunkScratch::default());
        for (k, o) in out.chunks_mut(LANES).enumerate() {
            let r = k * LANES..k * LANES + o.len();
            points.load(&frames[r.clone()], &hs[r.clone()]);
            self.eval_chunk(&points, &uvs[r], footprint, &mut scratch, o);
        }
    }

    /// [`eval`](Self::eval) at a chunk of points (their shading frames and initial highlight
    /// vectors, which each layer takes into its own frame), with (u, v) `uvs`, into `out`;
    /// `scratch` is working memory a caller keeps from one chunk to the next.
    ///
    /// # Panics
    /// If `uvs` or `out` is not as long as the chunk.
    pub(crate) fn eval_chunk(
        &self,
        points: &PointChunk,
        uvs: &[Vec2],
        footprint: Footprint,
        scratch: &mut ChunkScratch,
        out: &mut [Shade],
    ) {
        let n = points.len();
        assert!(uvs.len() == n && out.len() == n, "chunk lengths differ");
        let ChunkScratch {
            layer,
            shapes,
            paints,
        } = scratch;
        let (s, p) = (&mut shapes[..n], &mut paints[..n]);
        self.shape_chunk(points, layer, uvs, footprint, s, p);
        for ((o, s), p) in out.iter_mut().zip(s.iter()).zip(p.iter()) {
            *o = Shade {
                coverage: s * p.opacity,
                colour: p.colour,
            };
        }
    }

    /// The layers of the expression, left to right.
    #[must_use]
    pub fn layers(&self) -> Vec<&PreparedLayer> {
        let mut layers = Vec::new();
        self.push_layers(&mut layers);
        layers
    }

    fn push_layers<'a>(&'a self, layers: &mut Vec<&'a PreparedLayer>) {
        match self {
            PreparedExpr::Layer(layer) => layers.push(layer),
            PreparedExpr::Combine(_, a, b) => {
                a.push_layers(layers);
                b.push_layers(layers);
            }
        }
    }

    /// The paint of the leftmost layer, to fill buffers with.
    fn first_paint(&self) -> Paint {
        match self {
            PreparedExpr::Layer(l) => l.paint(),
            PreparedExpr::Combine(_, a, _) => a.first_paint(),
        }
    }

    /// Shape coverage and paint at a chunk of points with (u, v) `uvs`.
    fn shape_chunk(
        &self,
        points: &PointChunk,
        scratch: &mut LayerScratch,
        uvs: &[Vec2],
        footprint: Footprint,
        shapes: &mut [f32],
        paints: &mut [Paint],
    ) {
        match self {
            PreparedExpr::Layer(l) => {
                l.shape_chunk(points, scratch, uvs, footprint, shapes);
                paints.fill(l.paint());
            }
            PreparedExpr::Combine(op, a, b) => {
                a.shape_chunk(points, scratch, uvs, footprint, shapes, paints);
                let mut b_shapes = [0.0; LANES];
                let mut b_paints = [b.first_paint(); LANES];
                let n = shapes.len();
                let (bs, bp) = (&mut b_shapes[..n], &mut b_paints[..n]);
                b.shape_chunk(points, scratch, uvs, footprint, bs, bp);
                for i in 0..n {
                    (shapes[i], paints[i]) = op.combine((shapes[i], paints[i]), (bs[i], bp[i]));
                }
            }
        }
    }

    /// [`eval`](Self::eval) from the signed value `s` of each layer at the point, `signed[j]`
    /// for layer `j` (numbered left to right, as [`layers`](Self::layers) lists them), as
    /// [`PreparedLayer::signed_chunk`] gives them: the Booleans of the layers' shapes
    /// ([`PreparedLayer::shape_from_signed`]), as [`eval_chunk`](Self::eval_chunk) takes them.
    ///
    /// # Panics
    /// If `signed` has fewer values than the expression has layers.
    #[must_use]
    pub(crate) fn eval_signed(&self, signed: &[f32], uv: Vec2, footprint: Footprint) -> Shade {
        let mut next = 0;
        let (shape, paint) = self.shape_signed(signed, uv, footprint, &mut next);
        Shade {
            coverage: shape * paint.opacity,
            colour: paint.colour,
        }
    }

    /// The shape and paint of [`eval_signed`](Self::eval_signed); `next` numbers the layers as
    /// they are met.
    fn shape_signed(
        &self,
        signed: &[f32],
        uv: Vec2,
        footprint: Footprint,
        next: &mut usize,
    ) -> (f32, Paint) {
        match self {
            PreparedExpr::Layer(l) => {
                let shape = l.shape_from_signed(signed[*next], uv, footprint);
                *next += 1;
                (shape, l.paint())
            }
            PreparedExpr::Combine(op, a, b) => {
                let a = a.shape_signed(signed, uv, footprint, next);
                let b = b.shape_signed(signed, uv, footprint, next);
                op.combine(a, b)
            }
        }
    }

    /// [`eval`](Self::eval) with hard edges but that of layer `layer` (numbered left to right,
    /// as [`layers`](Self::layers) lists them), which covers `edge(s)` of the pixel from its
    /// signed value `s` ([`PreparedLayer::shape_by`]). Where one layer's edge crosses a pixel
    /// and every other layer covers all of it or none, each Boolean is that of a constant with
    /// the one edge's coverage, and the result is the pixel's mean highlight.
    #[must_use]
    pub fn eval_with_edge(
        &self,
        frame: &TangentFrame,
        uv: Vec2,
        h: Vec3,
        layer: usize,
        edge: &dyn Fn(f32) -> f32,
    ) -> Shade {
        let mut next = 0;
        let (shape, paint) = self.shape_with_edge(frame, uv, h, (layer, edge), &mut next);
        Shade {
            coverage: shape * paint.opacity,
            colour: paint.colour,
        }
    }

    /// The shape and paint of [`eval_with_edge`](Self::eval_with_edge); `next` numbers the
    /// layers as they are met.
    fn shape_with_edge(
        &self,
        frame: &TangentFrame,
        uv: Vec2,
        h: Vec3,
        edge: (usize, &dyn Fn(f32) -> f32),
        next: &mut usize,
    ) -> (f32, Paint) {
        match self {
            PreparedExpr::Layer(l) => {
                let shape = if *next == edge.0 {
                    l.shape_by(frame, uv, h, edge.1)
                } else {
                    l.shape(frame, uv, h, Footprint::HARD)
                };
                *next += 1;
                (shape, l.paint())
            }
            PreparedExpr::Combine(op, a, b) => {
                let a = a.shape_with_edge(frame, uv, h, edge, next);
                let b = b.shape_with_edge(frame, uv, h, edge, next);
                op.combine(a, b)
            }
        }
    }

    fn shape(&self, frame: &TangentFrame, uv: Vec2, h: Vec3, footprint: Footprint) -> (f32, Paint) {
        match self {
            PreparedExpr::Layer(l) => (l.shape(frame, uv, h, footprint), l.paint()),
            PreparedExpr::Combine(op, a, b) => op.combine(
                a.shape(frame, uv, h, footprint),
                b.shape(frame, uv, h, footprint),
            ),
        }
    }
}

/// Working memory of [`PreparedExpr::eval_chunk`].
#[derive(Clone, Debug)]
pub struct ChunkScratch {
    layer: LayerScratch,
    shapes: [f32; LANES],
    paints: [Paint; LANES],
}

impl Default for ChunkScratch {
    fn default() -> Self {
        Self {
            layer: LayerScratch::default(),
            shapes: [0.0; LANES],
            paints: [Paint {
                colour: Vec3::ZERO,
                opacity: 0.0,
            }; LANES],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn paint(r: f32, opacity: f32) -> Paint {
        Paint {
            colour: Vec3::new(r, 0.0, 0.0),
            opacity,
        }
    }

    #[test]
    fn colour_rule() {
        let a = (0.3, paint(1.0, 1.0));
        let b = (0.7, paint(2.0, 0.5));
        assert_eq!(Boolean::Union.combine(a, b), b);
        assert_eq!(Boolean::Union.combine(b, a), b);
        assert_eq!(Boolean::Union.combine(a, (0.3, b.1)), a);
        assert_eq!(Boolean::Subtract.combine(a, b), (0.3, a.1));
        assert_eq!(Boolean::Subtract.combine(b, a), (0.7, b.1));
        assert_eq!(Boolean::Intersect.combine(b, a), (0.3, b.1));
    }

    fn layer(epsilon: f32, opacity: f32) -> Expr {
        Expr::Layer(Layer {
            stack: vec![],
            epsilon,
            colour: [epsilon, 0.0, 0.0],
            opacity,
            feather: None,
            mask: None,
            pin: None,
            frame: crate::highlight::LayerFrame::Patch,
            shape: crate::highlight::Shape::Disc,
            shape_map: None,
        })
    }

    #[test]
    fn opacity_scales_final_coverage_and_subtrahend_cuts_fully() {
        let frame = TangentFrame::new(Vec3::X, Vec3::Y, Vec3::Z);
        let e = Expr::Subtract(Box::new(layer(0.5, 0.5)), Box::new(layer(0.1, 0.2)))
            .prepare()
            .unwrap();
        let centre = e.eval(&frame, Vec2::ZERO, Vec3::Z, Footprint::HARD);
        assert_eq!(centre.coverage, 0.0);
        let h = Vec3::new(0.6, 0.0, 0.8); // 1 − cos = 0.2: in the ring.
        let ring = e.eval(&frame, Vec2::ZERO, h, Footprint::HARD);
        assert_eq!(ring.coverage, 0.5);
        assert_eq!(ring.colour.x, 0.5);
    }

    #[test]
    fn one_layer_edge_given_the_others_hard() {
        // A \ B at h in the ring (inside A, ε 0.5; outside B, ε 0.1), opacity 0.5.
        let frame = TangentFrame::new(Vec3::X, Vec3::Y, Vec3::Z);
        let e = Expr::Subtract(Box::new(layer(0.5, 0.5)), Box::new(layer(0.1, 1.0)))
            .prepare()
            .unwrap();
        let h = Vec3::new(0.6, 0.0, 0.8);
        // B's edge covering 0.3 of the pixel cuts 0.3 of A's.
        let cut = e.eval_with_edge(&frame, Vec2::ZERO, h, 1, &|_| 0.3);
        assert!((cut.coverage - 0.5 * 0.7).abs() < 1e-6, "{cut:?}");
        assert_eq!(cut.colour.x, 0.5);
        // A's edge covering 0.3 of it, B hard outside: 0.3 of A. The edge sees A's own s,
        // ε − (1 − cos) = 0.5 − 0.2.
        let s_of_a = std::cell::Cell::new(0.0);
        let edge = |s: f32| {
            s_of_a.set(s);
            0.3
        };
        let part = e.eval_with_edge(&frame, Vec2::ZERO, h, 0, &edge);
        assert!((part.coverage - 0.5 * 0.3).abs() < 1e-6, "{part:?}");
        assert!((s_of_a.get() - 0.3).abs() < 1e-6, "{}", s_of_a.get());
        // With every edge hard otherwise, as eval.
        let hard = e.eval_with_edge(&frame, Vec2::ZERO, h, 0, &|s| f32::from(s > 0.0));
        assert_eq!(hard, e.eval(&frame, Vec2::ZERO, h, Footprint::HARD));
    }

    #[test]
    fn shades_from_the_layers_signed_values_are_the_shades_evaluated() {
        // Three layers under two Booleans, each with its own stack, over vectors that fall
        // inside, outside and between them: the shade taken from the layers' `s` in the order
        // `layers` lists them is the shade evaluated, to the bit; in another order it is not.
        let one = |epsilon: f32, alpha: f32, opacity: f32| {
            Expr::Layer(Layer {
                opacity,
                ..Layer::new(
                    vec![crate::highlight::Op::Translate { alpha, beta: 0.0 }],
                    epsilon,
                    [epsilon, 0.5, 0.0],
                )
            })
        };
        let e = Expr::Subtract(
            Box::new(Expr::Union(
                Box::new(one(0.3, 0.0, 1.0)),
                Box::new(one(0.05, 0.3, 0.5)),
            )),
            Box::new(one(0.02, 0.1, 1.0)),
        )
        .prepare()
        .unwrap();
        let layers = e.layers();
        let frame = TangentFrame::new(Vec3::X, Vec3::Y, Vec3::Z);
        let mut differs_reversed = false;
        for i in 0..200 {
            let a = i as f32 * 0.37;
            let r = (i % 17) as f32 / 17.0;
            let h = Vec3::new(r * a.cos(), r * a.sin(), 1.0).normalize();
            let uv = Vec2::new(i as f32 / 200.0, 0.5);
            let signed: Vec<f32> = layers.iter().map(|l| l.signed(&frame, h)).collect();
            let evaluated = e.eval(&frame, uv, h, Footprint::HARD);
            assert_eq!(
                e.eval_signed(&signed, uv, Footprint::HARD),
                evaluated,
                "{h}"
            );
            let reversed: Vec<f32> = signed.iter().rev().copied().collect();
            differs_reversed |= e.eval_signed(&reversed, uv, Footprint::HARD) != evaluated;
        }
        assert!(differs_reversed);
    }

    #[test]
    fn batch_equals_single_calls() {
        let frame = TangentFrame::new(Vec3::X, Vec3::Y, Vec3::Z);
        let e = Expr::Union(
            Box::new(layer(0.02, 1.0)),
            Box::new(Expr::Subtract(
                Box::new(layer(0.3, 0.5)),
                Box::new(layer(0.1, 1.0)),
            )),
        )
        .prepare()
        .unwrap();
        let count = LANES + 13;
        let frames = vec![frame; count];
        let uvs = vec![Vec2::ZERO; count];
        let hs: Vec<Vec3> = (0..count)
            .map(|i| Vec3::new(i as f32 / count as f32, 0.0, 1.0).normalize())
            .collect();
        let mut out = vec![
            Shade {
                coverage: -1.0,
                colour: Vec3::ZERO
            };
            count
        ];
        e.eval_many(&frames, &uvs, &hs, Footprint { x: 0.001, y: 0.0 }, &mut out);
        for i in 0..count {
            assert_eq!(
                out[i],
                e.eval(&frame, uvs[i], hs[i], Footprint { x: 0.001, y: 0.0 })
            );
        }
        // The centre (layer 1), the ring (layer 2 minus 3, half opacity) and outside all occur.
        let colours: Vec<f32> = out.iter().map(|s| s.colour.x).collect();
        assert!(colours.contains(&0.02) && colours.contains(&0.3));
        assert!(out.iter().any(|s| s.coverage == 0.0));
    }

    #[test]
    fn errors_number_layers_left_to_right() {
        let e = Expr::Union(Box::new(layer(0.1, 1.0)), Box::new(layer(0.1, 2.0)));
        let msg = e.validate().unwrap_err().to_string();
        assert!(msg.starts_with("layers[1]: opacity is 2"), "{msg}");
    }

    #[test]
    fn map_reaches_nested_layers() {
        let e = Expr::Intersect(
            Box::new(layer(0.1, 1.0)),
            Box::new(Expr::Union(
                Box::new(layer(0.2, 1.0)),
                Box::new(layer(0.3, 1.0)),
            )),
        );
        let mut seen = Vec::new();
        let _ = e.map(|x| seen.push(*x));
        // Each layer: ε, 3 colour components, opacity.
        assert_eq!(seen.len(), 15);
        assert_eq!([seen[0], seen[5], seen[10]], [0.1, 0.2, 0.3]);
    }

    #[test]
    fn layers_are_found_left_to_right_with_their_routes() {
        let mut e = Expr::Intersect(
            Box::new(layer(0.1, 1.0)),
            Box::new(Expr::Subtract(
                Box::new(layer(0.2, 1.0)),
                Box::new(layer(0.3, 1.0)),
            )),
        );
        let eps: Vec<f32> = e.layers().iter().map(|l| l.epsilon).collect();
        assert_eq!(eps, [0.1, 0.2, 0.3]);
        assert_eq!(e.layer_route(0), Some(vec![0, 0]));
        assert_eq!(e.layer_route(1), Some(vec![1, 0, 0]));
        assert_eq!(e.layer_route(2), Some(vec![1, 1, 0]));
        assert_eq!(e.layer_route(3), None);
        e.layers_mut()[2].epsilon = 0.4;
        assert!(matches!(&e, Expr::Intersect(_, b)
            if matches!(&**b, Expr::Subtract(_, c) if matches!(&**c, Expr::Layer(l) if l.epsilon == 0.4))));
    }
}
