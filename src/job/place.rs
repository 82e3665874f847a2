//! Placing a highlight where the animator points: the surface point under a pixel, and the
//! translation that centres a layer's highlight there.

use glam::Vec2;

use super::centres::{centres, refine, Centre, GRID};
use super::place_error::PlaceError;
use super::{JobError, RenderJob};
use crate::highlight::{HighlightError, Layer, Shape};
use crate::render::{Aovs, RenderedFrame};
use crate::shot::{rounded_number_text, FrameState, Shot};

/// Which highlight layer to place; `None` picks as [`RenderJob::place`] says.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LayerChoice {
    /// The highlight entry (includes first, from 0); it must be the one drawn on the patch.
    pub highlight: Option<usize>,
    /// The layer of its expression, left to right from 0.
    pub layer: Option<usize>,
}

/// A highlight layer's centre placed on the surface point under a pixel.
#[derive(Clone, Debug, PartialEq)]
pub struct Placement {
    /// The frame the camera, light and parameters were read at.
    pub frame: f64,
    /// The image position asked for, in pixels (a pixel's centre at integer values).
    pub pixel: (f64, f64),
    /// The patch under the pixel (index into the shot's library).
    pub patch: usize,
    /// Its parameters where the pixel's ray meets it.
    pub uv: (f64, f64),
    /// The highlight entry drawn on the patch (includes first).
    pub highlight: usize,
    /// The layer placed, left to right from 0.
    pub layer: usize,
    /// The index in the layer's stack of the translation solved for.
    pub op: usize,
    /// The translation `(α, β)` that centres the layer's highlight on the point.
    pub translation: Vec2,
    /// How near the placed layer comes to a highlight centre on each patch it is drawn on.
    pub residuals: Vec<Residual>,
    /// Every centre of the placed layer, on every patch it is drawn on, the deepest first, each
    /// with where it lands in the frame ([`Centre`]): more than one where the highlight shows
    /// twice. A centre where the eye sees the surface's back is listed where the frame shows it.
    pub centres: Vec<Centre>,
}

/// How near a placed layer's highlight comes to having a centre on one patch: one `(α, β)`
/// serves every patch of the layer, each in its own frame, so only the patch under the pixel
/// is sure to hold the centre.
#[derive(Clone, Debug, PartialEq)]
pub struct Residual {
    /// The patch (index into the shot's library).
    pub patch: usize,
    /// The least `‖N − H'‖² / 2` found on the patch: 0 at a centre, below ε inside the
    /// highlight of the disc (for a drawn shape too, where the outline's point (0, 0) lands).
    pub nearest: f32,
    /// Where on the patch it was found.
    pub uv: (f64, f64),
    /// Whether the highlight shows on the patch at all: `nearest < ε` for the disc; for a drawn
    /// shape, whether it covers the point nearest its centre.
    pub covered: bool,
}

/// The highlight layer drawn on the surface point under a pixel ([`RenderJob::layer_under`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LayerUnder {
    /// The patch under the pixel (index into the shot's library).
    pub patch: usize,
    /// Its parameters where the pixel's ray meets it.
    pub uv: (f64, f64),
    /// The highlight entry drawn on the patch (includes first).
    pub highlight: usize,
    /// The layer, left to right from 0.
    pub layer: usize,
}

impl RenderJob {
    /// Places a highlight layer's centre on the surface point under image position `pixel`
    /// (in pixels, pixel `(i, j)`'s centre at `(i, j)`) at `frame`.
    ///
    /// The patch under the pixel is the one the job's renderer draws there (its patch-id AOV);
    /// its `(u, v)` are then refined onto the ray through the pixel by the Newton steps of
    /// refined frames. The layer is `choice.layer`, or the first with a translation; the
    /// translation solved is its placing translation ([`Layer::centring_translation`]: closed
    /// form, under this frame's camera and light, with the operations before it read at this
    /// frame). Errors when the pixel is outside the image or off the model, the patch has no
    /// highlight (or not `choice.highlight`), the layer has no translation or is pinned.
    pub fn place(
        &mut self,
        frame: f64,
        pixel: (f64, f64),
        choice: LayerChoice,
    ) -> Result<Placement, PlaceError> {
        let placement = self.place_centre(frame, pixel, choice)?;
        self.complete(placement)
    }

