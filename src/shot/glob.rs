//! Glob patterns over patch names: `*` any run of characters (including none), `?` one
//! character, `[abc]` / `[a-c]` / `[!a-c]` one character of (or not of) a set.

/// Calls `pick` with every patch of `library` that `pattern` picks: the patches it names and
/// the members of the parts it names (a patch once per part that holds it). Whether it picked
/// any.
pub(super) fn pick_each(
    pattern: &str,
    library: &crate::geom::PatchLibrary,
    mut pick: impl FnMut(usize),
) -> bool {
    let mut any = false;
    for (patch, named) in library.patches.iter().enumerate() {
        if matches(pattern, &named.name) {
            pick(patch);
            any = true;
        }
    }
    for group in &library.groups {
        if matches(pattern, &group.name) {
            group.patches.iter().for_each(|&patch| pick(patch));
            any = true;
        }
    }
    any
}

/// Whether `name` matches `pattern` as a whole.
pub fn matches(pattern: &str, name: &str) -> bool {
    let pattern: Vec<char> = pattern.chars().collect();
    let name: Vec<char> = name.chars().collect();
    matches_from(&pattern, &name)
}

fn matches_from(pattern: &[char], name: &[char]) -> bool {
    match pattern.split_first() {
        None => name.is_empty(),
        Some(('*', rest)) => (0..=name.len()).any(|skip| matches_from(rest, &name[skip..])),
        Some((first, rest)) => {
            let Some((&c, name_rest)) = name.split_first() else {
                return false;
            };
            match first {
                '?' => matches_from(rest, name_rest),
                '[' => match class(rest, c) {
                    Some((true, after)) => matches_from(after, name_rest),
                    Some((false, _)) => false,
                    // An unclosed `[` stands for itself.
                    None => c == '[' && matches_from(rest, name_rest),
                },
                &literal => literal == c && matches_from(rest, name_rest),
            }
        }
    }
}

/// Whether `c` is in the set that starts just after a `[`, and the pattern after its `]`;
/// `None` when the set is not closed.
fn class(pattern: &[char], c: char) -> Option<(bool, &[char])> {
    let (negated, body) = match pattern.first() {
        Some('!') => (true, &pattern[1..]),
        _ => (false, pattern),
    };
    // A `]` right at the start is a member, not the end.
    let start = usize::from(body.first() == Some(&']'));
    let end = start + body.get(start..)?.iter().position(|&x| x == ']')?;
    let set = &body[..end];
    let mut found = false;
    let mut i = 0;
    while i < set.len() {
        if i + 2 < set.len() && set[i + 1] == '-' {
            found |= (set[i]..=set[i + 2]).contains(&c);
            i += 3;
        } else {
            found |= set[i] == c;
            i += 1;
        }
    }
    Some((found != negated, &body[end + 1..]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stars_questions_and_sets_match_what_shells_match() {
        assert!(matches("teapot/*", "teapot/12"));
        assert!(matches("*", ""));
        assert!(!matches("teapot/*", "car/12"));
        assert!(matches("teapot/1?", "teapot/12"));
        assert!(!matches("teapot/1?", "teapot/1"));
        assert!(matches("teapot/1[6-9]", "teapot/17"));
        assert!(!matches("teapot/1[6-9]", "teapot/15"));
        assert!(matches("teapot/[!0-9]*", "teapot/lid"));
        assert!(!matches("teapot/[!0-9]*", "teapot/3"));
        assert!(matches("a[]]b", "a]b"));
        assert!(matches("a[b", "a[b"));
        assert!(matches("*/hood", "car/hood"));
        assert!(matches("c*r/*o*d", "car/hood"));
    }
}
