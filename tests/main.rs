//! glint's behaviour through its public API and its binary. One test crate with a module per
//! area, so that a build links one test binary; shared helpers are in `common`.

mod common;

mod accuracy_cli;
mod accuracy_ladder;
mod anim_tracks;
mod cli_probe;
mod cli_render;
mod geometry_derivatives;
mod geometry_sphere;
mod geometry_stability;
mod geometry_teapot;
mod highlight_serde;
mod highlight_sphere;
mod highlight_stability;
mod patch_files;
mod raster_coverage;
mod raster_determinism;
mod raster_geometry;
mod render_sphere;
mod render_teapot;
mod render_tessellate;
mod shot_errors;
mod shot_files;
mod shot_motion;
mod toon_detail;
mod toon_render;
mod toon_serde;
mod toon_shape;
mod toon_texture;
