//! A track shown on one line: as it is written in the file, or as its default would be written.

use super::number_text::{frame_text, number_text, value_text};
use super::param_sites::TrackMut;
use crate::anim::Track;

/// A track's text on one line: comments and line breaks dropped, blanks between items kept as
/// one space, no comma before a closing bracket. A track holds no strings, so every `//` in it
/// starts a comment.
#[must_use]
pub(super) fn one_line(written: &str) -> String {
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
#[must_use]
pub(super) fn default_text(track: &TrackMut) -> String {
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
#[must_use]
pub(super) fn written_track<T>(track: &Track<T>, components: impl Fn(&T) -> Vec<f32>) -> String {
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
