//! The variants of `glint sheet --vary PATH=V1,V2,…`: the arguments read, every combination
//! of their values, and the caption each combination goes by.

/// One `--vary PATH=V1,V2,…`: a parameter path of the shot and the values it takes, as written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Vary {
    pub path: String,
    pub values: Vec<String>,
}

/// Reads `PATH=V1,V2,…`. The path is what comes before the first `=`; the values are split on
/// the commas outside brackets, parentheses and double quotes, so that a tuple such as
/// `(1.0, 0.9, 0.8)` is one value. Each value is trimmed; none may be empty.
pub fn parse_vary(text: &str) -> Result<Vary, String> {
    let syntax =
        "write --vary PATH=V1,V2,… such as highlights[0].layers[0].stack[0].alpha=0,0.1,0.2";
    let Some(equals) = outside_brackets(text)
        .find(|&(_, c)| c == '=')
        .map(|(i, _)| i)
    else {
        return Err(format!("'{text}' has no '='; {syntax}"));
    };
    let (path, values) = (text[..equals].trim(), &text[equals + 1..]);
    if path.is_empty() {
        return Err(format!("'{text}' names no parameter before '='; {syntax}"));
    }
    if let Some((_, c)) = outside_brackets(path).find(|&(_, c)| c.is_whitespace()) {
        return Err(format!(
            "the parameter path '{path}' has a space ({c:?}) outside brackets and quotes; {syntax}"
        ));
    }
    split_outside_brackets(path).map_err(|e| format!("the parameter path '{path}': {e}"))?;
    let values = split_outside_brackets(values)
        .map_err(|e| format!("--vary {text}: in the values '{values}', {e}"))?
        .into_iter()
        .map(|v| v.trim().to_owned())
        .collect::<Vec<_>>();
    if values.iter().any(String::is_empty) {
        return Err(format!("'{text}' has an empty value; {syntax}"));
    }
    Ok(Vary {
        path: path.to_owned(),
        values,
    })
}

/// The characters of `text` (with their byte offsets) outside `( )`, `[ ]`, `{ }` and `"…"`,
/// brackets and quotes left out.
fn outside_brackets(text: &str) -> impl Iterator<Item = (usize, char)> + '_ {
    let (mut depth, mut quoted) = (0i32, false);
    text.char_indices().filter(move |&(_, c)| match c {
        '"' => {
            quoted = !quoted;
            false
        }
        _ if quoted => false,
        '(' | '[' | '{' => {
            depth += 1;
            false
        }
        ')' | ']' | '}' => {
            depth -= 1;
            false
        }
        _ => depth <= 0,
    })
}

