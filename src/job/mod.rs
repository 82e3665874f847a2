//! A render job: a loaded shot with the overrides a user gave (size, preset, AOVs, threads,
//! output), the frames to render and every file the shot depends on. It renders a frame to
//! images and statistics; writing them to files is a separate, atomic step.
//!
//! `glint render` is a loop over a job; anything else that renders shots (a watcher, a farm
//! task, a test) uses the same API:
//!
//! ```no_run
//! use glint::job::{Overrides, RenderJob};
//!
//! let mut job = RenderJob::load("shots/teapot_turntable.ron".as_ref(), &Overrides::default())?;
//! job.check_writable()?;
//! for frame in job.frames().to_vec() {
//!     let image = job.render_frame(frame as f64)?;
//!     job.write_frame(frame, &image)?;
//! }
//! # Ok::<(), glint::job::JobError>(())
//! ```

mod ceiling;
mod centres;
mod fingerprint;
mod frame_check;
mod frame_fingerprint;
mod frame_list;
mod memory;
mod pixel_of;
mod place;
mod place_error;
pub mod shade_place;
mod shape_point;
mod write;

use std::path::{Path, PathBuf};
use std::sync::Arc;

use thiserror::Error;

use ceiling::MemoryCeiling;
pub use centres::Centre;
pub use fingerprint::{Fingerprint, FINGERPRINT_KEY};
pub use frame_check::{aov_file_names, FileProblem, Scrutiny};
pub use frame_list::{frame_spec, parse_frames};
pub use memory::{bytes_text, default_memory_ceiling, estimate_peak_bytes, parse_memory_size};
pub use pixel_of::{PointInImage, VISIBLE_DEPTH_TOLERANCE};
pub use place::{LayerChoice, LayerUnder, Placement, Residual};
pub use place_error::PlaceError;
pub use shade_place::{ShadeChoice, ShadePlacement};
pub use shape_point::{ShapePoint, ShapePointError};

use crate::formats::atomic::{Durability, WriteError};
use crate::render::{RenderError, RenderedFrame, Renderer, Settings};
use crate::shot::{
    check_numbered, load_shot, resolve_path, Aov, FrameState, Preset, Shot, ShotError,
};

/// What a user asks for instead of what the shot says. `None` keeps the shot's own.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Overrides {
    /// The frames to render, in order [default: the shot's whole range].
    pub frames: Option<Vec<i64>>,
    /// Image size `(width, height)` instead of the shot's resolution.
    pub size: Option<(u32, u32)>,
    /// Accuracy preset instead of the shot's; the shot's explicit settings still refine it.
    pub preset: Option<Preset>,
    /// The AOVs instead of the shot's list.
    pub aovs: Option<Vec<Aov>>,
    /// Worker threads (0: one per core) instead of one per core.
    pub threads: Option<usize>,
    /// Output pattern, relative to the shot file's folder unless absolute.
    pub output: Option<PathBuf>,
    /// Also write each frame's lines as strokes, `NAME.####.svg` beside its colour
    /// ([`svg_document`](crate::formats::svg::svg_document)).
    pub svg: bool,
    /// The most memory a frame may need, in bytes, instead of
    /// [`default_memory_ceiling`]: a job whose frames would need more
    /// ([`estimate_peak_bytes`]) is refused before rendering.
    pub max_memory: Option<u64>,
}

