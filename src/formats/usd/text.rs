//! A USDA text layer read into a [`Layer`]; what composes layers (references, payloads,
//! inherits, variants, sublayers), animates values by splines or connects them is refused where
//! it is written.
//!
//! Time samples (`name.timeSamples = { time: value, … }`) are read as USD's text reader reads
//! them: sorted by time code, a time code written twice keeping the value written last. A time
//! code must be a finite number, and an attribute may hold at most [`MAX_SAMPLES`] samples.

use std::collections::HashMap;

use super::layer::{Layer, LayerTimes, Prim, Property, Sample, Value};
use super::lexer::{Spanned, Token};

/// What cannot be read, and where.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct ParseError {
    pub at: usize,
    pub message: String,
}

/// Metadata keys that compose other layers or variants into a prim or layer.
pub(super) const COMPOSITION: [&str; 8] = [
    "references",
    "payload",
    "inherits",
    "specializes",
    "variantSets",
    "variants",
    "subLayers",
    "relocates",
];

/// List-operation prefixes of metadata and relationships.
const LIST_OPS: [&str; 6] = ["prepend", "append", "add", "delete", "reorder", "explicit"];

/// The most prims and child prims may nest.
const MAX_DEPTH: usize = 256;

/// The most time samples one attribute may hold.
pub const MAX_SAMPLES: usize = 100_000;

/// Reads the layer whose tokens (after the header line) are `tokens`, `end` the text's length.
pub(super) fn parse(tokens: &[Spanned], end: usize) -> Result<Layer, ParseError> {
    let mut p = Parser { tokens, i: 0, end };
    let mut layer = Layer {
        up_axis: None,
        times: LayerTimes::default(),
        prims: Vec::new(),
    };
    if p.peek_punct('(') {
        let meta = p.metadata("the layer")?;
        layer.up_axis = meta.up_axis;
        layer.times = meta.times;
    }
    while p.i < tokens.len() {
        layer.prims.push(p.prim(0)?);
    }
    Ok(layer)
}

struct Parser<'a> {
    tokens: &'a [Spanned],
    i: usize,
    end: usize,
}

/// What glint reads of a metadata block.
#[derive(Default)]
struct Metadata {
    up_axis: Option<(String, usize)>,
    times: LayerTimes,
    inactive: bool,
}

