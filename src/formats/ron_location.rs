//! Positions in RON text for error messages: 1-based line and column, where a value starts, and
//! the closest valid name to a misspelt one.

/// The 1-based line and column of byte `offset` in `text`.
pub fn position_of(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before[before.rfind('\n').map_or(0, |i| i + 1)..]
        .chars()
        .count()
        + 1;
    (line, col)
}

/// The byte offset of 1-based `(line, col)` in `text`, if it is inside the text.
fn offset_of(text: &str, (line, col): (usize, usize)) -> Option<usize> {
    let line_start = text
        .split_inclusive('\n')
        .take(line.checked_sub(1)?)
        .map(str::len)
        .sum::<usize>();
    Some(
        line_start
            + text
                .get(line_start..)?
                .char_indices()
                .nth(col.checked_sub(1)?)?
                .0,
    )
}

/// Where the value that ends with the `)` or `]` at 1-based `(line, col)` starts: the
/// identifier before its matching `(` (as in `Nurbs(...)`), or the bracket itself. `None` when
/// no closing bracket is there.
pub fn start_of_value_closed_at(text: &str, at: (usize, usize)) -> Option<(usize, usize)> {
    let close = offset_of(text, at)?;
    let (open_char, close_char) = match text.as_bytes().get(close) {
        Some(b')') => ('(', ')'),
        Some(b']') => ('[', ']'),
        _ => return None,
    };
    let mut depth = 0usize;
    let open = text[..=close].rfind(|c| {
        if c == close_char {
            depth += 1;
        } else if c == open_char {
            depth -= 1;
        }
        depth == 0
    })?;
    let head = text[..open].trim_end_matches(|c: char| c.is_alphanumeric() || c == '_');
    Some(position_of(text, head.len()))
}

/// The name in `candidates` closest to `found`, if one is close enough to be a likely misspelling.
pub fn closest_name<'a>(found: &str, candidates: &[&'a str]) -> Option<&'a str> {
    candidates
        .iter()
        .map(|&c| (strsim::jaro_winkler(found, c), c))
        .filter(|&(score, _)| score > 0.8)
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, c)| c)
}

/// Where a RON parse error is best shown in `text`, and what to say there, from the parser's
/// error `code` at 1-based `at`:
///
/// - a value that failed its own checks, or lacks a field, is shown where it starts (the parser
///   stops at its closing bracket);
/// - a missing comma is shown right after the value it should follow (the parser stops at the
///   next item, often on the next line), a `;` where a `,` belongs at the `;`, and a file that
///   ends inside a bracket at that bracket;
/// - `=` where a `:` belongs says so, and a missing `:` asks for one;
/// - everything else as [`explain`] words it, where the parser stopped.
#[must_use]
pub fn explain_at(text: &str, code: &ron::Error, at: (usize, usize)) -> ((usize, usize), String) {
    let offset = offset_of(text, at).unwrap_or(text.len());
    let next = text[offset.min(text.len())..].trim_start().chars().next();
    match code {
        ron::Error::Message(_) | ron::Error::MissingStructField { .. } => (
            start_of_value_closed_at(text, at).unwrap_or(at),
            explain(code),
        ),
        ron::Error::ExpectedComma => {
            let last_line = !text[offset.min(text.len())..].trim_end().contains('\n');
            let start = offset
                + (text[offset.min(text.len())..].len()
                    - text[offset.min(text.len())..].trim_start().len());
            match (next, brackets(text)) {
                (Some(';'), _) => (
                    at,
                    "expected `,` here, not `;`: items are separated by commas".into(),
                ),
                (Some('='), _) => (at, COLON_NOT_EQUALS.into()),
                (_, Brackets::Mismatched { open, close }) if close == start => {
                    mismatched(text, open, close)
                }
                (_, Brackets::Unclosed(_)) if last_line => {
                    ends_open(text).unwrap_or_else(|| (at, explain(code)))
                }
                _ => {
                    let end = end_of_previous_value(text, offset);
                    let (line, _) = position_of(text, offset);
                    (
                        position_of(text, end),
                        format!(
                            "a `,` is missing here, between this value and the next item \
                             (line {line}); items of a list, tuple or struct are separated by \
                             commas"
                        ),
                    )
                }
            }
        }
        ron::Error::Eof => ends_open(text).unwrap_or_else(|| (at, explain(code))),
        ron::Error::ExpectedMapColon if next == Some('=') => (at, COLON_NOT_EQUALS.into()),
        ron::Error::ExpectedMapColon => (
            at,
            "expected `:` between a field name (or map key) and its value".into(),
        ),
        _ => (at, explain(code)),
    }
}

