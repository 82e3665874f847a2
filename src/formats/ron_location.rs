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

    #[test]
    fn misspellings_find_their_field_and_strangers_do_not() {
        let fields = ["epsilon", "colour", "opacity", "stack"];
        assert_eq!(closest_name("epsilom", &fields), Some("epsilon"));
        assert_eq!(closest_name("color", &fields), Some("colour"));
        assert_eq!(closest_name("zebra", &fields), None);
    }
}
