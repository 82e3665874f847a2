//! Editing one track of a shot or look file's text in place: only the track's own text changes,
//! and the result is read back and checked to differ from the file in that track alone.

use std::fmt;
use std::ops::Range;
use std::path::Path;

use super::number_text::{frame_text, number_text, value_text};
use super::param_path::{HighlightRef, ParamPath};
use super::param_sites::{ParsedFile, TrackMut};
use super::track_edit::{edited, TrackEdit, ValueEdit};
use super::track_splice::{apply, track_splice, Splice, TextEdit};
use super::ShotError;
use crate::anim::{Interpolate, Track};
use crate::formats::ron_location::position_of;
use crate::formats::ron_paths::Step::{self, Index};
use crate::formats::ron_paths::{locate_or_nearest, try_span};

/// Why a track could not be edited. Each is one line; [`EditError::in_file`] places it in the
/// file edited.
#[derive(Clone, Debug, PartialEq)]
pub enum EditError {
    /// The text is not a shot or look file that reads.
    Parse {
        line: usize,
        col: usize,
        message: String,
    },
    /// The path names no track of the file.
    BadPath {
        /// The path as written.
        written: String,
        /// Why it names no track.
        reason: String,
        /// The valid path of the file closest to it as written.
        nearest: Option<ParamPath>,
    },
    /// The value is not one the track can take (the wrong number of components, not finite, a
    /// direction of no length).
    BadValue {
        path: ParamPath,
        line: usize,
        col: usize,
        reason: String,
    },
    /// The frame is not a finite number.
    BadFrame { frame: f64 },
    /// A key to delete that the track does not have.
    NoKey {
        path: ParamPath,
        line: usize,
        col: usize,
        frame: f64,
        /// The frames of the keys it has.
        frames: Vec<f64>,
    },
    /// The edit could not be made as asked without changing more than the track (the text is
    /// not written as expected, or does not read back as intended); nothing is written.
    Unchecked {
        path: ParamPath,
        line: usize,
        col: usize,
        reason: String,
    },
}

impl EditError {
    /// The 1-based line and column the error is about, where it has one: the track's value (or
    /// the deepest value written on its path).
    #[must_use]
    pub fn place(&self) -> Option<(usize, usize)> {
        match self {
            EditError::Parse { line, col, .. }
            | EditError::BadValue { line, col, .. }
            | EditError::NoKey { line, col, .. }
            | EditError::Unchecked { line, col, .. } => Some((*line, *col)),
            EditError::BadPath { .. } | EditError::BadFrame { .. } => None,
        }
    }

    /// The sentence that says what is wrong, without the place.
    #[must_use]
    pub fn message(&self) -> String {
        match self {
            EditError::Parse { message, .. } => message.clone(),
            EditError::BadPath {
                written,
                reason,
                nearest: Some(near),
            } => format!("`{written}`: {reason}; the nearest valid path is `{near}`"),
            EditError::BadPath {
                written,
                reason,
                nearest: None,
            } => format!("`{written}`: {reason}"),
            EditError::BadValue { path, reason, .. } => format!("{path}: {reason}"),
            EditError::BadFrame { frame } => format!("the frame {frame} is not a finite number"),
            EditError::NoKey {
                path,
                frame,
                frames,
                ..
            } => format!(
                "{path} has no key at frame {}; {}",
                frame_text(*frame),
                keys_message(frames)
            ),
            EditError::Unchecked { path, reason, .. } => {
                format!("{path}: {reason}; the file is left as it is")
            }
        }
    }

    /// The error placed in the file at `file`: `FILE:LINE:COL: message`, or `FILE: message`.
    #[must_use]
    pub fn in_file(&self, file: &Path) -> ShotError {
        let path = file.display().to_string();
        let message = self.message();
        match self.place() {
            Some((line, col)) => ShotError::At {
                path,
                line,
                col,
                message,
            },
            None => ShotError::File { path, message },
        }
    }
}

impl fmt::Display for EditError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if let Some((line, col)) = self.place() {
            write!(f, "{line}:{col}: ")?;
        }
        f.write_str(&self.message())
    }
}

impl std::error::Error for EditError {}

fn keys_message(frames: &[f64]) -> String {
    if frames.is_empty() {
        return "it is a constant, with no keys".to_string();
    }
    let frames: Vec<String> = frames.iter().map(|&f| frame_text(f)).collect();
    format!("its keys are at frames {}", frames.join(", "))
}

