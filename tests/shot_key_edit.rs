//! One track of every shipped shot and look file edited in its text (`glint::shot::edit_text`):
//! every byte outside the track's text as it was, every other track as it was, and the edited
//! track what the edit asks — for every parameter path of every file, and for random paths,
//! frames and values.

use std::path::PathBuf;

use glam::Vec3;
use glint::anim::{Key, Track};
use glint::shot::{
    edit_text, param_paths, track_span, track_text, track_texts, DetailParam, EditError,
    LayerParam, MaterialParam, ParamPath, TrackEdit,
};
use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};

use crate::common::repo_file;

/// Every shipped shot and look file with its text.
fn shipped() -> Vec<(PathBuf, String)> {
    let mut files = Vec::new();
    for folder in ["shots", "shots/looks"] {
        for entry in std::fs::read_dir(repo_file(folder)).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_some_and(|e| e == "ron") {
                let text = std::fs::read_to_string(&path).unwrap();
                files.push((path, text));
            }
        }
    }
    files.sort();
    assert!(files.len() >= 10, "only {} files", files.len());
    files
}

/// How the value of the track at `path` is written.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Shape {
    /// One number, one track.
    Number,
    /// `(x, y, z)`, one track.
    Vector,
    /// `(a, b, c)`, three tracks.
    Triple,
}

fn shape(path: &ParamPath) -> Shape {
    match path {
        ParamPath::Camera(param) => match param {
            glint::shot::CameraParam::Eye
            | glint::shot::CameraParam::Target
            | glint::shot::CameraParam::Up => Shape::Vector,
            glint::shot::CameraParam::FovYDegrees
            | glint::shot::CameraParam::Height
            | glint::shot::CameraParam::OrbitAzimuth
            | glint::shot::CameraParam::OrbitElevation
            | glint::shot::CameraParam::OrbitDistance
            | glint::shot::CameraParam::OrbitRadius
            | glint::shot::CameraParam::OrbitHeight => Shape::Number,
        },
        ParamPath::Light(_) => Shape::Vector,
        ParamPath::Material { param, .. } => match param {
            MaterialParam::Base | MaterialParam::BandColour(_) => Shape::Vector,
            MaterialParam::Detail(DetailParam::Focus(None)) => Shape::Triple,
            MaterialParam::Threshold(_) | MaterialParam::Detail(_) | MaterialParam::ShapeWeight => {
                Shape::Number
            }
        },
        ParamPath::Highlight { param, .. } => match param {
            LayerParam::Colour(None) => Shape::Triple,
            LayerParam::Colour(Some(_))
            | LayerParam::Epsilon
            | LayerParam::Opacity
            | LayerParam::Feather
            | LayerParam::MaskU(_)
            | LayerParam::MaskV(_)
            | LayerParam::MaskFeather
            | LayerParam::PinU
            | LayerParam::PinV
            | LayerParam::Op { .. } => Shape::Number,
        },
        ParamPath::Shade { .. } => Shape::Number,
    }
}

/// A track as shown by `track_text`, read as one scalar track per component (`none`, an
/// absent feather, as no track).
fn components(shown: &str, shape: Shape) -> Vec<Track<f32>> {
    if shown == "none" {
        return Vec::new();
    }
    fn read<T: serde::de::DeserializeOwned>(shown: &str) -> T {
        ron::from_str(shown).unwrap_or_else(|e| panic!("{shown}: {e}"))
    }
    match shape {
        Shape::Number => vec![read::<Track<f32>>(shown)],
        Shape::Triple => read::<[Track<f32>; 3]>(shown).to_vec(),
        Shape::Vector => {
            let track = read::<Track<Vec3>>(shown);
            (0..3)
                .map(|c| match &track {
                    Track::Constant(v) => Track::Constant(v[c]),
                    Track::Keys(keys) => Track::Keys(
                        keys.iter()
                            .map(|k| Key {
                                frame: k.frame,
                                value: k.value[c],
                            })
                            .collect(),
                    ),
                })
                .collect()
        }
    }
}

fn frames(track: &Track<f32>) -> Vec<f64> {
    track.key_frames().collect()
}

