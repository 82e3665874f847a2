//! Checking every track of a shot at every frame it can take, before any frame is rendered.

use std::collections::BTreeSet;

use super::pin::pin_path;
use super::source::Source;
use super::validated::{MaterialState, Shot};
use super::written::Written;
use super::ShotError;
use crate::anim::Keyed;
use crate::formats::ron_paths::Step::{self, Entry, Field, Index};
use crate::geom::MAX_COORDINATE;
use crate::highlight::{Expr, HighlightError, Light, Mask, ShadeStack, Shape};
use crate::render::LineStyle;

/// Checks the camera, light, materials, highlights, shade stacks and line styles at every frame
/// they can
/// take.
///
/// Between keys every value moves linearly, and the ranges of materials and highlights are
/// intervals and orderings, which hold along a line once they hold at its ends: so each
/// material, each highlight layer's own parameters, each operation and each line style is
/// checked at its own keys (and at the first frame, for constants), and the work grows with the keys and
/// operations written, not with frames × operations. The camera is the exception — eye and
/// target can meet, or the line of sight turn onto `up`, between two keys where both are
/// fine — so it and the light are checked at every frame of the range and at their keys.
///
/// `sources[0]` is the shot file; `material_sources` names the file each material is written
/// in, `highlights_written` where each highlight entry is, `shade_written` each shade entry.
pub(super) fn check_every_frame(
    shot: &Shot,
    sources: &[Source],
    material_sources: &[usize],
    highlights_written: &[Written],
    shade_written: &[Written],
) -> Result<(), ShotError> {
    check_every_frame_counted(
        shot,
        sources,
        material_sources,
        highlights_written,
        shade_written,
    )
    .map(|_| ())
}