    /// A placement with its residuals and centres found.
    fn complete(&mut self, mut placement: Placement) -> Result<Placement, PlaceError> {
        let frame = placement.frame;
        let state = self.shot.at(frame);
        let mut placed = state.highlights[placement.highlight].layers()[placement.layer].clone();
        placed.stack[placement.op] = crate::highlight::Op::Translate {
            alpha: placement.translation.x,
            beta: placement.translation.y,
        };
        placement.residuals = residuals(&self.shot, placement.highlight, &placed, &state)?;
        let mut found = centres(
            &self.shot,
            (placement.highlight, &placed),
            &state,
            Some((placement.patch, placement.uv)),
        )
        .map_err(|e| PlaceError::Layer(e.to_string()))?;
        for centre in &mut found {
            centre.pixel = Some(self.pixel_of(frame, centre.patch, centre.uv)?);
        }
        // A centre on the side of a surface the eye sees from behind shows only where the frame
        // shows it: an open sheet's back; on a closed body it lies within, never seen.
        found.retain(|c| !c.back || c.pixel.is_some_and(|p| p.visible));
        placement.centres = found;
        Ok(placement)
    }

    /// Every centre of layer `layer` of highlight entry `highlight` as it is read at `frame`
    /// (a pinned layer centred on its point), on every patch the entry is drawn on, the
    /// deepest first, each with where it lands in the frame; a centre where the eye sees the
    /// surface's back only where the frame shows it (as [`RenderJob::place`] lists them).
    /// Errors when there is no such entry or layer, or the layer does not prepare.
    pub fn centres_at(
        &mut self,
        frame: f64,
        highlight: usize,
        layer: usize,
    ) -> Result<Vec<Centre>, PlaceError> {
        let state = self.shot.at(frame);
        let Some(layers) = state.highlights.get(highlight).map(|e| e.layers()) else {
            return Err(PlaceError::Layer(format!(
                "the shot has {} highlight entries, numbered from 0, so there is no highlight \
                 {highlight}",
                state.highlights.len()
            )));
        };
        let Some(&chosen) = layers.get(layer) else {
            return Err(PlaceError::Layer(format!(
                "highlight {highlight} has {} layer(s), numbered from 0, so there is no layer \
                 {layer}",
                layers.len()
            )));
        };
        let mut found = centres(&self.shot, (highlight, chosen), &state, None)
            .map_err(|e| PlaceError::Layer(e.to_string()))?;
        for centre in &mut found {
            centre.pixel = Some(self.pixel_of(frame, centre.patch, centre.uv)?);
        }
        found.retain(|c| !c.back || c.pixel.is_some_and(|p| p.visible));
        Ok(found)
    }

    /// The highlight layer drawn on the surface point under `pixel` at `frame`
    /// ([`point_under`](Self::point_under)): the entry drawn on its patch (which must be
    /// `choice.highlight` if given), and its layer `choice.layer`, or the first with a
    /// translation. Errors as [`RenderJob::place`] does for the pixel, the entry and the layer.
    pub fn layer_under(
        &mut self,
        frame: f64,
        pixel: (f64, f64),
        choice: LayerChoice,
    ) -> Result<LayerUnder, PlaceError> {
        let (patch, uv) = self.point_under(frame, pixel)?;
        let at = format!("under pixel ({}, {})", pixel.0, pixel.1);
        let (drawn, layer) = self.choose_layer(frame, patch, choice, &at)?;
        Ok(LayerUnder {
            patch,
            uv,
            highlight: drawn,
            layer,
        })
    }

    /// The highlight layer drawn on `(u, v)` of patch `patch` at `frame`: the entry drawn on
    /// the patch (which must be `choice.highlight` if given), and its layer `choice.layer`, or
    /// the first with a translation. Errors as [`RenderJob::layer_under`] does for the entry
    /// and the layer.
    pub fn layer_at(
        &self,
        frame: f64,
        (patch, uv): (usize, (f64, f64)),
        choice: LayerChoice,
    ) -> Result<LayerUnder, PlaceError> {
        let at = format!(
            "at (u, v) = ({}, {})",
            rounded_number_text(uv.0 as f32),
            rounded_number_text(uv.1 as f32)
        );
        let (highlight, layer) = self.choose_layer(frame, patch, choice, &at)?;
        Ok(LayerUnder {
            patch,
            uv,
            highlight,
            layer,
        })
    }

