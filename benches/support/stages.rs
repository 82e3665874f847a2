//! A frame's time by stage, for the benchmarks that render whole frames.

use glint::render::{RenderStats, Renderer, Scene, Settings};

/// Seconds of one stage in a frame's statistics.
type Stage = fn(&RenderStats) -> f64;

/// The stages of a frame, in the order they run.
const STAGES: [(&str, Stage); 9] = [
    ("tessellation", |s| s.tessellation.seconds),
    ("raster", |s| s.raster.seconds),
    ("g-buffer", |s| s.gbuffer.seconds),
    ("detail", |s| s.detail.seconds),
    ("shade", |s| s.shade.seconds),
    ("outline", |s| s.outline.seconds),
    ("aov", |s| s.aov.seconds),
    ("resolve", |s| s.resolve.seconds),
    ("total", |s| s.total_seconds),
];

/// Prints each variant's frame time by stage (ms), the median over frames rendered one after
/// another, and the samples its surfaces cover. The detail pass is part of the shade stage.
pub fn print_stages(title: &str, variants: &[(&str, &Scene, &Settings)]) {
    const FRAMES: usize = 40;
    println!("\n{title} (median of {FRAMES} frames, ms)");
    print!("{:<14}", "stage");
    for (name, _, _) in variants {
        print!(" {name:>15}");
    }
    println!();
    let stats: Vec<Vec<RenderStats>> = variants
        .iter()
        .map(|(_, scene, settings)| {
            let mut renderer = Renderer::new(scene.library);
            (0..FRAMES)
                .map(|_| renderer.render(scene, settings).unwrap().stats)
                .collect()
        })
        .collect();
    for (stage_name, stage) in STAGES {
        print!("{stage_name:<14}");
        for frames in &stats {
            let mut seconds: Vec<f64> = frames.iter().map(stage).collect();
            seconds.sort_by(f64::total_cmp);
            print!(" {:>15.3}", seconds[FRAMES / 2] * 1e3);
        }
        println!();
    }
    print!("{:<14}", "covered");
    for frames in &stats {
        print!(" {:>15}", frames[0].raster.pixels);
    }
    println!();
}
