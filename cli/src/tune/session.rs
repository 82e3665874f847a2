//! One tuning session: the shot file's text as last read or written (the truth), the jobs that
//! render it at preview and final quality with changes not yet accepted, and the history of
//! accepted changes. Synchronous; the server calls it from its blocking pool, one request at a
//! time.

use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::{Deserialize, Serialize};

use super::change::{apply_changes, Change, OpKind};
use super::error::TuneError;
use super::history::History;
use super::view::{highlight_views, pin_at, shade_views, shape_view, StateView};
use glint::formats::image_encoding::colour_rgba8;
use glint::formats::replace_text::replace_text;
use glint::highlight::{Op, MAX_OUTLINE_SEGMENTS};
use glint::job::{
    JobError, LayerChoice, Overrides, PlaceError, RenderJob, ShadeChoice, ShapePointError,
};
use glint::picture::overlay::{
    draw_band_edges, draw_centre, draw_matte, draw_pin, draw_seams, draw_track,
};
use glint::render::{Stage, SurfacePoint};
use glint::shot::{
    load_shot_text, Aov, HighlightRef, LayerParam, MaterialState, OpParam, ParamPath, Preset,
    ShadeParam,
};

/// The quality a frame is rendered at.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Quality {
    /// The `preview` preset: what follows every change.
    #[default]
    Preview,
    /// The `final` preset: when the user pauses.
    Final,
}

/// The marks drawn over a frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Overlays {
    /// Patch seams and the silhouette.
    pub seams: bool,
    /// The highlight matte, tinted, with its edge.
    pub matte: bool,
    /// Every pin of the shot file's layers, and, on frames without unsaved changes, where its
    /// point goes over the shot: a dot where it lands on every frame.
    pub pins: bool,
    /// The cel bands' edges: the terminator and every band's, where `N·L'` crosses them.
    pub terminator: bool,
    /// Every centre of this layer, `[highlight entry, layer]`: a cross on each where the frame
    /// shows it. Drawn on frames without unsaved changes only, so that a drag stays quick.
    pub centres: Option<[usize; 2]>,
}

/// A frame asked for: at a frame, a quality, with overlays, and with changes made to the text
/// in memory only.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct FrameRequest {
    pub frame: f64,
    pub quality: Quality,
    pub overlays: Overlays,
    /// Changes shown but not written (a slider being dragged).
    pub changes: Vec<Change>,
}

/// A rendered frame for the page: sRGB RGBA8, rows from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct FrameImage {
    pub width: u32,
    pub height: u32,
    pub rgba: Vec<u8>,
    /// The render alone, in milliseconds.
    pub render_ms: f64,
    /// The stages that ran, by name.
    pub stages: Vec<&'static str>,
    /// The centres of the layer the centres overlay asked for, where each lands in the image
    /// (a pixel's centre at integer values) and whether the frame shows it; None where none
    /// were asked for or the frame had unsaved changes.
    pub centres: Option<Vec<([f64; 2], bool)>>,
}

/// What is under a pixel: the patch, its parts, its (u, v), and the highlight drawn on it.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Pick {
    pub patch: String,
    pub parts: Vec<String>,
    pub uv: [f64; 2],
    /// The highlight entry drawn on the patch (includes first), if any.
    pub highlight: Option<usize>,
    /// Its layers that cover the point at this frame.
    pub covering: Vec<usize>,
    /// The shade entries whose stacks act on its light (includes first), in order.
    pub shade: Vec<usize>,
    /// `N·L'` there: what its tone reads (the designed light's, with shade entries).
    pub n_dot_l: f32,
}

/// A pointer dragging a highlight layer at a frame: its centre goes where the pointer is.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DragRequest {
    pub frame: f64,
    /// The image position, pixel centres at integer values.
    pub x: f64,
    pub y: f64,
    /// The highlight entry (includes first) and its layer.
    pub highlight: usize,
    pub layer: usize,
    #[serde(default)]
    pub quality: Quality,
    #[serde(default)]
    pub overlays: Overlays,
}