/// `text` with the track at `path` edited as `edit` says, every byte outside the track's text
/// as it was.
///
/// The track's value is replaced where it is written (`0.25`, `(1.0, 0.98, 0.9)`, or its keys
/// `[(1, 0.341), (17, 0.229)]`): a key at the frame has its value replaced, a new key is
/// inserted in frame order in the style its list is written in (on the same line, or on a line
/// of its own), a constant keyed becomes `[(frame, value)]`, a deleted key goes with its
/// separator or its line, and deleting the last key leaves the text of the value it held. A
/// track left to its default (`camera.up`, a layer's `opacity` or `feather`) is added to its
/// struct. A `colour` or `focus` keyed or deleted as a whole is three tracks edited alike.
///
/// The result is read back and compared with the file as first read with that one track
/// changed; any other difference is an error and nothing is returned.
pub fn edit_text(text: &str, path: &ParamPath, edit: &TrackEdit) -> Result<String, EditError> {
    if let Some(frame) = edit.frame().filter(|f| !f.is_finite()) {
        return Err(EditError::BadFrame { frame });
    }
    let mut expected = read_file(text)?;
    let path = resolve(&mut expected, path)?;
    let Some(site) = expected.site(&path) else {
        return Err(unknown_path_without_list(&path));
    };
    let (line, col) = position_of(text, locate_or_nearest(text, &site.steps));
    let splices = edit_site(text, &site.steps, site.track, edit).map_err(|problem| {
        let path = path.clone();
        match problem {
            Problem::Value(reason) => EditError::BadValue {
                path,
                line,
                col,
                reason,
            },
            Problem::NoKey(frame, frames) => EditError::NoKey {
                path,
                line,
                col,
                frame,
                frames,
            },
            Problem::NotAsWritten => EditError::Unchecked {
                path,
                line,
                col,
                reason: "the track is not written the way its value reads".to_string(),
            },
        }
    })?;
    let edited = apply(text, &splices);
    let unchecked = |reason: String| EditError::Unchecked {
        path: path.clone(),
        line,
        col,
        reason,
    };
    match read_file(&edited) {
        Ok(reread) if reread == expected => Ok(edited),
        Ok(_) => Err(unchecked(
            "the edited file reads back with more changed than this track".to_string(),
        )),
        Err(e) => Err(unchecked(format!(
            "the edited file does not read back (at {e})"
        ))),
    }
}

/// `text` with each of `edits` made in turn ([`edit_text`]); the first that fails stops them.
pub fn apply_edits(text: &str, edits: &[(ParamPath, TrackEdit)]) -> Result<String, EditError> {
    edits
        .iter()
        .try_fold(text.to_string(), |text, (path, edit)| {
            edit_text(&text, path, edit)
        })
}

/// Every parameter path of the file `text`, in the order written: the camera's and light's
/// tracks, each material's, each highlight layer's (entries by index), and after a whole
/// `colour` or `focus` each of its components. Tracks left to their default are included.
pub fn param_paths(text: &str) -> Result<Vec<ParamPath>, EditError> {
    Ok(read_file(text)?.paths())
}

/// Every parameter path of the file `text` ([`param_paths`]) with its track on one line
/// ([`track_text`]).
pub fn track_texts(text: &str) -> Result<Vec<(ParamPath, String)>, EditError> {
    let mut file = read_file(text)?;
    let mut tracks = Vec::new();
    file.for_each_site(&mut |site| {
        let shown = match try_span(text, &site.steps) {
            Some(span) => one_line(&text[span]),
            None => default_text(&site.track),
        };
        tracks.push((site.path.clone(), shown));
        if let TrackMut::Triple(components) = &site.track {
            for (c, component) in components.iter().enumerate() {
                let mut steps = site.steps.clone();
                steps.push(Index(c));
                let shown = match try_span(text, &steps) {
                    Some(span) => one_line(&text[span]),
                    None => written_track(component, |&x| vec![x]),
                };
                if let Some(path) = site.path.try_with_component(c) {
                    tracks.push((path, shown));
                }
            }
        }
    });
    Ok(tracks)
}

/// The path `written` as a path of the file `text`: read, and naming a track of it. Otherwise a
/// [`EditError::BadPath`] with the valid path closest to what was written.
pub fn parse_param_path(text: &str, written: &str) -> Result<ParamPath, EditError> {
    let mut file = read_file(text)?;
    let path = written
        .parse::<ParamPath>()
        .map_err(|e| bad_path(&mut file, written, e.reason))?;
    resolve(&mut file, &path)?;
    Ok(path)
}

