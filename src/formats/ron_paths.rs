//! Where a value is written in RON text, found by its path (`instances[2].name`): its start, so
//! that an error about a parsed value points at the value itself, and its span and the spans of
//! its items, so that one value can be rewritten with every other byte left as it is.
//!
//! `ron` keeps no positions for the values it has parsed, so this walks the text's structure
//! again: structs and enum variants `Name(field: value, …)`, tuples `(a, b)`, lists `[a, b]`,
//! maps `{key: value}`, strings (plain, raw and byte), chars, numbers, identifiers, `//` and
//! nested `/* */` comments, and `#![…]` attributes at the top. `Some(x)` is looked through, as
//! the `implicit_some` extension the shot reader enables makes it optional.

use std::ops::Range;

/// One step of a path into a RON document.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Step<'a> {
    /// The named field of a struct or struct-like variant: `name: value`.
    Field(&'a str),
    /// An item of a list or tuple, counted from 0.
    Index(usize),
    /// The entry of a map whose key is the string `key`. As the last step it is located at the
    /// key (where the entry's name is written); otherwise the walk goes on into its value.
    Entry(&'a str),
}

/// The byte offset in `text` of the value at `path` or, where the path is not written in full
/// (a defaulted field, an item beyond the list), of the deepest value on it that is; 0 where
/// nothing of it is written.
#[must_use]
pub fn locate_or_nearest(text: &str, path: &[Step]) -> usize {
    (0..=path.len())
        .rev()
        .find_map(|depth| try_locate(text, &path[..depth]))
        .unwrap_or(0)
}

/// The byte offset in `text` of the value at `path`, or `None` where it is not written there
/// (or the text is malformed before it is reached).
#[must_use]
pub fn try_locate(text: &str, path: &[Step]) -> Option<usize> {
    Cursor::at_top_level(text)?.find(path, 0)
}

/// The name written before the top-level value's bracket (`Shot` in `Shot(…)`), after blanks
/// and `#![…]` attributes; `None` when it has none.
#[must_use]
pub fn top_level_name(text: &str) -> Option<&str> {
    Cursor::at_top_level(text)?.identifier()
}

/// The bytes of `text` the value at `path` is written in, from its first to just past its last;
/// a `Some(…)` around it is looked through, so the span is of the value inside. `None` where it
/// is not written (or the text is malformed before it ends).
#[must_use]
pub fn try_span(text: &str, path: &[Step]) -> Option<Range<usize>> {
    let mut cursor = Cursor::at_top_level(text)?;
    cursor.find(path, 0)?;
    cursor.enter_some();
    let start = cursor.at;
    cursor.skip_value()?;
    Some(start..cursor.at)
}

/// The spans of the items of the list, tuple, map or struct at `path` (a `Some(…)` and a
/// variant's name before the bracket looked through), in the order written: each item's value,
/// and for a map entry or a struct field from its key or name to the end of its value.
/// Separators, blanks and comments between items are in no span. `None` where the value is not
/// written or is not bracketed.
#[must_use]
pub fn try_item_spans(text: &str, path: &[Step]) -> Option<Vec<Range<usize>>> {
    let mut cursor = Cursor::at_top_level(text)?;
    cursor.find(path, 0)?;
    cursor.enter_some();
    if cursor.identifier().is_some() {
        cursor.skip_blank();
    }
    let close = match cursor.peek()? {
        '(' => ')',
        '[' => ']',
        '{' => '}',
        _ => return None,
    };
    cursor.at += 1;
    let mut items = Vec::new();
    loop {
        cursor.skip_blank();
        if cursor.eat(close) {
            return Some(items);
        }
        let start = cursor.at;
        cursor.skip_nested(1)?;
        let mut end = cursor.at;
        cursor.skip_blank();
        if cursor.eat(':') {
            cursor.skip_blank();
            cursor.skip_nested(1)?;
            end = cursor.at;
            cursor.skip_blank();
        }
        items.push(start..end);
        if !cursor.eat(',') && cursor.peek() != Some(close) {
            return None;
        }
    }
}

/// Nesting deeper than this is treated as malformed, so hostile text cannot exhaust the stack.
const MAX_DEPTH: usize = 128;

struct Cursor<'t> {
    text: &'t str,
    at: usize,
}

impl<'t> Cursor<'t> {
    /// A cursor at the top-level value of `text`: past blanks and `#![…]` attributes.
    fn at_top_level(text: &'t str) -> Option<Self> {
        let mut cursor = Cursor { text, at: 0 };
        cursor.skip_blank();
        while cursor.rest().starts_with("#!") {
            cursor.at += 2;
            cursor.skip_blank();
            cursor.skip_value()?;
            cursor.skip_blank();
        }
        Some(cursor)
    }

