//! Render statistics: what each stage did and how long it took. A stage the scene does not use
//! reports zero pixels.

use std::time::Instant;

use serde::Serialize;

/// One stage's work.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct StageStats {
    /// Pixels (or samples, under supersampling) the stage processed.
    pub pixels: u64,
    /// Wall-clock time in seconds.
    pub seconds: f64,
}

/// Per-stage statistics of one rendered frame.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct RenderStats {
    /// Whether the mesh had to be rebuilt (false when the cached one served).
    pub tessellation_rebuilt: bool,
    pub triangles: usize,
    pub tessellation: StageStats,
    /// Pixels: samples covered by a surface.
    pub raster: StageStats,
    /// Pixels: covered samples filled (0 when the frame's only effect is the cel tone over
    /// interpolated frames, which is shaded straight from the visibility buffer).
    pub gbuffer: StageStats,
    /// NURBS frames evaluated per pixel (exact and refined frames).
    pub exact_frames: u64,
    /// Pixels: samples on X-Toon patches, whose shading normal, detail and texture colour were
    /// computed (0 without X-Toon). Seconds: the pass that runs them ahead of shading when a
    /// designed highlight uses the abstracted frame, and is part of `shade`'s time; 0 when the
    /// shade pass computes them as it goes.
    pub detail: StageStats,
    /// Pixels: samples shaded (tone, and highlights where a patch has them).
    pub shade: StageStats,
    /// Samples on highlighted patches: the only ones a half vector was built for.
    pub highlight_pixels: u64,
    /// Pixels: samples the outline pass examined (0 without outlines).
    pub outline: StageStats,
    /// Pixels: AOV values filled (0 without AOVs).
    pub aov: StageStats,
    /// Pixels: output pixels resolved from samples (0 without supersampling).
    pub resolve: StageStats,
    /// The whole frame.
    pub total_seconds: f64,
}

/// Runs `work` and returns its result with the seconds it took.
pub fn timed<T>(work: impl FnOnce() -> T) -> (T, f64) {
    let start = Instant::now();
    let value = work();
    (value, start.elapsed().as_secs_f64())
}