/// What an edit makes of one component track, as docs/shot-format.md says: set, the constant;
/// keyed, the key at the frame replaced or added in frame order (a constant or no track: the
/// one key); deleted, the key gone (the last: its value as the constant), a track without that
/// key untouched.
fn expected(old: Option<&Track<f32>>, edit: &Edit, value: f32) -> Option<Track<f32>> {
    let keys = match old {
        Some(Track::Keys(keys)) => keys.clone(),
        Some(Track::Constant(_)) | None => Vec::new(),
    };
    Some(match *edit {
        Edit::Set => Track::Constant(value),
        Edit::Key(frame) => {
            let mut keys: Vec<Key<f32>> = keys.into_iter().filter(|k| k.frame != frame).collect();
            keys.push(Key { frame, value });
            keys.sort_by(|a, b| a.frame.total_cmp(&b.frame));
            Track::Keys(keys)
        }
        Edit::Delete(frame) => match keys.iter().position(|k| k.frame == frame) {
            None => return old.cloned(),
            Some(_) if keys.len() == 1 => Track::Constant(keys[0].value),
            Some(at) => {
                let mut keys = keys;
                keys.remove(at);
                Track::Keys(keys)
            }
        },
    })
}

#[derive(Clone, Copy, Debug)]
enum Edit {
    Set,
    Key(f64),
    Delete(f64),
}

/// Edits `path` in `text` with `values` and checks the result; a key to delete that no component
/// has must be refused.
fn check(file: &str, text: &str, path: &ParamPath, edit: Edit, values: [f32; 3]) {
    let shape = shape(path);
    let written: Vec<String> = values.iter().map(|v| v.to_string()).collect();
    let value = match shape {
        Shape::Number => written[0].clone(),
        Shape::Vector | Shape::Triple => format!("({})", written.join(", ")),
    };
    let track_edit = match edit {
        Edit::Set => TrackEdit::Set(value),
        Edit::Key(frame) => TrackEdit::Key { frame, value },
        Edit::Delete(frame) => TrackEdit::Delete { frame },
    };
    let context = format!("{file}: {path}: {track_edit:?}");
    let before = components(&track_text(text, path).unwrap(), shape);
    let result = edit_text(text, path, &track_edit);
    if let Edit::Delete(frame) = edit {
        let has_key = before.iter().any(|t| frames(t).contains(&frame));
        if !has_key {
            assert!(
                matches!(result, Err(EditError::NoKey { .. })),
                "{context}: {result:?}"
            );
            return;
        }
    }
    let edited = result.unwrap_or_else(|e| panic!("{context}: {e}"));

    // Every byte outside the track's text is as it was.
    let prefix = text
        .bytes()
        .zip(edited.bytes())
        .take_while(|(a, b)| a == b)
        .count();
    let suffix = text
        .bytes()
        .rev()
        .zip(edited.bytes().rev())
        .take_while(|(a, b)| a == b)
        .count();
    match track_span(text, path).unwrap() {
        Some(span) => assert!(
            prefix >= span.start && suffix >= text.len() - span.end,
            "{context}: bytes outside {span:?} changed"
        ),
        // Not written: the edit adds it, and removes nothing.
        None => assert!(
            prefix + suffix >= text.len(),
            "{context}: bytes were removed"
        ),
    }

    // Every other track is as it was, and there are the same tracks.
    let (whole, _) = path.without_component();
    let old_tracks = track_texts(text).unwrap();
    let new_tracks = track_texts(&edited).unwrap();
    assert_eq!(
        old_tracks.iter().map(|t| &t.0).collect::<Vec<_>>(),
        new_tracks.iter().map(|t| &t.0).collect::<Vec<_>>(),
        "{context}"
    );
    for ((other, old), (_, new)) in old_tracks.iter().zip(&new_tracks) {
        if other.without_component().0 != whole {
            assert_eq!(old, new, "{context}: {other} changed");
        }
    }

    // The edited track is what the edit asks.
    let after = components(&track_text(&edited, path).unwrap(), shape);
    let count = match shape {
        Shape::Number => 1,
        Shape::Vector | Shape::Triple => 3,
    };
    assert_eq!(after.len(), count, "{context}");
    for (c, after) in after.iter().enumerate() {
        let want = expected(before.get(c), &edit, values[c]);
        assert_eq!(Some(after), want.as_ref(), "{context}: component {c}");
    }
}

#[test]
fn every_track_of_every_shipped_file_is_set_keyed_and_unkeyed_alone() {
    let mut edits = 0;
    for (file, text) in shipped() {
        let file = file.display().to_string();
        for path in param_paths(&text).unwrap() {
            let shape = shape(&path);
            let before = components(&track_text(&text, &path).unwrap(), shape);
            let values = [0.25, 0.5, 0.75];
            check(&file, &text, &path, Edit::Set, values);
            check(&file, &text, &path, Edit::Key(0.5), values);
            edits += 2;
            if let Some(&first) = before.iter().flat_map(frames).collect::<Vec<_>>().first() {
                check(&file, &text, &path, Edit::Key(first), values);
                check(&file, &text, &path, Edit::Delete(first), values);
                edits += 2;
            }
        }
    }
    assert!(edits > 300, "only {edits} edits");
}