/// The bytes of `text` the track at `path` is written in, or `None` for a track left to its
/// default. For a whole `colour` or `focus`, the span of all three.
pub fn track_span(text: &str, path: &ParamPath) -> Result<Option<Range<usize>>, EditError> {
    let mut file = read_file(text)?;
    let path = resolve(&mut file, path)?;
    let site = file
        .site(&path)
        .ok_or_else(|| unknown_path_without_list(&path))?;
    Ok(try_span(text, &site.steps))
}

/// The track at `path` of the file `text` on one line, as written there (comments and line
/// breaks dropped), or, left to its default, as it would be written (`none` for no feather).
pub fn track_text(text: &str, path: &ParamPath) -> Result<String, EditError> {
    let mut file = read_file(text)?;
    let path = resolve(&mut file, path)?;
    let site = file
        .site(&path)
        .ok_or_else(|| unknown_path_without_list(&path))?;
    Ok(match try_span(text, &site.steps) {
        Some(span) => one_line(&text[span]),
        None => default_text(&site.track),
    })
}

/// The text read as a shot or look file.
pub(super) fn read_file(text: &str) -> Result<ParsedFile, EditError> {
    ParsedFile::parse(text).map_err(|e| match e {
        ShotError::At {
            line, col, message, ..
        } => EditError::Parse { line, col, message },
        ShotError::File { message, .. } => EditError::Parse {
            line: 1,
            col: 1,
            message,
        },
    })
}

/// `path` with a highlight named by its pattern named by its index instead, checked to name a
/// track of `file`.
fn resolve(file: &mut ParsedFile, path: &ParamPath) -> Result<ParamPath, EditError> {
    let resolved = match path {
        ParamPath::Highlight {
            entry: HighlightRef::Selector(pattern),
            layer,
            param,
        } => {
            let index = match file.entries_selected_by(pattern)[..] {
                [index] => index,
                [] => {
                    let reason = format!("no highlight entry of this file picks \"{pattern}\"");
                    return Err(bad_path(file, &path.to_string(), reason));
                }
                ref several => {
                    let named: Vec<String> =
                        several.iter().map(|i| format!("highlights[{i}]")).collect();
                    let reason = format!(
                        "more than one highlight entry picks \"{pattern}\"; name one by its index: {}",
                        named.join(", ")
                    );
                    return Err(bad_path(file, &path.to_string(), reason));
                }
            };
            ParamPath::Highlight {
                entry: HighlightRef::Index(index),
                layer: *layer,
                param: *param,
            }
        }
        ParamPath::Highlight { .. }
        | ParamPath::Camera(_)
        | ParamPath::Light(_)
        | ParamPath::Material { .. } => path.clone(),
    };
    if file.site(&resolved).is_none() {
        return Err(unknown_path(file, path));
    }
    Ok(resolved)
}

/// A [`EditError::BadPath`] for `path`, which names no track of `file`.
fn unknown_path(file: &mut ParsedFile, path: &ParamPath) -> EditError {
    let reason = match path {
        ParamPath::Material { name, .. } if !file.material_names().contains(&name.as_str()) => {
            let includes = file.includes();
            if includes.is_empty() {
                format!("this file defines no material \"{name}\"")
            } else {
                format!(
                    "this file defines no material \"{name}\"; the materials of its includes ({}) are edited in those files",
                    includes.join(", ")
                )
            }
        }
        ParamPath::Camera(_)
        | ParamPath::Light(_)
        | ParamPath::Material { .. }
        | ParamPath::Highlight { .. } => "this file has no such track".to_string(),
    };
    bad_path(file, &path.to_string(), reason)
}

fn unknown_path_without_list(path: &ParamPath) -> EditError {
    EditError::BadPath {
        written: path.to_string(),
        reason: "this file has no such track".to_string(),
        nearest: None,
    }
}

