//! Editing a highlight layer's structure in a shot or look file's text: an operation inserted,
//! removed or moved in its stack, its mask added or removed, its pin set or removed, its shape
//! drawn or made the disc again — each as splices of the text, every other byte kept, and the
//! result read back and checked to differ in that alone.

use super::error::EditError;
use super::layer_text::{mask_text, op_text};
use super::number_text::number_text;
use super::outline_edit::{check_key, key_frames, key_splice, reshaped, rounded, shape_field_text};
use super::read::{read_back, read_file};
use super::track_splice::{apply, insert_item, remove_item, Splice};
use crate::anim::Track;
use crate::formats::ron_paths::Step::Field;
use crate::formats::ron_paths::{try_item_spans, try_span};
use crate::highlight::{Layer, Mask, Op, Outline, Pin, Segment, Shape};

/// A change to the structure of one highlight layer.
#[derive(Clone, Debug, PartialEq)]
pub enum LayerEdit {
    /// `op` put into the stack at `index` (0 first; the stack's length last), its numbers
    /// constants.
    InsertOp { index: usize, op: Op<f32> },
    /// The operation at `index` taken out of the stack.
    RemoveOp { index: usize },
    /// The operation at `from` moved to `to`, the others keeping their order.
    MoveOp { from: usize, to: usize },
    /// A mask over the whole unit square `[0, 1] × [0, 1]` with no feather, to narrow.
    AddMask,
    /// The mask taken out.
    RemoveMask,
    /// The pin moved to the patch named `patch` (a patch name, not a part), its `member` 0.
    PinTo { patch: String },
    /// The layer pinned to `(u, v)` of the patch named `patch`, constants: a pin added as the
    /// layer's last field, or the layer's pin replaced whole.
    Pin { patch: String, u: f32, v: f32 },
    /// The pin taken out: the layer's translation is used as written again.
    Unpin,
    /// The pin made to hold the shape the layer has at `frame` (`hold: frame` in the pin,
    /// replacing the frame it held), or with None to let the shape follow the view again
    /// (the pin's `hold` taken out).
    Hold { frame: Option<i64> },
    /// The shape made the drawn outline of the corners `points`, in the coordinates
    /// `t′ = ((H′, du), (H′, dv))` (docs/highlights.md, "Drawn outlines"), each coordinate
    /// written to 4 decimal places. With `key: None`, the plain `shape: Outline([…])` in place
    /// of the disc or any outline. With `key: Some(frame)`, a key of `OutlineKeys`: a keyed
    /// outline's key at that frame is replaced or the key inserted in frame order, and must
    /// have as many points as the other keys; the disc or a plain outline keyed becomes
    /// `OutlineKeys` of this one key (as a constant track keyed becomes its one key).
    Outline {
        key: Option<f64>,
        points: Vec<[f32; 2]>,
    },
    /// The shape made the ε-disc again: the `shape` field taken out.
    Disc,
}

impl LayerEdit {
    /// The edit made on a parsed layer, as the text edit must read back.
    fn apply_to(&self, layer: &mut Layer<Track<f32>>) {
        match self {
            LayerEdit::InsertOp { index, op } => {
                layer.stack.insert(*index, op.map(|&x| Track::Constant(x)));
            }
            LayerEdit::RemoveOp { index } => {
                layer.stack.remove(*index);
            }
            LayerEdit::MoveOp { from, to } => {
                let op = layer.stack.remove(*from);
                layer.stack.insert(*to, op);
            }
            LayerEdit::AddMask => {
                let Mask { u, v, feather } = unit_mask();
                layer.mask = Some(Mask {
                    u: (u.0.into(), u.1.into()),
                    v: (v.0.into(), v.1.into()),
                    feather: feather.into(),
                });
            }
            LayerEdit::RemoveMask => layer.mask = None,
            LayerEdit::PinTo { patch } => {
                if let Some(pin) = &mut layer.pin {
                    pin.patch.clone_from(patch);
                    pin.member = 0;
                }
            }
            LayerEdit::Pin { patch, u, v } => {
                // A pin moved keeps the shape it held.
                let hold = layer.pin.as_ref().and_then(|pin| pin.hold);
                layer.pin = Some(Pin {
                    patch: patch.clone(),
                    member: 0,
                    u: Track::Constant(*u),
                    v: Track::Constant(*v),
                    hold,
                });
            }
            LayerEdit::Unpin => layer.pin = None,
            LayerEdit::Hold { frame } => {
                if let Some(pin) = &mut layer.pin {
                    pin.hold = *frame;
                }
            }
            LayerEdit::Outline { key, points } => reshaped(&mut layer.shape, *key, points),
            LayerEdit::Disc => layer.shape = Shape::Disc,
        }
    }