/// Where the file ends with a bracket still open, or a bracket closed by another kind, and
/// the message that says so; `None` when every bracket is closed by its own kind.
fn ends_open(text: &str) -> Option<((usize, usize), String)> {
    match brackets(text) {
        Brackets::Unclosed(open) => Some((
            position_of(text, open),
            format!(
                "the file ends before this `{}` is closed",
                &text[open..=open]
            ),
        )),
        Brackets::Mismatched { open, close } => Some(mismatched(text, open, close)),
        Brackets::Balanced => None,
    }
}

/// The message for the closing bracket at `close` that meets the opening one at `open`.
fn mismatched(text: &str, open: usize, close: usize) -> ((usize, usize), String) {
    let want = match text.as_bytes()[open] {
        b'(' => ')',
        b'[' => ']',
        _ => '}',
    };
    let (line, col) = position_of(text, open);
    (
        position_of(text, close),
        format!(
            "this `{}` meets the `{}` opened at line {line}, column {col}: a `{want}` is missing \
             before it",
            &text[close..=close],
            &text[open..=open]
        ),
    )
}

const COLON_NOT_EQUALS: &str = "write `name: value`: a field name is followed by `:`, not `=`";

/// The byte offset just after the last character before `offset` that is not blank or inside
/// a `//` comment: where the value before `offset` ends.
fn end_of_previous_value(text: &str, offset: usize) -> usize {
    let mut end = offset;
    loop {
        let before = text[..end].trim_end();
        // A `//` comment on the last line is skipped whole.
        let line_start = before.rfind('\n').map_or(0, |i| i + 1);
        match code_part(&before[line_start..]) {
            Some(code) if code.trim().is_empty() => end = line_start,
            Some(code) => return line_start + code.trim_end().len(),
            None => return before.len(),
        }
        if end == 0 {
            return 0;
        }
    }
}

/// The part of a line before a `//` comment that is not inside a string; `None` when the line
/// has no such comment.
fn code_part(line: &str) -> Option<&str> {
    let mut in_string = false;
    let mut escaped = false;
    for (i, c) in line.char_indices() {
        match c {
            '\\' if in_string => escaped = !escaped,
            '"' if !escaped => in_string = !in_string,
            '/' if !in_string && line[i..].starts_with("//") => return Some(&line[..i]),
            _ => escaped = false,
        }
        if c != '\\' {
            escaped = false;
        }
    }
    None
}

/// What the brackets of a text do, strings and comments skipped.
#[derive(Debug, PartialEq)]
enum Brackets {
    /// Every bracket is closed by its own kind.
    Balanced,
    /// The bracket at this byte offset is still open at the end (the innermost such).
    Unclosed(usize),
    /// The closing bracket at `close` meets the opening bracket at `open` of another kind.
    Mismatched { open: usize, close: usize },
}

/// How the brackets of `text` pair up, up to the first that does not.
fn brackets(text: &str) -> Brackets {
    let mut open = Vec::new();
    let mut chars = text.char_indices().peekable();
    while let Some((i, c)) = chars.next() {
        match c {
            '"' => {
                let mut escaped = false;
                for (_, s) in chars.by_ref() {
                    match s {
                        '\\' if !escaped => escaped = true,
                        '"' if !escaped => break,
                        _ => escaped = false,
                    }
                }
            }
            '/' if chars.peek().map(|&(_, n)| n) == Some('/') => {
                for (_, s) in chars.by_ref() {
                    if s == '\n' {
                        break;
                    }
                }
            }
            '(' | '[' | '{' => open.push(i),
            ')' | ']' | '}' => {
                let Some(o) = open.pop() else {
                    return Brackets::Balanced;
                };
                let pair = (text.as_bytes()[o], c);
                if !matches!(pair, (b'(', ')') | (b'[', ']') | (b'{', '}')) {
                    return Brackets::Mismatched { open: o, close: i };
                }
            }
            _ => {}
        }
    }
    open.pop().map_or(Brackets::Balanced, Brackets::Unclosed)
}