/// Why a job cannot be made or a frame of it rendered or written.
#[derive(Debug, Error)]
pub enum JobError {
    /// The shot cannot be used.
    #[error(transparent)]
    Shot(#[from] ShotError),
    /// The overrides ask for something the shot cannot be rendered with.
    #[error("{shot}: {message}")]
    Overrides { shot: String, message: String },
    /// An output folder cannot be made or written in.
    #[error("{0}")]
    Output(String),
    /// A frame could not be rendered.
    #[error("frame {frame}: {source}")]
    Render { frame: f64, source: RenderError },
    /// A frame's files could not be written.
    #[error(transparent)]
    Write(#[from] WriteError),
}

impl JobError {
    /// Whether the input is at fault (a shot, an option, an output folder): exit code 2 on the
    /// command line; otherwise the work failed (exit code 1).
    #[must_use]
    pub fn is_bad_input(&self) -> bool {
        match self {
            JobError::Shot(_) | JobError::Overrides { .. } | JobError::Output(_) => true,
            JobError::Render {
                source: RenderError::MeshTooLarge { .. },
                ..
            } => true,
            JobError::Render { .. } | JobError::Write(_) => false,
        }
    }
}

/// `shot` with `overrides` applied, its settings and its frames ([`RenderJob::new`]).
fn apply(mut shot: Shot, overrides: &Overrides) -> Result<(Shot, Settings, Vec<i64>), JobError> {
    let refuse = |message: String| JobError::Overrides {
        shot: shot.path.display().to_string(),
        message,
    };
    let mut settings = shot.settings_with(overrides.preset, overrides.size);
    if let Some(threads) = overrides.threads {
        settings.threads = threads;
    }
    settings.validate().map_err(|e| refuse(e.to_string()))?;
    let (first, last) = shot.frames;
    let frames = match &overrides.frames {
        Some(frames) => frames.clone(),
        None => (first..=last).collect(),
    };
    if let Some(outside) = frames.iter().find(|f| !(first..=last).contains(*f)) {
        return Err(refuse(format!(
            "frame {outside} is outside the shot's frame range {first}-{last}"
        )));
    }
    if let Some(aovs) = &overrides.aovs {
        shot.aovs.clone_from(aovs);
    }
    if let Some(out) = &overrides.output {
        let folder = shot.path.parent().unwrap_or(Path::new(""));
        shot.output = resolve_path(folder, out);
    }
    check_numbered(&shot.output, frames.len()).map_err(refuse)?;
    Ok((shot, settings, frames))
}

/// The memory a frame of the job needs at most: [`estimate_peak_bytes`] with the largest mesh
/// `renderer` makes at up to 16 of `frames` ([`sampled_frames`](memory::sampled_frames)).
fn frame_memory(shot: &Shot, settings: &Settings, frames: &[i64], renderer: &Renderer) -> u64 {
    let vertices = memory::sampled_frames(frames)
        .into_iter()
        .map(|frame| renderer.mesh_vertices(&shot.camera_at(frame as f64), settings))
        .max()
        .unwrap_or(0);
    estimate_peak_bytes(settings, &shot.aovs, vertices)
}

/// Refuses a job whose frames would need more memory than `ceiling` (the one the overrides
/// set, default [`default_memory_ceiling`]), estimated at up to 16 of its frames
/// ([`sampled_frames`](memory::sampled_frames)) with the mesh `renderer` would make for each;
/// then limits `renderer`'s meshes to what is left beside the image, so that a frame between
/// those whose view would need a larger mesh is refused when it comes. An allocation of the
/// estimate that the system refuses (a limit on the address space) is reported here rather
/// than aborted on halfway through a frame.
fn limit_memory(
    shot: &Shot,
    settings: &Settings,
    frames: &[i64],
    renderer: &mut Renderer,
    ceiling: MemoryCeiling,
) -> Result<(), JobError> {
    let refuse = |message: String| JobError::Overrides {
        shot: shot.path.display().to_string(),
        message,
    };
    let needed = frame_memory(shot, settings, frames, renderer);
    let MemoryCeiling {
        bytes: limit,
        whose,
    } = ceiling;
    let size = format!("{}×{}", settings.width, settings.height);
    if needed > limit {
        return Err(refuse(format!(
            "a frame at {size} with these settings needs about {}, above {} ({whose}); \
             render smaller, with less supersampling or a coarser tessellation, or raise the \
             ceiling with --max-memory {}G",
            bytes_text(needed),
            bytes_text(limit),
            needed.div_ceil(1 << 30),
        )));
    }
    let mut probe: Vec<u8> = Vec::new();
    if probe
        .try_reserve_exact(usize::try_from(needed).unwrap_or(usize::MAX))
        .is_err()
    {
        return Err(refuse(format!(
            "a frame at {size} with these settings needs about {}, and the system refuses to \
             allocate that much (a memory limit on this process?)",
            bytes_text(needed)
        )));
    }
    renderer.set_max_mesh_vertices(Some(memory::max_mesh_vertices(settings, &shot.aovs, limit)));
    Ok(())
}

/// A shot ready to render: its settings, frames and output with the overrides applied, and a
/// renderer that keeps the model's tessellation and working memory from frame to frame.
pub struct RenderJob {
    shot: Shot,
    overrides: Overrides,
    settings: Settings,
    frames: Vec<i64>,
    renderer: Renderer,
    durability: Durability,
    /// What every frame's fingerprint shares, made when first asked for.
    digest: std::sync::OnceLock<Option<sha2::Sha256>>,
    /// The memory ceiling, made once: a reload keeps it.
    ceiling: MemoryCeiling,
}

/// What [`RenderJob::reload`] did with the model.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reloaded {
    /// The model is the same patch for patch: the renderer, with its tessellation and the
    /// last frame's surfaces, was kept.
    ModelKept,
    /// The model changed (a patch file, or an instance's file or placement): a new renderer.
    ModelChanged,
}

impl RenderJob {
    /// Loads the shot at `path` and applies `overrides` ([`RenderJob::new`]).
    pub fn load(path: &Path, overrides: &Overrides) -> Result<Self, JobError> {
        Self::new(load_shot(path)?, overrides)
    }

