//! An X-Toon tone (Barla et al. 2006): a 2D toon texture looked up at `(n'·l, D)`, with D from
//! a detail map and n' the shading normal, optionally blended toward an abstracted shape.

use std::sync::Arc;

use glam::{Vec2, Vec3};
use serde::Deserialize;

use super::detail::{DetailMap, PreparedDetail, ViewDetail};
use super::error::XToonError;
use super::shape::{AbstractShape, HighlightFrame, PreparedShape, ShapeDetail};
use super::texture::ToonTexture;

/// The parameters of an X-Toon tone; the texture is given beside them, as an image.
///
/// RON:
/// ```text
/// (detail: Depth(z_min: 6.0, r: 3.0), invert: false,
///  shape: Some((abstraction: Ellipsoid, weight: 0.5, highlight_frame: Abstracted)))
/// ```
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct XToon<P = f32> {
    /// Where the detail D comes from.
    pub detail: DetailMap<P>,
    /// Use `1 − D` (the paper's Figure 4: low detail where the map is high). Default false.
    #[serde(default)]
    pub invert: bool,
    /// Shading normals blended toward an abstracted shape. None (or left out): the true
    /// normals.
    pub shape: Option<ShapeDetail<P>>,
}

impl<P> XToon<P> {
    /// The same tone with every numeric parameter mapped through `f`.
    #[must_use]
    pub fn map<Q>(&self, mut f: impl FnMut(&P) -> Q) -> XToon<Q> {
        XToon {
            detail: self.detail.map(&mut f),
            invert: self.invert,
            shape: self.shape.as_ref().map(|s| s.map(&mut f)),
        }
    }
}

impl XToon<f32> {
    /// Checks the detail map and the shape detail.
    pub fn validate(&self) -> Result<(), XToonError> {
        self.detail.validate()?;
        if let Some(s) = &self.shape {
            s.validate()?;
        }
        Ok(())
    }

    /// Validates and prepares the tone with its `texture` and, when it has shape detail, the
    /// model's abstracted `shape` (built once per model by
    /// [`Abstraction::build`](super::Abstraction::build); ignored without shape detail).
    pub fn prepare(
        &self,
        texture: Arc<ToonTexture>,
        shape: Option<&Arc<AbstractShape>>,
    ) -> Result<PreparedXToon, XToonError> {
        self.validate()?;
        let shape = match (&self.shape, shape) {
            (Some(detail), Some(built)) => detail.prepare(built)?,
            (Some(detail), None) => {
                return Err(XToonError::Shape(format!(
                    "the shape detail needs the model's {:?} shape, and none was given",
                    detail.abstraction
                )))
            }
            (None, _) => None,
        };
        Ok(PreparedXToon {
            texture,
            detail: self.detail.prepare(self.invert)?,
            shape,
        })
    }
}

/// A validated X-Toon tone, ready to shade with.
#[derive(Clone, Debug, PartialEq)]
pub struct PreparedXToon {
    texture: Arc<ToonTexture>,
    detail: PreparedDetail,
    /// None without shape detail or with w = 0.
    shape: Option<PreparedShape>,
}

/// What the tone gives at one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct XToonShade {
    /// Linear RGB from the texture.
    pub colour: Vec3,
    /// The shading normal n' the tone used.
    pub normal: Vec3,
}

impl PreparedXToon {
    /// Whether highlights on this patch use the abstracted frame (shape detail with w > 0 and
    /// [`HighlightFrame::Abstracted`]).
    #[must_use]
    pub fn abstracts_highlights(&self) -> bool {
        self.shape
            .as_ref()
            .is_some_and(|s| s.highlight_frame() == HighlightFrame::Abstracted)
    }

    /// The tone seen from `eye` looking along the unit `forward`: place it once per frame.
    #[must_use]
    pub fn in_view(&self, eye: Vec3, forward: Vec3) -> ViewXToon<'_> {
        ViewXToon {
            tone: self,
            detail: self.detail.in_view(eye, forward),
        }
    }
}

/// An X-Toon tone placed in a view, evaluated per point.
#[derive(Clone, Copy, Debug)]
pub struct ViewXToon<'a> {
    tone: &'a PreparedXToon,
    detail: ViewDetail,
}

/// A surface point as the tone sees it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfacePoint {
    pub position: Vec3,
    /// The unit normal, facing the viewer.
    pub normal: Vec3,
    pub patch: usize,
    pub uv: Vec2,
}

/// The most points [`ViewXToon::shade_run`] takes at once.
pub const RUN: usize = 64;

impl ViewXToon<'_> {
    /// Whether the tone reads the view vector: the orientation maps do, the depth maps do not.
    #[inline]
    #[must_use]
    pub fn uses_view(&self) -> bool {
        self.detail.uses_view()
    }

    /// The tone at `point`, seen along the unit vector `view(position)` (toward the eye; asked
    /// for only by the orientation maps) and lit from the unit `light(position, normal)`: n' the
    /// shading normal ([`PreparedShape::shading_normal`], or n), D from the detail map (the
    /// highlight map reflects about n' or n, as the shape detail's [`HighlightFrame`] says;
    /// near-silhouette uses n), and the texture at `(n'·l, D)`.
    #[must_use]
    pub fn shade(
        &self,
        point: &SurfacePoint,
        view: impl Fn(Vec3) -> Vec3,
        light: impl Fn(Vec3, Vec3) -> Vec3,
    ) -> XToonShade {
        let mut out = [NO_SHADE];
        self.shade_run(1, |_| *point, |_| view(point.position), light, &mut out);
        out[0]
    }

    /// [`shade`](Self::shade) at `point(i)` for i < `n` ≤ [`RUN`] into `out[i]`, seen along the
    /// unit `view(i)` (asked for only when [`uses_view`](Self::uses_view)): first every shading
    /// normal, then per point its detail and texture lookup. The points' independent
    /// chains of square roots and divisions overlap in the processor, and the loops are inlined
    /// whole into the caller's.
    ///
    /// # Panics
    /// If `n` is more than [`RUN`] or than there are outputs.
    #[inline(always)]
    pub fn shade_run(
        &self,
        n: usize,
        point: impl Fn(usize) -> SurfacePoint,
        view: impl Fn(usize) -> Vec3,
        light: impl Fn(Vec3, Vec3) -> Vec3,
        out: &mut [XToonShade],
    ) {
        assert!(n <= RUN && out.len() >= n, "bad run");
        // The shading normals, when a shape abstracts them.
        let mut abstracted_normals = [Vec3::ZERO; RUN];
        let shaped = self.tone.shape.as_ref().map(|shape| {
            shape.shading_normals(&point, &mut abstracted_normals[..n]);
            &abstracted_normals[..n]
        });
        let abstracted = self.tone.abstracts_highlights();
        let uses_view = self.uses_view();
        for (i, o) in out[..n].iter_mut().enumerate() {
            let p = point(i);
            let shading = shaped.map_or(p.normal, |normals| normals[i]);
            let light = light(p.position, p.normal);
            let view = if uses_view { view(i) } else { Vec3::ZERO };
            let highlight = if abstracted { shading } else { p.normal };
            let d = self
                .detail
                .value(p.position, view, light, p.normal, highlight);
            *o = XToonShade {
                colour: self.tone.texture.sample(shading.dot(light), d),
                normal: shading,
            };
        }
    }
}

/// A shade to fill output arrays with before they are written.
pub const NO_SHADE: XToonShade = XToonShade {
    colour: Vec3::ZERO,
    normal: Vec3::Z,
};