/// A RON error message a person can act on: unknown names get the closest valid one and the
/// list of valid ones.
pub fn explain(code: &ron::Error) -> String {
    let list = |names: &[&str]| {
        names
            .iter()
            .map(|n| format!("`{n}`"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let inside = |outer: &Option<String>| {
        outer
            .as_ref()
            .map_or_else(String::new, |o| format!(" in `{o}`"))
    };
    let suggest = |found: &str, expected: &[&str]| {
        closest_name(found, expected).map_or_else(String::new, |c| format!("did you mean `{c}`? "))
    };
    match code {
        ron::Error::NoSuchStructField {
            expected,
            found,
            outer,
        } => format!(
            "unknown field `{found}`{}; {}valid fields are {}",
            inside(outer),
            suggest(found, expected),
            list(expected)
        ),
        ron::Error::NoSuchEnumVariant {
            expected,
            found,
            outer,
        } => format!(
            "unknown variant `{found}`{}; {}valid variants are {}",
            inside(outer),
            suggest(found, expected),
            list(expected)
        ),
        ron::Error::MissingStructField { field, outer } => {
            format!("missing field `{field}`{}; add it", inside(outer))
        }
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_value_starts_at_its_name_or_its_opening_bracket() {
        let text = "(a: Nurbs(x: (1, 2)),\n b: [(1, 2), (3, 4)])";
        assert_eq!(start_of_value_closed_at(text, (1, 20)), Some((1, 5)));
        assert_eq!(start_of_value_closed_at(text, (2, 20)), Some((2, 5)));
        assert_eq!(start_of_value_closed_at(text, (2, 2)), None);
        assert_eq!(start_of_value_closed_at(text, (9, 1)), None);
    }

    fn hint(text: &str) -> ((usize, usize), String) {
        let e = ron::from_str::<ron::Value>(text).unwrap_err();
        explain_at(text, &e.code, (e.span.start.line, e.span.start.col))
    }

    #[test]
    fn a_missing_comma_is_shown_after_the_value_it_should_follow() {
        let (at, message) = hint("(\n  a: 1 // one\n  // more\n  b: 2,\n)");
        assert_eq!(at, (2, 7), "{message}");
        assert!(message.contains("line 4"), "{message}");
        let (at, _) = hint("[(1, 2.0) (3, \"a // b\")]");
        assert_eq!(at, (1, 10));
        let (at, message) = hint("(a: 1; b: 2)");
        assert_eq!(at, (1, 6));
        assert!(message.contains("not `;`"), "{message}");
        let (_, message) = hint("(a = 1)");
        assert!(message.contains("not `=`"), "{message}");
    }

    #[test]
    fn a_file_that_ends_early_points_at_the_open_bracket() {
        let (at, message) = hint("(a: [1, 2,\n  3, \"]\"");
        assert_eq!(at, (1, 5), "{message}");
        assert!(message.contains("`[` is closed"), "{message}");
    }

    #[test]
    fn a_bracket_closed_by_another_kind_names_the_one_it_meets() {
        let (at, message) = hint("(a: [(1, 2.0\n], b: 1)");
        assert_eq!(at, (2, 1), "{message}");
        assert!(
            message.contains("`(` opened at line 1, column 6: a `)` is missing"),
            "{message}"
        );
        assert_eq!(brackets("(\"(\" // (\n)"), Brackets::Balanced);
    }

    #[test]
    fn misspellings_find_their_field_and_strangers_do_not() {
        let fields = ["epsilon", "colour", "opacity", "stack"];
        assert_eq!(closest_name("epsilom", &fields), Some("epsilon"));
        assert_eq!(closest_name("color", &fields), Some("colour"));
        assert_eq!(closest_name("zebra", &fields), None);
    }
}