    /// The highlight entry drawn on patch `patch` (which must be `choice.highlight` if given)
    /// and its layer `choice.layer`, or the first with a translation; `at` says where the point
    /// is, for messages.
    fn choose_layer(
        &self,
        frame: f64,
        patch: usize,
        choice: LayerChoice,
        at: &str,
    ) -> Result<(usize, usize), PlaceError> {
        let shot = &self.shot;
        let name = &shot.library.patches[patch].name;
        let Some(drawn) = shot.highlight_of(patch) else {
            return Err(PlaceError::NoHighlight(format!(
                "{name}, {at}, has no designed highlight; add an entry to `highlights` whose \
                 patches select it"
            )));
        };
        if let Some(asked) = choice.highlight.filter(|&h| h != drawn) {
            return Err(PlaceError::NoHighlight(format!(
                "highlight {asked} is not the one drawn on {name}, {at}: highlight {drawn} is"
            )));
        }
        let state = shot.at(frame);
        let layers = state.highlights[drawn].layers();
        let layer = match choice.layer {
            Some(k) if k < layers.len() => k,
            Some(k) => {
                return Err(PlaceError::Layer(format!(
                    "highlight {drawn} has {} layer(s), numbered from 0, so there is no layer {k}",
                    layers.len()
                )))
            }
            None => layers
                .iter()
                .position(|l| l.placing_translation().is_some())
                .unwrap_or(0),
        };
        Ok((drawn, layer))
    }

    /// [`place`](Self::place) on a named surface point rather than the one under a pixel:
    /// `(u, v)` of patch `patch` (clamped to its domain), as the model is posed at `frame`,
    /// seen or not. The placement's pixel is where the point lands in the frame
    /// ([`RenderJob::pixel_of`]), meaningful when it is in front of the camera. Errors as
    /// `place` does for the entry and the layer.
    pub fn place_at(
        &mut self,
        frame: f64,
        (patch, uv): (usize, (f64, f64)),
        choice: LayerChoice,
    ) -> Result<Placement, PlaceError> {
        let domain = self.shot.library.patches[patch].surface.domain();
        let uv = (
            uv.0.clamp(domain.u.0, domain.u.1),
            uv.1.clamp(domain.v.0, domain.v.1),
        );
        let under = self.layer_at(frame, (patch, uv), choice)?;
        let pixel = self.pixel_of(frame, patch, uv)?.pixel;
        let placement = self.centre_on(frame, pixel, under)?;
        self.complete(placement)
    }

    /// [`RenderJob::place`] without the residuals and centres (both empty): the translation
    /// alone, for a highlight that follows a pointer.
    pub fn place_centre(
        &mut self,
        frame: f64,
        pixel: (f64, f64),
        choice: LayerChoice,
    ) -> Result<Placement, PlaceError> {
        let under = self.layer_under(frame, pixel, choice)?;
        self.centre_on(frame, pixel, under)
    }

    /// The placing translation that centres the layer `under` names on its point, the point
    /// being at `pixel` of the frame.
    fn centre_on(
        &self,
        frame: f64,
        pixel: (f64, f64),
        under: LayerUnder,
    ) -> Result<Placement, PlaceError> {
        let LayerUnder {
            patch,
            uv,
            highlight: drawn,
            layer,
        } = under;
        let shot = &self.shot;
        let name = &shot.library.patches[patch].name;
        let state = shot.at(frame);
        let layers = state.highlights[drawn].layers();
        if shot.pinned_patch(drawn, layer).is_some() {
            let pinned = &shot.library.patches[shot.pinned_patch(drawn, layer).unwrap_or(patch)];
            return Err(PlaceError::Layer(format!(
                "highlights[{drawn}].layers[{layer}] is pinned to a point of {}, and its translation is \
                 solved on every frame; to move it, pin it here: pin: (patch: \"{name}\", u: {}, v: {})",
                pinned.name,
                rounded_number_text(uv.0 as f32),
                rounded_number_text(uv.1 as f32)
            )));
        }
        let chosen: &Layer = layers[layer];
        // The surface as it is posed at this frame: a moving instance's patch is not where it
        // rests.
        let point = shot.highlight_point(&state, patch, uv);
        let translation = shot
            .layer_on(chosen, patch, frame)
            .centring_translation_at(&point.frame, point.half_vector)
            .map_err(|e| match e {
                HighlightError::NoTranslation => {
                    PlaceError::Layer(format!("highlights[{drawn}].layers[{layer}]: {e}"))
                }
                other => PlaceError::Layer(format!(
                    "highlights[{drawn}].layers[{layer}] at frame {frame}: {other}"
                )),
            })?;
        let op = chosen
            .placing_translation()
            .expect("a translation was just solved for");
        Ok(Placement {
            frame,
            pixel,
            patch,
            uv,
            highlight: drawn,
            layer,
            op,
            translation,
            residuals: Vec::new(),
            centres: Vec::new(),
        })
    }

