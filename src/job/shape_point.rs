//! The point of a layer's drawn outline under a pixel: the tangent coordinates t′ of the
//! layer's transformed highlight vector at the surface point the pixel shows.

use glam::Vec2;
use thiserror::Error;

use super::place::{LayerChoice, LayerUnder};
use super::place_error::PlaceError;
use super::RenderJob;
use crate::highlight::{Shape, OUTLINE_BOUND};

/// Where a pixel lies in a layer's outline coordinates ([`RenderJob::shape_point`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShapePoint {
    /// The image position asked for, in pixels (a pixel's centre at integer values).
    pub pixel: (f64, f64),
    /// The patch under the pixel (index into the shot's library).
    pub patch: usize,
    /// Its parameters where the pixel's ray meets it.
    pub uv: (f64, f64),
    /// The highlight entry drawn on the patch (includes first).
    pub highlight: usize,
    /// The layer, left to right from 0.
    pub layer: usize,
    /// `t′ = ((H′, du), (H′, dv))`: the coordinates an outline is drawn in
    /// (docs/highlights.md, "Drawn outlines"), with `|t′| ≤ OUTLINE_BOUND`.
    pub t: Vec2,
}

/// Why a pixel has no point in a layer's outline coordinates.
#[derive(Debug, Error)]
pub enum ShapePointError {
    /// The pixel shows no surface, or not one the layer is drawn on, or the layer does not
    /// exist ([`RenderJob::layer_under`]).
    #[error(transparent)]
    Place(#[from] PlaceError),
    /// The pixel shows another patch than the outline's first point, and the layer's operations
    /// act in each patch's own frame, so t′ on the two patches are not in the same axes.
    #[error(
        "pixel ({x}, {y}) shows {found}, but the outline's first point is on {first}; the \
         layer acts in each patch's own (du, dv), so an outline is drawn on one patch (or give \
         the layer an Along frame)"
    )]
    OtherPatch {
        x: f64,
        y: f64,
        found: String,
        first: String,
    },
    /// The transformed highlight vector points below the surface there: `(H′, N) ≤ 0`, where
    /// t′ no longer tells H′ apart.
    #[error(
        "pixel ({x}, {y}) is where highlights[{highlight}].layers[{layer}] turns H' below the \
         surface ((H', N) = {normal:.4} ≤ 0): no outline can reach it; draw nearer the \
         highlight's centre"
    )]
    BelowSurface {
        x: f64,
        y: f64,
        highlight: usize,
        layer: usize,
        normal: f32,
    },
    /// t′ lies outside the disc `|t′| ≤ OUTLINE_BOUND` an outline must keep to.
    #[error(
        "pixel ({x}, {y}) is at t' = ({:.4}, {:.4}) of highlights[{highlight}].layers[{layer}], \
         {:.4} from its centre, outside the allowed |t'| ≤ {OUTLINE_BOUND}; draw nearer the \
         highlight's centre",
        t.x,
        t.y,
        t.length()
    )]
    OutOfBound {
        x: f64,
        y: f64,
        highlight: usize,
        layer: usize,
        t: Vec2,
    },
}

impl ShapePointError {
    /// Whether the input is at fault (exit code 2), not the work.
    #[must_use]
    pub fn is_bad_input(&self) -> bool {
        match self {
            ShapePointError::Place(e) => e.is_bad_input(),
            ShapePointError::OtherPatch { .. }
            | ShapePointError::BelowSurface { .. }
            | ShapePointError::OutOfBound { .. } => true,
        }
    }
}

