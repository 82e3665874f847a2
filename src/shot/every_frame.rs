//! Checking every track of a shot at every frame it can take, before any frame is rendered.

use std::collections::BTreeSet;

use super::load::Written;
use super::pin::pin_path;
use super::source::Source;
use super::validated::{MaterialState, Shot};
use super::ShotError;
use crate::formats::ron_paths::Step::{Entry, Field, Index};
use crate::highlight::Light;

/// Checks the camera, light, materials and highlights at every frame of the range and at every
/// key of every track ([`Shot::for_each_param`]): between keys every value moves linearly, so
/// the ranges (intervals) hold everywhere once they hold there.
///
/// `sources[0]` is the shot file; `material_sources` names the file each material is written
/// in, `highlights_written` where each highlight entry is.
pub(super) fn check_every_frame(
    shot: &Shot,
    sources: &[Source],
    material_sources: &[usize],
    highlights_written: &[Written],
) -> Result<(), ShotError> {
    let mut frames: BTreeSet<u64> = (shot.frames.0..=shot.frames.1)
        .map(|f| (f as f64).to_bits())
        .collect();
    shot.for_each_param(&mut |track| {
        track.for_each_key(&mut |frame| {
            frames.insert(frame.to_bits());
        });
    });

    let shot_source = &sources[0];
    for frame in frames.into_iter().map(f64::from_bits) {
        let state = shot.at(frame);
        state.camera.validate().map_err(|e| {
            shot_source.error_at(&[Field("camera")], format!("at frame {frame}: {e}"))
        })?;
        match state.light {
            Light::Point { position } if !position.is_finite() => {
                return Err(shot_source.error_at(
                    &[Field("light")],
                    format!("at frame {frame}: the light position must be finite"),
                ));
            }
            Light::Point { .. } | Light::Directional { .. } => {}
        }
        for ((material, name), &source) in state
            .materials
            .iter()
            .zip(shot.material_names())
            .zip(material_sources)
        {
            let valid = match material {
                MaterialState::Cel(ramp) => ramp.validate().map_err(|e| e.to_string()),
                MaterialState::XToon(tone) => tone.validate().map_err(|e| e.to_string()),
            };
            valid.map_err(|e| {
                sources[source].error_at(
                    &[Field("materials"), Entry(name)],
                    format!("material \"{name}\" at frame {frame}: {e}"),
                )
            })?;
        }
        for (entry, ((expr, selector), written)) in state
            .highlights
            .iter()
            .zip(shot.highlight_selectors())
            .zip(highlights_written)
            .enumerate()
        {
            shot.check_pins(entry, frame, |k, message| {
                let spec = &shot.highlights[entry].expr;
                sources[written.source].error_at(&pin_path(*written, spec, k), message)
            })?;
            expr.validate().map_err(|e| {
                let pattern = &selector[0];
                sources[written.source].error_at(
                    &[Field("highlights"), Index(written.index), Field("patches")],
                    format!("the highlight on \"{pattern}\" at frame {frame}: {e}"),
                )
            })?;
        }
    }
    Ok(())
}