impl Parser<'_> {
    fn at(&self) -> usize {
        self.tokens.get(self.i).map_or(self.end, |t| t.at)
    }

    fn error<T>(&self, message: impl Into<String>) -> Result<T, ParseError> {
        Err(ParseError {
            at: self.at(),
            message: message.into(),
        })
    }

    fn peek(&self) -> Option<&Token> {
        self.tokens.get(self.i).map(|t| &t.token)
    }

    fn peek_punct(&self, c: char) -> bool {
        self.peek() == Some(&Token::Punct(c))
    }

    fn peek_word(&self) -> Option<&str> {
        match self.peek() {
            Some(Token::Word(w)) => Some(w),
            _ => None,
        }
    }

    fn expect_punct(&mut self, c: char, what: &str) -> Result<(), ParseError> {
        if self.peek_punct(c) {
            self.i += 1;
            Ok(())
        } else {
            self.error(format!("expected `{c}` {what}"))
        }
    }

    /// A prim: `def [TYPE] "name" [(metadata)] { properties and prims }`.
    fn prim(&mut self, depth: usize) -> Result<Prim, ParseError> {
        let at = self.at();
        if depth > MAX_DEPTH {
            return self.error(format!("prims nest more than {MAX_DEPTH} deep"));
        }
        match self.peek_word() {
            Some("def") => self.i += 1,
            Some(specifier @ ("over" | "class")) => {
                return self.error(format!(
                    "`{specifier}` prims compose opinions from other prims or layers, which glint does not read; flatten the stage (usdcat --flatten) and export again"
                ))
            }
            _ => return self.error("expected a prim: `def TYPE \"name\" { … }`"),
        }
        let type_name = match self.peek() {
            Some(Token::Word(w)) => {
                let w = w.clone();
                self.i += 1;
                Some(w)
            }
            _ => None,
        };
        let name = match self.peek() {
            Some(Token::Str(s)) => {
                let s = s.clone();
                self.i += 1;
                s
            }
            _ => return self.error("expected the prim's name, in quotes"),
        };
        if name.is_empty() || name.contains('/') {
            return Err(ParseError {
                at,
                message: format!("\"{name}\" is not a prim name"),
            });
        }
        let mut inactive = false;
        if self.peek_punct('(') {
            let meta = self.metadata(&format!("prim \"{name}\""))?;
            inactive = meta.inactive;
        }
        self.expect_punct('{', &format!("to open prim \"{name}\""))?;
        let mut prim = Prim {
            type_name,
            name,
            at,
            inactive,
            properties: Vec::new(),
            children: Vec::new(),
        };
        let mut attributes = HashMap::new();
        loop {
            match self.peek() {
                None => {
                    return Err(ParseError {
                        at,
                        message: format!("prim \"{}\" is not closed by `}}`", prim.name),
                    })
                }
                Some(Token::Punct('}')) => {
                    self.i += 1;
                    return Ok(prim);
                }
                Some(Token::Word(w)) if w == "def" || w == "over" || w == "class" => {
                    let child = self.prim(depth + 1)?;
                    prim.children.push(child);
                }
                Some(Token::Word(w)) if w == "variantSet" => {
                    return self.error(format!(
                        "prim \"{}\" has a variant set, which glint does not read; choose the variant and flatten the stage (usdcat --flatten)",
                        prim.name
                    ))
                }
                Some(Token::Punct(';')) => self.i += 1,
                _ => {
                    if let Some(property) = self.property(&prim.name)? {
                        add_property(&mut prim.properties, &mut attributes, property);
                    }
                }
            }
        }
    }

    /// A property: `[custom] [uniform] TYPE[[]] name[.suffix] [= value] [(metadata)]`, or
    /// `[LIST_OP] rel name [= targets]`; None for a list edit of a relationship glint does
    /// not read (`reorder properties`).
    fn property(&mut self, prim: &str) -> Result<Option<Property>, ParseError> {
        let mut list_op = false;
        while let Some(w) = self.peek_word() {
            if matches!(w, "custom" | "uniform" | "varying" | "config") {
                self.i += 1;
            } else if LIST_OPS.contains(&w) {
                list_op = true;
                self.i += 1;
            } else {
                break;
            }
        }
        let Some(type_word) = self.peek_word().map(str::to_string) else {
            return self.error(format!("expected a property of prim \"{prim}\""));
        };
        self.i += 1;
        if list_op && matches!(type_word.as_str(), "nameChildren" | "properties") {
            // `reorder nameChildren = [...]`: an ordering, nothing to read.
            self.expect_punct('=', "after the reorder")?;
            self.value()?;
            return Ok(None);
        }
        let mut type_name = type_word;
        if self.peek_punct('[') {
            self.i += 1;
            self.expect_punct(']', "to close the array type")?;
            type_name.push_str("[]");
        }
        let at = self.at();
        let name = match self.peek() {
            Some(Token::Word(w)) => w.clone(),
            _ => return self.error(format!("expected the name of a `{type_name}` property")),
        };
        self.i += 1;
        if let Some(base) = name.strip_suffix(".spline") {
            return Err(ParseError {
                at,
                message: format!(
                    "prim \"{prim}\": `{base}` is animated by a spline; glint reads time samples, not splines (export the animation baked to time samples)"
                ),
            });
        }
        if let Some(base) = name.strip_suffix(".timeSamples") {
            self.expect_punct('=', &format!("after `{name}`"))?;
            let samples = self.time_samples(&name)?;
            if self.peek_punct('(') {
                self.metadata(&format!("property `{name}`"))?;
            }
            return Ok(Some(Property {
                name: base.to_string(),
                type_name,
                default: None,
                samples,
                at,
            }));
        }
        if let Some(base) = name.strip_suffix(".connect") {
            if self.peek_punct('=') {
                self.i += 1;
                self.value()?;
            }
            return Ok(Some(Property {
                name: base.to_string(),
                type_name: format!("{type_name}.connect"),
                default: None,
                samples: Vec::new(),
                at,
            }));
        }
        let value = if self.peek_punct('=') {
            self.i += 1;
            Some(self.value()?)
        } else {
            None
        };
        if self.peek_punct('(') {
            self.metadata(&format!("property `{name}`"))?;
        }
        Ok(Some(Property {
            name,
            type_name,
            default: value,
            samples: Vec::new(),
            at,
        }))
    }

    /// The time samples `{ time: value, … }` of the attribute `name`, sorted by time; a time
    /// written twice keeps its last value, as USD's reader does.
    fn time_samples(&mut self, name: &str) -> Result<Vec<Sample>, ParseError> {
        self.expect_punct('{', &format!("to open the time samples of `{name}`"))?;
        let mut samples: Vec<Sample> = Vec::new();
        loop {
            let at = self.at();
            let time = match self.peek() {
                None => {
                    return self.error(format!(
                        "the time samples of `{name}` are not closed by `}}`"
                    ))
                }
                Some(Token::Punct('}')) => {
                    self.i += 1;
                    break;
                }
                Some(Token::Number(t)) => *t,
                Some(Token::Word(w)) if matches!(w.as_str(), "inf" | "nan") => f64::NAN,
                _ => {
                    return self.error(format!(
                        "expected a time code (a number) in the time samples of `{name}`"
                    ))
                }
            };
            if !time.is_finite() {
                return self.error(format!(
                    "the time code of a sample of `{name}` is not a finite number"
                ));
            }
            if samples.len() >= MAX_SAMPLES {
                return self.error(format!("`{name}` has more than {MAX_SAMPLES} time samples"));
            }
            self.i += 1;
            self.expect_punct(':', "after the time code")?;
            if self.peek_word() == Some("None") {
                return self.error(format!(
                    "a sample of `{name}` is blocked (None); glint reads sampled values only"
                ));
            }
            let value = self.value()?;
            samples.push(Sample { time, value, at });
            if self.peek_punct(',') {
                self.i += 1;
            } else if !self.peek_punct('}') {
                return self.error(format!(
                    "expected `,` or `}}` in the time samples of `{name}`"
                ));
            }
        }
        // Sorted by time; of equal times the last written is kept (a stable sort keeps them in
        // the order written).
        samples.sort_by(|a, b| a.time.total_cmp(&b.time));
        let mut kept: Vec<Sample> = Vec::with_capacity(samples.len());
        for sample in samples {
            match kept.last_mut() {
                Some(last) if last.time == sample.time => *last = sample,
                _ => kept.push(sample),
            }
        }
        Ok(kept)
    }

    /// A metadata block `( … )` of `whose`: entries `[LIST_OP] key = value`, or a bare doc
    /// string. Composition arcs are refused.
    fn metadata(&mut self, whose: &str) -> Result<Metadata, ParseError> {
        self.expect_punct('(', "to open metadata")?;
        let mut meta = Metadata::default();
        loop {
            match self.peek() {
                None => return self.error(format!("the metadata of {whose} is not closed by `)`")),
                Some(Token::Punct(')')) => {
                    self.i += 1;
                    return Ok(meta);
                }
                Some(Token::Punct(';' | ',')) | Some(Token::Str(_)) => self.i += 1,
                Some(Token::Word(_)) => {
                    let entry_at = self.at();
                    let mut key = self.peek_word().unwrap_or_default().to_string();
                    self.i += 1;
                    if LIST_OPS.contains(&key.as_str()) {
                        key = self.peek_word().unwrap_or_default().to_string();
                        self.i += 1;
                    }
                    if COMPOSITION.contains(&key.as_str()) {
                        return Err(ParseError {
                            at: entry_at,
                            message: format!(
                                "{whose} has `{key}`, a composition arc glint does not follow; flatten the stage into one layer (usdcat --flatten in.usda -o flat.usda)"
                            ),
                        });
                    }
                    if self.peek_punct('=') {
                        self.i += 1;
                        let value_at = self.at();
                        let value = self.value()?;
                        let time_entry = match key.as_str() {
                            "timeCodesPerSecond" => Some(&mut meta.times.time_codes_per_second),
                            "framesPerSecond" => Some(&mut meta.times.frames_per_second),
                            "startTimeCode" => Some(&mut meta.times.start_time_code),
                            "endTimeCode" => Some(&mut meta.times.end_time_code),
                            _ => None,
                        };
                        if let Some(entry) = time_entry {
                            match value {
                                Value::Number(x) if x.is_finite() => *entry = Some((x, value_at)),
                                _ => {
                                    return Err(ParseError {
                                        at: value_at,
                                        message: format!(
                                            "{whose}: `{key}` must be a finite number"
                                        ),
                                    })
                                }
                            }
                            continue;
                        }
                        match (key.as_str(), value) {
                            ("upAxis", Value::Str(axis)) => meta.up_axis = Some((axis, value_at)),
                            ("active", Value::Other) => {
                                meta.inactive = matches!(
                                    self.tokens.get(self.i - 1).map(|t| &t.token),
                                    Some(Token::Word(w)) if w == "false"
                                );
                            }
                            _ => {}
                        }
                    }
                }
                _ => return self.error(format!("unexpected text in the metadata of {whose}")),
            }
        }
    }

    /// A value: a number, string, tuple, list, dictionary, word, path or asset.
    fn value(&mut self) -> Result<Value, ParseError> {
        self.value_at(0)
    }

    fn value_at(&mut self, depth: usize) -> Result<Value, ParseError> {
        if depth > MAX_DEPTH {
            return self.error(format!("values nest more than {MAX_DEPTH} deep"));
        }
        let Some(token) = self.peek().cloned() else {
            return self.error("expected a value");
        };
        self.i += 1;
        match token {
            Token::Number(x) => Ok(Value::Number(x)),
            Token::Str(s) => Ok(Value::Str(s)),
            Token::Word(w) => Ok(match w.as_str() {
                "inf" => Value::Number(f64::INFINITY),
                "nan" => Value::Number(f64::NAN),
                _ => Value::Other,
            }),
            Token::Path(_) | Token::Asset(_) => Ok(Value::Other),
            Token::Punct(open @ ('(' | '[')) => {
                let close = if open == '(' { ')' } else { ']' };
                let mut items = Vec::new();
                loop {
                    if self.peek_punct(close) {
                        self.i += 1;
                        break;
                    }
                    items.push(self.value_at(depth + 1)?);
                    if self.peek_punct(',') {
                        self.i += 1;
                    } else if !self.peek_punct(close) {
                        return self.error(format!("expected `,` or `{close}`"));
                    }
                }
                Ok(if open == '(' {
                    Value::Tuple(items)
                } else {
                    Value::List(items)
                })
            }
            Token::Punct('{') => {
                // A dictionary (customData, a time-sample table read elsewhere): skipped whole.
                let mut open = 1usize;
                while open > 0 {
                    match self.peek() {
                        None => return self.error("a dictionary `{` is not closed"),
                        Some(Token::Punct('{')) => open += 1,
                        Some(Token::Punct('}')) => open -= 1,
                        _ => {}
                    }
                    self.i += 1;
                }
                Ok(Value::Other)
            }
            Token::Punct(c) => {
                self.i -= 1;
                self.error(format!("expected a value, not `{c}`"))
            }
        }
    }
}