impl RenderJob {
    /// The point t′ of a highlight layer's outline coordinates under image position `pixel`
    /// (in pixels, pixel `(i, j)`'s centre at `(i, j)`) at `frame`.
    ///
    /// The surface point is the one [`RenderJob::layer_under`] finds (the patch the frame draws
    /// there, its (u, v) refined onto the pixel's ray), the layer `choice` names on the entry
    /// drawn there. At that point, under this frame's camera and light, H is Blinn's half
    /// vector, H′ the layer's stack applied to it in the layer's frame as the renderer applies
    /// it (read at this frame, a pinned layer centred on its pin, an `Along` axis turned with
    /// the patch), and
    ///
    /// ```text
    /// t′ = ((H′, du), (H′, dv))     with (H′, N) > 0 and |t′| ≤ OUTLINE_BOUND
    /// ```
    ///
    /// in the layer's frame `(du, dv, N)`. Errors when the pixel is outside the image, shows no
    /// surface, or a patch without that highlight; when `(H′, N) ≤ 0`; when `|t′|` is beyond
    /// [`OUTLINE_BOUND`].
    pub fn shape_point(
        &mut self,
        frame: f64,
        pixel: (f64, f64),
        choice: LayerChoice,
    ) -> Result<ShapePoint, ShapePointError> {
        let LayerUnder {
            patch,
            uv,
            highlight,
            layer,
        } = self.layer_under(frame, pixel, choice)?;
        let state = self.shot.at(frame);
        let chosen = state.highlights[highlight].layers()[layer];
        let mut drawn = self.shot.layer_on(chosen, patch, frame);
        // t′ is what the shape is tested on, not made by it: a shape being redrawn need not be
        // valid.
        drawn.shape = Shape::Disc;
        let prepared = drawn.prepare().map_err(|e| {
            PlaceError::Layer(format!(
                "highlights[{highlight}].layers[{layer}] at frame {frame}: {e}"
            ))
        })?;
        let point = self.shot.highlight_point(&state, patch, uv);
        let own = prepared.frame_at(&point.frame);
        let local = own.to_local(prepared.highlight_vector(&point.frame, point.half_vector));
        let (x, y) = pixel;
        if local.z <= 0.0 {
            return Err(ShapePointError::BelowSurface {
                x,
                y,
                highlight,
                layer,
                normal: local.z,
            });
        }
        let t = Vec2::new(local.x, local.y);
        if t.length() > OUTLINE_BOUND {
            return Err(ShapePointError::OutOfBound {
                x,
                y,
                highlight,
                layer,
                t,
            });
        }
        Ok(ShapePoint {
            pixel,
            patch,
            uv,
            highlight,
            layer,
            t,
        })
    }