/// [`check_every_frame`], and how many checks it made (of a camera, a light, a material, a
/// layer's own parameters, an operation or a pin at one frame).
fn check_every_frame_counted(
    shot: &Shot,
    sources: &[Source],
    material_sources: &[usize],
    highlights_written: &[Written],
    shade_written: &[Written],
) -> Result<usize, ShotError> {
    let first = shot.frames.0 as f64;
    let mut checks = 0;
    let shot_source = &sources[0];

    let mut frames: BTreeSet<u64> = (shot.frames.0..=shot.frames.1)
        .map(|f| (f as f64).to_bits())
        .collect();
    let mut add = |track: &dyn Keyed| {
        track.for_each_key(&mut |frame| {
            frames.insert(frame.to_bits());
        });
    };
    shot.camera.for_each_param(&mut add);
    shot.light.for_each_param(&mut add);
    for frame in frames.into_iter().map(f64::from_bits) {
        checks += 1;
        if let Some(orbit) = &shot.camera.orbit {
            orbit.check_at(frame).map_err(|e| {
                shot_source.error_at(
                    &[Field("camera"), Field("orbit"), Field(e.field)],
                    e.message,
                )
            })?;
        }
        shot.camera_at(frame).validate().map_err(|e| {
            shot_source.error_at(&[Field("camera")], format!("at frame {frame}: {e}"))
        })?;
        match shot.light_at(frame) {
            Light::Point { position }
                if !(position.is_finite()
                    && position.abs().max_element() <= MAX_COORDINATE as f32) =>
            {
                return Err(shot_source.error_at(
                    &[Field("light")],
                    format!(
                        "at frame {frame}: the light position must be finite, each coordinate \
                         within ±{MAX_COORDINATE:e}"
                    ),
                ));
            }
            Light::Point { .. } | Light::Directional { .. } => {}
        }
    }

    for (((name, material), &source), _) in shot
        .materials
        .iter()
        .zip(material_sources)
        .zip(shot.material_names())
    {
        let frames = key_frames(first, |add| material.for_each_param(add));
        check_at(&frames, shot.frames, &mut checks, |frame| {
            let valid = match material.at(frame) {
                MaterialState::Cel(ramp) => ramp.validate().map_err(|e| e.to_string()),
                MaterialState::XToon(tone) => tone.validate().map_err(|e| e.to_string()),
            };
            valid.map_err(|e| {
                sources[source].error_at(
                    &[Field("materials"), Entry(name)],
                    format!("material \"{name}\" at frame {frame}: {e}"),
                )
            })
        })?;
    }

    for (entry, (highlight, written)) in shot.highlights.iter().zip(highlights_written).enumerate()
    {
        let source = &sources[written.source];
        let pattern = &highlight.patches.patterns()[0];
        for (k, layer) in highlight.expr.layers().into_iter().enumerate() {
            // What is wrong with layer k at `frame`, reported where `path` is written.
            let invalid = |path: &[Step], frame: f64, e: HighlightError| {
                source.error_at(
                    path,
                    format!(
                        "the highlight on \"{pattern}\" at frame {frame}: {}",
                        e.at(format!("layers[{k}]"))
                    ),
                )
            };
            if !layer.shape.is_disc() {
                let path = shape_path(*written, &highlight.expr, k);
                // Counts and bounds hold along a morph once they hold at its keys; a frame
                // between two keys may cross itself, and is filled by the non-zero winding rule.
                let frames = key_frames(first, |add| {
                    let _visited: Shape<()> = layer.shape.map(|t| add(t));
                });
                check_at(&frames, shot.frames, &mut checks, |frame| {
                    layer
                        .shape
                        .map(|t| t.at(frame))
                        .validate()
                        .map_err(|e| invalid(&path, frame, e))
                })?;
            }
            let own = layer.without_stack();
            let frames = key_frames(first, |add| own.for_each_param(|t| add(t)));
            check_at(&frames, shot.frames, &mut checks, |frame| {
                if let Some(pin) = &layer.pin {
                    shot.check_pin(entry, k, pin, frame).map_err(|message| {
                        source.error_at(&pin_path(*written, &highlight.expr, k), message)
                    })?;
                }
                own.map(|t| t.at(frame))
                    .validate()
                    .map_err(|e| invalid(&layer_path(*written, &highlight.expr, k), frame, e))
            })?;
            for (i, op) in layer.stack.iter().enumerate() {
                let frames = key_frames(first, |add| op.for_each_param(|t| add(t)));
                check_at(&frames, shot.frames, &mut checks, |frame| {
                    let at_frame = op.map(|t| t.at(frame));
                    at_frame.validate().map_err(|e| {
                        // At the operation itself, as its parameter path names it.
                        let mut path = layer_path(*written, &highlight.expr, k);
                        path.extend([Field("stack"), Index(i)]);
                        invalid(
                            &path,
                            frame,
                            e.at(format!("stack[{i}] ({})", at_frame.name())),
                        )
                    })
                })?;
            }
        }
    }
    for (spec, written) in shot.shade.iter().zip(shade_written) {
        let source = &sources[written.source];
        let pattern = &spec.patches.patterns()[0];
        let entry = [Field("shade"), Index(written.index)];
        for (i, op) in spec.stack.iter().enumerate() {
            let frames = key_frames(first, |add| op.for_each_param(|t| add(t)));
            check_at(&frames, shot.frames, &mut checks, |frame| {
                let at_frame = op.map(|t| t.at(frame));
                at_frame.validate().map_err(|e| {
                    let mut path = entry.to_vec();
                    path.extend([Field("stack"), Index(i)]);
                    source.error_at(
                        &path,
                        format!(
                            "the shade on \"{pattern}\" at frame {frame}: {}",
                            e.at(format!("stack[{i}] ({})", at_frame.name()))
                        ),
                    )
                })
            })?;
        }
        if let Some(mask) = &spec.mask {
            let frames = key_frames(first, |add| {
                let _visited: Mask<()> = mask.map(|t| add(t));
            });
            check_at(&frames, shot.frames, &mut checks, |frame| {
                let at_frame = ShadeStack {
                    stack: Vec::new(),
                    mask: Some(mask.map(|t| t.at(frame))),
                };
                at_frame.validate().map_err(|e| {
                    let mut path = entry.to_vec();
                    path.push(Field("mask"));
                    source.error_at(
                        &path,
                        format!("the shade on \"{pattern}\" at frame {frame}: {e}"),
                    )
                })
            })?;
        }
    }
    // A dash pattern holds for the whole shot: checked once, where it is written.
    let hidden = shot
        .outlines
        .iter()
        .map(|o| (o.hidden.as_ref(), vec![Field("render"), Field("outlines")]))
        .chain(
            shot.lines
                .iter()
                .enumerate()
                .map(|(entry, l)| (l.hidden.as_ref(), vec![Field("lines"), Index(entry)])),
        );
    for (spec, mut path) in hidden {
        if let Some(spec) = spec {
            crate::render::Dash::try_new(&spec.dash).map_err(|e| {
                path.extend([Field("hidden"), Field("dash")]);
                shot_source.error_at(&path, e)
            })?;
        }
    }
    if let Some(outlines) = &shot.outlines {
        let frames = key_frames(first, |add| outlines.for_each_param(add));
        check_at(&frames, shot.frames, &mut checks, |frame| {
            outlines.at(frame).1.validate().map_err(|e| {
                shot_source.error_at(
                    &[Field("render"), Field("outlines")],
                    format!("the outlines at frame {frame}: {e}"),
                )
            })
        })?;
    }
    for (entry, line) in shot.lines.iter().enumerate() {
        let frames = key_frames(first, |add| line.for_each_param(add));
        // What the entry sets, over a style valid in every field.
        let valid = LineStyle::new(1.0, glam::Vec3::ZERO);
        check_at(&frames, shot.frames, &mut checks, |frame| {
            line.at(frame).over(valid).validate().map_err(|e| {
                shot_source.error_at(
                    &[Field("lines"), Index(entry)],
                    format!("the line style at frame {frame}: {e}"),
                )
            })
        })?;
    }
    Ok(checks)
}

