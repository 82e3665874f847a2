//! What `--stats` prints of a frame: each stage's work and time.

use glint::render::{RenderStats, Stage};

/// One line per stage, in pipeline order, for `--stats`: what it processed and its time, or
/// that the previous frame's result was reused, or that the plan skipped it.
pub(crate) fn stats_report(frame: i64, s: &RenderStats) -> String {
    let mut out = format!(
        "frame {frame} stats: {:.2} ms total, {} triangles (tessellation {})",
        s.total_seconds * 1e3,
        s.triangles,
        if s.tessellation_rebuilt {
            format!(
                "rebuilt: {} patch grids evaluated, {} kept",
                s.grids_evaluated, s.grids_kept
            )
        } else {
            "cached".to_string()
        }
    );
    for stage in Stage::ALL {
        let name = stage.name();
        if s.ran(stage) {
            let st = s[stage];
            let unit = if stage == Stage::Tessellate {
                "tri"
            } else {
                "px"
            };
            out.push_str(&format!(
                "\n  {name:<12} {:>10} {unit:<3} {:>8.2} ms",
                st.pixels,
                st.seconds * 1e3
            ));
        } else if s.reused(stage) {
            out.push_str(&format!("\n  {name:<12} {:>10}", "reused"));
        } else {
            out.push_str(&format!("\n  {name:<12} {:>10}", "skipped"));
        }
    }
    if s.ran(Stage::Rasterize) && s.triangles_rasterized < s.triangles {
        out.push_str(&format!(
            "\n  rasterized {} of {} triangles: the others' visibility was kept",
            s.triangles_rasterized, s.triangles
        ));
    }
    if s.texels_kept > 0 {
        out.push_str(&format!(
            "\n  G-buffer: {} texels kept from the previous frame",
            s.texels_kept
        ));
    }
    if s.intersection_pairs_kept + s.intersection_pairs_tested > 0 {
        out.push_str(&format!(
            "\n  intersections found again: {} patch pairs kept, {} tested",
            s.intersection_pairs_kept, s.intersection_pairs_tested
        ));
    }
    if s.silhouettes_kept > 0 {
        out.push_str(&format!(
            "\n  silhouettes: {} patches' kept from the previous frame",
            s.silhouettes_kept
        ));
    }
    out.push_str(&format!(
        "\n  exact frames {}, highlighted samples {}, X-Toon samples {}",
        s.exact_frames, s.highlight_pixels, s.xtoon_pixels
    ));
    out
}