    /// [`shape_point`](Self::shape_point) for each of `pixels` in turn, all of the same layer
    /// (the one the first pixel finds, when `choice` leaves it open): the points of an outline
    /// drawn on the frame. A layer acting in each patch's own frame must have every point on
    /// the first point's patch ([`ShapePointError::OtherPatch`]); the first error stops them.
    pub fn shape_points(
        &mut self,
        frame: f64,
        pixels: &[(f64, f64)],
        choice: LayerChoice,
    ) -> Result<Vec<ShapePoint>, ShapePointError> {
        let mut points: Vec<ShapePoint> = Vec::with_capacity(pixels.len());
        let mut choice = choice;
        for &pixel in pixels {
            let point = self.shape_point(frame, pixel, choice)?;
            if let Some(first) = points.first() {
                let along = !self.shot.highlight_layers(first.highlight)[first.layer]
                    .frame
                    .is_patch();
                if point.patch != first.patch && !along {
                    let name = |p: usize| self.shot.library.patches[p].name.clone();
                    return Err(ShapePointError::OtherPatch {
                        x: pixel.0,
                        y: pixel.1,
                        found: name(point.patch),
                        first: name(first.patch),
                    });
                }
            } else {
                choice = LayerChoice {
                    highlight: Some(point.highlight),
                    layer: Some(point.layer),
                };
            }
            points.push(point);
        }
        Ok(points)
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use glam::DVec3;

    use super::*;
    use crate::job::Overrides;
    use crate::shot::load_shot_text;

    const SIDE: u32 = 64;

    /// shots/sphere_ops.ron rendered `SIDE`² at `preview`, its translation keyed to `alpha`
    /// at frame 12: there its stack is `Translate(alpha, 0.0)` and operations that leave H
    /// alone.
    fn sphere_job(alpha: f64) -> RenderJob {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("shots/sphere_ops.ron");
        let text = std::fs::read_to_string(&path).unwrap();
        let keyed = text.replace("(12, 0.35)", &format!("(12, {alpha})"));
        assert!(text.contains("(12, 0.35)"), "the shot keys α at frame 12");
        let overrides = Overrides {
            size: Some((SIDE, SIDE)),
            preset: Some(crate::shot::Preset::Preview),
            ..Overrides::default()
        };
        RenderJob::new(load_shot_text(&path, keyed).unwrap(), &overrides).unwrap()
    }

    /// t′ at the unit sphere's point seen at pixel `(i, j)` from the shot's camera (eye
    /// (0, −6, 0) looking at the origin along +y, +z up, orthographic of height 2.4) under its
    /// light toward (0.35, −1, 0.45), with the stack `Translate(α, 0)`, computed in closed form:
    /// the point p on the ray, N = p, du east `(−p_y, p_x, 0)/|…|`, dv = N × du (north),
    /// H = (L + V)/|L + V|, H′ = (H_u + α, H_v, H_n)/|…| in (du, dv, N). `None` off the sphere;
    /// otherwise `(t′_u, t′_v, (H′, N))`.
    fn closed_form(i: f64, j: f64, alpha: f64) -> Option<DVec3> {
        let side = f64::from(SIDE);
        let x = (2.0 * (i + 0.5) / side - 1.0) * 1.2;
        let z = (1.0 - 2.0 * (j + 0.5) / side) * 1.2;
        let depth = 1.0 - x * x - z * z;
        if depth <= 0.0 {
            return None;
        }
        let p = DVec3::new(x, -depth.sqrt(), z);
        let du = DVec3::new(-p.y, p.x, 0.0).try_normalize()?;
        let dv = p.cross(du);
        let light = DVec3::new(0.35, -1.0, 0.45).normalize();
        let view = DVec3::new(0.0, -1.0, 0.0);
        let h = (light + view).normalize();
        let moved = DVec3::new(h.dot(du) + alpha, h.dot(dv), h.dot(p));
        Some(moved / moved.length())
    }

    #[test]
    fn t_prime_under_a_pixel_is_the_sphere_s_closed_form() {
        let (mut checked, mut below, mut beyond) = (0, 0, 0);
        for alpha in [0.35, 0.9] {
            let (c, b, o) = compared(alpha);
            checked += c;
            below += b;
            beyond += o;
        }
        assert!(
            checked > 150 && below > 0 && beyond > 0,
            "{checked} checked, {below} below the surface, {beyond} out of bound"
        );
    }

    /// [`RenderJob::shape_point`] at every third pixel of the sphere with the translation
    /// `alpha`, against [`closed_form`]: how many points matched, and how many were refused
    /// below the surface and out of bound.
    fn compared(alpha: f64) -> (usize, usize, usize) {
        let mut job = sphere_job(alpha);
        let choice = LayerChoice::default();
        let (mut checked, mut below, mut beyond) = (0, 0, 0);
        for j in (2..SIDE - 2).step_by(3) {
            for i in (2..SIDE - 2).step_by(3) {
                let (fi, fj) = (f64::from(i), f64::from(j));
                let Some(want) = closed_form(fi, fj, alpha) else {
                    continue;
                };
                // Pixels whose centre is this close to the silhouette may show the background.
                let x = (2.0 * (fi + 0.5) / f64::from(SIDE) - 1.0) * 1.2;
                let z = (1.0 - 2.0 * (fj + 0.5) / f64::from(SIDE)) * 1.2;
                if x * x + z * z > 0.95 {
                    continue;
                }
                let got = job.shape_point(12.0, (fi, fj), choice);
                let tangent = want.truncate().length();
                if want.z > 1e-3 && tangent < f64::from(OUTLINE_BOUND) - 1e-3 {
                    let point = got.unwrap_or_else(|e| panic!("({i}, {j}): {e}"));
                    let miss = (point.t.as_dvec2() - want.truncate()).length();
                    assert!(miss < 2e-4, "({i}, {j}): t' {} for {want}", point.t);
                    assert_eq!((point.highlight, point.layer, point.patch), (0, 0, 0));
                    checked += 1;
                } else if want.z < -1e-3 {
                    let e = got.unwrap_err();
                    assert!(
                        matches!(e, ShapePointError::BelowSurface { .. }),
                        "({i}, {j}): {e}"
                    );
                    below += 1;
                } else if want.z > 1e-3 && tangent > f64::from(OUTLINE_BOUND) + 1e-3 {
                    let e = got.unwrap_err();
                    assert!(
                        matches!(e, ShapePointError::OutOfBound { .. }),
                        "({i}, {j}): {e}"
                    );
                    beyond += 1;
                }
            }
        }
        (checked, below, beyond)
    }

    #[test]
    fn pixels_off_the_sphere_and_outside_the_image_are_refused() {
        let mut job = sphere_job(0.35);
        let choice = LayerChoice::default();
        let corner = job.shape_point(12.0, (1.0, 1.0), choice).unwrap_err();
        assert!(
            matches!(corner, ShapePointError::Place(PlaceError::OffModel { .. })),
            "{corner}"
        );
        assert!(corner.is_bad_input());
        let outside = job.shape_point(12.0, (-3.0, 10.0), choice).unwrap_err();
        assert!(
            matches!(
                outside,
                ShapePointError::Place(PlaceError::OutsideImage { .. })
            ),
            "{outside}"
        );
        let no_layer = LayerChoice {
            highlight: None,
            layer: Some(3),
        };
        let e = job.shape_point(12.0, (32.0, 32.0), no_layer).unwrap_err();
        assert!(e.to_string().contains("no layer 3"), "{e}");
        let centre = (f64::from(SIDE) / 2.0, f64::from(SIDE) / 2.0);
        let points = job
            .shape_points(12.0, &[centre, (30.0, 34.0), (1.0, 1.0)], choice)
            .unwrap_err();
        assert!(matches!(points, ShapePointError::Place(_)), "{points}");
    }
}
