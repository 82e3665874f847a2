//! The tokens of a USDA text layer, each with the byte offset it starts at.

/// One token of USDA text.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Token {
    /// `(` `)` `[` `]` `{` `}` `=` `,` `;` `:`
    Punct(char),
    /// A quoted string, `"…"`, `'…'` or triple-quoted, unescaped.
    Str(String),
    /// An asset path, `@…@` or `@@@…@@@`.
    Asset(String),
    /// A prim or property path, `<…>`.
    Path(String),
    /// A number as written.
    Number(f64),
    /// A keyword, type name, identifier or namespaced property name (`xformOp:translate`,
    /// `points.timeSamples`), or `inf`, `nan`, `None`, `true`.
    Word(String),
}

/// A token and where it starts.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Spanned {
    pub token: Token,
    pub at: usize,
}

/// What cannot be read as tokens, and where.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct LexError {
    pub at: usize,
    pub message: String,
}

/// The tokens of `text` after its first line (the `#usda 1.0` header), comments (`#` to the
/// end of the line) left out.
pub(super) fn tokens(text: &str) -> Result<Vec<Spanned>, LexError> {
    let bytes = text.as_bytes();
    let mut out = Vec::new();
    let mut i = text.find('\n').map_or(text.len(), |n| n + 1);
    while i < bytes.len() {
        let c = bytes[i];
        match c {
            b' ' | b'\t' | b'\r' | b'\n' => i += 1,
            b'#' => {
                while i < bytes.len() && bytes[i] != b'\n' {
                    i += 1;
                }
            }
            b'(' | b')' | b'[' | b']' | b'{' | b'}' | b'=' | b',' | b';' | b':' => {
                out.push(Spanned {
                    token: Token::Punct(c as char),
                    at: i,
                });
                i += 1;
            }
            b'"' | b'\'' => {
                let (s, end) = string(text, i)?;
                out.push(Spanned {
                    token: Token::Str(s),
                    at: i,
                });
                i = end;
            }
            b'@' => {
                let (s, end) = delimited(
                    text,
                    i,
                    if text[i..].starts_with("@@@") {
                        "@@@"
                    } else {
                        "@"
                    },
                )?;
                out.push(Spanned {
                    token: Token::Asset(s),
                    at: i,
                });
                i = end;
            }
            b'<' => {
                let (s, end) = delimited(text, i, ">")?;
                out.push(Spanned {
                    token: Token::Path(s),
                    at: i,
                });
                i = end;
            }
            b'-' | b'+' | b'.' | b'0'..=b'9' => {
                let start = i;
                i += 1;
                while i < bytes.len()
                    && (bytes[i].is_ascii_alphanumeric() || matches!(bytes[i], b'.' | b'-' | b'+'))
                {
                    // A sign only right after an exponent's `e`.
                    if matches!(bytes[i], b'-' | b'+') && !matches!(bytes[i - 1], b'e' | b'E') {
                        break;
                    }
                    i += 1;
                }
                let written = &text[start..i];
                let value = match written {
                    "-inf" => f64::NEG_INFINITY,
                    "+inf" => f64::INFINITY,
                    _ => written.parse::<f64>().map_err(|_| LexError {
                        at: start,
                        message: format!("`{written}` is not a number"),
                    })?,
                };
                out.push(Spanned {
                    token: Token::Number(value),
                    at: start,
                });
            }
            c if c.is_ascii_alphabetic() || c == b'_' => {
                let start = i;
                while i < bytes.len()
                    && (bytes[i].is_ascii_alphanumeric()
                        || bytes[i] == b'_'
                        || (matches!(bytes[i], b':' | b'.')
                            && i + 1 < bytes.len()
                            && (bytes[i + 1].is_ascii_alphabetic() || bytes[i + 1] == b'_')))
                {
                    i += 1;
                }
                out.push(Spanned {
                    token: Token::Word(text[start..i].to_string()),
                    at: start,
                });
            }
            _ => {
                let ch = text[i..].chars().next().unwrap_or('?');
                return Err(LexError {
                    at: i,
                    message: format!("`{ch}` is not USDA text here"),
                });
            }
        }
    }
    Ok(out)
}

/// The string starting at `start` (a quote), unescaped, and the offset after it.
fn string(text: &str, start: usize) -> Result<(String, usize), LexError> {
    let quote = &text[start..start + 1];
    let triple = quote.repeat(3);
    if text[start..].starts_with(&triple) {
        let body = start + 3;
        return match text[body..].find(&triple) {
            Some(n) => Ok((text[body..body + n].to_string(), body + n + 3)),
            None => Err(LexError {
                at: start,
                message: "this string is not closed".to_string(),
            }),
        };
    }
    let mut out = String::new();
    let mut chars = text[start + 1..].char_indices();
    while let Some((k, c)) = chars.next() {
        match c {
            '\\' => match chars.next() {
                Some((_, 'n')) => out.push('\n'),
                Some((_, 't')) => out.push('\t'),
                Some((_, e)) => out.push(e),
                None => break,
            },
            '\n' => break,
            c if c.to_string() == quote => return Ok((out, start + 1 + k + 1)),
            c => out.push(c),
        }
    }
    Err(LexError {
        at: start,
        message: "this string is not closed on its line".to_string(),
    })
}