/// A pointer dragging the edge of a patch's cel shadow at a frame: a band's edge goes where the
/// pointer is, by the placing translation of a shade entry ([`RenderJob::place_shade`]).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShadeDragRequest {
    pub frame: f64,
    /// The image position, pixel centres at integer values.
    pub x: f64,
    pub y: f64,
    /// The shade entry (includes first); default: the last that picks the patch there.
    #[serde(default)]
    pub entry: Option<usize>,
    /// The band whose edge moves, from 0; default: the one whose edge is nearest.
    #[serde(default)]
    pub band: Option<usize>,
    #[serde(default)]
    pub quality: Quality,
    #[serde(default)]
    pub overlays: Overlays,
}

/// An outline drawn on the frame: its corners' image positions, sent when it is finished.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DrawRequest {
    pub frame: f64,
    /// The highlight entry (includes first) and its layer.
    pub highlight: usize,
    pub layer: usize,
    /// The corners in order, image positions with pixel centres at integer values.
    pub points: Vec<[f64; 2]>,
    /// Key the outline at `frame` even where the layer's outline is not keyed yet.
    #[serde(default)]
    pub key: bool,
}

/// A job and the text its shot was loaded from.
struct Rendering {
    job: RenderJob,
    text: String,
    /// An input other than the shot file changed: load again even for the same text.
    stale: bool,
}

/// One tuning session of one shot file.
pub struct Session {
    path: PathBuf,
    text: String,
    version: u64,
    history: History,
    /// Why there is nothing to undo, when an edit made elsewhere cleared the history.
    history_note: Option<String>,
    preview: Rendering,
    final_frames: Rendering,
    disk_error: Option<String>,
}

/// The most changes one request may carry: a drag makes three, a slider one.
pub const MAX_CHANGES: usize = 64;

/// Refuses more changes than [`MAX_CHANGES`] in one request.
fn check_changes(changes: &[Change]) -> Result<(), TuneError> {
    if changes.len() > MAX_CHANGES {
        return Err(TuneError::Bad(format!(
            "{} changes in one request; at most {MAX_CHANGES} are taken",
            changes.len()
        )));
    }
    Ok(())
}

/// The AOVs every frame of a session is rendered with: the patch under each pixel for picking
/// and seams, the matte for its overlay.
const SESSION_AOVS: [Aov; 3] = [Aov::PatchId, Aov::Matte, Aov::NDotL];

fn bad(e: impl std::fmt::Display) -> TuneError {
    TuneError::Bad(e.to_string())
}

fn job_error(e: JobError) -> TuneError {
    if e.is_bad_input() {
        TuneError::Bad(e.to_string())
    } else {
        TuneError::Failed(e.to_string())
    }
}

/// Whether `a` and `b` name the same file.
fn same_file(a: &Path, b: &Path) -> bool {
    std::fs::canonicalize(a)
        .ok()
        .zip(std::fs::canonicalize(b).ok())
        .is_some_and(|(a, b)| a == b)
}

fn place_error(e: PlaceError) -> TuneError {
    if e.is_bad_input() {
        TuneError::Bad(e.to_string())
    } else {
        TuneError::Failed(e.to_string())
    }
}

impl Session {
    /// Opens the shot at `path`, its frames rendered at `size` (the shot's resolution if
    /// `None`). The file must load as `glint render` loads it.
    pub fn open(path: &Path, size: Option<(u32, u32)>) -> Result<Self, JobError> {
        let text = std::fs::read_to_string(path).map_err(|e| {
            JobError::Shot(glint::shot::ShotError::File {
                path: path.display().to_string(),
                message: format!("cannot read the file: {e}"),
            })
        })?;
        let rendering = |preset| -> Result<Rendering, JobError> {
            let overrides = Overrides {
                size,
                preset: Some(preset),
                aovs: Some(SESSION_AOVS.to_vec()),
                ..Overrides::default()
            };
            let shot = load_shot_text(path, text.clone())?;
            Ok(Rendering {
                job: RenderJob::new(shot, &overrides)?,
                text: text.clone(),
                stale: false,
            })
        };
        Ok(Self {
            path: path.to_path_buf(),
            preview: rendering(Preset::Preview)?,
            final_frames: rendering(Preset::Final)?,
            text,
            version: 1,
            history: History::default(),
            history_note: None,
            disk_error: None,
        })
    }

    /// The shot file.
    #[must_use]
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Grows with every change of the file.
    #[must_use]
    pub fn version(&self) -> u64 {
        self.version
    }