/// A [`EditError::BadPath`] naming the path of `file` closest to `written` (by edit distance),
/// highlights both by index and, where a pattern picks one entry alone, by that pattern.
fn bad_path(file: &mut ParsedFile, written: &str, reason: String) -> EditError {
    let mut candidates = file.paths();
    let patterns: Vec<Option<String>> = file
        .entry_patterns()
        .iter()
        .map(|patterns| {
            patterns
                .iter()
                .find(|p| file.entries_selected_by(p).len() == 1)
                .cloned()
        })
        .collect();
    let by_pattern: Vec<ParamPath> = candidates
        .iter()
        .filter_map(|path| match path {
            ParamPath::Highlight {
                entry: HighlightRef::Index(index),
                layer,
                param,
            } => patterns
                .get(*index)
                .cloned()
                .flatten()
                .map(|pattern| ParamPath::Highlight {
                    entry: HighlightRef::Selector(pattern),
                    layer: *layer,
                    param: *param,
                }),
            ParamPath::Highlight { .. }
            | ParamPath::Camera(_)
            | ParamPath::Light(_)
            | ParamPath::Material { .. } => None,
        })
        .collect();
    candidates.extend(by_pattern);
    // Paths under the same first name (`camera`, `light`, `materials`, `highlights`) first.
    let root = |path: &str| {
        path.split(['.', '[', '{'])
            .next()
            .unwrap_or_default()
            .to_string()
    };
    let nearest = candidates.into_iter().min_by_key(|c| {
        let shown = c.to_string();
        (
            root(&shown) != root(written),
            strsim::levenshtein(written, &shown),
        )
    });
    EditError::BadPath {
        written: written.to_string(),
        reason,
        nearest,
    }
}

/// What is wrong with an edit of a track that exists.
enum Problem {
    Value(String),
    NoKey(f64, Vec<f64>),
    NotAsWritten,
}

/// The splices that edit the track written at `steps`, which replacing `track` with what the
/// edit makes of it mirrors.
fn edit_site(
    text: &str,
    steps: &[Step],
    track: TrackMut<'_>,
    edit: &TrackEdit,
) -> Result<Vec<Splice>, Problem> {
    match track {
        TrackMut::Scalar(track) => one_track(text, steps, track, &read_edit(edit, 1)?),
        TrackMut::Point(track) => one_track(text, steps, track, &read_edit(edit, 3)?),
        TrackMut::Direction(track) => one_track(text, steps, track, &read_edit(edit, 3)?),
        TrackMut::Optional(slot) => {
            // Left out, the track is absent: like a constant, it has no key to delete.
            let mut track = slot.clone().unwrap_or(Track::Constant(0.0));
            let splices = one_track(text, steps, &mut track, &read_edit(edit, 1)?)?;
            *slot = Some(track);
            Ok(splices)
        }
        TrackMut::Triple(tracks) => triple(text, steps, tracks, &read_edit(edit, 3)?),
    }
}

fn read_edit(edit: &TrackEdit, components: usize) -> Result<ValueEdit<Vec<f32>>, Problem> {
    edit.read(components).map_err(Problem::Value)
}

/// The splice editing one track, and the track replaced by its edit.
fn one_track<T: Interpolate>(
    text: &str,
    steps: &[Step],
    track: &mut Track<T>,
    edit: &ValueEdit<Vec<f32>>,
) -> Result<Vec<Splice>, Problem> {
    let typed = edit
        .try_map(|components| T::from_components(components))
        .map_err(Problem::Value)?;
    let new = edited(track, &typed).map_err(|frames| match edit {
        ValueEdit::Delete(frame) => Problem::NoKey(*frame, frames),
        ValueEdit::Set(_) | ValueEdit::Key(..) => Problem::NotAsWritten,
    })?;
    let frames: Option<Vec<f64>> = match track {
        Track::Constant(_) => None,
        Track::Keys(_) => Some(track.key_frames().collect()),
    };
    let splice = track_splice(text, steps, frames.as_deref(), &text_edit(edit))
        .ok_or(Problem::NotAsWritten)?;
    *track = new;
    Ok(vec![splice])
}

