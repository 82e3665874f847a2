//! Editing a highlight layer's structure in a shot or look file's text: an operation inserted,
//! removed or moved in its stack, its mask added or removed — each as splices of the text, every
//! other byte kept, and the result read back and checked to differ in that alone.

use super::error::EditError;
use super::layer_text::{mask_text, op_text};
use super::number_text::number_text;
use super::read::read_file;
use super::track_splice::{apply, insert_item, remove_item, Splice};
use crate::anim::Track;
use crate::formats::ron_paths::Step::Field;
use crate::formats::ron_paths::{try_item_spans, try_span};
use crate::highlight::{Layer, Mask, Op, Pin};

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
                layer.pin = Some(Pin {
                    patch: patch.clone(),
                    member: 0,
                    u: Track::Constant(*u),
                    v: Track::Constant(*v),
                });
            }
            LayerEdit::Unpin => layer.pin = None,
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
        LayerEdit::Pin { u, v, .. } if !(u.is_finite() && v.is_finite()) => {
            return Err(bad(format!(
                "a pin's (u, v) must be finite, not ({u}, {v})"
            )))
        }
        LayerEdit::AddMask
        | LayerEdit::RemoveMask
        | LayerEdit::PinTo { .. }
        | LayerEdit::Pin { .. }
        | LayerEdit::Unpin => {}
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
                    let before = (*index < items.len()).then_some(*index);
                    vec![insert_item(text, &items, before, &item)
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
            let written = format!(
                "pin: (patch: {}, u: {}, v: {})",
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
    let edited = apply(text, &splices);
    match read_file(&edited) {
        Ok(reread) if reread == expected => Ok(edited),
        Ok(_) => Err(unchecked(
            "the edited file reads back with more changed than this layer",
        )),
        Err(e) => Err(unchecked(&format!(
            "the edited file does not read back (at {e})"
        ))),
    }
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
        let e = edit_layer(&text, 0, 1, &pin(f32::NAN, 0.5)).unwrap_err();
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