    /// The state the page shows at `frame`.
    pub fn state(&mut self, frame: f64) -> Result<StateView, TuneError> {
        check_frame(frame)?;
        let text = self.text.clone();
        sync(&mut self.preview, &self.path, &text)?;
        let (undo, redo) = self.history.depth();
        let settings = self.preview.job.settings();
        let shot = self.preview.job.shot();
        Ok(StateView {
            version: self.version,
            file: shot.path.display().to_string(),
            frame,
            frames: [shot.frames.0, shot.frames.1],
            fps: shot.fps,
            size: [settings.width, settings.height],
            undo,
            redo,
            disk_error: self.disk_error.clone(),
            history_note: self.history_note.clone(),
            highlights: highlight_views(shot, &text, frame)?,
            shade: shade_views(shot, &text, frame)?,
            op_kinds: OpKind::ALL.map(OpKind::name),
        })
    }

    /// Renders the frame `request` asks for, with its changes made to the text in memory only:
    /// the file is not touched. A change that is not valid is refused as it would be if it were
    /// written.
    pub fn render(&mut self, request: &FrameRequest) -> Result<FrameImage, TuneError> {
        check_frame(request.frame)?;
        let text =
            apply_changes(&self.text, &request.changes).map_err(|e| bad(e.in_file(&self.path)))?;
        let rendering = match request.quality {
            Quality::Preview => &mut self.preview,
            Quality::Final => &mut self.final_frames,
        };
        sync(rendering, &self.path, &text)?;
        // Centres are searched for over every patch of the layer's entry, and a pin's track
        // poses the model on every frame: not while a change is being dragged.
        let mut overlays = request.overlays;
        let still = request.changes.is_empty();
        if !still {
            overlays.centres = None;
        }
        draw(&mut rendering.job, request.frame, overlays, still)
    }

    /// What is under pixel `(x, y)` at `frame`.
    pub fn pick(&mut self, frame: f64, (x, y): (f64, f64)) -> Result<Pick, TuneError> {
        check_frame(frame)?;
        let text = self.text.clone();
        sync(&mut self.preview, &self.path, &text)?;
        let job = &mut self.preview.job;
        let (patch, uv) = job.point_under(frame, (x, y)).map_err(place_error)?;
        let shot = job.shot();
        let highlight = shot.highlight_of(patch);
        let state = shot.at(frame);
        // The model as posed at this frame: names are the same in every pose, surfaces not.
        let library = &state.library;
        let covering = match highlight {
            Some(entry) => {
                let point = shot.highlight_point(&state, patch, uv);
                state.highlights[entry]
                    .layers()
                    .iter()
                    .enumerate()
                    .filter(|(_, layer)| {
                        layer
                            .prepare()
                            .is_ok_and(|p| p.signed(&point.frame, point.half_vector) > 0.0)
                    })
                    .map(|(k, _)| k)
                    .collect()
            }
            None => Vec::new(),
        };
        let point = SurfacePoint::new(
            &library.patches[patch].surface,
            uv,
            &state.camera,
            &state.light,
        );
        let scene = state
            .scene(shot)
            .map_err(|e| TuneError::Bad(e.to_string()))?;
        let n_dot_l = scene.tone_n_dot_l(
            patch as u32,
            &point.frame,
            glam::Vec2::new(uv.0 as f32, uv.1 as f32),
            point.position,
        );
        Ok(Pick {
            patch: library.patches[patch].name.clone(),
            parts: library.groups_of(patch).map(|g| g.name.clone()).collect(),
            uv: [uv.0, uv.1],
            highlight,
            covering,
            shade: shot.shade_of(patch).iter().map(|&e| e as usize).collect(),
            n_dot_l,
        })
    }