    /// The job of rendering `shot` as `overrides` ask: every frame must lie in the shot's
    /// range, the settings must be valid, and an output pattern for more than one frame must
    /// number them.
    pub fn new(shot: Shot, overrides: &Overrides) -> Result<Self, JobError> {
        let (shot, settings, frames) = apply(shot, overrides)?;
        let mut renderer = Renderer::new(Arc::clone(&shot.library));
        let ceiling = MemoryCeiling::set_or_default(overrides.max_memory);
        limit_memory(&shot, &settings, &frames, &mut renderer, ceiling)?;
        Ok(Self {
            shot,
            overrides: overrides.clone(),
            settings,
            frames,
            renderer,
            durability: Durability::Synced,
            digest: std::sync::OnceLock::new(),
            ceiling,
        })
    }

    /// Loads the shot again from its file, with the same overrides, after an edit. When the
    /// model is the same patch for patch, the new shot shares this job's model and the job
    /// keeps its renderer, so that the next frame reuses the tessellation and, if its camera
    /// and settings are those of the last frame rendered, that frame's surfaces too. On an
    /// error the job is left as it was.
    pub fn reload(&mut self) -> Result<Reloaded, JobError> {
        let shot = load_shot(&self.shot.path)?;
        self.replace_shot(shot)
    }

    /// Renders `shot` from now on, with the same overrides, as [`RenderJob::reload`] does with
    /// the shot read from its file: for an edit not saved yet (a shot loaded from text with
    /// `load_shot_text`). On an error the job is left as it was.
    pub fn replace_shot(&mut self, mut shot: Shot) -> Result<Reloaded, JobError> {
        // The renderer draws poses of the job's model: the new shot keeps it when its model is
        // the same patch for patch.
        let reloaded = if *shot.library == *self.shot.library {
            shot.library = Arc::clone(&self.shot.library);
            Reloaded::ModelKept
        } else {
            Reloaded::ModelChanged
        };
        let (shot, settings, frames) = apply(shot, &self.overrides)?;
        let ceiling = self.ceiling;
        if reloaded == Reloaded::ModelChanged {
            let mut renderer = Renderer::new(Arc::clone(&shot.library));
            limit_memory(&shot, &settings, &frames, &mut renderer, ceiling)?;
            self.renderer = renderer;
        } else {
            limit_memory(&shot, &settings, &frames, &mut self.renderer, ceiling)?;
        }
        (self.shot, self.settings, self.frames) = (shot, settings, frames);
        self.digest = std::sync::OnceLock::new();
        Ok(reloaded)
    }