#[test]
fn random_paths_frames_and_values_edit_one_track_alone() {
    let files = shipped();
    let sites: Vec<(usize, ParamPath)> = files
        .iter()
        .enumerate()
        .flat_map(|(i, (_, text))| param_paths(text).unwrap().into_iter().map(move |p| (i, p)))
        .collect();
    let strategy = (
        0..sites.len(),
        0..3u8,
        any::<prop::sample::Index>(),
        any::<bool>(),
        -20.0f64..140.0,
        prop::array::uniform3(-10.0f32..10.0),
    );
    let mut runner = TestRunner::new(Config {
        cases: 256,
        failure_persistence: None,
        ..Config::default()
    });
    runner
        .run(
            &strategy,
            |(site, kind, pick, existing, frame, mut values)| {
                let (file, path) = &sites[site];
                let (name, text) = &files[*file];
                let shape = shape(path);
                let keys: Vec<f64> = components(&track_text(text, path).unwrap(), shape)
                    .iter()
                    .flat_map(frames)
                    .collect();
                // Half the time a frame that is a key; otherwise one on the half-frame grid.
                let frame = match (existing, keys.is_empty()) {
                    (true, false) => *pick.get(&keys),
                    _ => (frame * 2.0).round() / 2.0,
                };
                // A direction may not be (0, 0, 0).
                values[0] = values[0].abs().max(0.01);
                let edit = match kind {
                    0 => Edit::Set,
                    1 => Edit::Key(frame),
                    _ => Edit::Delete(frame),
                };
                check(&name.display().to_string(), text, path, edit, values);
                Ok(())
            },
        )
        .unwrap();
}

#[test]
fn the_documented_example_paths_resolve_on_their_shots() {
    let doc = std::fs::read_to_string(repo_file("docs/shot-format.md")).unwrap();
    let start = doc.find("## Parameter paths").unwrap();
    let end = doc[start..]
        .find("## Editing from the command line")
        .unwrap()
        + start;
    let mut checked = 0;
    for row in doc[start..end].lines() {
        // `| `PATH` | `shots/FILE.ron` … |`
        let cells: Vec<&str> = row.split(" | ").collect();
        let (Some(path), Some(file)) = (cells.first(), cells.get(1)) else {
            continue;
        };
        let (Some(path), Some(file)) = (
            path.strip_prefix("| `").and_then(|p| p.strip_suffix('`')),
            file.strip_prefix("`shots/")
                .and_then(|f| f.split('`').next()),
        ) else {
            continue;
        };
        let text = std::fs::read_to_string(repo_file(&format!("shots/{file}"))).unwrap();
        let parsed = glint::shot::parse_param_path(&text, path)
            .unwrap_or_else(|e| panic!("{file}: {path}: {e}"));
        assert_eq!(parsed.to_string(), path);
        checked += 1;
    }
    assert!(checked >= 12, "only {checked} examples");
}

#[test]
fn an_edited_text_loads_as_the_shot_it_would_be_without_writing_it() {
    let shipped = repo_file("shots/sphere_ops.ron");
    let text = std::fs::read_to_string(&shipped).unwrap();
    let epsilon: ParamPath = "highlights[0].layers[0].epsilon".parse().unwrap();
    let edits = [
        (
            epsilon.clone(),
            TrackEdit::Key {
                frame: 1.0,
                value: "0.02".into(),
            },
        ),
        (
            epsilon,
            TrackEdit::Key {
                frame: 61.0,
                value: "0.06".into(),
            },
        ),
    ];
    let edited = glint::shot::apply_edits(&text, &edits).unwrap();
    // A file of that name does not exist; the sphere it places is still found beside it.
    let beside = repo_file("shots/sphere_ops_variant.ron");
    assert!(!beside.exists());
    let shot = glint::shot::load_shot_text(&beside, edited).unwrap();
    let epsilon_at = |frame: f64| match &shot.at(frame).highlights[0] {
        glint::highlight::Expr::Layer(layer) => layer.epsilon,
        other => panic!("{other:?}"),
    };
    assert_eq!(epsilon_at(1.0), 0.02);
    assert!((epsilon_at(31.0) - 0.04).abs() < 1e-6);
    assert_eq!(epsilon_at(90.0), 0.06);
    assert_eq!(shot.path, beside);
    // The same text loads as the shipped file does.
    let same = glint::shot::load_shot_text(&beside, text).unwrap();
    assert_eq!(
        same.at(31.0),
        glint::shot::load_shot(&shipped).unwrap().at(31.0)
    );
}