/// Where layer `layer` of a highlight entry's expression writes its `shape`.
fn shape_path<P>(written: Written, expr: &Expr<P>, layer: usize) -> Vec<Step<'static>> {
    let mut path = layer_path(written, expr, layer);
    path.push(Field("shape"));
    path
}

/// Where layer `layer` of a highlight entry's `expr` is written, in its file.
fn layer_path<P>(written: Written, expr: &Expr<P>, layer: usize) -> Vec<Step<'static>> {
    let mut path = vec![Field("highlights"), Index(written.index), Field("expr")];
    path.extend(
        expr.layer_route(layer)
            .unwrap_or_default()
            .into_iter()
            .map(Index),
    );
    path
}

/// Runs `check` at each of `frames`, in order, counting the checks in `checks`. Where one
/// fails, the error named is at the first whole frame of the shot's `range` after the last
/// frame that passed, when the check fails there — the first frame that would render wrong —
/// and otherwise at the frame that failed; the search runs only once, on the way out.
fn check_at<E>(
    frames: &[f64],
    (first, last): (i64, i64),
    checks: &mut usize,
    mut check: impl FnMut(f64) -> Result<(), E>,
) -> Result<(), E> {
    let mut passed = f64::NEG_INFINITY;
    for &frame in frames {
        *checks += 1;
        if let Err(at_key) = check(frame) {
            // Whole frames strictly between `passed` and `frame` (casts saturate).
            let from = (passed.floor() as i64).saturating_add(1).max(first);
            let to = (frame.ceil() as i64).saturating_sub(1).min(last);
            for whole in from..=to {
                check(whole as f64)?;
            }
            return Err(at_key);
        }
        passed = frame;
    }
    Ok(())
}

/// The frames at which a group of tracks, each linear between its keys, takes every value it
/// turns at: `first` and every key of the tracks `visit` names, in order, once each.
fn key_frames(first: f64, visit: impl FnOnce(&mut dyn FnMut(&dyn Keyed))) -> Vec<f64> {
    let mut frames = vec![first];
    visit(&mut |track| track.for_each_key(&mut |frame| frames.push(frame)));
    frames.sort_by(f64::total_cmp);
    frames.dedup();
    frames
}

#[cfg(test)]
mod tests;