    /// The memory one frame of this job needs at most, estimated before rendering: what a farm
    /// task should request ([`estimate_peak_bytes`], with the largest mesh of up to 16 of its
    /// frames).
    #[must_use]
    pub fn peak_bytes(&self) -> u64 {
        frame_memory(&self.shot, &self.settings, &self.frames, &self.renderer)
    }

    /// The shot, with the overridden AOVs and output.
    #[must_use]
    pub fn shot(&self) -> &Shot {
        &self.shot
    }

    /// The settings every frame is rendered with.
    #[must_use]
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// The frames to render, in order.
    #[must_use]
    pub fn frames(&self) -> &[i64] {
        &self.frames
    }

    /// Every file the shot depends on: the shot file, its includes, patch files and toon
    /// textures. A change to any of them can change a frame.
    #[must_use]
    pub fn inputs(&self) -> &[PathBuf] {
        &self.shot.inputs
    }

    /// The file frame `frame`'s colour is written to (its AOVs go beside it).
    #[must_use]
    pub fn frame_path(&self, frame: i64) -> PathBuf {
        self.shot.frame_path(frame)
    }

    /// Every track of the shot read at `frame` (fractional frames allowed), with the model
    /// there: what [`FrameState::scene`] makes the frame's scene of.
    #[must_use]
    pub fn state(&self, frame: f64) -> FrameState {
        self.shot.at(frame)
    }

    /// Renders `frame` (fractional frames allowed): its colour, AOVs and statistics. Nothing
    /// is written.
    pub fn render_frame(&mut self, frame: f64) -> Result<RenderedFrame, JobError> {
        let state = self.shot.at(frame);
        let scene = state.scene(&self.shot)?;
        self.renderer
            .render(&scene, &self.settings)
            .map_err(|source| JobError::Render { frame, source })
    }

    /// Makes the output folders of every frame of the job and checks that files can be
    /// created in them, before anything is rendered.
    pub fn check_writable(&self) -> Result<(), JobError> {
        for &frame in &self.frames {
            write::check_writable(&self.frame_path(frame)).map_err(JobError::Output)?;
        }
        Ok(())
    }

    /// Whether frame files are synced to the disk before they are renamed into place
    /// ([`Durability::Synced`], the default, for frames a farm relies on); a preview made again at
    /// every save may skip it ([`Durability::Unsynced`]), and stays atomic.
    pub fn set_durability(&mut self, durability: Durability) {
        self.durability = durability;
    }

    /// Removes what earlier, killed runs left half-written beside `frame`'s files (their stale
    /// temporaries, [`remove_stale_temporaries`](crate::formats::atomic::remove_stale_temporaries)):
    /// for a frame that is skipped, as writing does for one that is rendered.
    pub fn clear_stale_temporaries(&self, frame: i64) -> Result<(), JobError> {
        Ok(write::clear_stale_temporaries(&self.frame_path(frame))?)
    }

    /// Writes `image`, rendered for `frame`, to its files, each stamped with the frame's
    /// [`fingerprint`](RenderJob::fingerprint): stale temporaries of earlier, killed
    /// runs cleared, each file written atomically, the EXR (when there are AOVs) and the AOV
    /// PNGs first and the colour PNG last, so that once the colour exists the whole frame does.
    /// Returns the paths written.
    pub fn write_frame(&self, frame: i64, image: &RenderedFrame) -> Result<Vec<PathBuf>, JobError> {
        let files = write::FrameFiles {
            exr: !self.shot.aovs.is_empty(),
            svg: self.overrides.svg,
        };
        let fingerprint = self.fingerprint(frame);
        Ok(write::write_frame(
            image,
            &self.frame_path(frame),
            files,
            self.durability,
            fingerprint.as_ref(),
        )?)
    }
}