/// The splices editing three tracks written together: set as one `(a, b, c)`, keyed or
/// deleted one component at a time.
fn triple(
    text: &str,
    steps: &[Step],
    tracks: &mut [Track<f32>; 3],
    edit: &ValueEdit<Vec<f32>>,
) -> Result<Vec<Splice>, Problem> {
    let component_steps = |c: usize| {
        let mut path = steps.to_vec();
        path.push(Index(c));
        path
    };
    match edit {
        ValueEdit::Set(values) => {
            let splice =
                track_splice(text, steps, None, &text_edit(edit)).ok_or(Problem::NotAsWritten)?;
            for (track, &value) in tracks.iter_mut().zip(values) {
                *track = Track::Constant(value);
            }
            Ok(vec![splice])
        }
        ValueEdit::Key(frame, values) => {
            let mut splices = Vec::new();
            for (c, (track, &value)) in tracks.iter_mut().zip(values).enumerate() {
                let one = ValueEdit::Key(*frame, vec![value]);
                splices.extend(one_track(text, &component_steps(c), track, &one)?);
            }
            Ok(splices)
        }
        ValueEdit::Delete(frame) => {
            let mut splices = Vec::new();
            let mut frames = Vec::new();
            for (c, track) in tracks.iter_mut().enumerate() {
                if track.key_frames().any(|k| k == *frame) {
                    splices.extend(one_track(text, &component_steps(c), track, edit)?);
                } else {
                    frames.extend(track.key_frames());
                }
            }
            if splices.is_empty() {
                frames.sort_by(f64::total_cmp);
                frames.dedup();
                return Err(Problem::NoKey(*frame, frames));
            }
            Ok(splices)
        }
    }
}

/// The edit with its value and frame written as the file writes them.
fn text_edit(edit: &ValueEdit<Vec<f32>>) -> TextEdit {
    match edit {
        ValueEdit::Set(value) => TextEdit::Set {
            value: value_text(value, number_text),
        },
        ValueEdit::Key(frame, value) => TextEdit::Key {
            frame: *frame,
            frame_text: frame_text(*frame),
            value: value_text(value, number_text),
        },
        ValueEdit::Delete(frame) => TextEdit::Delete { frame: *frame },
    }
}

/// A track's text on one line: comments and line breaks dropped, blanks between items kept as
/// one space, no comma before a closing bracket. A track holds no strings, so every `//` in it
/// starts a comment.
fn one_line(written: &str) -> String {
    let mut out = String::new();
    for line in written.lines() {
        let code = line.split("//").next().unwrap_or_default().trim();
        if code.is_empty() {
            continue;
        }
        if !(out.is_empty() || out.ends_with(['(', '['])) {
            out.push(' ');
        }
        out.push_str(code);
    }
    for (trailing, close) in [(", ]", "]"), (",]", "]"), (", )", ")"), (",)", ")")] {
        out = out.replace(trailing, close);
    }
    out
}

/// A track that is not written, as it would be written: its default value.
fn default_text(track: &TrackMut) -> String {
    match track {
        TrackMut::Scalar(track) => written_track(track, |&x| vec![x]),
        TrackMut::Optional(None) => "none".to_string(),
        TrackMut::Optional(Some(track)) => written_track(track, |&x| vec![x]),
        TrackMut::Point(track) => written_track(track, |v| v.to_array().to_vec()),
        TrackMut::Direction(track) => written_track(track, |d| d.0.to_array().to_vec()),
        TrackMut::Triple(tracks) => {
            let written: Vec<String> = tracks
                .iter()
                .map(|t| written_track(t, |&x| vec![x]))
                .collect();
            format!("({})", written.join(", "))
        }
    }
}