    /// The edit as it reads back once written: a drawn outline's coordinates rounded as they
    /// are written.
    fn as_written(&self) -> LayerEdit {
        match self {
            LayerEdit::Outline { key, points } => LayerEdit::Outline {
                key: *key,
                points: rounded(points),
            },
            other => other.clone(),
        }
    }
}

/// Which of a struct's `fields` (spans of `name: value` items in `text`) is `name`.
fn field_index(text: &str, fields: &[std::ops::Range<usize>], name: &str) -> Option<usize> {
    fields.iter().position(|span| {
        text[span.clone()]
            .strip_prefix(name)
            .is_some_and(|rest| rest.trim_start().starts_with(':'))
    })
}

fn unit_mask() -> Mask<f32> {
    Mask {
        u: (0.0, 1.0),
        v: (0.0, 1.0),
        feather: 0.0,
    }
}

/// `text` with layer `layer` (left to right through the Booleans, from 0) of highlight entry
/// `entry` of the file changed as `edit` says.
///
/// An operation is inserted and removed as a list item in the style the stack is written in
/// (one line, or an item a line); a move rewrites the items between the two places, each in
/// the text of the operation that now stands there. A mask is added as the layer's last field
/// and removed with its separator. The result is read back and compared with the file as first
/// read with that change made; any other difference is an error and nothing is returned.
pub fn edit_layer(
    text: &str,
    entry: usize,
    layer: usize,
    edit: &LayerEdit,
) -> Result<String, EditError> {
    let edit = &edit.as_written();
    let mut expected = read_file(text)?;
    let named = format!("highlights[{entry}].layers[{layer}]");
    let bad = |reason: String| EditError::BadPath {
        written: named.clone(),
        reason,
        nearest: None,
    };
    let Some((parsed, steps)) = expected.layer_mut(entry, layer) else {
        return Err(bad("the file has no such highlight layer".to_string()));
    };
    let count = parsed.stack.len();
    let keyed_at = key_frames(&parsed.shape);
    let operation = |index: usize| {
        if index < count {
            Ok(())
        } else {
            Err(bad(format!(
                "the stack has {count} operation(s), numbered from 0, so there is no operation {index}"
            )))
        }
    };
    match edit {
        LayerEdit::InsertOp { index, op } => {
            if *index > count {
                return Err(bad(format!(
                    "the stack has {count} operation(s), so a new one goes at 0 to {count}, not {index}"
                )));
            }
            op.validate().map_err(|e| bad(e.to_string()))?;
        }
        LayerEdit::RemoveOp { index } => operation(*index)?,
        LayerEdit::MoveOp { from, to } => {
            operation(*from)?;
            operation(*to)?;
        }
        LayerEdit::AddMask if parsed.mask.is_some() => {
            return Err(bad("the layer has a mask already".to_string()))
        }
        LayerEdit::RemoveMask if parsed.mask.is_none() => {
            return Err(bad("the layer has no mask to remove".to_string()))
        }
        LayerEdit::PinTo { .. } if parsed.pin.is_none() => {
            return Err(bad("the layer has no pin to move".to_string()))
        }
        LayerEdit::Unpin if parsed.pin.is_none() => {
            return Err(bad("the layer has no pin to remove".to_string()))
        }
        LayerEdit::Hold { .. } if parsed.pin.is_none() => {
            return Err(bad(
                "the layer has no pin, and only a pinned layer holds its shape: pin it first \
                 (glint place --pin)"
                    .to_string(),
            ))
        }
        LayerEdit::Hold { frame: None }
            if parsed.pin.as_ref().is_some_and(|p| p.hold.is_none()) =>
        {
            return Err(bad("the layer's pin holds no shape to let go".to_string()))
        }
        LayerEdit::Pin { u, v, .. } if !(u.is_finite() && v.is_finite()) => {
            return Err(bad(format!(
                "a pin's (u, v) must be finite, not ({u}, {v})"
            )))
        }
        LayerEdit::Outline { key, points } => {
            if let Some(frame) = key.filter(|f| !f.is_finite()) {
                return Err(bad(format!(
                    "an outline key's frame must be a finite number, not {frame}"
                )));
            }
            let drawn = Outline {
                segments: points.iter().map(|&p| Segment::Corner(p)).collect(),
            };
            drawn
                .validate()
                .map_err(|e| bad(format!("the drawn outline: {e}")))?;
            if let (Some(frame), Shape::Morph(morph)) = (key, &parsed.shape) {
                check_key(morph, *frame, points).map_err(bad)?;
            }
        }
        LayerEdit::Disc if parsed.shape.is_disc() => {
            return Err(bad("the layer's shape is the disc already".to_string()))
        }
        LayerEdit::AddMask
        | LayerEdit::RemoveMask
        | LayerEdit::PinTo { .. }
        | LayerEdit::Pin { .. }
        | LayerEdit::Unpin
        | LayerEdit::Hold { .. }
        | LayerEdit::Disc => {}
    }
    edit.apply_to(parsed);
    let unchecked = |reason: &str| bad(format!("{reason}; the file is left as it is"));
    let mut stack_steps = steps.clone();
    stack_steps.push(Field("stack"));
    let splices = match edit {
        LayerEdit::InsertOp { index, op } => {
            let items = try_item_spans(text, &stack_steps);
            let item = op_text(op, number_text);
            match items {
                Some(items) if !items.is_empty() => {
                    vec![insert_item(text, &items, Some(*index), &item)
                        .ok_or_else(|| unchecked("the stack is not written as it reads"))?]
                }
                _ => {
                    let span = try_span(text, &stack_steps)
                        .ok_or_else(|| unchecked("the stack is not written as it reads"))?;
                    vec![Splice {
                        span,
                        text: format!("[{item}]"),
                    }]
                }
            }
        }
        LayerEdit::RemoveOp { index } => {
            let items = try_item_spans(text, &stack_steps)
                .filter(|items| items.len() == count)
                .ok_or_else(|| unchecked("the stack is not written as it reads"))?;
            if count == 1 {
                let span = try_span(text, &stack_steps)
                    .ok_or_else(|| unchecked("the stack is not written as it reads"))?;
                vec![Splice {
                    span,
                    text: "[]".to_string(),
                }]
            } else {
                vec![remove_item(text, &items, *index)]
            }
        }
        LayerEdit::MoveOp { from, to } => {
            let items = try_item_spans(text, &stack_steps)
                .filter(|items| items.len() == count)
                .ok_or_else(|| unchecked("the stack is not written as it reads"))?;
            let mut order: Vec<usize> = (0..count).collect();
            let moved = order.remove(*from);
            order.insert(*to, moved);
            (0..count)
                .filter(|&k| order[k] != k)
                .map(|k| Splice {
                    span: items[k].clone(),
                    text: text[items[order[k]].clone()].to_string(),
                })
                .collect()
        }
        LayerEdit::AddMask => {
            let fields = try_item_spans(text, &steps)
                .ok_or_else(|| unchecked("the layer is not written as it reads"))?;
            vec![
                insert_item(text, &fields, None, &mask_text(&unit_mask(), number_text))
                    .ok_or_else(|| unchecked("the layer is not written as it reads"))?,
            ]
        }
        LayerEdit::RemoveMask => {
            let fields = try_item_spans(text, &steps)
                .ok_or_else(|| unchecked("the layer is not written as it reads"))?;
            let index = field_index(text, &fields, "mask")
                .ok_or_else(|| unchecked("the mask is not written as it reads"))?;
            vec![remove_item(text, &fields, index)]
        }
        LayerEdit::Pin { patch, u, v } => {
            let hold = match parsed.pin.as_ref().and_then(|pin| pin.hold) {
                Some(frame) => format!(", hold: {frame}"),
                None => String::new(),
            };
            let written = format!(
                "pin: (patch: {}, u: {}, v: {}{hold})",
                serde_json::to_string(patch).unwrap_or_default(),
                number_text(*u),
                number_text(*v)
            );
            let fields = try_item_spans(text, &steps)
                .ok_or_else(|| unchecked("the layer is not written as it reads"))?;
            match field_index(text, &fields, "pin") {
                Some(index) => vec![Splice {
                    span: fields[index].clone(),
                    text: written,
                }],
                None => vec![insert_item(text, &fields, None, &written)
                    .ok_or_else(|| unchecked("the layer is not written as it reads"))?],
            }
        }
        LayerEdit::Unpin => {
            let fields = try_item_spans(text, &steps)
                .ok_or_else(|| unchecked("the layer is not written as it reads"))?;
            let index = field_index(text, &fields, "pin")
                .ok_or_else(|| unchecked("the pin is not written as it reads"))?;
            vec![remove_item(text, &fields, index)]
        }
        LayerEdit::Hold { frame } => {
            let mut pin_steps = steps.clone();
            pin_steps.push(Field("pin"));
            let fields = try_item_spans(text, &pin_steps)
                .ok_or_else(|| unchecked("the pin is not written as it reads"))?;
            let held = field_index(text, &fields, "hold");
            match (frame, held) {
                (Some(frame), Some(index)) => vec![Splice {
                    span: fields[index].clone(),
                    text: format!("hold: {frame}"),
                }],
                (Some(frame), None) => {
                    vec![insert_item(text, &fields, None, &format!("hold: {frame}"))
                        .ok_or_else(|| unchecked("the pin is not written as it reads"))?]
                }
                (None, Some(index)) => vec![remove_item(text, &fields, index)],
                (None, None) => return Err(unchecked("the pin's hold is not written as it reads")),
            }
        }
        LayerEdit::Outline { key, points } => match (key, &keyed_at) {
            (Some(frame), Some(frames)) => {
                vec![key_splice(text, &steps, frames, *frame, points)
                    .ok_or_else(|| unchecked("the outline's keys are not written as they read"))?]
            }
            _ => {
                let written = shape_field_text(*key, points);
                let fields = try_item_spans(text, &steps)
                    .ok_or_else(|| unchecked("the layer is not written as it reads"))?;
                match field_index(text, &fields, "shape") {
                    Some(index) => vec![Splice {
                        span: fields[index].clone(),
                        text: written,
                    }],
                    None => vec![insert_item(text, &fields, None, &written)
                        .ok_or_else(|| unchecked("the layer is not written as it reads"))?],
                }
            }
        },
        LayerEdit::Disc => {
            let fields = try_item_spans(text, &steps)
                .ok_or_else(|| unchecked("the layer is not written as it reads"))?;
            let index = field_index(text, &fields, "shape")
                .ok_or_else(|| unchecked("the shape is not written as it reads"))?;
            vec![remove_item(text, &fields, index)]
        }
        LayerEdit::PinTo { patch } => {
            let mut pin = steps.clone();
            pin.push(Field("pin"));
            let at = |field| {
                let mut path = pin.clone();
                path.push(Field(field));
                try_span(text, &path)
            };
            let name =
                at("patch").ok_or_else(|| unchecked("the pin is not written as it reads"))?;
            let quoted = serde_json::to_string(patch).unwrap_or_default();
            let mut splices = vec![Splice {
                span: name,
                text: quoted,
            }];
            if let Some(member) = at("member") {
                splices.push(Splice {
                    span: member,
                    text: "0".to_string(),
                });
            }
            splices
        }
    };
    read_back(apply(text, &splices), &expected, "layer").map_err(|reason| unchecked(&reason))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::highlight::Axis;
    use crate::shot::fixtures::shot_with_highlights;

    fn shot(stack: &str, rest: &str) -> String {
        shot_with_highlights(&format!(
            r#"[(patches: "*", expr: Union(
        Layer((stack: [Rotate(degrees: 5.0)], epsilon: 0.1, colour: (1.0, 1.0, 1.0))),
        Layer((
            stack: {stack},
            epsilon: 0.05, // small
            colour: (1.0, 1.0, 1.0),{rest}
        )),
    ))]"#
        ))
    }

    fn translate() -> Op<f32> {
        Op::Translate {
            alpha: 0.25,
            beta: -0.5,
        }
    }

    #[test]
    fn an_operation_is_inserted_in_the_stack_s_style() {
        let one_line = shot("[Rotate(degrees: 30.0), Scale(delta: 0.5, axis: V)]", "");
        let insert = LayerEdit::InsertOp {
            index: 1,
            op: translate(),
        };
        let edited = edit_layer(&one_line, 0, 1, &insert).unwrap();
        assert_eq!(
            edited,
            shot(
                "[Rotate(degrees: 30.0), Translate(alpha: 0.25, beta: -0.5), Scale(delta: 0.5, axis: V)]",
                ""
            )
        );
        let lines = shot(
            "[\n                Rotate(degrees: 30.0),\n            ]",
            "",
        );
        let at_end = LayerEdit::InsertOp {
            index: 1,
            op: translate(),
        };
        let edited = edit_layer(&lines, 0, 1, &at_end).unwrap();
        assert_eq!(
            edited,
            shot(
                "[\n                Rotate(degrees: 30.0),\n                Translate(alpha: 0.25, beta: -0.5),\n            ]",
                ""
            )
        );
        let empty = shot("[]", "");
        let first = LayerEdit::InsertOp {
            index: 0,
            op: translate(),
        };
        let edited = edit_layer(&empty, 0, 1, &first).unwrap();
        assert_eq!(edited, shot("[Translate(alpha: 0.25, beta: -0.5)]", ""));
    }

    #[test]
    fn operations_are_removed_and_moved_keeping_the_rest() {
        let text = shot(
            "[Rotate(degrees: 30.0), Translate(alpha: [(1, 0.0), (24, 0.5)], beta: 0.1), Split(gamma_u: 0.2, gamma_v: 0.0)]",
            "",
        );
        let removed = edit_layer(&text, 0, 1, &LayerEdit::RemoveOp { index: 0 }).unwrap();
        assert_eq!(
            removed,
            shot(
                "[Translate(alpha: [(1, 0.0), (24, 0.5)], beta: 0.1), Split(gamma_u: 0.2, gamma_v: 0.0)]",
                ""
            )
        );
        let moved = edit_layer(&text, 0, 1, &LayerEdit::MoveOp { from: 2, to: 0 }).unwrap();
        assert_eq!(
            moved,
            shot(
                "[Split(gamma_u: 0.2, gamma_v: 0.0), Rotate(degrees: 30.0), Translate(alpha: [(1, 0.0), (24, 0.5)], beta: 0.1)]",
                ""
            )
        );
        let single = shot("[Rotate(degrees: 30.0)]", "");
        let emptied = edit_layer(&single, 0, 1, &LayerEdit::RemoveOp { index: 0 }).unwrap();
        assert_eq!(emptied, shot("[]", ""));
    }

    #[test]
    fn a_mask_is_added_and_removed() {
        let text = shot("[]", "");
        let added = edit_layer(&text, 0, 1, &LayerEdit::AddMask).unwrap();
        assert!(
            added.contains("mask: (u: (0.0, 1.0), v: (0.0, 1.0), feather: 0.0)"),
            "{added}"
        );
        let removed = edit_layer(&added, 0, 1, &LayerEdit::RemoveMask).unwrap();
        assert_eq!(removed, text);
        let again = edit_layer(&added, 0, 1, &LayerEdit::AddMask).unwrap_err();
        assert!(again.to_string().contains("has a mask already"), "{again}");
        let none = edit_layer(&removed, 0, 1, &LayerEdit::RemoveMask).unwrap_err();
        assert!(none.to_string().contains("no mask to remove"), "{none}");
    }

    #[test]
    fn a_pin_moves_to_another_patch() {
        let text = shot(
            "[]",
            "\n            pin: (patch: \"ball/body\", member: 2, u: 0.5, v: [(1, 0.25)]),",
        );
        let moved = edit_layer(
            &text,
            0,
            1,
            &LayerEdit::PinTo {
                patch: "ball/4".to_string(),
            },
        )
        .unwrap();
        assert_eq!(
            moved,
            shot(
                "[]",
                "\n            pin: (patch: \"ball/4\", member: 0, u: 0.5, v: [(1, 0.25)]),"
            )
        );
        let unpinned = shot("[]", "");
        let e = edit_layer(
            &unpinned,
            0,
            1,
            &LayerEdit::PinTo {
                patch: "ball/4".to_string(),
            },
        )
        .unwrap_err();
        assert!(e.to_string().contains("no pin"), "{e}");
    }

    #[test]
    fn a_pin_is_added_replaced_and_removed() {
        let text = shot("[]", "");
        let pin = |u: f32, v: f32| LayerEdit::Pin {
            patch: "ball/4".to_string(),
            u,
            v,
        };
        let pinned = edit_layer(&text, 0, 1, &pin(0.25, 0.5)).unwrap();
        assert!(
            pinned.contains("pin: (patch: \"ball/4\", u: 0.25, v: 0.5)"),
            "{pinned}"
        );
        // A pin written with keys and a member is replaced whole.
        let keyed = shot(
            "[]",
            "\n            pin: (patch: \"ball/body\", member: 2, u: 0.5, v: [(1, 0.25)]),",
        );
        let replaced = edit_layer(&keyed, 0, 1, &pin(0.75, 0.125)).unwrap();
        assert_eq!(
            replaced,
            shot(
                "[]",
                "\n            pin: (patch: \"ball/4\", u: 0.75, v: 0.125),"
            )
        );
        let unpinned = edit_layer(&replaced, 0, 1, &LayerEdit::Unpin).unwrap();
        assert_eq!(unpinned, text);
        let e = edit_layer(&text, 0, 1, &LayerEdit::Unpin).unwrap_err();
        assert!(e.to_string().contains("no pin to remove"), "{e}");
        for (u, v) in [(f32::NAN, 0.5), (0.5, f32::INFINITY)] {
            let e = edit_layer(&text, 0, 1, &pin(u, v)).unwrap_err();
            assert!(
                e.to_string().contains("a pin's (u, v) must be finite"),
                "({u}, {v}): {e}"
            );
        }
    }

    #[test]
    fn a_pin_holds_a_shape_keeps_it_when_moved_and_lets_it_go() {
        let text = shot("[]", "");
        let hold = |frame| LayerEdit::Hold { frame };
        let e = edit_layer(&text, 0, 1, &hold(Some(12))).unwrap_err();
        assert!(e.to_string().contains("only a pinned layer holds"), "{e}");
        let keyed = shot(
            "[]",
            "\n            pin: (patch: \"ball/body\", member: 2, u: 0.5, v: [(1, 0.25)]),",
        );
        // The hold goes into the pin, which keeps its keys and member.
        let held = edit_layer(&keyed, 0, 1, &hold(Some(12))).unwrap();
        assert_eq!(
            held,
            shot(
                "[]",
                "\n            pin: (patch: \"ball/body\", member: 2, u: 0.5, v: [(1, 0.25)], hold: 12),"
            )
        );
        let moved = edit_layer(&held, 0, 1, &hold(Some(-3))).unwrap();
        assert!(moved.contains("v: [(1, 0.25)], hold: -3)"), "{moved}");
        // A pin put elsewhere keeps the shape it held.
        let repinned = edit_layer(
            &moved,
            0,
            1,
            &LayerEdit::Pin {
                patch: "ball/4".to_string(),
                u: 0.75,
                v: 0.125,
            },
        )
        .unwrap();
        assert!(
            repinned.contains("pin: (patch: \"ball/4\", u: 0.75, v: 0.125, hold: -3)"),
            "{repinned}"
        );
        let released = edit_layer(&held, 0, 1, &hold(None)).unwrap();
        assert_eq!(released, keyed);
        let e = edit_layer(&keyed, 0, 1, &hold(None)).unwrap_err();
        assert!(e.to_string().contains("holds no shape"), "{e}");
    }

    /// The outline of layer 1 as `text` reads: each key's frame (none for a plain outline) with
    /// its points at that frame.
    fn outline_of(text: &str) -> Vec<(Option<f64>, Vec<[f32; 2]>)> {
        let mut parsed = read_file(text).unwrap();
        let (layer, _) = parsed.layer_mut(0, 1).unwrap();
        let corners = |segments: &[Segment<f32>]| -> Vec<[f32; 2]> {
            segments
                .iter()
                .map(|s| match s {
                    Segment::Corner(p) => *p,
                    Segment::Bezier(_) => panic!("a Bezier"),
                })
                .collect()
        };
        match &layer.shape {
            Shape::Disc => Vec::new(),
            Shape::Outline(outline) => {
                let at_rest = outline.map(|t| t.at(0.0));
                vec![(None, corners(&at_rest.segments))]
            }
            Shape::Morph(morph) => morph
                .keys
                .iter()
                .map(|(frame, outline)| (Some(*frame), corners(&outline.segments)))
                .collect(),
        }
    }

    fn draw(key: Option<f64>, points: &[[f32; 2]]) -> LayerEdit {
        LayerEdit::Outline {
            key,
            points: points.to_vec(),
        }
    }

    const TRIANGLE: [[f32; 2]; 3] = [[0.0, 0.2], [0.173_205, -0.1], [-0.173_205_1, -0.1]];

    #[test]
    fn a_drawn_outline_is_written_to_four_places_and_the_disc_gives_the_file_back() {
        let text = shot("[]", "");
        let drawn = edit_layer(&text, 0, 1, &draw(None, &TRIANGLE)).unwrap();
        assert!(
            drawn.contains("shape: Outline([(0.0, 0.2), (0.1732, -0.1), (-0.1732, -0.1)]),"),
            "{drawn}"
        );
        assert_eq!(
            outline_of(&drawn),
            vec![(None, vec![[0.0, 0.2], [0.1732, -0.1], [-0.1732, -0.1]])]
        );
        // Drawn again, the outline is replaced in place.
        let square = [[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1], [-0.1, 0.1]];
        let again = edit_layer(&drawn, 0, 1, &draw(None, &square)).unwrap();
        assert_eq!(
            again,
            drawn.replace(
                "[(0.0, 0.2), (0.1732, -0.1), (-0.1732, -0.1)]",
                "[(-0.1, -0.1), (0.1, -0.1), (0.1, 0.1), (-0.1, 0.1)]"
            )
        );
        let disc = edit_layer(&again, 0, 1, &LayerEdit::Disc).unwrap();
        assert_eq!(disc, text);
        let e = edit_layer(&disc, 0, 1, &LayerEdit::Disc).unwrap_err();
        assert!(e.to_string().contains("disc already"), "{e}");
    }

    #[test]
    fn keys_are_replaced_or_inserted_in_frame_order() {
        let text = shot("[]", "");
        let first = edit_layer(&text, 0, 1, &draw(Some(12.0), &TRIANGLE)).unwrap();
        assert!(
            first.contains(
                "shape: OutlineKeys([(12, [(0.0, 0.2), (0.1732, -0.1), (-0.1732, -0.1)])]),"
            ),
            "{first}"
        );
        let wider = [[0.0, 0.3], [0.25, -0.15], [-0.25, -0.15]];
        let before = edit_layer(&first, 0, 1, &draw(Some(1.0), &wider)).unwrap();
        let after = edit_layer(&before, 0, 1, &draw(Some(24.5), &wider)).unwrap();
        let frames: Vec<Option<f64>> = outline_of(&after).iter().map(|k| k.0).collect();
        assert_eq!(frames, [Some(1.0), Some(12.0), Some(24.5)]);
        assert!(after.contains("(24.5, [(0.0, 0.3), (0.25, -0.15), (-0.25, -0.15)])"));
        // The key at 12 replaced: the others as they were.
        let replaced = edit_layer(&after, 0, 1, &draw(Some(12.0), &wider)).unwrap();
        assert_eq!(
            replaced,
            after.replace(
                "(12, [(0.0, 0.2), (0.1732, -0.1), (-0.1732, -0.1)])",
                "(12, [(0.0, 0.3), (0.25, -0.15), (-0.25, -0.15)])"
            )
        );
        // A plain outline keyed becomes its one key.
        let plain = edit_layer(&text, 0, 1, &draw(None, &wider)).unwrap();
        let keyed = edit_layer(&plain, 0, 1, &draw(Some(6.0), &TRIANGLE)).unwrap();
        assert_eq!(
            outline_of(&keyed),
            outline_of(&first)
                .into_iter()
                .map(|(_, p)| (Some(6.0), p))
                .collect::<Vec<_>>()
        );
    }

    #[test]
    fn drawn_outlines_that_cannot_be_written_are_refused_and_write_nothing() {
        let text = shot("[]", "");
        let keyed = edit_layer(&text, 0, 1, &draw(Some(12.0), &TRIANGLE)).unwrap();
        let square = [[-0.1, -0.1], [0.1, -0.1], [0.1, 0.1], [-0.1, 0.1]];
        let e = edit_layer(&keyed, 0, 1, &draw(Some(30.0), &square)).unwrap_err();
        assert!(
            e.to_string().contains(
                "the outline key at frame 30 would have 4 points but the key at frame 12 has 3"
            ),
            "{e}"
        );
        // Replacing the only key may change its count.
        assert!(edit_layer(&keyed, 0, 1, &draw(Some(12.0), &square)).is_ok());
        for (points, says) in [
            (vec![[0.0, 0.0], [0.1, 0.0]], "at least 3"),
            (
                vec![[0.0, 0.0], [0.995, 0.0], [0.0, 0.1]],
                "outside the allowed",
            ),
            (
                vec![[0.0, 0.0], [0.2, 0.2], [0.2, 0.0], [0.0, 0.2]],
                "crosses itself",
            ),
            (
                vec![[0.0, f32::NAN], [0.2, 0.2], [0.2, 0.0]],
                "not a finite",
            ),
        ] {
            let e = edit_layer(&text, 0, 1, &draw(None, &points)).unwrap_err();
            assert!(e.to_string().contains(says), "{points:?}: {e}");
        }
        let e = edit_layer(&text, 0, 1, &draw(Some(f64::NAN), &TRIANGLE)).unwrap_err();
        assert!(e.to_string().contains("finite"), "{e}");
    }

    #[test]
    fn out_of_range_indices_and_bad_operations_are_refused() {
        let text = shot("[Rotate(degrees: 30.0)]", "");
        for edit in [
            LayerEdit::RemoveOp { index: 1 },
            LayerEdit::MoveOp { from: 0, to: 3 },
            LayerEdit::InsertOp {
                index: 2,
                op: translate(),
            },
            LayerEdit::InsertOp {
                index: 0,
                op: Op::Scale {
                    delta: 2.0,
                    axis: Axis::U,
                },
            },
            LayerEdit::RemoveMask,
        ] {
            let e = edit_layer(&text, 0, 1, &edit).unwrap_err();
            assert!(
                e.to_string().contains("highlights[0].layers[1]"),
                "{edit:?}: {e}"
            );
        }
        let e = edit_layer(&text, 0, 2, &LayerEdit::RemoveOp { index: 0 }).unwrap_err();
        assert!(e.to_string().contains("no such highlight layer"), "{e}");
    }
}
