//! `glint patches --map`: the patch map of a model or of a shot's placed instances, seen by the
//! shot's camera or from a three-quarter view, written to a PNG.

use std::path::Path;
use std::sync::Arc;

use anyhow::anyhow;

use super::CliError;
use glint::formats::png::{write_png, PngLayout};
use glint::geom::PatchLibrary;
use glint::picture::{part_legend, patch_labels, render_patch_map, try_three_quarter_camera};
use glint::render::{RenderError, Settings};
use glint::shot::{Preset, Shot};

/// The map's size for a patch file when none is given.
pub const DEFAULT_MAP_SIZE: (u32, u32) = (800, 600);

/// What the map shows: the model of `file`, through `shot`'s camera at `frame` when it is a
/// shot, at `size`.
pub struct MapView<'a> {
    pub file: &'a Path,
    pub shot: Option<&'a Shot>,
    pub frame: Option<f64>,
    pub size: Option<(u32, u32)>,
}

/// Renders the patch map of `library` as `view` asks and writes it to `out`, atomically.
///
/// For a shot: its camera and its model at `frame` (default its first frame, which must lie in
/// its range), its resolution and tessellation at the preview preset; patch names lose their
/// instance prefix when the shot places one instance. For a patch file: the three-quarter view of
/// [`try_three_quarter_camera`] at [`DEFAULT_MAP_SIZE`] and the preview preset.
pub fn write_map(
    library: &Arc<PatchLibrary>,
    view: &MapView<'_>,
    out: &Path,
) -> Result<(), CliError> {
    let bad = |message: String| CliError::BadInput(anyhow!(message));
    let file = view.file.display();
    let (camera, settings, prefix, library) = match view.shot {
        Some(shot) => {
            let (first, last) = shot.frames;
            let frame = view.frame.unwrap_or(first as f64);
            if !(frame >= first as f64 && frame <= last as f64) {
                return Err(bad(format!(
                    "{file}: --frame {frame} is outside the shot's frame range {first}-{last}"
                )));
            }
            let settings = shot.settings_with(Some(Preset::Preview), view.size);
            let prefix = match shot.instances.as_slice() {
                [only] => Some(format!("{}/", only.name)),
                _ => None,
            };
            // The model as the frame poses it.
            let state = shot.at(frame);
            (state.camera, settings, prefix, state.library)
        }
        None => {
            if view.frame.is_some() {
                return Err(bad(format!(
                    "{file}: --frame picks the camera of a shot's frame, and this is a patch file, shown from a three-quarter view"
                )));
            }
            let (width, height) = view.size.unwrap_or(DEFAULT_MAP_SIZE);
            let camera = try_three_quarter_camera(library, f64::from(width) / f64::from(height))
                .ok_or_else(|| {
                    bad(format!(
                        "{file}: the model has no finite control points to frame"
                    ))
                })?;
            (
                camera,
                Settings::preview(width, height),
                None,
                Arc::clone(library),
            )
        }
    };
    let library = &library;
    let labels = patch_labels(library, prefix.as_deref());
    let legend = part_legend(library, prefix.as_deref());
    let map =
        render_patch_map(library, camera, &settings, &labels, &legend).map_err(|e| match e {
            RenderError::Camera(_)
            | RenderError::Settings(_)
            | RenderError::MeshTooLarge { .. } => bad(format!("{file}: {e}")),
            RenderError::Threads { .. }
            | RenderError::OtherModel
            | RenderError::LooksPerPatch { .. } => CliError::Failed(e.into()),
        })?;
    if let Some(folder) = out.parent().filter(|f| !f.as_os_str().is_empty()) {
        std::fs::create_dir_all(folder).map_err(|e| {
            bad(format!(
                "cannot make the folder {} for the map: {e}",
                folder.display()
            ))
        })?;
    }
    let (width, height) = map.image.dimensions();
    write_png(out, width, height, PngLayout::Rgba8, map.image.as_raw())
        .map_err(|e| CliError::Failed(e.into()))
}
