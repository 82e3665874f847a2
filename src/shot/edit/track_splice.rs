//! How a track's text changes: its value replaced, a key's value replaced, a key inserted into
//! or removed from its list in the style the list is written in, or a field that was left out
//! added — each one splice of the text, every byte outside it kept.

use std::ops::Range;

use crate::formats::ron_paths::Step::{self, Field, Index};
use crate::formats::ron_paths::{try_item_spans, try_span};

/// Bytes `span` of a text replaced by `text` (an insertion where the span is empty).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(super) struct Splice {
    pub span: Range<usize>,
    pub text: String,
}

/// A track's edit as text: the value and the frame already written.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum TextEdit {
    /// Make the track the constant written `value`.
    Set { value: String },
    /// Key it at `frame` (written `frame_text`) to the value written `value`.
    Key {
        frame: f64,
        frame_text: String,
        value: String,
    },
    /// Delete its key at `frame`.
    Delete { frame: f64 },
}

/// `text` with `splices` applied; they must not overlap.
#[must_use]
pub(super) fn apply(text: &str, splices: &[Splice]) -> String {
    let mut ordered: Vec<&Splice> = splices.iter().collect();
    ordered.sort_by_key(|s| std::cmp::Reverse(s.span.start));
    let mut out = text.to_string();
    for splice in ordered {
        out.replace_range(splice.span.clone(), &splice.text);
    }
    out
}

/// The splice that makes the track written at `steps` of `text` what `edit` says, given the
/// frames of its keys (`None` for a constant, or for a track that is not written).
///
/// - Set: the track's text becomes the value.
/// - Key: a constant becomes `[(frame, value)]`; in a list, the value of the key at the frame is
///   replaced, or the new key is inserted before the first key after it ([`insert_item`]).
/// - Delete: the key is removed from its list ([`remove_item`]); the last key gives way to the
///   text of its value.
/// - A track left out (a defaulted field) is added to its struct as `name: text`.
///
/// `None` when the text is not shaped as the frames say, or when deleting a key the track does
/// not have.
#[must_use]
pub(super) fn track_splice(
    text: &str,
    steps: &[Step],
    frames: Option<&[f64]>,
    edit: &TextEdit,
) -> Option<Splice> {
    let Some(span) = try_span(text, steps) else {
        let (Field(name), parent) = steps.split_last()? else {
            return None;
        };
        let written = match edit {
            TextEdit::Set { value } => value.clone(),
            TextEdit::Key {
                frame_text, value, ..
            } => format!("[({frame_text}, {value})]"),
            TextEdit::Delete { .. } => return None,
        };
        let fields = try_item_spans(text, parent)?;
        return insert_item(text, &fields, None, &format!("{name}: {written}"));
    };
    let key_at = |frame: f64| frames.and_then(|f| f.iter().position(|&k| k == frame));
    let item = |index: usize, part: usize| {
        let mut path = steps.to_vec();
        path.extend([Index(index), Index(part)]);
        try_span(text, &path)
    };
    match (edit, frames) {
        (TextEdit::Set { value }, _) => Some(Splice {
            span,
            text: value.clone(),
        }),
        (
            TextEdit::Key {
                frame_text, value, ..
            },
            None,
        ) => Some(Splice {
            span,
            text: format!("[({frame_text}, {value})]"),
        }),
        (
            TextEdit::Key {
                frame,
                frame_text,
                value,
            },
            Some(frames),
        ) => match key_at(*frame) {
            Some(index) => Some(Splice {
                span: item(index, 1)?,
                text: value.clone(),
            }),
            None => {
                let keys = try_item_spans(text, steps)?;
                let before = frames.iter().position(|&k| k > *frame);
                let key = format!("({frame_text}, {value})");
                (keys.len() == frames.len())
                    .then(|| insert_item(text, &keys, before, &key))
                    .flatten()
            }
        },
        (TextEdit::Delete { .. }, None) => None,
        (TextEdit::Delete { frame }, Some(frames)) => {
            let index = key_at(*frame)?;
            if frames.len() == 1 {
                let value = item(index, 1)?;
                return Some(Splice {
                    span,
                    text: text[value].to_string(),
                });
            }
            let keys = try_item_spans(text, steps)?;
            (keys.len() == frames.len()).then(|| remove_item(text, &keys, index))
        }
    }
}

