//! A loaded and validated shot: the model with every instance placed, and every track ready to
//! be read at any frame.

use std::path::PathBuf;
use std::sync::Arc;

use glam::Vec3;

use super::file::{
    Aov, CameraSpec, HighlightSpec, LightSpec, LineSpec, OutlinesSpec, Preset, ShadeSpec,
};
use super::output::frame_path;
use crate::anim::Track;
use crate::geom::PatchLibrary;
use crate::render::tessellate::Density;
use crate::render::{Antialias, Aovs, FrameMode, Settings};
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
    pub library: Arc<PatchLibrary>,
    /// Every file the shot was made from: the shot file, its includes, patch files and toon
    /// textures, each once, in the order they were read.
    pub inputs: Vec<PathBuf>,
    /// How many of `inputs`, from the first, are the shot file and its includes.
    pub(super) shot_files: usize,
    pub instances: Vec<Instance>,
    /// Image size, accuracy and threads as the shot asks for them.
    pub settings: Settings,
    pub(super) accuracy: Accuracy,
    /// Lines on, and the style of the patches no `lines` entry restyles.
    pub(super) outlines: Option<OutlinesSpec>,
    /// The `lines` entries, in the order written.
    pub(super) lines: Vec<LineSpec>,
    /// Per patch of `library`, the `lines` entries that pick it, in order.
    pub(super) patch_lines: Vec<Vec<u32>>,
    pub aovs: Vec<Aov>,
    pub(super) camera: CameraSpec,
    pub(super) light: LightSpec,
    pub(super) materials: Vec<(String, Material)>,
    pub(super) highlights: Vec<HighlightSpec>,
    /// The material (index into `materials`) of each patch of `library`.
    pub(super) patch_material: Vec<usize>,
    /// The highlight entry (index into `highlights`) of each patch, if any.
    pub(super) patch_highlight: Vec<Option<usize>>,
    /// Per highlight entry, per layer left to right: the patch its pin names, if pinned.
    pub(super) pins: Vec<Vec<Option<usize>>>,
    /// How each instance is placed at any frame, in the order of `instances`.
    pub(super) poses: Vec<super::pose::InstancePose>,
    /// Per highlight entry: the file it is written in and its index in that file's
    /// `highlights` list.
    pub(super) highlights_written: Vec<(PathBuf, usize)>,
    /// The shade entries, includes first, in the order written.
    pub(super) shade: Vec<ShadeSpec>,
    /// Per patch of `library`, the shade entries that pick it, in order.
    pub(super) patch_shade: Vec<Vec<u32>>,
    /// Per shade entry: the file it is written in and its index in that file's `shade` list.
    pub(super) shade_written: Vec<(PathBuf, usize)>,
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

impl Shot {
    /// The names of the materials, in the order of `FrameState::materials`.
    pub fn material_names(&self) -> impl Iterator<Item = &str> {
        self.materials.iter().map(|(name, _)| name.as_str())
    }

    /// The selector of each highlight entry as written, in the order of
    /// `FrameState::highlights`.
    pub fn highlight_selectors(&self) -> impl Iterator<Item = &[String]> {
        self.highlights.iter().map(|h| h.patches.patterns())
    }

    /// The material index of patch `patch`.
    pub fn material_of(&self, patch: usize) -> usize {
        self.patch_material[patch]
    }

    /// Where highlight entry `entry` is written: the file (the shot or an include) and its
    /// index in that file's `highlights` list, as a parameter path counts it.
    #[must_use]
    pub fn highlight_written(&self, entry: usize) -> Option<(&std::path::Path, usize)> {
        self.highlights_written
            .get(entry)
            .map(|(path, index)| (path.as_path(), *index))
    }

    /// The files the shot's model and textures were read from: its inputs but the shot file and
    /// its includes, whose values each frame reads ([`Shot::at`]).
    #[must_use]
    pub fn asset_inputs(&self) -> &[PathBuf] {
        &self.inputs[self.shot_files.min(self.inputs.len())..]
    }

    /// How many highlight entries the shot has (includes first).
    #[must_use]
    pub fn highlight_count(&self) -> usize {
        self.highlights.len()
    }

    /// The layers of highlight entry `entry` as written, left to right through its Booleans,
    /// each parameter a track; empty for an entry the shot does not have.
    #[must_use]
    pub fn highlight_layers(
        &self,
        entry: usize,
    ) -> Vec<&crate::highlight::Layer<crate::anim::Track<f32>>> {
        self.highlights
            .get(entry)
            .map(|h| h.expr.layers())
            .unwrap_or_default()
    }

    /// Whether the shot draws lines.
    #[must_use]
    pub fn has_lines(&self) -> bool {
        self.outlines.is_some()
    }

    /// How many shade entries the shot has (includes first).
    #[must_use]
    pub fn shade_count(&self) -> usize {
        self.shade.len()
    }

    /// The shade entries that pick patch `patch`, in the order their stacks act.
    #[must_use]
    pub fn shade_of(&self, patch: usize) -> &[u32] {
        &self.patch_shade[patch]
    }

    /// The selector of each shade entry as written, in the order of `FrameState::shade`.
    pub fn shade_selectors(&self) -> impl Iterator<Item = &[String]> {
        self.shade.iter().map(|s| s.patches.patterns())
    }

    /// Shade entry `entry` as written: its stack and mask, every number a track.
    #[must_use]
    pub fn shade_stack(&self, entry: usize) -> Option<crate::highlight::ShadeStack<Track<f32>>> {
        self.shade.get(entry).map(ShadeSpec::stack)
    }

    /// Where shade entry `entry` is written: the file (the shot or an include) and its index in
    /// that file's `shade` list, as a parameter path counts it.
    #[must_use]
    pub fn shade_written(&self, entry: usize) -> Option<(&std::path::Path, usize)> {
        self.shade_written
            .get(entry)
            .map(|(path, index)| (path.as_path(), *index))
    }

    /// The highlight entry of patch `patch`, if it has one.
    pub fn highlight_of(&self, patch: usize) -> Option<usize> {
        self.patch_highlight[patch]
    }

    /// The light highlight entry `entry` reads (`light:`); the scene's for an entry that is
    /// not there.
    #[must_use]
    pub fn highlight_light(&self, entry: usize) -> crate::highlight::HighlightLight {
        self.highlights
            .get(entry)
            .map(|h| h.light)
            .unwrap_or_default()
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
            n_dot_l: on(Aov::NDotL),
            outline: on(Aov::Outline),
        }
    }
}