    /// The changes that put the centre of the layer `request` names on the surface point under
    /// its pixel, keyed at its frame: the layer's placing translation (`glint place`); a stack
    /// without one gets a translation at its start; a pinned layer has its pin's (u, v) keyed,
    /// and moved to the patch under the pointer when that patch has the same highlight and the
    /// pin has no keys at other frames.
    pub fn drag_changes(&mut self, request: &DragRequest) -> Result<Vec<Change>, TuneError> {
        check_frame(request.frame)?;
        let text = self.text.clone();
        sync(&mut self.preview, &self.path, &text)?;
        let file_index = self.file_index(request.highlight)?;
        let job = &mut self.preview.job;
        let (entry, layer, frame) = (request.highlight, request.layer, request.frame);
        let path = |param| {
            ParamPath::Highlight {
                entry: HighlightRef::Index(file_index),
                layer,
                param,
            }
            .to_string()
        };
        let key = |param, value: f64| Change::Key {
            path: path(param),
            frame,
            value: vec![value as f32],
        };
        if let Some(pinned) = job.shot().pinned_patch(entry, layer) {
            let (patch, uv) = job
                .point_under(frame, (request.x, request.y))
                .map_err(place_error)?;
            let shot = job.shot();
            let name = |p: usize| shot.library.patches[p].name.clone();
            let mut changes = Vec::new();
            if patch != pinned {
                if shot.highlight_of(patch) != Some(entry) {
                    return Err(TuneError::Bad(format!(
                        "highlights[{entry}].layers[{layer}] is pinned to {}; {} under the \
                         pointer has another highlight, so the pin cannot move there",
                        name(pinned),
                        name(patch)
                    )));
                }
                let pin = shot.highlight_layers(entry)[layer].pin.as_ref();
                let keyed_elsewhere = pin.is_some_and(|pin| {
                    (pin.u.key_frames().chain(pin.v.key_frames())).any(|k| k != frame)
                });
                if keyed_elsewhere {
                    return Err(TuneError::Bad(format!(
                        "highlights[{entry}].layers[{layer}] is pinned to {} with keys at other \
                         frames, which belong to that patch; drag it on {} or delete those keys",
                        name(pinned),
                        name(pinned)
                    )));
                }
                changes.push(Change::PinTo {
                    highlight: file_index,
                    layer,
                    patch: name(patch),
                });
            }
            changes.extend([key(LayerParam::PinU, uv.0), key(LayerParam::PinV, uv.1)]);
            return Ok(changes);
        }
        let state = job.shot().at(frame);
        let chosen = state
            .highlights
            .get(entry)
            .and_then(|expr| expr.layers().get(layer).map(|l| (*l).clone()))
            .ok_or_else(|| {
                TuneError::Bad(format!(
                    "highlight {entry} has no layer {layer} (layers are numbered from 0)"
                ))
            })?;
        if chosen.placing_translation().is_none() {
            // A stack without a translation gets one at its start, solved as a pin solves it.
            let (patch, uv) = job
                .point_under(frame, (request.x, request.y))
                .map_err(place_error)?;
            let shot = job.shot();
            if shot.highlight_of(patch) != Some(entry) {
                return Err(TuneError::Bad(format!(
                    "{}, under the pointer, does not have highlight {entry}",
                    shot.library.patches[patch].name
                )));
            }
            let point = shot.highlight_point(&state, patch, uv);
            let centred = shot
                .layer_on(&chosen, patch, request.frame)
                .centred_at(&point.frame, point.half_vector)
                .map_err(|e| TuneError::Bad(format!("highlights[{entry}].layers[{layer}]: {e}")))?;
            let Some(Op::Translate { alpha, beta }) = centred.stack.first() else {
                return Err(TuneError::Failed(
                    "the centred layer does not start with its translation".to_string(),
                ));
            };
            let op = |param| LayerParam::Op { index: 0, param };
            return Ok(vec![
                Change::InsertOp {
                    highlight: file_index,
                    layer,
                    index: 0,
                    op: OpKind::Translate,
                },
                key(op(OpParam::Alpha), f64::from(*alpha)),
                key(op(OpParam::Beta), f64::from(*beta)),
            ]);
        }
        let choice = LayerChoice {
            highlight: Some(entry),
            layer: Some(layer),
        };
        let placed = job
            .place_centre(frame, (request.x, request.y), choice)
            .map_err(place_error)?;
        let op = |param| LayerParam::Op {
            index: placed.op,
            param,
        };
        Ok(vec![
            key(op(OpParam::Alpha), f64::from(placed.translation.x)),
            key(op(OpParam::Beta), f64::from(placed.translation.y)),
        ])
    }

