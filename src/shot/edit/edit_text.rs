//! Editing one track of a shot or look file's text in place: only the track's own text changes,
//! and the result is read back and checked to differ from the file in that track alone.

use super::error::EditError;
use super::number_text::{frame_text, number_text, value_text};
use super::param_path::ParamPath;
use super::param_sites::TrackMut;
use super::read::{read_back, read_file};
use super::resolve::{resolve, unknown_path_without_list};
use super::track_edit::{edited, TrackEdit, ValueEdit};
use super::track_splice::{apply, track_splice, Splice, TextEdit};
use crate::anim::{Interpolate, Track};
use crate::formats::ron_location::position_of;
use crate::formats::ron_paths::locate_or_nearest;
use crate::formats::ron_paths::Step::{self, Index};

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
    read_back(apply(text, &splices), &expected, "track").map_err(|reason| EditError::Unchecked {
        path,
        line,
        col,
        reason,
    })
}

/// `text` with each of `edits` made in turn ([`edit_text`]); the first that fails stops them.
pub fn apply_edits(text: &str, edits: &[(ParamPath, TrackEdit)]) -> Result<String, EditError> {
    edits
        .iter()
        .try_fold(text.to_string(), |text, (path, edit)| {
            edit_text(&text, path, edit)
        })
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
        .try_map(|components| {
            let wide: Vec<f64> = components.iter().map(|&c| f64::from(c)).collect();
            T::from_components(&wide)
        })
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shot::fixtures::{param_path, STYLED_SHOT};
    use crate::shot::parse_param_path;

    fn key(frame: f64, value: &str) -> TrackEdit {
        TrackEdit::Key {
            frame,
            value: value.to_string(),
        }
    }

    fn set(value: &str) -> TrackEdit {
        TrackEdit::Set(value.to_string())
    }

    /// `STYLED_SHOT` with `old` (which occurs once) replaced by `new`.
    fn shot_with(old: &str, new: &str) -> String {
        assert_eq!(STYLED_SHOT.matches(old).count(), 1, "{old}");
        STYLED_SHOT.replace(old, new)
    }

    fn edited(written: &str, edit: &TrackEdit) -> String {
        edit_text(STYLED_SHOT, &param_path(written), edit).unwrap_or_else(|e| panic!("{e}"))
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
        let at = param_path("camera.projection.height");
        let keyed = edit_text(STYLED_SHOT, &at, &key(5.0, "3")).unwrap();
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
        let colour = param_path("highlights[0].layers[0].colour");
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
        let twice = STYLED_SHOT.replace("\"ball/a\", \"ball/b\"", "\"ball/*\"");
        let error = edit_text(
            &twice,
            &param_path("highlights[\"ball/*\"].layers[0].epsilon"),
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
        let nearest = |written: &str| match parse_param_path(STYLED_SHOT, written) {
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
        let error = edit_text(
            STYLED_SHOT,
            &param_path("light.position"),
            &set("(1, 2, 3)"),
        )
        .unwrap_err();
        let shown = error.in_file("x.ron".as_ref()).to_string();
        assert!(
            shown.starts_with("x.ron: `light.position`: this file has no such track"),
            "{shown}"
        );
    }

    #[test]
    fn bad_values_frames_and_missing_keys_are_refused_where_the_track_is() {
        let alpha = param_path("highlights[0].layers[1].stack[0].alpha");
        let error = edit_text(STYLED_SHOT, &alpha, &TrackEdit::Delete { frame: 2.0 }).unwrap_err();
        let (line, col) = position_of(STYLED_SHOT, STYLED_SHOT.find("[(1, 0.6)").unwrap());
        assert_eq!(error.place(), Some((line, col)));
        assert!(
            error
                .message()
                .ends_with("has no key at frame 2; its keys are at frames 1, 24"),
            "{error}"
        );
        let error = edit_text(STYLED_SHOT, &param_path("camera.eye"), &set("0.5")).unwrap_err();
        assert!(matches!(error, EditError::BadValue { .. }), "{error}");
        let error =
            edit_text(STYLED_SHOT, &param_path("light.towards"), &set("(0, 0, 0)")).unwrap_err();
        assert!(error.message().contains("no length"), "{error}");
        assert_eq!(
            edit_text(STYLED_SHOT, &alpha, &key(f64::INFINITY, "0.1")),
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
            (param_path("camera.eye"), key(1.0, "(0, -6, 0)")),
            (param_path("camera.eye"), key(24.0, "(6, 0, 0)")),
            (param_path("highlights[1].layers[0].epsilon"), set("0.02")),
        ];
        let text = apply_edits(STYLED_SHOT, &edits).unwrap();
        let expected = shot_with(
            "eye: (0.0, -6.0, 0.0)",
            "eye: [(1, (0.0, -6.0, 0.0)), (24, (6.0, 0.0, 0.0))]",
        )
        .replace("epsilon: 0.01", "epsilon: 0.02");
        assert_eq!(text, expected);
        let looks =
            "Looks(\n    materials: {\n        \"clay\": Cel(base: (0.3, 0.1, 0.06)),\n    },\n)\n";
        let at = param_path("materials{\"clay\"}.base");
        assert_eq!(
            edit_text(looks, &at, &key(10.0, "(0.2, 0.1, 0.1)")).unwrap(),
            looks.replace("(0.3, 0.1, 0.06)", "[(10, (0.2, 0.1, 0.1))]")
        );
        assert!(parse_param_path(looks, "camera.eye").is_err());
    }
}
