//! glint's behaviour through its public API and its binary. One test crate with a module per
//! area, so that a build links one test binary; shared helpers are in `common`.

mod common;

mod accuracy_cli;
mod accuracy_ladder;
mod anim_tracks;
mod animator_task;
mod cli_bench_loop;
mod cli_farm;
mod cli_key;
mod cli_layer;
mod cli_probe;
mod cli_render;
mod cli_watch;
mod farm_verify;
mod fingerprint_edits;
mod fuzz_replay;
mod geometry_derivatives;
mod geometry_sphere;
mod geometry_stability;
mod geometry_teapot;
mod hardening;
mod highlight_hold;
mod highlight_outline;
mod highlight_place;
mod highlight_seams;
mod highlight_serde;
mod highlight_sphere;
mod highlight_stability;
mod import_loops;
mod job_reload;
mod lines_svg;
mod model_parts;
mod motion_fingerprint;
mod motion_loop;
mod motion_pin;
mod motion_rigid;
mod outline_errors;
mod outline_inspect;
mod outline_place;
mod patch_files;
mod pictures;
mod raster_coverage;
mod raster_determinism;
mod raster_geometry;
mod render_adaptive;
mod render_line_styles;
mod render_lines;
mod render_lines_kinds;
mod render_lines_motion;
mod render_motion_reuse;
mod render_reuse;
mod render_sphere;
mod render_teapot;
mod render_tessellate;
mod render_trim;
mod shade_key;
mod shade_place;
mod shade_plan;
mod shade_sphere;
mod shot_errors;
mod shot_files;
mod shot_key_edit;
mod shot_motion;
mod shot_orbit;
mod shot_usd_motion;
mod toon_detail;
mod toon_render;
mod toon_serde;
mod toon_shape;
mod toon_texture;
mod tune_api;
mod tune_http;
mod tutorial;
mod usd_import;
mod usd_import_twins;
mod usd_motion;

/// `autotests = false` makes this file the only test crate: a test file it does not declare
/// would never be compiled, let alone run.
#[test]
fn every_test_file_is_a_module_of_this_crate() {
    let main = include_str!("main.rs");
    let folder = crate::common::root().join("tests");
    let mut missing = Vec::new();
    for entry in std::fs::read_dir(&folder).unwrap() {
        let path = entry.unwrap().path();
        let Some(stem) = path.file_stem().and_then(|s| s.to_str()) else {
            continue;
        };
        let is_module = path.extension().is_some_and(|e| e == "rs") || path.join("mod.rs").exists();
        if is_module && stem != "main" && !main.contains(&format!("\nmod {stem};")) {
            missing.push(stem.to_string());
        }
    }
    assert!(
        missing.is_empty(),
        "not declared in tests/main.rs: {missing:?}"
    );
}
