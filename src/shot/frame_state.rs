//! A shot's state at one frame: every track read there, and the scene the renderer draws.

use std::sync::Arc;

use glam::DVec3;

use super::file::{LightSpec, ProjectionSpec};
use super::layer_axes::has_axes;
use super::line_styles::LineFields;
use super::orbit::OrbitSpec;
use super::validated::{Material, MaterialState, Shot};
use super::ShotError;
use crate::geom::PatchLibrary;
use crate::highlight::{DesignedLight, Expr, Light, PreparedExpr, ShadeStack};
use crate::render::{Camera, LineStyle, Outlines, PatchLook, Projection, Scene, Tone};
use crate::toon::CelRamp;

/// Every track of a shot read at one frame.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameState {
    pub frame: f64,
    /// The model at this frame ([`Shot::library_at`]): the shot's own library when nothing
    /// moves.
    pub library: Arc<PatchLibrary>,
    pub camera: Camera,
    pub light: Light,
    /// Each material, in the order of [`Shot::material_names`].
    pub materials: Vec<MaterialState>,
    /// Each highlight entry's expression, in the order they are written (includes first), the
    /// axes of `Along` layer frames in the model's coordinates ([`Shot::expr_on`] turns them
    /// into a patch's), with every pinned layer centred on its point ([`Layer::centred_at`]) and its pin
    /// cleared.
    ///
    /// [`Layer::centred_at`]: crate::highlight::Layer::centred_at
    pub highlights: Vec<Expr>,
    /// Each shade entry's stack and mask, in the order they are written (includes first).
    pub shade: Vec<ShadeStack>,
    /// The outlines, and the style of a patch no `lines` entry restyles; None without lines.
    pub outlines: Option<(Outlines, LineStyle)>,
    /// What each `lines` entry sets, in the order written.
    pub lines: Vec<LineFields>,
}

/// The frames the pins of one frame hold their shapes from ([`Pin::hold`]), each posed once.
///
/// [`Pin::hold`]: crate::highlight::Pin::hold
#[derive(Default)]
pub(super) struct HeldFrames(Vec<FrameState>);

impl Shot {
    /// Every track read at `frame` (fractional frames allowed). Pure: the same frame always
    /// gives the same state, and nothing is read from or written to disk.
    #[must_use]
    pub fn at(&self, frame: f64) -> FrameState {
        let mut state = self.posed_at(frame);
        // The frames pins hold their shapes from, posed once each.
        let mut held = HeldFrames::default();
        state.highlights = self
            .highlights
            .iter()
            .enumerate()
            .map(|(entry, h)| {
                let mut expr = h.expr.map(|t| t.at(frame));
                self.centre_pins(entry, &mut expr, &state, &mut held);
                expr
            })
            .collect();
        state
    }

    /// Every track but the highlights' read at `frame`: the model posed, the camera, light,
    /// materials, shade and lines; no highlight entry.
    fn posed_at(&self, frame: f64) -> FrameState {
        FrameState {
            frame,
            library: self.library_at(frame),
            camera: self.camera_at(frame),
            light: self.light_at(frame),
            materials: self.materials.iter().map(|(_, m)| m.at(frame)).collect(),
            highlights: Vec::new(),
            shade: self.shade.iter().map(|s| s.at(frame)).collect(),
            outlines: self.outlines.as_ref().map(|o| o.at(frame)),
            lines: self.lines.iter().map(|l| l.at(frame)).collect(),
        }
    }

    /// The state at `frame` without its highlights, as a pin that holds its shape from that
    /// frame reads it: posed once per frame asked for.
    pub(super) fn held_frame<'a>(&self, held: &'a mut HeldFrames, frame: i64) -> &'a FrameState {
        let index = match held.0.iter().position(|s| s.frame == frame as f64) {
            Some(index) => index,
            None => {
                held.0.push(self.posed_at(frame as f64));
                held.0.len() - 1
            }
        };
        &held.0[index]
    }

    /// The camera's tracks read at `frame`.
    #[must_use]
    pub fn camera_at(&self, frame: f64) -> Camera {
        let camera = &self.camera;
        let projection = match &camera.projection {
            ProjectionSpec::Perspective { fov_y_degrees } => Projection::Perspective {
                fov_y_degrees: fov_y_degrees.at(frame),
            },
            ProjectionSpec::Orthographic { height } => Projection::Orthographic {
                height: height.at(frame),
            },
        };
        Camera {
            eye: self.eye_at(frame).as_vec3(),
            target: camera.target.at(frame),
            up: camera.up.at(frame),
            projection,
            near: camera.near,
            far: camera.far,
        }
    }

    /// The camera's orbit, when its eye orbits the target rather than following an `eye` track.
    #[must_use]
    pub fn orbit(&self) -> Option<&OrbitSpec> {
        self.camera.orbit.as_ref()
    }

    /// The camera's eye at `frame`, in f64: its `eye` track, or where its orbit puts it about
    /// the target ([`OrbitSpec::eye_at`]). A camera with neither, which the shot reader
    /// refuses, looks along +y from one unit before its target.
    #[must_use]
    pub fn eye_at(&self, frame: f64) -> DVec3 {
        let camera = &self.camera;
        let target = camera.target.at(frame).as_dvec3();
        match (&camera.orbit, &camera.eye) {
            (Some(orbit), _) => orbit.eye_at(target, frame),
            (None, Some(eye)) => eye.at(frame).as_dvec3(),
            (None, None) => target - DVec3::Y,
        }
    }

    /// The light's track read at `frame`.
    #[must_use]
    pub fn light_at(&self, frame: f64) -> Light {
        match &self.light {
            LightSpec::Directional { towards } => Light::Directional {
                towards: towards.at(frame).0,
            },
            LightSpec::Point { position } => Light::Point {
                position: position.at(frame),
            },
        }
    }
}