    /// The change that gives the layer `request` names the outline drawn through its pixels:
    /// each pixel mapped to the layer's t′ at the request's frame
    /// ([`RenderJob::shape_point`](glint::job::RenderJob::shape_point)), every point on the
    /// layer's highlight (and, for a layer acting in its patches' own frames, on the first
    /// point's patch), within `|t′| ≤ 0.99`. It is keyed at the frame when the request asks,
    /// or when the layer's outline is keyed already (as a slider keys a keyed track); otherwise
    /// it is the plain outline.
    pub fn draw_changes(&mut self, request: &DrawRequest) -> Result<Vec<Change>, TuneError> {
        check_frame(request.frame)?;
        if request.points.len() > MAX_OUTLINE_SEGMENTS {
            return Err(TuneError::Bad(format!(
                "{} points drawn; an outline has at most {MAX_OUTLINE_SEGMENTS}",
                request.points.len()
            )));
        }
        let text = self.text.clone();
        sync(&mut self.preview, &self.path, &text)?;
        let file_index = self.file_index(request.highlight)?;
        let (entry, layer, frame) = (request.highlight, request.layer, request.frame);
        let job = &mut self.preview.job;
        let Some(written) = job.shot().highlight_layers(entry).get(layer).copied() else {
            return Err(TuneError::Bad(format!(
                "highlight {entry} has no layer {layer} (layers are numbered from 0)"
            )));
        };
        let keyed = !shape_view(&written.shape).1.is_empty();
        let pixels: Vec<(f64, f64)> = request.points.iter().map(|&[x, y]| (x, y)).collect();
        let choice = LayerChoice {
            highlight: Some(entry),
            layer: Some(layer),
        };
        let points = job
            .shape_points(frame, &pixels, choice)
            .map_err(|e| match e {
                ShapePointError::Place(e) => place_error(e),
                other => TuneError::Bad(other.to_string()),
            })?;
        Ok(vec![Change::Outline {
            highlight: file_index,
            layer,
            key: (request.key || keyed).then_some(frame),
            points: points.iter().map(|p| p.t.to_array()).collect(),
        }])
    }

    /// The changes a shade drag makes: its entry's placing translation keyed at the frame to
    /// the `(α, β)` that puts the band's edge under the pointer ([`RenderJob::place_shade`]).
    pub fn shade_drag_changes(
        &mut self,
        request: &ShadeDragRequest,
    ) -> Result<Vec<Change>, TuneError> {
        check_frame(request.frame)?;
        let text = self.text.clone();
        sync(&mut self.preview, &self.path, &text)?;
        let choice = ShadeChoice {
            entry: request.entry,
            band: request.band,
        };
        let placed = self
            .preview
            .job
            .place_shade(request.frame, (request.x, request.y), choice)
            .map_err(place_error)?;
        let shot = self.preview.job.shot();
        let Some((file, index)) = shot.shade_written(placed.entry) else {
            return Err(TuneError::Failed(format!(
                "shade entry {} is not in the shot",
                placed.entry
            )));
        };
        if !same_file(file, &self.path) {
            return Err(TuneError::Bad(format!(
                "shade entry {} is written in {}; tune changes only the shot file {}: edit the \
                 include with `glint key`",
                placed.entry,
                file.display(),
                self.path.display()
            )));
        }
        let key = |param, value: f32| Change::Key {
            path: ParamPath::Shade {
                entry: index,
                param: ShadeParam::Op {
                    index: placed.op,
                    param,
                },
            }
            .to_string(),
            frame: request.frame,
            value: vec![value],
        };
        Ok(vec![
            key(OpParam::Alpha, placed.translation.x),
            key(OpParam::Beta, placed.translation.y),
        ])
    }

    /// The index in the shot file's `highlights` of highlight entry `entry`; an entry written
    /// in an include is refused: the session writes no file but the shot.
    fn file_index(&self, entry: usize) -> Result<usize, TuneError> {
        let shot = self.preview.job.shot();
        let Some((file, index)) = shot.highlight_written(entry) else {
            return Err(TuneError::Bad(format!(
                "the shot has {} highlight entries, numbered from 0, so there is no entry {entry}",
                shot.highlight_count()
            )));
        };
        if !same_file(file, &self.path) {
            return Err(TuneError::Bad(format!(
                "highlight {entry} is written in {}; tune changes only the shot file {}: edit \
                 the include with `glint key`",
                file.display(),
                self.path.display()
            )));
        }
        Ok(index)
    }