/// Where the line holding byte `at` starts.
fn line_start(text: &str, at: usize) -> usize {
    text[..at].rfind('\n').map_or(0, |i| i + 1)
}

/// Where the line holding byte `at` ends: at its `\r\n` or `\n`, or the end of the text.
fn line_end(text: &str, at: usize) -> usize {
    let end = text[at..].find('\n').map_or(text.len(), |i| at + i);
    if end > at && text.as_bytes()[end - 1] == b'\r' {
        end - 1
    } else {
        end
    }
}

/// Where the line after the one holding byte `at` starts (the end of the text on the last).
fn next_line_start(text: &str, at: usize) -> usize {
    text[at..].find('\n').map_or(text.len(), |i| at + i + 1)
}

/// The line break the text uses: `\r\n` where it has one, `\n` otherwise.
fn line_break(text: &str) -> &'static str {
    if text.contains("\r\n") {
        "\r\n"
    } else {
        "\n"
    }
}

/// The blanks before `at` on its line, when nothing else is before it there.
fn alone_indent(text: &str, at: usize) -> Option<&str> {
    let before = &text[line_start(text, at)..at];
    before.trim().is_empty().then_some(before)
}

/// Where the comma after an item ending at `end` ends, if one follows it (after spaces).
fn comma_after(text: &str, end: usize) -> Option<usize> {
    let rest = &text[end..];
    let spaces = rest.len() - rest.trim_start_matches([' ', '\t']).len();
    rest[spaces..].starts_with(',').then_some(end + spaces + 1)
}

/// Whether the rest of the line from `at` holds nothing but blanks and a `//` comment.
fn rest_of_line_is_blank(text: &str, at: usize) -> bool {
    let rest = text[at..line_end(text, at)].trim_start();
    rest.is_empty() || rest.starts_with("//")
}

/// The splice that adds `item` to a bracketed group whose items are written at `items` (at
/// least one): before item `before`, or after the last one for `None` or an index past it. A
/// group written one item to a line gets the new item on a line of its own, indented as its
/// neighbour and followed by a comma; a group on one line gets it with `, ` between. `None`
/// when `items` is empty.
#[must_use]
pub(super) fn insert_item(
    text: &str,
    items: &[Range<usize>],
    before: Option<usize>,
    item: &str,
) -> Option<Splice> {
    let insert = |at: usize, text: String| Splice { span: at..at, text };
    let br = line_break(text);
    if let Some(next) = before.and_then(|i| items.get(i)) {
        return Some(match alone_indent(text, next.start) {
            Some(indent) => insert(next.start, format!("{item},{br}{indent}")),
            None => insert(next.start, format!("{item}, ")),
        });
    }
    let last = items.last()?;
    Some(
        match (alone_indent(text, last.start), comma_after(text, last.end)) {
            (Some(indent), Some(comma)) if rest_of_line_is_blank(text, comma) => {
                insert(line_end(text, comma), format!("{br}{indent}{item},"))
            }
            (Some(indent), Some(comma)) => insert(comma, format!("{br}{indent}{item},")),
            (Some(indent), None) => insert(last.end, format!(",{br}{indent}{item}")),
            (None, _) => insert(last.end, format!(", {item}")),
        },
    )
}