    /// Moves into the `Some(…)` written here, if one is, to the value inside (after blanks);
    /// otherwise stays.
    fn enter_some(&mut self) {
        let before = self.at;
        if self.identifier() == Some("Some") {
            self.skip_blank();
            if self.eat('(') {
                self.skip_blank();
                return;
            }
        }
        self.at = before;
    }

    fn rest(&self) -> &'t str {
        &self.text[self.at..]
    }

    fn peek(&self) -> Option<char> {
        self.rest().chars().next()
    }

    fn eat(&mut self, c: char) -> bool {
        let found = self.peek() == Some(c);
        if found {
            self.at += c.len_utf8();
        }
        found
    }

    /// Skips white space and comments.
    fn skip_blank(&mut self) {
        loop {
            let rest = self.rest();
            let trimmed = rest.trim_start();
            self.at += rest.len() - trimmed.len();
            if trimmed.starts_with("//") {
                self.at += trimmed.find('\n').unwrap_or(trimmed.len());
            } else if trimmed.starts_with("/*") {
                self.skip_block_comment();
            } else {
                return;
            }
        }
    }

    /// Skips a `/* … */` comment, which may nest; an unclosed one runs to the end.
    fn skip_block_comment(&mut self) {
        let mut depth = 0usize;
        while self.at < self.text.len() {
            let rest = self.rest();
            if rest.starts_with("/*") {
                depth += 1;
                self.at += 2;
            } else if rest.starts_with("*/") {
                depth -= 1;
                self.at += 2;
                if depth == 0 {
                    return;
                }
            } else {
                self.at += rest.chars().next().map_or(1, char::len_utf8);
            }
        }
    }

    /// An identifier (`r#` raw identifiers included), if one starts here.
    fn identifier(&mut self) -> Option<&'t str> {
        let rest = self.rest();
        let body = rest.strip_prefix("r#").unwrap_or(rest);
        let first = body.chars().next()?;
        if !(first.is_alphabetic() || first == '_') {
            return None;
        }
        let len = body
            .find(|c: char| !(c.is_alphanumeric() || c == '_'))
            .unwrap_or(body.len());
        self.at += rest.len() - body.len() + len;
        Some(&body[..len])
    }

    /// The contents of a string (plain, raw or byte) starting here, escapes left as written.
    fn string(&mut self) -> Option<&'t str> {
        let rest = self.rest();
        let body = rest.strip_prefix('b').unwrap_or(rest);
        if let Some(raw) = body.strip_prefix('r') {
            let hashes = raw.len() - raw.trim_start_matches('#').len();
            let open = raw[hashes..].strip_prefix('"')?;
            let close = format!("\"{}", "#".repeat(hashes));
            let end = open.find(&close)?;
            self.at += rest.len() - open.len() + end + close.len();
            return Some(&open[..end]);
        }
        let open = body.strip_prefix('"')?;
        let mut escaped = false;
        for (i, c) in open.char_indices() {
            match (escaped, c) {
                (true, _) => escaped = false,
                (false, '\\') => escaped = true,
                (false, '"') => {
                    self.at += rest.len() - open.len() + i + 1;
                    return Some(&open[..i]);
                }
                (false, _) => {}
            }
        }
        None
    }

    /// Skips one value of any kind.
    fn skip_value(&mut self) -> Option<()> {
        self.skip_nested(0)
    }

    fn skip_nested(&mut self, depth: usize) -> Option<()> {
        if depth > MAX_DEPTH {
            return None;
        }
        let rest = self.rest();
        match self.peek()? {
            '"' => self.string().map(drop),
            'b' | 'r' if self.string().is_some() => Some(()),
            '\'' => {
                let body = &rest[1..];
                let skip = match body.strip_prefix('\\') {
                    Some(escaped) => 1 + escaped.chars().next()?.len_utf8(),
                    None => 0,
                };
                let len = skip + body.get(skip..)?.find('\'')?;
                self.at += len + 2;
                Some(())
            }
            '(' | '[' | '{' => self.skip_group(depth),
            c if c.is_alphabetic() || c == '_' => {
                self.identifier()?;
                let before = self.at;
                self.skip_blank();
                if self.peek() == Some('(') {
                    self.skip_group(depth)
                } else {
                    self.at = before;
                    Some(())
                }
            }
            _ => {
                let len = rest
                    .find(|c: char| c.is_whitespace() || ",:()[]{}/".contains(c))
                    .unwrap_or(rest.len());
                if len == 0 {
                    return None;
                }
                self.at += len;
                Some(())
            }
        }
    }

    /// Skips a bracketed group and everything in it.
    fn skip_group(&mut self, depth: usize) -> Option<()> {
        let close = match self.peek()? {
            '(' => ')',
            '[' => ']',
            _ => '}',
        };
        self.at += 1;
        loop {
            self.skip_blank();
            if self.eat(close) {
                return Some(());
            }
            if !(self.eat(',') || self.eat(':')) {
                self.skip_nested(depth + 1)?;
            }
        }
    }

    /// Walks `path` from the value starting here (after blanks).
    fn find(&mut self, path: &[Step], depth: usize) -> Option<usize> {
        if depth > MAX_DEPTH {
            return None;
        }
        self.skip_blank();
        let start = self.at;
        let Some((step, rest)) = path.split_first() else {
            return Some(start);
        };
        let name = self.identifier();
        self.skip_blank();
        if name == Some("Some") && self.eat('(') {
            return self.find(path, depth + 1);
        }
        match *step {
            Step::Field(field) => {
                if !self.eat('(') {
                    return None;
                }
                loop {
                    self.skip_blank();
                    let name = self.identifier()?;
                    self.skip_blank();
                    if !self.eat(':') {
                        return None;
                    }
                    if name == field {
                        return self.find(rest, depth + 1);
                    }
                    self.next_item(depth)?;
                }
            }
            Step::Index(index) => {
                if !(self.eat('(') || self.eat('[')) {
                    return None;
                }
                for _ in 0..index {
                    self.skip_blank();
                    if matches!(self.peek(), Some(')' | ']')) {
                        return None;
                    }
                    self.next_item(depth)?;
                }
                self.skip_blank();
                if matches!(self.peek(), Some(')' | ']') | None) {
                    return None;
                }
                self.find(rest, depth + 1)
            }
            Step::Entry(key) => {
                if !self.eat('{') {
                    return None;
                }
                loop {
                    self.skip_blank();
                    let key_at = self.at;
                    let found = match self.string() {
                        Some(written) => written == key,
                        None => {
                            self.skip_value()?;
                            false
                        }
                    };
                    self.skip_blank();
                    if !self.eat(':') {
                        return None;
                    }
                    if found {
                        return if rest.is_empty() {
                            Some(key_at)
                        } else {
                            self.find(rest, depth + 1)
                        };
                    }
                    self.next_item(depth)?;
                }
            }
        }
    }

    /// Skips the value here and the comma after it.
    fn next_item(&mut self, depth: usize) -> Option<()> {
        self.skip_blank();
        self.skip_nested(depth + 1)?;
        self.skip_blank();
        self.eat(',');
        Some(())
    }
}