    /// Makes `changes` and writes the file: each is checked as `glint key` checks it, and the
    /// result must load as the shot; otherwise nothing is written. Returns the new version.
    pub fn commit(&mut self, changes: &[Change]) -> Result<u64, TuneError> {
        check_changes(changes)?;
        self.adopt_disk()?;
        let edited = apply_changes(&self.text, changes).map_err(|e| bad(e.in_file(&self.path)))?;
        if edited == self.text {
            return Ok(self.version);
        }
        self.write(edited.clone())?;
        let before = std::mem::replace(&mut self.text, edited);
        self.history.record(before, self.text.clone());
        self.history_note = None;
        Ok(self.bump())
    }

    /// Undoes the last accepted change, writing the file back as it was before it.
    pub fn undo(&mut self) -> Result<u64, TuneError> {
        self.adopt_disk()?;
        let Some(before) = self.history.undo(&self.text) else {
            return Err(TuneError::Conflict("there is nothing to undo".to_string()));
        };
        self.write(before.clone())?;
        self.text = before;
        Ok(self.bump())
    }

    /// Makes the last undone change again.
    pub fn redo(&mut self) -> Result<u64, TuneError> {
        self.adopt_disk()?;
        let Some(after) = self.history.redo(&self.text) else {
            return Err(TuneError::Conflict("there is nothing to redo".to_string()));
        };
        self.write(after.clone())?;
        self.text = after;
        Ok(self.bump())
    }

    /// Takes in a change of the shot's inputs made elsewhere (an editor saving the file, a
    /// patch file or texture written): the file's text is read again; a text that loads
    /// becomes the session's (and the history, which no longer applies, is forgotten); one
    /// that does not is reported in the state until it is fixed. Returns whether anything
    /// changed.
    pub fn inputs_changed(&mut self) -> bool {
        let Ok(text) = std::fs::read_to_string(&self.path) else {
            return false;
        };
        if text == self.text && self.disk_error.is_none() {
            // The session's own write, or another input: load again from the files.
            self.preview.stale = true;
            self.final_frames.stale = true;
            self.bump();
            return true;
        }
        match load_shot_text(&self.path, text.clone()) {
            Ok(_) => {
                self.text = text;
                self.disk_error = None;
                if self.history.depth() != (0, 0) {
                    self.history_note = Some(
                        "the file was changed outside tune: the changes before that cannot be \
                         undone or redone here"
                            .to_string(),
                    );
                }
                self.history.clear();
                self.preview.stale = true;
                self.final_frames.stale = true;
            }
            Err(e) => self.disk_error = Some(e.to_string()),
        }
        self.bump();
        true
    }

    /// Refuses to change a file that was changed elsewhere and not yet taken in.
    fn adopt_disk(&mut self) -> Result<(), TuneError> {
        let on_disk = std::fs::read_to_string(&self.path).map_err(|e| {
            TuneError::Failed(format!(
                "{}: cannot read the file: {e}",
                self.path.display()
            ))
        })?;
        if on_disk == self.text {
            return Ok(());
        }
        self.inputs_changed();
        Err(TuneError::Conflict(format!(
            "{} was changed elsewhere; the page now shows it as it is, so make the change again",
            self.path.display()
        )))
    }

    /// Writes `text` to the shot file after checking that it loads.
    fn write(&self, text: String) -> Result<(), TuneError> {
        load_shot_text(&self.path, text.clone()).map_err(bad)?;
        replace_text(&self.path, &text).map_err(|e| TuneError::Failed(e.to_string()))
    }

    fn bump(&mut self) -> u64 {
        self.version += 1;
        self.version
    }
}

/// Refuses a frame that is not a finite number.
fn check_frame(frame: f64) -> Result<(), TuneError> {
    if frame.is_finite() {
        Ok(())
    } else {
        Err(TuneError::Bad(format!(
            "the frame {frame} is not a finite number"
        )))
    }
}

/// Makes `rendering` render the shot whose file's text is `text`.
fn sync(rendering: &mut Rendering, path: &Path, text: &str) -> Result<(), TuneError> {
    if rendering.text == text && !rendering.stale {
        return Ok(());
    }
    let shot = load_shot_text(path, text.to_string()).map_err(bad)?;
    rendering.job.replace_shot(shot).map_err(job_error)?;
    rendering.text = text.to_string();
    rendering.stale = false;
    Ok(())
}

