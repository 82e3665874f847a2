//! A change the page asks for, as it arrives over HTTP (JSON), and the file text it makes: a
//! track keyed, set or a key deleted ([`edit_text`]), or a layer's structure changed
//! ([`edit_layer`]) — the same edits, with the same checks, as `glint key`.

use serde::{Deserialize, Serialize};

use glint::highlight::{Axis, Op, SquareStyle};
use glint::shot::{
    edit_layer, edit_text, number_text, parse_param_path, value_text, EditError, LayerEdit,
    TrackEdit,
};

/// One change, JSON-tagged by `kind`:
///
/// ```json
/// {"kind": "key", "path": "highlights[0].layers[0].stack[0].alpha", "frame": 12, "value": [0.3]}
/// {"kind": "set", "path": "highlights[0].layers[0].colour", "value": [1.0, 0.9, 0.8]}
/// {"kind": "delete", "path": "highlights[0].layers[0].epsilon", "frame": 12}
/// {"kind": "insert_op", "highlight": 0, "layer": 0, "index": 1, "op": "Rotate"}
/// {"kind": "remove_op", "highlight": 0, "layer": 0, "index": 1}
/// {"kind": "move_op", "highlight": 0, "layer": 0, "from": 1, "to": 0}
/// {"kind": "add_mask", "highlight": 0, "layer": 0}
/// {"kind": "remove_mask", "highlight": 0, "layer": 0}
/// {"kind": "pin_to", "highlight": 0, "layer": 0, "patch": "teapot/5"}
/// {"kind": "pin", "highlight": 0, "layer": 0, "patch": "teapot/5", "u": 0.4, "v": 0.25}
/// {"kind": "unpin", "highlight": 0, "layer": 0}
/// {"kind": "outline", "highlight": 0, "layer": 0, "key": 12, "points": [[0.0, 0.2], [0.17, -0.1], [-0.17, -0.1]]}
/// {"kind": "disc", "highlight": 0, "layer": 0}
/// ```
///
/// Paths are parameter paths of the shot file (docs/shot-format.md); `highlight` is the index
/// of an entry in the shot file's own `highlights` list.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case", deny_unknown_fields)]
pub enum Change {
    /// Key the track at `frame` to `value` (one number, or three for a colour).
    Key {
        path: String,
        frame: f64,
        value: Vec<f32>,
    },
    /// Make the track the constant `value`.
    Set { path: String, value: Vec<f32> },
    /// Delete the track's key at `frame`.
    Delete { path: String, frame: f64 },
    /// Insert an operation of kind `op` with the parameters that leave H as it is.
    InsertOp {
        highlight: usize,
        layer: usize,
        index: usize,
        op: OpKind,
    },
    /// Remove the operation at `index`.
    RemoveOp {
        highlight: usize,
        layer: usize,
        index: usize,
    },
    /// Move the operation at `from` to `to`.
    MoveOp {
        highlight: usize,
        layer: usize,
        from: usize,
        to: usize,
    },
    /// Give the layer a mask over the unit square.
    AddMask { highlight: usize, layer: usize },
    /// Take the layer's mask out.
    RemoveMask { highlight: usize, layer: usize },
    /// Move the layer's pin to the patch named `patch`.
    PinTo {
        highlight: usize,
        layer: usize,
        patch: String,
    },
    /// Pin the layer to `(u, v)` of the patch named `patch`: a pin added, or the layer's pin
    /// replaced whole ([`LayerEdit::Pin`]).
    Pin {
        highlight: usize,
        layer: usize,
        patch: String,
        u: f32,
        v: f32,
    },
    /// Take the layer's pin out ([`LayerEdit::Unpin`]).
    Unpin { highlight: usize, layer: usize },
    /// Make the layer's pin hold the shape it has at `frame`, or with None let the shape follow
    /// the view again ([`LayerEdit::Hold`]).
    Hold {
        highlight: usize,
        layer: usize,
        frame: Option<i64>,
    },
    /// Give the layer the drawn outline of the corners `points` in t′, keyed at `key` when it
    /// is given ([`LayerEdit::Outline`]).
    Outline {
        highlight: usize,
        layer: usize,
        #[serde(default)]
        key: Option<f64>,
        points: Vec<[f32; 2]>,
    },
    /// Make the layer's shape the disc again.
    Disc { highlight: usize, layer: usize },
}

/// An operation's kind, as the page offers it to insert.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub enum OpKind {
    Translate,
    Rotate,
    Scale,
    Split,
    Square,
}

impl OpKind {
    /// Every kind, in the order the page offers them.
    pub const ALL: [OpKind; 5] = [
        OpKind::Translate,
        OpKind::Rotate,
        OpKind::Scale,
        OpKind::Split,
        OpKind::Square,
    ];