#[cfg(test)]
mod tests {
    use super::Step::{Entry, Field, Index};
    use super::*;

    const SHOT: &str = r##"#![enable(implicit_some)]
// a comment with name: "decoy"
Shot(
    /* a /* nested */ comment: "x" */
    frames: (1, 10),
    instances: [
        (name: "a", file: "s.ron", material: "m"),
        (name: r#"b"#, file: "s.ron", material: "m", transform: Some((scale: 2.0))),
    ],
    materials: {
        "plain": Cel(base: (0, 0, 1)),
        "m": XToon(texture: "t.png", detail: Depth(near: 1.0, far: 2.0)),
    },
    highlights: [(patches: ["a/*", "b/*"], expr: Layer((epsilon: 0.1, c: 'x')))],
)
"##;

    fn at(needle: &str) -> usize {
        SHOT.find(needle).unwrap()
    }

    #[test]
    fn fields_items_and_entries_are_found_where_written() {
        assert_eq!(try_locate(SHOT, &[Field("frames")]), Some(at("(1, 10)")));
        assert_eq!(
            try_locate(SHOT, &[Field("instances"), Index(1), Field("name")]),
            Some(at("r#\"b\"#"))
        );
        assert_eq!(
            try_locate(SHOT, &[Field("instances"), Index(0), Field("material")]),
            Some(at("\"m\")"))
        );
        assert_eq!(
            try_locate(SHOT, &[Field("materials"), Entry("m")]),
            Some(at("\"m\": XToon"))
        );
        assert_eq!(
            try_locate(SHOT, &[Field("materials"), Entry("m"), Field("texture")]),
            Some(at("\"t.png\""))
        );
        assert_eq!(
            try_locate(
                SHOT,
                &[Field("highlights"), Index(0), Field("patches"), Index(1)]
            ),
            Some(at("\"b/*\""))
        );
        assert_eq!(
            try_locate(
                SHOT,
                &[
                    Field("highlights"),
                    Index(0),
                    Field("expr"),
                    Index(0),
                    Field("c")
                ]
            ),
            Some(at("'x'"))
        );
    }

    fn spanned(text: &str, span: Option<Range<usize>>) -> Option<&str> {
        span.map(|r| &text[r])
    }

    #[test]
    fn spans_run_from_a_value_to_its_end_through_some() {
        let span = |path: &[Step]| spanned(SHOT, try_span(SHOT, path));
        assert_eq!(span(&[Field("frames")]), Some("(1, 10)"));
        assert_eq!(
            span(&[Field("instances"), Index(1), Field("transform")]),
            Some("(scale: 2.0)")
        );
        assert_eq!(
            span(&[Field("materials"), Entry("m"), Field("detail")]),
            Some("Depth(near: 1.0, far: 2.0)")
        );
        assert_eq!(
            span(&[Field("instances"), Index(1), Field("name")]),
            Some("r#\"b\"#")
        );
        assert_eq!(
            span(&[Field("instances"), Index(0), Field("transform")]),
            None
        );
    }

    #[test]
    fn items_are_spanned_without_their_separators() {
        let items = |path: &[Step]| {
            try_item_spans(SHOT, path)
                .map(|spans| spans.into_iter().map(|r| &SHOT[r]).collect::<Vec<_>>())
        };
        assert_eq!(
            items(&[Field("instances"), Index(0)]),
            Some(vec!["name: \"a\"", "file: \"s.ron\"", "material: \"m\""])
        );
        assert_eq!(
            items(&[Field("highlights"), Index(0), Field("patches")]),
            Some(vec!["\"a/*\"", "\"b/*\""])
        );
        assert_eq!(
            items(&[Field("materials"), Entry("m"), Field("detail")]),
            Some(vec!["near: 1.0", "far: 2.0"])
        );
        assert_eq!(
            items(&[Field("instances"), Index(1), Field("transform")]),
            Some(vec!["scale: 2.0"])
        );
        assert_eq!(items(&[Field("materials")]).map(|i| i.len()), Some(2));
        assert_eq!(items(&[Field("frames"), Index(0)]), None);
        assert_eq!(try_item_spans("Shot(a: [1 2])", &[Field("a")]), None);
        assert_eq!(
            try_item_spans("(a: [ /* c */ 1 , 2, // d\n ])", &[Field("a")]),
            Some(vec![14..15, 18..19])
        );
    }

    #[test]
    fn the_top_level_name_is_read_past_comments_and_attributes() {
        assert_eq!(top_level_name(SHOT), Some("Shot"));
        assert_eq!(top_level_name("// c\n(patches: [])"), None);
        assert_eq!(top_level_name(""), None);
    }

    #[test]
    fn some_is_looked_through() {
        assert_eq!(
            try_locate(
                SHOT,
                &[
                    Field("instances"),
                    Index(1),
                    Field("transform"),
                    Field("scale")
                ]
            ),
            Some(at("2.0"))
        );
    }

    #[test]
    fn what_is_not_written_falls_back_to_the_deepest_written_value() {
        let path = [Field("instances"), Index(0), Field("transform")];
        assert_eq!(try_locate(SHOT, &path), None);
        assert_eq!(locate_or_nearest(SHOT, &path), at("(name: \"a\""));
        assert_eq!(try_locate(SHOT, &[Field("instances"), Index(2)]), None);
        assert_eq!(try_locate(SHOT, &[Field("materials"), Entry("none")]), None);
        assert_eq!(locate_or_nearest(SHOT, &[Field("nothing")]), at("Shot("));
    }

    #[test]
    fn malformed_and_hostile_text_gives_none_not_a_panic() {
        let deep = "[".repeat(100_000);
        for text in [
            "",
            "(",
            "Shot(frames",
            "Shot(frames: \"unclosed",
            "Shot(a: 'x",
            "Shot(a: '\\",
            "Shot(a: '\\'', frames: 1)",
            "Shot(a: r##\"x\"#)",
            "/* unclosed",
            "Shot(a: [1, 2, 3",
            "Shot(a: {\"k\": 1",
            "Shot(é: 1, frames: 2)",
            deep.as_str(),
        ] {
            let _ = try_locate(text, &[Field("frames")]);
            let _ = try_locate(text, &[Field("a"), Index(5), Entry("k")]);
            let _ = locate_or_nearest(text, &[Field("a"), Index(0)]);
            let _ = try_span(text, &[Field("a"), Index(0)]);
            let _ = try_item_spans(text, &[Field("a")]);
            let _ = try_item_spans(text, &[]);
        }
        assert_eq!(try_locate(&deep, &[Index(0); 200]), None);
        assert_eq!(
            try_locate("Shot(a: [1, 2, 3", &[Field("a"), Index(3)]),
            None
        );
        let accented = "Shot(é: 1, frames: 2)";
        assert_eq!(
            try_locate(accented, &[Field("frames")]),
            accented.find("2)")
        );
    }
}
