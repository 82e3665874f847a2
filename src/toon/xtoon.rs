//! An X-Toon tone (Barla et al. 2006): a 2D toon texture looked up at `(n'·l, D)`, with D from
//! a detail map and n' the shading normal, optionally blended toward an abstracted shape.

use std::sync::Arc;

use glam::Vec3;
use serde::Deserialize;

use super::detail::{DetailMap, PreparedDetail, ViewDetail};
use super::error::XToonError;
use super::point_run::PointRun;
use super::shape::{AbstractShape, HighlightFrame, PreparedShape, ShapeDetail};
use super::texture::ToonTexture;
use crate::math::{Lanes, LANES};

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
    /// Use `1 − D` (Figure 4 of Barla, Thollot & Markosian 2006: low detail where the map is
    /// high). Default false.
    #[serde(default)]
    pub invert: bool,
    /// Shading normals blended toward an abstracted shape. None (or left out): the true
    /// normals.
    pub shape: Option<ShapeDetail<P>>,
}

impl<P> XToon<P> {
    /// Calls `f` with every numeric parameter, in the order of [`map`](Self::map), which
    /// it is built on: a parameter `map` reaches is visited, with no second list to keep.
    pub fn for_each_param(&self, mut f: impl FnMut(&P)) {
        let _visited: XToon<()> = self.map(|p| f(p));
    }

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

impl ViewXToon<'_> {
    /// Whether the tone reads the view vector: the orientation maps do, the depth maps do not.
    #[inline]
    #[must_use]
    pub fn uses_view(&self) -> bool {
        self.detail.uses_view()
    }

    /// The tone at each of `points` into `colour[k]`, seen along the unit `view[k]` (toward the
    /// eye; read only when the tone [uses it](Self::uses_view)) and lit from the unit
    /// `light[k]`: n' the shading normal ([`PreparedShape::shading_normals`], computed into
    /// `abstracted`, or n), D from the detail map (the highlight map reflects about n' or n, as
    /// the shape detail's [`HighlightFrame`] says; near-silhouette uses n), and the texture at
    /// `(n'·l, D)`. Returns the shading normals.
    ///
    /// Each stage is a loop of its own over the points, held one array per coordinate, so that
    /// it vectorizes.
    ///
    /// # Panics
    /// If `colour` is not `points.len` long.
    #[inline(always)]
    pub(crate) fn shade_run<'a>(
        &self,
        points: &'a PointRun,
        view: &Lanes,
        light: &Lanes,
        abstracted: &'a mut Lanes,
        colour: &mut [Vec3],
    ) -> &'a Lanes {
        let n = points.len;
        assert_eq!(colour.len(), n, "one colour per point");
        let shading = match &self.tone.shape {
            Some(shape) => {
                shape.shading_normals(points, abstracted);
                abstracted
            }
            None => &points.normal,
        };
        let mut n_dot_l = [0.0; LANES];
        for (k, nl) in n_dot_l[..n].iter_mut().enumerate() {
            *nl = shading.get(k).dot(light.get(k));
        }
        let highlight = if self.tone.abstracts_highlights() {
            shading
        } else {
            &points.normal
        };
        let mut detail = [0.0; LANES];
        self.detail
            .values(points, view, light, highlight, &mut detail[..n]);
        self.tone
            .texture
            .sample_run(&n_dot_l[..n], &detail[..n], colour);
        shading
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{shapes, NamedPatch, PatchLibrary};
    use crate::toon::Abstraction;
    use glam::{DVec3, Vec2};

    /// A unit vector that turns with `k`.
    fn direction(k: usize, turn: f32) -> Vec3 {
        let a = k as f32 * turn;
        Vec3::new(a.cos(), a.sin(), 0.3 * (2.0 * a).sin()).normalize()
    }

    #[test]
    fn a_run_shades_each_point_as_it_would_alone() {
        let library = PatchLibrary {
            patches: vec![NamedPatch {
                name: "sphere".into(),
                trim: None,
                surface: shapes::sphere(DVec3::ZERO, 2.0).unwrap(),
            }],
            groups: Vec::new(),
        };
        let texels: Vec<Vec3> = (0..8 * 4)
            .map(|k| Vec3::new((k % 8) as f32 / 7.0, (k / 8) as f32 / 3.0, 0.5))
            .collect();
        let texture = Arc::new(ToonTexture::new(8, 4, texels).unwrap());
        // A full run and a short one, of points of every kind of lane on a sphere.
        let mut run = PointRun {
            len: LANES,
            ..PointRun::default()
        };
        let (mut view, mut light) = (Lanes::default(), Lanes::default());
        for k in 0..LANES {
            let n = direction(k, 0.7);
            let uv = Vec2::new(k as f32 / 9.0 - 1.0, (k % 5) as f32 * 0.9);
            run.set(k, 2.0 * n, n, uv);
            view.set(k, direction(k, 1.3));
            light.set(k, direction(k + 3, 0.4));
        }
        let details = [
            DetailMap::Depth { z_min: 1.0, r: 3.0 },
            DetailMap::DepthOfField {
                focus: [0.0, 1.0, 0.0],
                z_min: 0.5,
                r: 2.0,
            },
            DetailMap::NearSilhouette { r: 2.5 },
            DetailMap::Highlight { s: 7.0 },
        ];
        let shapes = [
            None,
            Some(Abstraction::Ellipsoid),
            Some(Abstraction::Smoothed { iterations: 2 }),
        ];
        for (detail, abstraction) in details.iter().flat_map(|d| shapes.map(|s| (d, s))) {
            let built = abstraction.map(|a| a.build(&library).unwrap());
            let tone = XToon {
                detail: detail.clone(),
                invert: true,
                shape: abstraction.map(|abstraction| ShapeDetail {
                    abstraction,
                    weight: 0.6,
                    highlight_frame: HighlightFrame::Abstracted,
                }),
            }
            .prepare(Arc::clone(&texture), built.as_ref())
            .unwrap();
            let tone = tone.in_view(Vec3::new(0.0, -6.0, 0.0), Vec3::Y);
            for len in [LANES, 7] {
                let run = PointRun { len, ..run.clone() };
                let (mut abstracted, mut colour) = (Lanes::default(), [Vec3::NAN; LANES]);
                let normals =
                    *tone.shade_run(&run, &view, &light, &mut abstracted, &mut colour[..len]);
                for (k, &colour) in colour[..len].iter().enumerate() {
                    let one = PointRun::one(
                        run.position.get(k),
                        run.normal.get(k),
                        0,
                        Vec2::new(run.u[k], run.v[k]),
                    );
                    let (view, light) = (Lanes::first(view.get(k)), Lanes::first(light.get(k)));
                    let mut alone = [Vec3::NAN];
                    let normal = tone
                        .shade_run(&one, &view, &light, &mut Lanes::default(), &mut alone)
                        .get(0);
                    let case = format!("{detail:?}, {abstraction:?}, point {k} of {len}");
                    assert!(colour.is_finite(), "{case}");
                    assert_eq!(colour, alone[0], "{case}");
                    assert_eq!(normals.get(k), normal, "{case}");
                }
            }
        }
    }
}