impl Material {
    /// Every track of the material read at `frame`.
    #[must_use]
    pub fn at(&self, frame: f64) -> MaterialState {
        match self {
            Material::Cel { base, bands } => MaterialState::Cel(CelRamp {
                base: base.at(frame),
                bands: bands
                    .iter()
                    .map(|(threshold, colour)| (threshold.at(frame), colour.at(frame)))
                    .collect(),
            }),
            Material::XToon { tone, .. } => MaterialState::XToon(tone.map(|t| t.at(frame))),
        }
    }
}

impl FrameState {
    /// The scene the renderer draws for this state of `shot`.
    pub fn scene<'a>(&'a self, shot: &'a Shot) -> Result<Scene<'a>, ShotError> {
        let invalid = |message: String| ShotError::File {
            path: shot.path.display().to_string(),
            message: format!("at frame {}: {message}", self.frame),
        };
        let prepared = self
            .highlights
            .iter()
            .map(Expr::prepare)
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| invalid(e.to_string()))?;
        let tones = self
            .materials
            .iter()
            .zip(&shot.materials)
            .map(|(state, (name, material))| match (state, material) {
                (MaterialState::Cel(ramp), _) => Ok(Tone::Cel(ramp.clone())),
                (MaterialState::XToon(tone), Material::XToon { texture, shape, .. }) => tone
                    .prepare(Arc::clone(texture), shape.as_ref())
                    .map(Tone::XToon)
                    .map_err(|e| invalid(format!("material \"{name}\": {e}"))),
                (MaterialState::XToon(_), Material::Cel { .. }) => Err(invalid(format!(
                    "material \"{name}\" is not the shot's material of that name"
                ))),
            })
            .collect::<Result<Vec<_>, _>>()?;
        // A layer's `Along` axis is written in its model's coordinates: on a turned patch it is
        // drawn turned, prepared once per entry and rotation.
        let mut turned: Vec<(usize, [u64; 4], PreparedExpr)> = Vec::new();
        let mut highlight_of = |patch: usize| -> Result<Option<PreparedExpr>, ShotError> {
            let Some(h) = shot.highlight_of(patch) else {
                return Ok(None);
            };
            if !has_axes(&self.highlights[h]) {
                return Ok(Some(prepared[h].clone()));
            }
            let rotation = shot.rotation_at(patch, self.frame);
            let key = rotation.to_array().map(f64::to_bits);
            if let Some((_, _, p)) = turned.iter().find(|(e, k, _)| *e == h && *k == key) {
                return Ok(Some(p.clone()));
            }
            let p = shot
                .expr_on(&self.highlights[h], patch, self.frame)
                .prepare()
                .map_err(|e| invalid(e.to_string()))?;
            turned.push((h, key, p.clone()));
            Ok(Some(p))
        };
        let highlights = (0..shot.library.patches.len())
            .map(&mut highlight_of)
            .collect::<Result<Vec<_>, _>>()?;
        let shade = self
            .shade
            .iter()
            .map(ShadeStack::prepare)
            .collect::<Result<Vec<_>, _>>()
            .map_err(|e| invalid(format!("shade: {e}")))?;
        let looks = (0..shot.library.patches.len())
            .zip(highlights)
            .map(|(patch, highlight)| PatchLook {
                tone: tones[shot.material_of(patch)].clone(),
                designed_light: match shot.shade_of(patch) {
                    [] => None,
                    entries => Some(
                        DesignedLight::new(
                            entries.iter().map(|&e| shade[e as usize].clone()).collect(),
                        )
                        .read_by_highlight(
                            shot.highlight_of(patch)
                                .map(|h| shot.highlight_light(h))
                                .unwrap_or_default(),
                        ),
                    ),
                },
                highlight,
                lines: self.outlines.map(|(_, style)| {
                    shot.patch_lines[patch].iter().fold(style, |style, &entry| {
                        self.lines[entry as usize].over(style)
                    })
                }),
            })
            .collect::<Vec<PatchLook>>();
        // Material borders alone read the patches' materials.
        let material_borders = looks.iter().any(|look| {
            look.lines
                .is_some_and(|style| style.draws(crate::render::LineKind::MaterialBorder))
        });
        let materials = if material_borders {
            (0..shot.library.patches.len())
                .map(|patch| shot.material_of(patch) as u32)
                .collect()
        } else {
            Vec::new()
        };
        Ok(Scene {
            library: &self.library,
            looks,
            camera: self.camera,
            light: self.light,
            outlines: self.outlines.map(|(outlines, _)| outlines),
            aovs: shot.aov_switches(),
            materials,
        })
    }
}