    /// The frame `state` drawn without lines, with only the AOVs `aovs`: what looking up the
    /// surface at a pixel reads.
    pub(super) fn lookup_image(
        &mut self,
        state: &FrameState,
        aovs: Aovs,
    ) -> Result<RenderedFrame, PlaceError> {
        let mut scene = state.scene(&self.shot).map_err(JobError::from)?;
        scene.aovs = aovs;
        scene.outlines = None;
        self.renderer
            .render(&scene, &self.settings)
            .map_err(|source| {
                PlaceError::Job(JobError::Render {
                    frame: state.frame,
                    source,
                })
            })
    }

    /// The patch drawn at image position `pixel` (in pixels, pixel `(i, j)`'s centre at
    /// `(i, j)`) at `frame`, and its parameters where the pixel's ray meets it: the patch from
    /// the patch-id AOV of the frame, its `(u, v)` refined onto the ray by the Newton steps of
    /// refined frames. Errors when the pixel is outside the image or shows no patch.
    pub fn point_under(
        &mut self,
        frame: f64,
        pixel: (f64, f64),
    ) -> Result<(usize, (f64, f64)), PlaceError> {
        let (width, height) = (self.settings.width, self.settings.height);
        let position = (pixel.0 + 0.5, pixel.1 + 0.5);
        let inside = |p: f64, side: u32| p >= 0.0 && p < f64::from(side);
        if !(inside(position.0, width) && inside(position.1, height)) {
            return Err(PlaceError::OutsideImage {
                x: pixel.0,
                y: pixel.1,
                width,
                height,
            });
        }
        let state = self.shot.at(frame);
        let aovs = Aovs {
            patch_id: true,
            uv: true,
            ..Aovs::default()
        };
        let image = self.lookup_image(&state, aovs)?;
        let index = position.1 as usize * width as usize + position.0 as usize;
        let ids = image.aovs.patch_id.as_deref().unwrap_or_default();
        let uvs = image.aovs.uv.as_deref().unwrap_or_default();
        let (Some(&patch), Some(&uv)) = (ids.get(index), uvs.get(index)) else {
            return Err(off_model(position, frame));
        };
        let Some(named) = state.library.patches.get(patch as usize) else {
            return Err(off_model(position, frame));
        };
        let surface = &named.surface;
        let start = (f64::from(uv.x), f64::from(uv.y));
        let (origin, direction) = state.camera.ray_through(position, (width, height));
        let uv = surface
            .try_refine_on_ray(start, origin, direction)
            .unwrap_or(start);
        Ok((patch as usize, uv))
    }
}

/// The residual of `layer`, placed, on every patch highlight entry `entry` is drawn on: each
/// patch posed as `state` has it, under its camera and light.
fn residuals(
    shot: &Shot,
    entry: usize,
    layer: &Layer,
    state: &FrameState,
) -> Result<Vec<Residual>, PlaceError> {
    let prepared = layer
        .prepare()
        .map_err(|e| PlaceError::Layer(e.to_string()))?;
    // The centre is where H' = N whatever the shape: a drawn layer's is measured as its disc's,
    // `‖N − H'‖²/2 = ε − s_disc`, and it shows where its own s is positive.
    let disc = Layer {
        shape: Shape::Disc,
        ..layer.clone()
    }
    .prepare()
    .map_err(|e| PlaceError::Layer(e.to_string()))?;
    let mut residuals = Vec::new();
    for (patch, named) in state.library.patches.iter().enumerate() {
        if shot.highlight_of(patch) != Some(entry) {
            continue;
        }
        let domain = named.surface.domain();
        let point = |uv: (f64, f64)| shot.highlight_point(state, patch, uv);
        let distance = |uv: (f64, f64)| {
            let point = point(uv);
            layer.epsilon - disc.signed(&point.frame, point.half_vector)
        };
        let last = (GRID - 1) as f64;
        let mut best = (f32::INFINITY, domain.center());
        for i in 0..GRID {
            for j in 0..GRID {
                let uv = domain.lerp(i as f64 / last, j as f64 / last);
                let nearest = distance(uv);
                if nearest < best.0 {
                    best = (nearest, uv);
                }
            }
        }
        let (uv, nearest) = refine(&distance, domain, (best.1, best.0));
        let best = (nearest, uv);
        residuals.push(Residual {
            patch,
            nearest: best.0.max(0.0),
            uv: best.1,
            covered: if layer.shape.is_disc() {
                best.0 < layer.epsilon
            } else {
                let nearest = point(best.1);
                prepared.signed(&nearest.frame, nearest.half_vector) > 0.0
            },
        });
    }
    Ok(residuals)
}

fn off_model(position: (f64, f64), frame: f64) -> PlaceError {
    PlaceError::OffModel {
        x: position.0 - 0.5,
        y: position.1 - 0.5,
        frame,
    }
}
