//! What trims cost a frame: each trimmed model shipped in `patches/` (the speaker and the car
//! panels, through their shots) rendered with its trims and with the same patches untrimmed, at
//! 1280 × 720 with the shot's own preset (`final`) and with `preview`, outlines on, side by side
//! in turns
//! (`support/frames.rs`). Each variant steps through the shot's frames, one per render, so the
//! moving camera makes every frame tessellate, rasterize and find its lines again. Run with
//! `cargo bench --bench trim`; it prints each variant's frame time by stage, then the ratios
//! trimmed / untrimmed, and the same ratios were the trim edges (the rims drawn at one sample)
//! to take no time: what the rest of the trims, and what their openings show, cost.

// Variant::render is for benchmarks that render one scene again and again.
#[allow(dead_code)]
#[path = "support/frames.rs"]
mod frames;

use std::cell::Cell;
use std::sync::Arc;

use frames::Variant;
use glint::geom::PatchLibrary;
use glint::render::{Renderer, Settings, Stage};
use glint::shot::load_shot;

const ROUNDS: usize = 12;

fn main() {
    for name in ["speaker", "car_doors"] {
        let shot = load_shot(std::path::Path::new(&format!("shots/{name}.ron"))).unwrap();
        let mut untrimmed: PatchLibrary = (*shot.library).clone();
        for patch in &mut untrimmed.patches {
            patch.trim = None;
        }
        let untrimmed = Arc::new(untrimmed);
        let trimmed = shot
            .library
            .patches
            .iter()
            .filter(|p| p.trim.is_some())
            .count();
        let mut shot_settings = shot.settings;
        shot_settings.width = 1280;
        shot_settings.height = 720;
        let preview = Settings::preview(1280, 720);
        let (first, count) = (shot.frames.0, shot.frames.1 - shot.frames.0 + 1);
        let shot = &shot;
        // The frame each variant renders next: they step through the shot alike.
        let variant = |label: &'static str, library: &Arc<PatchLibrary>, settings: Settings| {
            let mut renderer = Renderer::new(Arc::clone(library));
            let library = Arc::clone(library);
            let next = Cell::new(0i64);
            Variant::new(label, move || {
                let frame = first + next.get() % count;
                next.set(next.get() + 1);
                let state = shot.at(frame as f64);
                let mut scene = state.scene(shot).unwrap();
                scene.library = &library;
                Some(renderer.render(&scene, &settings).unwrap().stats)
            })
        };
        let mut variants = [
            variant("trimmed", &shot.library, shot_settings),
            variant("untrimmed", &untrimmed, shot_settings),
            variant("trimmed_preview", &shot.library, preview),
            variant("untrimmed_preview", &untrimmed, preview),
        ];
        let measured = frames::measure(&mut variants, ROUNDS);
        measured.print_frames(&format!(
            "{name}: {} patches, {trimmed} trimmed, 1280 × 720; the shot's preset ({:?}) and preview",
            shot.library.patches.len(),
            shot_settings.antialias
        ));
        let pairs = [
            ("trimmed", "untrimmed"),
            ("trimmed_preview", "untrimmed_preview"),
        ];
        measured.print_ratios(name, &pairs);
        measured.print_ratios_without(Stage::TrimEdges, &pairs[..1]);
    }
}