/// The text from `start` to the next `close` after the opening one, and the offset after it.
fn delimited(text: &str, start: usize, close: &str) -> Result<(String, usize), LexError> {
    // `<` opens what `>` closes, and `@` or `@@@` what they close: the opener is as long.
    let open = close.len();
    match text[start + open..].find(close) {
        Some(n) if !text[start + open..start + open + n].contains('\n') => Ok((
            text[start + open..start + open + n].to_string(),
            start + open + n + close.len(),
        )),
        _ => Err(LexError {
            at: start,
            message: format!("this is not closed by `{close}` on its line"),
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_kind_of_token_is_read_with_its_place() {
        let text = "#usda 1.0\ndef Xform \"car\" ( kind = \"component\" ) {\n    double3 xformOp:translate = (1, -2.5e-1, 3) # a comment\n    rel material:binding = </Looks/red>\n    asset a = @./t.png@\n    uniform token[] xformOpOrder = ['xformOp:translate']\n    float b = -inf\n}\n";
        let tokens = tokens(text).unwrap();
        let words: Vec<&Token> = tokens.iter().map(|t| &t.token).collect();
        assert_eq!(words[0], &Token::Word("def".into()));
        assert!(words.contains(&&Token::Word("xformOp:translate".into())));
        assert!(words.contains(&&Token::Number(-0.25)));
        assert!(words.contains(&&Token::Path("/Looks/red".into())));
        assert!(words.contains(&&Token::Asset("./t.png".into())));
        assert!(words.contains(&&Token::Str("xformOp:translate".into())));
        assert!(words.contains(&&Token::Number(f64::NEG_INFINITY)));
        assert!(
            !words.contains(&&Token::Word("comment".into())),
            "comments are skipped"
        );
        let translate = tokens
            .iter()
            .find(|t| t.token == Token::Word("xformOp:translate".into()))
            .unwrap();
        assert_eq!(&text[translate.at..translate.at + 17], "xformOp:translate");
    }

    /// Every token of `text` after its header, with the text from where it starts.
    fn read(text: &str) -> Vec<(Token, &str)> {
        tokens(text)
            .unwrap()
            .into_iter()
            .map(|t| (t.token, &text[t.at..]))
            .collect()
    }

    #[test]
    fn quoted_strings_of_every_kind_read_to_their_close_and_no_further() {
        let text = concat!(
            "#usda 1.0\n",
            r#""""two"#,
            "\n",
            r#"lines""" x '''it's''' y "a\"b\n\tc" 'q' z"#,
            "\n"
        );
        let s = |v: &str| Token::Str(v.into());
        let w = |v: &str| Token::Word(v.into());
        let want = [
            (s("two\nlines"), r#""""two"#),
            (w("x"), "x '''"),
            (s("it's"), "'''it's"),
            (w("y"), r#"y ""#),
            (s("a\"b\n\tc"), r#""a\"#),
            (s("q"), "'q'"),
            (w("z"), "z\n"),
        ];
        let got = read(text);
        assert_eq!(got.len(), want.len(), "{got:?}");
        for ((token, at), (want, starts)) in got.iter().zip(&want) {
            assert_eq!(token, want);
            assert!(at.starts_with(starts), "{token:?} read at {at:?}");
        }
    }

    #[test]
    fn a_namespaced_word_goes_on_only_where_a_letter_or_underscore_follows_its_colon_or_dot() {
        let text = "#usda 1.0\nprimvars:_st a._b c:1 e_2:f.g h:\n";
        let w = |v: &str| Token::Word(v.into());
        let got: Vec<Token> = read(text).into_iter().map(|(t, _)| t).collect();
        let want = [
            w("primvars:_st"),
            w("a._b"),
            w("c"),
            Token::Punct(':'),
            Token::Number(1.0),
            w("e_2:f.g"),
            w("h"),
            Token::Punct(':'),
        ];
        assert_eq!(got, want);
    }

    #[test]
    fn assets_and_paths_read_to_their_close_on_their_line() {
        let text = "#usda 1.0\n</a/b> @@@./c d.usd@@@\n@e.usd@ x\n";
        let got = read(text);
        assert_eq!(
            got.iter().map(|(t, _)| t.clone()).collect::<Vec<_>>(),
            [
                Token::Path("/a/b".into()),
                Token::Asset("./c d.usd".into()),
                Token::Asset("e.usd".into()),
                Token::Word("x".into()),
            ]
        );
        assert!(got[2].1.starts_with("@e.usd@ x"));
        for broken in ["<a\nb>", "<ab\n>", "@a\n@", "@@@a\n@@@", "@@@a@@"] {
            let text = format!("#usda 1.0\nrel r = {broken}\n");
            let e = tokens(&text).unwrap_err();
            assert_eq!(e.at, text.find(&broken[..1]).unwrap(), "{broken:?}");
            assert!(
                e.message.contains("on its line"),
                "{broken:?}: {}",
                e.message
            );
        }
    }

    #[test]
    fn an_unclosed_string_is_an_error_where_it_starts() {
        let text = "#usda 1.0\ndef \"a\n";
        let e = tokens(text).unwrap_err();
        assert_eq!(e.at, text.find("\"a").unwrap());
    }
}