/// The splice that removes item `index` of a bracketed group whose items are written at `items`
/// (at least two). An item alone on its line goes with its line (its comma and a `//` comment
/// after it included); otherwise it goes with the separator after it, or, the last item, with
/// the separator before it.
#[must_use]
pub(super) fn remove_item(text: &str, items: &[Range<usize>], index: usize) -> Splice {
    let item = &items[index];
    let after = comma_after(text, item.end).unwrap_or(item.end);
    let span = if alone_indent(text, item.start).is_some() && rest_of_line_is_blank(text, after) {
        line_start(text, item.start)..next_line_start(text, after)
    } else if let Some(next) = items.get(index + 1) {
        item.start..next.start
    } else {
        items[index - 1].end..item.end
    };
    Splice {
        span,
        text: String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spans(text: &str, items: &[&str]) -> Vec<Range<usize>> {
        items
            .iter()
            .map(|item| {
                let start = text.find(item).unwrap();
                start..start + item.len()
            })
            .collect()
    }

    #[test]
    fn insertions_follow_a_one_line_group() {
        let text = "[(1, 0.5), (17, 0.25)]";
        let items = spans(text, &["(1, 0.5)", "(17, 0.25)"]);
        let with = |before| {
            apply(
                text,
                &[insert_item(text, &items, before, "(9, 0.1)").unwrap()],
            )
        };
        assert_eq!(with(Some(0)), "[(9, 0.1), (1, 0.5), (17, 0.25)]");
        assert_eq!(with(Some(1)), "[(1, 0.5), (9, 0.1), (17, 0.25)]");
        assert_eq!(with(None), "[(1, 0.5), (17, 0.25), (9, 0.1)]");
    }

    #[test]
    fn insertions_follow_a_group_of_one_item_a_line() {
        let text = "[\n    (1, 0.5), // first\n    (17, 0.25),\n]";
        let items = spans(text, &["(1, 0.5)", "(17, 0.25)"]);
        let with = |before| {
            apply(
                text,
                &[insert_item(text, &items, before, "(9, 0.1)").unwrap()],
            )
        };
        assert_eq!(
            with(Some(1)),
            "[\n    (1, 0.5), // first\n    (9, 0.1),\n    (17, 0.25),\n]"
        );
        assert_eq!(
            with(None),
            "[\n    (1, 0.5), // first\n    (17, 0.25),\n    (9, 0.1),\n]"
        );
        let bare = "(\n  a: 1,\n  b: 2 // two\n)";
        let fields = spans(bare, &["a: 1", "b: 2"]);
        assert_eq!(
            apply(bare, &[insert_item(bare, &fields, None, "c: 3").unwrap()]),
            "(\n  a: 1,\n  b: 2,\n  c: 3 // two\n)"
        );
        let commented = "(\n  a: 1,\n  b: 2, // two\n)";
        let fields = spans(commented, &["a: 1", "b: 2"]);
        assert_eq!(
            apply(
                commented,
                &[insert_item(commented, &fields, None, "c: 3").unwrap()]
            ),
            "(\n  a: 1,\n  b: 2, // two\n  c: 3,\n)"
        );
    }

    #[test]
    fn removals_take_their_separator_or_their_line() {
        let text = "[(1, 0.5), (9, 0.1), (17, 0.25)]";
        let items = spans(text, &["(1, 0.5)", "(9, 0.1)", "(17, 0.25)"]);
        let without = |index| apply(text, &[remove_item(text, &items, index)]);
        assert_eq!(without(0), "[(9, 0.1), (17, 0.25)]");
        assert_eq!(without(1), "[(1, 0.5), (17, 0.25)]");
        assert_eq!(without(2), "[(1, 0.5), (9, 0.1)]");
        let lines = "[\n    (1, 0.5),\n    (9, 0.1), // mid\n    (17, 0.25)\n]";
        let items = spans(lines, &["(1, 0.5)", "(9, 0.1)", "(17, 0.25)"]);
        let without = |index| apply(lines, &[remove_item(lines, &items, index)]);
        assert_eq!(without(1), "[\n    (1, 0.5),\n    (17, 0.25)\n]");
        assert_eq!(without(2), "[\n    (1, 0.5),\n    (9, 0.1), // mid\n]");
        // An item that shares its line goes with its separator, though the line ends after it.
        let shared = "[\n    (1, 0.5), (9, 0.1)\n]";
        let items = spans(shared, &["(1, 0.5)", "(9, 0.1)"]);
        let without = |index| apply(shared, &[remove_item(shared, &items, index)]);
        assert_eq!(without(1), "[\n    (1, 0.5)\n]");
        assert_eq!(without(0), "[\n    (9, 0.1)\n]");
        // A comma written after spaces goes with its item.
        let spaced = "[\n    (1, 0.5) ,\n    (9, 0.1) , // mid\n    (17, 0.25)\n]";
        let items = spans(spaced, &["(1, 0.5)", "(9, 0.1)", "(17, 0.25)"]);
        assert_eq!(
            apply(spaced, &[remove_item(spaced, &items, 1)]),
            "[\n    (1, 0.5) ,\n    (17, 0.25)\n]"
        );
    }

    #[test]
    fn an_item_added_before_a_closing_bracket_on_its_line_goes_before_it() {
        let text = "[\n    (1, 0.5),\n    (17, 0.25), ]";
        let items = spans(text, &["(1, 0.5)", "(17, 0.25)"]);
        assert_eq!(
            apply(
                text,
                &[insert_item(text, &items, None, "(20, 0.1)").unwrap()]
            ),
            "[\n    (1, 0.5),\n    (17, 0.25),\n    (20, 0.1), ]"
        );
        // After a comma written after spaces.
        let spaced = "[\n    (1, 0.5) , // one\n]";
        let items = spans(spaced, &["(1, 0.5)"]);
        assert_eq!(
            apply(
                spaced,
                &[insert_item(spaced, &items, None, "(20, 0.1)").unwrap()]
            ),
            "[\n    (1, 0.5) , // one\n    (20, 0.1),\n]"
        );
    }

    #[test]
    fn lines_end_as_the_text_ends_them() {
        let text = "[\r\n    (1, 0.5), // first\r\n    (17, 0.25),\r\n]";
        let items = spans(text, &["(1, 0.5)", "(17, 0.25)"]);
        let added = apply(
            text,
            &[insert_item(text, &items, None, "(20, 0.1)").unwrap()],
        );
        assert_eq!(
            added,
            "[\r\n    (1, 0.5), // first\r\n    (17, 0.25),\r\n    (20, 0.1),\r\n]"
        );
        // Before an item past the last: after the last.
        let past = insert_item(text, &items, Some(2), "(20, 0.1)").unwrap();
        assert_eq!(apply(text, &[past]), added);
        let added = apply(
            text,
            &[insert_item(text, &items, Some(1), "(9, 0.1)").unwrap()],
        );
        assert_eq!(
            added,
            "[\r\n    (1, 0.5), // first\r\n    (9, 0.1),\r\n    (17, 0.25),\r\n]"
        );
        assert_eq!(
            apply(text, &[remove_item(text, &items, 0)]),
            "[\r\n    (17, 0.25),\r\n]"
        );
        // From anywhere on a line, its end is there or after, before its line break.
        for at in 0..=text.len() {
            let end = line_end(text, at);
            assert!(
                end >= at && !text[at..end].contains(['\r', '\n']),
                "{at}: {end}"
            );
        }
    }

    #[test]
    fn splices_apply_from_the_back_so_spans_stay_true() {
        let text = "(a, b, c)";
        let splices = [
            Splice {
                span: 1..2,
                text: "[(1, a)]".into(),
            },
            Splice {
                span: 7..8,
                text: "z".into(),
            },
        ];
        assert_eq!(apply(text, &splices), "([(1, a)], b, z)");
        assert_eq!(insert_item(text, &[], None, "x"), None);
    }
}