/// `track` written as a file writes it, its values' components given by `components`.
fn written_track<T>(track: &Track<T>, components: impl Fn(&T) -> Vec<f32>) -> String {
    match track {
        Track::Constant(value) => value_text(&components(value), number_text),
        Track::Keys(keys) => {
            let keys: Vec<String> = keys
                .iter()
                .map(|k| {
                    format!(
                        "({}, {})",
                        frame_text(k.frame),
                        value_text(&components(&k.value), number_text)
                    )
                })
                .collect();
            format!("[{}]", keys.join(", "))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SHOT: &str = r#"// A shot.
Shot(
    resolution: (64, 48),
    frames: (1, 24),
    fps: 24,
    output: "out.####.png",
    instances: [(name: "ball", file: "sphere.ron", material: "m")],
    materials: {
        "m": Cel(base: (0.1, 0.1, 0.1), bands: [(0.0, (0.5, 0.5, 0.5))]),
    },
    camera: (
        eye: (0.0, -6.0, 0.0), // front
        target: (0.0, 0.0, 0.0),
        projection: Orthographic(height: 2.4),
    ),
    light: Directional(
        towards: [
            (1, (0.0, -1.0, 0.0)), // from the front
            (24, (1.0, 0.0, 0.0)),
        ],
    ),
    highlights: [
        (
            patches: "ball/*",
            expr: Subtract(
                Layer((stack: [Scale(delta: 0.5, axis: Angle(30.0))], epsilon: 0.08, colour: (1.0, 0.9, 0.6))),
                Layer((
                    stack: [Translate(alpha: [(1, 0.6), (24, 0.15)], beta: 0.0)],
                    epsilon: 0.08,
                    colour: (1.0, 1.0, 1.0),
                    feather: Some(0.01),
                    mask: (u: (0.0, 0.5), v: (0.0, 1.0), feather: 0.1),
                )),
            ),
        ),
        (patches: ["ball/a", "ball/b"], expr: Layer((stack: [], epsilon: 0.01, colour: (1, 1, 1)))),
    ],
)
"#;

    fn path(written: &str) -> ParamPath {
        written.parse().unwrap_or_else(|e| panic!("{e}"))
    }

    fn key(frame: f64, value: &str) -> TrackEdit {
        TrackEdit::Key {
            frame,
            value: value.to_string(),
        }
    }

    fn set(value: &str) -> TrackEdit {
        TrackEdit::Set(value.to_string())
    }

    /// `SHOT` with `old` (which occurs once) replaced by `new`.
    fn shot_with(old: &str, new: &str) -> String {
        assert_eq!(SHOT.matches(old).count(), 1, "{old}");
        SHOT.replace(old, new)
    }

    fn edited(written: &str, edit: &TrackEdit) -> String {
        edit_text(SHOT, &path(written), edit).unwrap_or_else(|e| panic!("{e}"))
    }

    #[test]
    fn paths_name_every_track_in_the_order_written() {
        let layer0 = "highlights[0].layers[0]";
        let layer1 = "highlights[0].layers[1]";
        let layer2 = "highlights[1].layers[0]";
        let mut expected: Vec<String> = [
            "camera.eye",
            "camera.target",
            "camera.up",
            "camera.projection.height",
            "light.towards",
            "materials{\"m\"}.base",
            "materials{\"m\"}.bands[0].threshold",
            "materials{\"m\"}.bands[0].colour",
        ]
        .map(String::from)
        .to_vec();
        let layer = |prefix: &str, fields: &[&str]| -> Vec<String> {
            fields.iter().map(|f| format!("{prefix}.{f}")).collect()
        };
        let colour = ["colour", "colour[0]", "colour[1]", "colour[2]"];
        expected.extend(layer(
            layer0,
            &["stack[0].delta", "stack[0].axis", "epsilon"],
        ));
        expected.extend(layer(layer0, &colour));
        expected.extend(layer(layer0, &["opacity", "feather"]));
        expected.extend(layer(
            layer1,
            &["stack[0].alpha", "stack[0].beta", "epsilon"],
        ));
        expected.extend(layer(layer1, &colour));
        expected.extend(layer(
            layer1,
            &[
                "opacity",
                "feather",
                "mask.u[0]",
                "mask.u[1]",
                "mask.v[0]",
                "mask.v[1]",
            ],
        ));
        expected.extend(
            layer(layer1, &["mask.feather", "epsilon"])
                .into_iter()
                .take(1),
        );
        expected.extend(layer(layer2, &["epsilon"]));
        expected.extend(layer(layer2, &colour));
        expected.extend(layer(layer2, &["opacity", "feather"]));
        let paths: Vec<String> = param_paths(SHOT)
            .unwrap()
            .iter()
            .map(ToString::to_string)
            .collect();
        assert_eq!(paths, expected);
        for written in &expected {
            assert_eq!(parse_param_path(SHOT, written), Ok(path(written)));
        }
    }

    #[test]
    fn a_new_key_joins_its_list_in_the_list_s_style() {
        assert_eq!(
            edited("light.towards", &key(12.0, "(0, 0, 1)")),
            shot_with(
                "            (24, (1.0, 0.0, 0.0)),\n",
                "            (12, (0.0, 0.0, 1.0)),\n            (24, (1.0, 0.0, 0.0)),\n"
            )
        );
        assert_eq!(
            edited(
                "highlights[0].layers[1].stack[0].alpha",
                &key(12.5, "-0.25")
            ),
            shot_with(
                "(1, 0.6), (24, 0.15)",
                "(1, 0.6), (12.5, -0.25), (24, 0.15)"
            )
        );
        assert_eq!(
            edited("highlights[0].layers[1].stack[0].alpha", &key(24.0, "0.3")),
            shot_with("(1, 0.6), (24, 0.15)", "(1, 0.6), (24, 0.3)")
        );
    }

    #[test]
    fn a_constant_keyed_is_one_key_and_its_last_key_deleted_the_constant_it_held() {
        let at = path("camera.projection.height");
        let keyed = edit_text(SHOT, &at, &key(5.0, "3")).unwrap();
        assert_eq!(keyed, shot_with("height: 2.4", "height: [(5, 3.0)]"));
        let back = edit_text(&keyed, &at, &TrackEdit::Delete { frame: 5.0 }).unwrap();
        assert_eq!(back, shot_with("height: 2.4", "height: 3.0"));
        assert_eq!(
            edited("light.towards", &TrackEdit::Delete { frame: 1.0 }),
            shot_with("            (1, (0.0, -1.0, 0.0)), // from the front\n", "")
        );
        assert_eq!(
            edited("materials{\"m\"}.base", &set("(0.2, 0.25, 1)")),
            shot_with("base: (0.1, 0.1, 0.1)", "base: (0.2, 0.25, 1.0)")
        );
    }

    #[test]
    fn a_track_left_to_its_default_is_added_to_its_struct() {
        assert_eq!(
            edited("camera.up", &set("(0, 1, 0)")),
            shot_with(
                "        projection: Orthographic(height: 2.4),\n",
                "        projection: Orthographic(height: 2.4),\n        up: (0.0, 1.0, 0.0),\n"
            )
        );
        assert_eq!(
            edited("highlights[0].layers[1].opacity", &key(3.0, "0.5")),
            shot_with(
                "feather: 0.1),\n",
                "feather: 0.1),\n                    opacity: [(3, 0.5)],\n"
            )
        );
        assert_eq!(
            edited("highlights[1].layers[0].feather", &set("0.002")),
            shot_with("colour: (1, 1, 1))", "colour: (1, 1, 1), feather: 0.002)")
        );
    }

    #[test]
    fn values_inside_some_angle_and_colour_are_edited_in_place() {
        assert_eq!(
            edited("highlights[0].layers[1].feather", &set("0.02")),
            shot_with("Some(0.01)", "Some(0.02)")
        );
        assert_eq!(
            edited("highlights[0].layers[0].stack[0].axis", &key(1.0, "45")),
            shot_with("Angle(30.0)", "Angle([(1, 45.0)])")
        );
        assert_eq!(
            edited("highlights[0].layers[1].mask.u[1]", &set("0.75")),
            shot_with("u: (0.0, 0.5)", "u: (0.0, 0.75)")
        );
        let keyed = edited(
            "highlights[0].layers[0].colour",
            &key(6.0, "(0.5, 0.25, 0)"),
        );
        assert_eq!(
            keyed,
            shot_with(
                "colour: (1.0, 0.9, 0.6)",
                "colour: ([(6, 0.5)], [(6, 0.25)], [(6, 0.0)])"
            )
        );
        let colour = path("highlights[0].layers[0].colour");
        let deleted = edit_text(&keyed, &colour, &TrackEdit::Delete { frame: 6.0 }).unwrap();
        assert_eq!(
            deleted,
            shot_with("colour: (1.0, 0.9, 0.6)", "colour: (0.5, 0.25, 0.0)")
        );
        assert_eq!(
            edited("highlights[0].layers[0].colour[1]", &key(2.0, "0.5")),
            shot_with("colour: (1.0, 0.9, 0.6)", "colour: (1.0, [(2, 0.5)], 0.6)")
        );
    }

    #[test]
    fn highlights_are_named_by_a_pattern_that_picks_one_entry() {
        let by_pattern = edited("highlights[\"ball/b\"].layers[0].epsilon", &set("0.02"));
        assert_eq!(
            by_pattern,
            edited("highlights[1].layers[0].epsilon", &set("0.02"))
        );
        let twice = SHOT.replace("\"ball/a\", \"ball/b\"", "\"ball/*\"");
        let error = edit_text(
            &twice,
            &path("highlights[\"ball/*\"].layers[0].epsilon"),
            &set("0.02"),
        )
        .unwrap_err();
        assert!(
            error.to_string().contains("highlights[0], highlights[1]"),
            "{error}"
        );
    }

    #[test]
    fn bad_paths_name_the_nearest_valid_path() {
        let nearest = |written: &str| match parse_param_path(SHOT, written) {
            Err(EditError::BadPath { nearest, .. }) => nearest.map(|p| p.to_string()),
            other => panic!("{other:?}"),
        };
        assert_eq!(
            nearest("highlights[0].layers[3].mask.feather").as_deref(),
            Some("highlights[0].layers[1].mask.feather")
        );
        assert_eq!(
            nearest("highlights[0].layers[0].epsilom").as_deref(),
            Some("highlights[0].layers[0].epsilon")
        );
        assert_eq!(
            nearest("highlights[\"bal/*\"].layers[0].epsilon").as_deref(),
            Some("highlights[\"ball/*\"].layers[0].epsilon")
        );
        assert_eq!(nearest("camera.fov").as_deref(), Some("camera.eye"));
        assert_eq!(
            nearest("highlights[0].layers[0].stack[0].alpha").as_deref(),
            Some("highlights[0].layers[1].stack[0].alpha")
        );
        let error = edit_text(SHOT, &path("light.position"), &set("(1, 2, 3)")).unwrap_err();
        let shown = error.in_file("x.ron".as_ref()).to_string();
        assert!(
            shown.starts_with("x.ron: `light.position`: this file has no such track"),
            "{shown}"
        );
    }

    #[test]
    fn bad_values_frames_and_missing_keys_are_refused_where_the_track_is() {
        let alpha = path("highlights[0].layers[1].stack[0].alpha");
        let error = edit_text(SHOT, &alpha, &TrackEdit::Delete { frame: 2.0 }).unwrap_err();
        let (line, col) = position_of(SHOT, SHOT.find("[(1, 0.6)").unwrap());
        assert_eq!(error.place(), Some((line, col)));
        assert!(
            error
                .message()
                .ends_with("has no key at frame 2; its keys are at frames 1, 24"),
            "{error}"
        );
        let error = edit_text(SHOT, &path("camera.eye"), &set("0.5")).unwrap_err();
        assert!(matches!(error, EditError::BadValue { .. }), "{error}");
        let error = edit_text(SHOT, &path("light.towards"), &set("(0, 0, 0)")).unwrap_err();
        assert!(error.message().contains("no length"), "{error}");
        assert_eq!(
            edit_text(SHOT, &alpha, &key(f64::INFINITY, "0.1")),
            Err(EditError::BadFrame {
                frame: f64::INFINITY
            })
        );
        let broken = edit_text("Shot(frames: (1, 2)", &alpha, &set("0.1")).unwrap_err();
        assert!(matches!(broken, EditError::Parse { .. }), "{broken}");
    }

    #[test]
    fn edits_in_sequence_and_look_files() {
        let edits = [
            (path("camera.eye"), key(1.0, "(0, -6, 0)")),
            (path("camera.eye"), key(24.0, "(6, 0, 0)")),
            (path("highlights[1].layers[0].epsilon"), set("0.02")),
        ];
        let text = apply_edits(SHOT, &edits).unwrap();
        let expected = shot_with(
            "eye: (0.0, -6.0, 0.0)",
            "eye: [(1, (0.0, -6.0, 0.0)), (24, (6.0, 0.0, 0.0))]",
        )
        .replace("epsilon: 0.01", "epsilon: 0.02");
        assert_eq!(text, expected);
        let looks =
            "Looks(\n    materials: {\n        \"clay\": Cel(base: (0.3, 0.1, 0.06)),\n    },\n)\n";
        let at = path("materials{\"clay\"}.base");
        assert_eq!(
            edit_text(looks, &at, &key(10.0, "(0.2, 0.1, 0.1)")).unwrap(),
            looks.replace("(0.3, 0.1, 0.06)", "[(10, (0.2, 0.1, 0.1))]")
        );
        assert!(parse_param_path(looks, "camera.eye").is_err());
    }

    #[test]
    fn a_track_is_shown_on_one_line() {
        assert_eq!(
            track_text(SHOT, &path("light.towards")).unwrap(),
            "[(1, (0.0, -1.0, 0.0)), (24, (1.0, 0.0, 0.0))]"
        );
        assert_eq!(
            track_text(SHOT, &path("camera.up")).unwrap(),
            "(0.0, 0.0, 1.0)"
        );
        assert_eq!(
            track_text(SHOT, &path("highlights[1].layers[0].feather")).unwrap(),
            "none"
        );
        let texts = track_texts(SHOT).unwrap();
        assert_eq!(texts.len(), param_paths(SHOT).unwrap().len());
        for (path, text) in texts {
            assert_eq!(track_text(SHOT, &path), Ok(text));
        }
    }
}