/// Adds `property` to `properties`, `attributes` indexing them by name: an attribute's time
/// samples and its default, written on two lines, are one property (time samples written again
/// replace the earlier ones). Anything else is added as written.
fn add_property(
    properties: &mut Vec<Property>,
    attributes: &mut HashMap<String, usize>,
    property: Property,
) {
    let is_value = |p: &Property| !p.type_name.ends_with(".connect") && p.type_name != "rel";
    let sampled_only = |p: &Property| p.default.is_none() && !p.samples.is_empty();
    if is_value(&property) {
        if let Some(&k) = attributes.get(&property.name) {
            let existing = &mut properties[k];
            if sampled_only(&property) {
                existing.samples = property.samples;
                existing.at = property.at;
                return;
            }
            if sampled_only(existing) && property.default.is_some() {
                existing.default = property.default;
                return;
            }
        } else {
            attributes.insert(property.name.clone(), properties.len());
        }
    }
    properties.push(property);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formats::usd::lexer::tokens;

    fn layer(text: &str) -> Result<Layer, ParseError> {
        let tokens = tokens(text).map_err(|e| ParseError {
            at: e.at,
            message: e.message,
        })?;
        parse(&tokens, text.len())
    }

    #[test]
    fn time_samples_are_sorted_a_repeated_time_keeps_the_last_and_join_the_default() {
        let text = "#usda 1.0\n(\n    timeCodesPerSecond = 30\n    startTimeCode = -2\n)\ndef Xform \"a\"\n{\n    double xformOp:rotateZ = 5\n    double xformOp:rotateZ.timeSamples = {\n        10: 3,\n        -1.5: 1,\n        10: 7,\n    }\n}\n";
        let layer = layer(text).unwrap();
        assert_eq!(layer.times.time_codes_per_second.map(|t| t.0), Some(30.0));
        assert_eq!(layer.times.start_time_code.map(|t| t.0), Some(-2.0));
        assert_eq!(layer.times.end_time_code, None);
        let prim = &layer.prims[0];
        assert_eq!(
            prim.properties.len(),
            1,
            "the default and the samples are one property"
        );
        let p = &prim.properties[0];
        assert_eq!(p.default, Some(Value::Number(5.0)));
        let samples: Vec<(f64, &Value)> = p.samples.iter().map(|s| (s.time, &s.value)).collect();
        assert_eq!(
            samples,
            [(-1.5, &Value::Number(1.0)), (10.0, &Value::Number(7.0))]
        );
        assert_eq!(p.first_value(), Some(&Value::Number(1.0)));
        assert!(p.varies());
        assert!(p.held_value().is_err());
        // The sample kept at 10 is the one written last, located at its time code.
        let last = text.rfind("10: 7").unwrap();
        assert_eq!(p.samples[1].at, last);
    }

    #[test]
    fn a_time_code_that_is_not_a_number_is_refused_where_it_is_written() {
        let text = "#usda 1.0\ndef Xform \"a\"\n{\n    double xformOp:rotateZ.timeSamples = {\n        \"one\": 3,\n    }\n}\n";
        let e = layer(text).unwrap_err();
        assert_eq!(e.at, text.find("\"one\"").unwrap());
        assert!(e.message.contains("expected a time code"), "{}", e.message);
    }

    #[test]
    fn samples_that_agree_are_one_value() {
        let text = "#usda 1.0\ndef Xform \"a\"\n{\n    int n.timeSamples = {\n        1: 4,\n        2: 4,\n    }\n}\n";
        let layer = layer(text).unwrap();
        let p = &layer.prims[0].properties[0];
        assert!(!p.varies());
        assert_eq!(p.held_value().unwrap(), Some(&Value::Number(4.0)));
    }
}
