//! A loaded shot and its state at a frame.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{DVec3, Vec3};

use super::file::{
    Aov, CameraSpec, HighlightSpec, LightSpec, OutlinesSpec, Preset, ProjectionSpec,
};
use super::ShotError;
use crate::anim::Track;
use crate::geom::PatchLibrary;
use crate::highlight::{Expr, Light};
use crate::render::tessellate::Density;
use crate::render::Tone;
use crate::render::{
    Antialias, Aovs, Camera, FrameMode, Outlines, PatchLook, Projection, Scene, Settings,
};
use crate::toon::{AbstractShape, CelRamp, ToonTexture, XToon};

/// A validated shot: the model with every instance placed, and every track ready to be read at
/// any frame.
#[derive(Debug)]
pub struct Shot {
    /// The shot file.
    pub path: PathBuf,
    /// The first and last frame, inclusive.
    pub frames: (i64, i64),
    pub fps: f64,
    /// The output pattern, resolved against the shot file's folder.
    pub output: PathBuf,
    /// Every patch of every instance, named `INSTANCE/PATCH`.
    pub library: PatchLibrary,
    pub instances: Vec<Instance>,
    /// Image size, accuracy and threads as the shot asks for them.
    pub settings: Settings,
    pub(super) accuracy: Accuracy,
    pub outlines: Option<Outlines>,
    pub aovs: Vec<Aov>,
    pub(super) camera: CameraSpec,
    pub(super) light: LightSpec,
    pub(super) materials: Vec<(String, Material)>,
    pub(super) highlights: Vec<HighlightSpec>,
    /// The material (index into `materials`) of each patch of `library`.
    pub(super) patch_material: Vec<usize>,
    /// The highlight entry (index into `highlights`) of each patch, if any.
    pub(super) patch_highlight: Vec<Option<usize>>,
}

/// The accuracy a shot asks for: a preset and the settings it overrides.
#[derive(Clone, Copy, Debug)]
pub(super) struct Accuracy {
    pub preset: Preset,
    pub tessellation: Option<Density>,
    pub frames: Option<FrameMode>,
    pub antialias: Option<Antialias>,
}

impl Accuracy {
    /// The settings of `preset` (default: the shot's own) at `width × height`, with the
    /// shot's explicit tessellation, frame mode and anti-aliasing over it.
    pub fn settings(&self, preset: Option<Preset>, (width, height): (u32, u32)) -> Settings {
        let mut settings = match preset.unwrap_or(self.preset) {
            Preset::Preview => Settings::preview(width, height),
            Preset::Final => Settings::final_quality(width, height),
        };
        if let Some(density) = self.tessellation {
            settings.density = density;
        }
        if let Some(frames) = self.frames {
            settings.frames = frames;
        }
        if let Some(antialias) = self.antialias {
            settings.antialias = antialias;
        }
        settings
    }
}

/// A material ready to be read at any frame.
#[derive(Debug)]
pub(super) enum Material {
    Cel {
        base: Track<Vec3>,
        bands: Vec<(Track<f32>, Track<Vec3>)>,
    },
    XToon {
        tone: XToon<Track<f32>>,
        texture: Arc<ToonTexture>,
        /// The model's abstracted shape, when the tone has shape detail.
        shape: Option<Arc<AbstractShape>>,
    },
}

/// A material's parameters at one frame.
#[derive(Clone, Debug, PartialEq)]
pub enum MaterialState {
    Cel(CelRamp),
    XToon(XToon),
}

/// One placed patch file.
#[derive(Clone, Debug, PartialEq)]
pub struct Instance {
    pub name: String,
    /// Its patches in the shot's library.
    pub patches: std::ops::Range<usize>,
}

/// Every track of a shot read at one frame.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameState {
    pub frame: f64,
    pub camera: Camera,
    pub light: Light,
    /// Each material, in the order of [`Shot::material_names`].
    pub materials: Vec<MaterialState>,
    /// Each highlight entry's expression, in the order they are written (includes first).
    pub highlights: Vec<Expr>,
}

impl Shot {
    /// Every track read at `frame` (fractional frames allowed). Pure: the same frame always
    /// gives the same state, and nothing is read from or written to disk.
    #[must_use]
    pub fn at(&self, frame: f64) -> FrameState {
        let camera = &self.camera;
        let projection = match &camera.projection {
            ProjectionSpec::Perspective { fov_y_degrees } => Projection::Perspective {
                fov_y_degrees: fov_y_degrees.at(frame),
            },
            ProjectionSpec::Orthographic { height } => Projection::Orthographic {
                height: height.at(frame),
            },
        };
        FrameState {
            frame,
            camera: Camera {
                eye: camera.eye.at(frame),
                target: camera.target.at(frame),
                up: camera.up.at(frame),
                projection,
                near: camera.near,
                far: camera.far,
            },
            light: match &self.light {
                LightSpec::Directional { towards } => Light::Directional {
                    towards: towards.at(frame).0,
                },
                LightSpec::Point { position } => Light::Point {
                    position: position.at(frame),
                },
            },
            materials: self
                .materials
                .iter()
                .map(|(_, m)| match m {
                    Material::Cel { base, bands } => MaterialState::Cel(CelRamp {
                        base: base.at(frame),
                        bands: bands
                            .iter()
                            .map(|(threshold, colour)| (threshold.at(frame), colour.at(frame)))
                            .collect(),
                    }),
                    Material::XToon { tone, .. } => MaterialState::XToon(tone.map(|t| t.at(frame))),
                })
                .collect(),
            highlights: self
                .highlights
                .iter()
                .map(|h| h.expr.map(|t| t.at(frame)))
                .collect(),
        }
    }