/// Renders `frame` of `job` with `overlays` drawn over it.
/// Renders `frame` of `job` with `overlays` drawn over it; pins' tracks only when `tracks`.
fn draw(
    job: &mut RenderJob,
    frame: f64,
    overlays: Overlays,
    tracks: bool,
) -> Result<FrameImage, TuneError> {
    let started = Instant::now();
    let image = job.render_frame(frame).map_err(job_error)?;
    let render_ms = started.elapsed().as_secs_f64() * 1e3;
    let (width, height) = (image.width, image.height);
    let mut rgba = colour_rgba8(&image.colour);
    if overlays.matte {
        if let Some(matte) = &image.aovs.matte {
            draw_matte(&mut rgba, matte, width, height);
        }
    }
    if overlays.terminator {
        if let (Some(n_dot_l), Some(ids)) = (&image.aovs.n_dot_l, &image.aovs.patch_id) {
            let shot = job.shot();
            let state = shot.at(frame);
            draw_band_edges(&mut rgba, n_dot_l, ids, (width, height), |patch| {
                let material = shot.material_of(patch as usize);
                match &state.materials[material] {
                    MaterialState::Cel(ramp) => Some((
                        material,
                        ramp.bands.iter().map(|(threshold, _)| *threshold).collect(),
                    )),
                    MaterialState::XToon(_) => None,
                }
            });
        }
    }
    if overlays.seams {
        if let Some(ids) = &image.aovs.patch_id {
            draw_seams(&mut rgba, ids, width, height);
        }
    }
    if overlays.pins {
        let shot = job.shot();
        let aspect = width as f32 / height as f32;
        // Where (u, v) of `patch` lands in this image at frame `at`, posed and seen then.
        let landing = |patch: usize, uv: (f64, f64), at: f64| {
            let library = shot.library_at(at);
            let camera = shot.camera_at(at);
            let surface = &library.patches[patch].surface;
            let domain = surface.domain();
            let (u, v) = (
                uv.0.clamp(domain.u.0, domain.u.1),
                uv.1.clamp(domain.v.0, domain.v.1),
            );
            let clip = camera.view_projection(aspect) * surface.point(u, v).as_vec3().extend(1.0);
            (clip.w > 0.0).then(|| {
                let (x, y) = (clip.x / clip.w, clip.y / clip.w);
                (
                    f64::from((x + 1.0) * 0.5 * width as f32) - 0.5,
                    f64::from((1.0 - y) * 0.5 * height as f32) - 0.5,
                )
            })
        };
        let (first, last) = shot.frames;
        for entry in 0..shot.highlight_count() {
            for (k, layer) in shot.highlight_layers(entry).into_iter().enumerate() {
                let Some(patch) = shot.pinned_patch(entry, k) else {
                    continue;
                };
                if tracks {
                    let track: Vec<(f64, f64)> = (first..=last)
                        .filter_map(|at| landing(patch, pin_at(layer, at as f64)?, at as f64))
                        .collect();
                    draw_track(&mut rgba, width, height, &track);
                }
                let Some(uv) = pin_at(layer, frame) else {
                    continue;
                };
                if let Some(pixel) = landing(patch, uv, frame) {
                    draw_pin(&mut rgba, width, height, pixel);
                }
            }
        }
    }
    let centres = match overlays.centres {
        Some([highlight, layer]) => {
            let found = job
                .centres_at(frame, highlight, layer)
                .map_err(place_error)?;
            let mut marked = Vec::with_capacity(found.len());
            for centre in found {
                let Some(pixel) = centre.pixel.filter(|p| p.in_front) else {
                    continue;
                };
                if pixel.visible {
                    draw_centre(&mut rgba, width, height, pixel.pixel);
                }
                marked.push(([pixel.pixel.0, pixel.pixel.1], pixel.visible));
            }
            Some(marked)
        }
        None => None,
    };
    let stages = Stage::ALL
        .into_iter()
        .filter(|&s| image.stats.ran(s))
        .map(Stage::name)
        .collect();
    Ok(FrameImage {
        width,
        height,
        rgba,
        render_ms,
        stages,
        centres,
    })
}