    /// The operation's name as a file writes it.
    #[must_use]
    pub fn name(self) -> &'static str {
        self.identity().name()
    }

    /// The operation of this kind that leaves H as it is: no step, no turn, no stretch (δ = 0),
    /// no split, no squaring (σ = 0, n = 1) — so that inserting it changes no pixel until a
    /// parameter is moved.
    #[must_use]
    pub fn identity(self) -> Op<f32> {
        match self {
            OpKind::Translate => Op::Translate {
                alpha: 0.0,
                beta: 0.0,
            },
            OpKind::Rotate => Op::Rotate { degrees: 0.0 },
            OpKind::Scale => Op::Scale {
                delta: 0.0,
                axis: Axis::U,
            },
            OpKind::Split => Op::Split {
                gamma_u: 0.0,
                gamma_v: 0.0,
            },
            OpKind::Square => Op::Square {
                sigma: 0.0,
                n: 1.0,
                style: SquareStyle::Tangent,
            },
        }
    }
}

impl Change {
    /// `text`, the shot file's, with the change made; an error names what is wrong in one
    /// line (a path that names no track, a value out of its range is caught when the result is
    /// loaded).
    pub fn apply(&self, text: &str) -> Result<String, EditError> {
        let track = |path: &str, edit: TrackEdit| {
            let path = parse_param_path(text, path)?;
            edit_text(text, &path, &edit)
        };
        let value = |v: &[f32]| value_text(v, number_text);
        match self {
            Change::Key {
                path,
                frame,
                value: v,
            } => track(
                path,
                TrackEdit::Key {
                    frame: *frame,
                    value: value(v),
                },
            ),
            Change::Set { path, value: v } => track(path, TrackEdit::Set(value(v))),
            Change::Delete { path, frame } => track(path, TrackEdit::Delete { frame: *frame }),
            Change::InsertOp {
                highlight,
                layer,
                index,
                op,
            } => edit_layer(
                text,
                *highlight,
                *layer,
                &LayerEdit::InsertOp {
                    index: *index,
                    op: op.identity(),
                },
            ),
            Change::RemoveOp {
                highlight,
                layer,
                index,
            } => edit_layer(
                text,
                *highlight,
                *layer,
                &LayerEdit::RemoveOp { index: *index },
            ),
            Change::MoveOp {
                highlight,
                layer,
                from,
                to,
            } => edit_layer(
                text,
                *highlight,
                *layer,
                &LayerEdit::MoveOp {
                    from: *from,
                    to: *to,
                },
            ),
            Change::AddMask { highlight, layer } => {
                edit_layer(text, *highlight, *layer, &LayerEdit::AddMask)
            }
            Change::RemoveMask { highlight, layer } => {
                edit_layer(text, *highlight, *layer, &LayerEdit::RemoveMask)
            }
            Change::PinTo {
                highlight,
                layer,
                patch,
            } => edit_layer(
                text,
                *highlight,
                *layer,
                &LayerEdit::PinTo {
                    patch: patch.clone(),
                },
            ),
            Change::Pin {
                highlight,
                layer,
                patch,
                u,
                v,
            } => edit_layer(
                text,
                *highlight,
                *layer,
                &LayerEdit::Pin {
                    patch: patch.clone(),
                    u: *u,
                    v: *v,
                },
            ),
            Change::Unpin { highlight, layer } => {
                edit_layer(text, *highlight, *layer, &LayerEdit::Unpin)
            }
            Change::Hold {
                highlight,
                layer,
                frame,
            } => edit_layer(text, *highlight, *layer, &LayerEdit::Hold { frame: *frame }),
            Change::Outline {
                highlight,
                layer,
                key,
                points,
            } => edit_layer(
                text,
                *highlight,
                *layer,
                &LayerEdit::Outline {
                    key: *key,
                    points: points.clone(),
                },
            ),
            Change::Disc { highlight, layer } => {
                edit_layer(text, *highlight, *layer, &LayerEdit::Disc)
            }
        }
    }
}

/// `text` with each of `changes` made in turn; the first that fails stops them.
pub fn apply_changes(text: &str, changes: &[Change]) -> Result<String, EditError> {
    changes
        .iter()
        .try_fold(text.to_string(), |text, change| change.apply(&text))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_identity_operation_is_valid_and_leaves_h_alone() {
        use glam::Vec3;
        use glint::highlight::TangentFrame;
        let frame = TangentFrame::new(Vec3::X, Vec3::Y, Vec3::Z);
        let h = Vec3::new(0.3, -0.2, 0.9).normalize();
        for kind in OpKind::ALL {
            let op = kind.identity().prepare().unwrap();
            let out = op.apply(&frame, h);
            assert!((out - h).length() < 1e-6, "{kind:?}: {out} for {h}");
        }
    }

    #[test]
    fn changes_read_from_json_by_kind() {
        let change: Change = serde_json::from_str(
            r#"{"kind": "key", "path": "highlights[0].layers[0].epsilon", "frame": 3, "value": [0.1]}"#,
        )
        .unwrap();
        assert_eq!(
            change,
            Change::Key {
                path: "highlights[0].layers[0].epsilon".to_string(),
                frame: 3.0,
                value: vec![0.1]
            }
        );
        let unknown = serde_json::from_str::<Change>(r#"{"kind": "explode"}"#).unwrap_err();
        assert!(unknown.to_string().contains("explode"), "{unknown}");
        let extra = serde_json::from_str::<Change>(
            r#"{"kind": "add_mask", "highlight": 0, "layer": 0, "rm": "-rf"}"#,
        )
        .unwrap_err();
        assert!(extra.to_string().contains("rm"), "{extra}");
    }
}