    /// The names of the materials, in the order of [`FrameState::materials`].
    pub fn material_names(&self) -> impl Iterator<Item = &str> {
        self.materials.iter().map(|(name, _)| name.as_str())
    }

    /// The selector of each highlight entry as written, in the order of
    /// [`FrameState::highlights`].
    pub fn highlight_selectors(&self) -> impl Iterator<Item = &[String]> {
        self.highlights.iter().map(|h| h.patches.patterns())
    }

    /// The material index of patch `patch`.
    pub fn material_of(&self, patch: usize) -> usize {
        self.patch_material[patch]
    }

    /// The highlight entry of patch `patch`, if it has one.
    pub fn highlight_of(&self, patch: usize) -> Option<usize> {
        self.patch_highlight[patch]
    }

    /// The file frame `frame` is written to: the output pattern with its run of `#` replaced
    /// by the frame number, zero-padded to the run's length.
    pub fn frame_path(&self, frame: i64) -> PathBuf {
        frame_path(&self.output, frame)
    }

    /// The settings for another preset or image size than the shot's own (what `glint render
    /// --preset --size` ask for): the shot's explicit accuracy settings still apply.
    pub fn settings_with(&self, preset: Option<Preset>, size: Option<(u32, u32)>) -> Settings {
        let size = size.unwrap_or((self.settings.width, self.settings.height));
        self.accuracy.settings(preset, size)
    }

    /// The renderer's AOV switches for this shot's AOV list.
    pub fn aov_switches(&self) -> Aovs {
        let on = |a: Aov| self.aovs.contains(&a);
        Aovs {
            matte: on(Aov::Matte),
            patch_id: on(Aov::PatchId),
            depth: on(Aov::Depth),
            normal: on(Aov::Normal),
            uv: on(Aov::Uv),
            n_dot_h: on(Aov::NDotH),
        }
    }
}

impl FrameState {
    /// The scene the renderer draws for this state of `shot`.
    pub fn scene<'a>(&self, shot: &'a Shot) -> Result<Scene<'a>, ShotError> {
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
        let looks = (0..shot.library.patches.len())
            .map(|patch| PatchLook {
                tone: tones[shot.material_of(patch)].clone(),
                highlight: shot.highlight_of(patch).map(|h| prepared[h].clone()),
            })
            .collect();
        Ok(Scene {
            library: &shot.library,
            looks,
            camera: self.camera,
            light: self.light,
            outlines: shot.outlines,
            aovs: shot.aov_switches(),
        })
    }
}

/// `pattern` with its last run of `#` replaced by `frame`, zero-padded to the run's length
/// (a pattern without `#` is returned as it is).
pub(super) fn frame_path(pattern: &Path, frame: i64) -> PathBuf {
    let text = pattern.to_string_lossy();
    let Some(end) = text.rfind('#').map(|i| i + 1) else {
        return pattern.to_path_buf();
    };
    let start = text[..end].trim_end_matches('#').len();
    let width = end - start;
    let number = if frame < 0 {
        format!(
            "-{:0width$}",
            frame.unsigned_abs(),
            width = width.saturating_sub(1)
        )
    } else {
        format!("{frame:0width$}")
    };
    PathBuf::from(format!("{}{number}{}", &text[..start], &text[end..]))
}

/// `base` joined with `path` (kept as it is when absolute), with `name/..` pairs removed, so
/// that messages show `out/a.png` rather than `shots/../out/a.png`.
pub fn resolve_path(base: &Path, path: &Path) -> PathBuf {
    let mut clean = PathBuf::new();
    for part in base.join(path).components() {
        match part {
            std::path::Component::CurDir => {}
            std::path::Component::ParentDir
                if matches!(
                    clean.components().next_back(),
                    Some(std::path::Component::Normal(_))
                ) =>
            {
                clean.pop();
            }
            other => clean.push(other),
        }
    }
    clean
}

impl From<&OutlinesSpec> for Outlines {
    fn from(spec: &OutlinesSpec) -> Self {
        Outlines {
            width: spec.width,
            colour: Vec3::from(spec.colour),
            crease_degrees: spec.crease_degrees,
            patch_borders: spec.patch_borders,
        }
    }
}

/// `p ↦ translate + R(axis, degrees) (scale · p)` as a point map.
pub(super) fn placement(
    translate: DVec3,
    axis: DVec3,
    degrees: f64,
    scale: f64,
) -> impl Fn(DVec3) -> DVec3 {
    let rotation = glam::DQuat::from_axis_angle(axis.normalize(), degrees.to_radians());
    move |p| translate + rotation * (scale * p)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frame_numbers_fill_the_last_run_of_hashes() {
        let p = |s: &str, f| frame_path(Path::new(s), f).display().to_string();
        assert_eq!(p("out/shot.####.png", 7), "out/shot.0007.png");
        assert_eq!(p("out/shot.##.png", 123), "out/shot.123.png");
        assert_eq!(p("out#/s.#.png", 5), "out#/s.5.png");
        assert_eq!(p("out/s.####.png", -3), "out/s.-003.png");
        assert_eq!(p("out/still.png", 3), "out/still.png");
    }

    #[test]
    fn resolved_paths_lose_their_detours() {
        let r = |a: &str, b: &str| resolve_path(Path::new(a), Path::new(b));
        assert_eq!(r("shots", "../out/a.png"), Path::new("out/a.png"));
        assert_eq!(r("shots/x", "./../../out"), Path::new("out"));
        assert_eq!(r("", "../out"), Path::new("../out"));
        assert_eq!(r("shots", "/abs/out"), Path::new("/abs/out"));
    }
}