/// `text` split at the commas outside `( )`, `[ ]`, `{ }` and `"…"`; an unmatched bracket or
/// quote is an error.
fn split_outside_brackets(text: &str) -> Result<Vec<&str>, String> {
    let mut parts = Vec::new();
    let mut open: Vec<char> = Vec::new();
    let mut quoted = false;
    let mut start = 0;
    for (i, c) in text.char_indices() {
        match c {
            '"' => quoted = !quoted,
            _ if quoted => {}
            '(' | '[' | '{' => open.push(c),
            ')' | ']' | '}' => {
                let opener = match c {
                    ')' => '(',
                    ']' => '[',
                    _ => '{',
                };
                if open.pop() != Some(opener) {
                    return Err(format!("'{c}' at character {} closes nothing", i + 1));
                }
            }
            ',' if open.is_empty() => {
                parts.push(&text[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    if quoted {
        return Err("a '\"' is not closed".into());
    }
    if let Some(c) = open.last() {
        return Err(format!("a '{c}' is not closed"));
    }
    parts.push(&text[start..]);
    Ok(parts)
}

/// The number of combinations of `varies`' values (the product of their counts), `None` past
/// `usize`.
#[must_use]
pub fn combination_count(varies: &[Vary]) -> Option<usize> {
    varies
        .iter()
        .try_fold(1usize, |n, v| n.checked_mul(v.values.len()))
}

/// Every combination of `varies`' values as one index into each value list, the last `--vary`
/// changing fastest (as nested loops in the order written).
#[must_use]
pub fn combinations(varies: &[Vary]) -> Vec<Vec<usize>> {
    let mut all = vec![Vec::new()];
    for vary in varies {
        all = all
            .into_iter()
            .flat_map(|prefix| {
                (0..vary.values.len()).map(move |i| {
                    let mut next = prefix.clone();
                    next.push(i);
                    next
                })
            })
            .collect();
    }
    all
}

/// The name each path goes by in a label: its last step (`alpha`), or as many last steps as
/// tell it apart from every other path (`stack[0].alpha` and `stack[1].alpha`). Steps are split
/// at the dots outside brackets.
#[must_use]
pub fn short_names(paths: &[&str]) -> Vec<String> {
    let steps: Vec<Vec<&str>> = paths.iter().map(|p| split_steps(p)).collect();
    let suffix = |s: &[&str], n: usize| s[s.len().saturating_sub(n)..].join(".");
    steps
        .iter()
        .enumerate()
        .map(|(i, own)| {
            (1..=own.len())
                .find(|&n| {
                    let name = suffix(own, n);
                    steps
                        .iter()
                        .enumerate()
                        .all(|(j, other)| j == i || suffix(other, n) != name)
                })
                .map_or_else(|| own.join("."), |n| suffix(own, n))
        })
        .collect()
}

/// `path` split at the dots outside brackets and quotes: `a[0].b{"x.y"}` gives `a[0]` and
/// `b{"x.y"}`.
fn split_steps(path: &str) -> Vec<&str> {
    let mut steps = Vec::new();
    let mut start = 0;
    for (i, _) in outside_brackets(path).filter(|&(_, c)| c == '.') {
        steps.push(&path[start..i]);
        start = i + 1;
    }
    steps.push(&path[start..]);
    steps
}

/// The label of one combination: `NAME=VALUE` for each `--vary`, in the order written, joined
/// by spaces (`alpha=0.2 beta=0.1`).
#[must_use]
pub fn variant_label(names: &[String], varies: &[Vary], combination: &[usize]) -> String {
    names
        .iter()
        .zip(varies)
        .zip(combination)
        .map(|((name, vary), &i)| format!("{name}={}", vary.values[i]))
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_split_on_commas_outside_tuples() {
        let v =
            parse_vary("highlights[1].layers[0].colour=(1.0, 0.9, 0.8), (0.5,0.5,0.5)").unwrap();
        assert_eq!(v.path, "highlights[1].layers[0].colour");
        assert_eq!(v.values, ["(1.0, 0.9, 0.8)", "(0.5,0.5,0.5)"]);
        let v = parse_vary("a.alpha= 0.1,0.2 ,-0.3").unwrap();
        assert_eq!(v.values, ["0.1", "0.2", "-0.3"]);
        let v = parse_vary(r#"materials{"a=b. c"}.base=[(1, (0, 0, 0)), (5, (1, 1, 1))],"x,y""#)
            .unwrap();
        assert_eq!(v.path, r#"materials{"a=b. c"}.base"#);
        assert_eq!(v.values, ["[(1, (0, 0, 0)), (5, (1, 1, 1))]", r#""x,y""#]);
    }

    #[test]
    fn malformed_arguments_say_what_is_wrong() {
        for (bad, says) in [
            ("alpha", "no '='"),
            ("=1,2", "names no parameter"),
            ("a b=1", "has a space"),
            ("a]=1", "']' at character 2 closes nothing"),
            ("alpha=1,,2", "empty value"),
            ("alpha=", "empty value"),
            ("c=(1, 2", "'(' is not closed"),
            ("c=1),2", "')' at character 2 closes nothing"),
            (
                "c=(1, 2]",
                "in the values '(1, 2]', ']' at character 6 closes nothing",
            ),
            ("c=\"a", "'\"' is not closed"),
        ] {
            let e = parse_vary(bad).unwrap_err();
            assert!(e.contains(says), "{bad}: {e}");
        }
    }

    #[test]
    fn combinations_run_as_nested_loops_and_are_counted() {
        let vary = |path: &str, n: usize| Vary {
            path: path.into(),
            values: (0..n).map(|i| i.to_string()).collect(),
        };
        let varies = [vary("a", 2), vary("b", 3)];
        assert_eq!(combination_count(&varies), Some(6));
        assert_eq!(
            combinations(&varies),
            [[0, 0], [0, 1], [0, 2], [1, 0], [1, 1], [1, 2]]
        );
        assert_eq!(combinations(&[]), [Vec::<usize>::new()]);
        // 256 values in each of 8 --vary: 2^64 combinations, past usize.
        let huge = vec![vary("a", 256); 8];
        assert_eq!(combination_count(&huge[..7]), Some(1 << 56));
        assert_eq!(combination_count(&huge), None);
    }

    #[test]
    fn labels_name_each_path_by_its_shortest_distinct_ending() {
        let names = short_names(&[
            "highlights[1].layers[0].stack[0].alpha",
            "highlights[1].layers[0].stack[0].beta",
        ]);
        assert_eq!(names, ["alpha", "beta"]);
        let names = short_names(&[
            "h[0].stack[0].alpha",
            "h[0].stack[1].alpha",
            "light.towards",
        ]);
        assert_eq!(names, ["stack[0].alpha", "stack[1].alpha", "towards"]);
        let names = short_names(&[r#"materials{"a.b"}.base"#, r#"materials{"c"}.base"#]);
        assert_eq!(
            names,
            [r#"materials{"a.b"}.base"#, r#"materials{"c"}.base"#]
        );
        let names = short_names(&["a.x", "b.a.x"]);
        assert_eq!(names, ["a.x", "b.a.x"]);
        let varies = [
            Vary {
                path: "s.alpha".into(),
                values: vec!["0.2".into(), "0.4".into()],
            },
            Vary {
                path: "s.beta".into(),
                values: vec!["0.1".into()],
            },
        ];
        let names = short_names(&["s.alpha", "s.beta"]);
        assert_eq!(
            variant_label(&names, &varies, &[1, 0]),
            "alpha=0.4 beta=0.1"
        );
    }
}
