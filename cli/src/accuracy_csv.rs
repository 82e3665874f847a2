//! The measurements as CSV text, one table per kind, with a header row. Labels hold no commas.

use std::fmt::Write;

use glint::accuracy::geometry::{FrameCost, MeshError};
use glint::accuracy::scaling::ScalingPoint;
use glint::accuracy::sweep::{Measurement, Summary};

/// Rows of `cells`, comma-separated, after the `header`.
fn table<const N: usize>(header: [&str; N], rows: impl Iterator<Item = [String; N]>) -> String {
    let mut text = header.join(",");
    text.push('\n');
    for row in rows {
        let _ = writeln!(text, "{}", row.join(","));
    }
    text
}

fn preset_label(preset: Option<&str>) -> String {
    preset.unwrap_or("").to_string()
}

/// One row per size, view and rung.
pub fn sweep(measurements: &[Measurement]) -> String {
    table(
        [
            "size",
            "pose",
            "stack",
            "preset",
            "density",
            "frames",
            "antialias",
            "triangles",
            "one_minus_iou",
            "boundary_px",
            "silhouette_one_minus_iou",
            "silhouette_px",
            "max_normal_deg",
            "mean_normal_deg",
            "frame_ms",
        ],
        measurements.iter().map(|m| {
            [
                m.size.to_string(),
                m.case.pose.to_string(),
                m.case.stack.to_string(),
                preset_label(m.rung.preset()),
                m.rung.density.to_string(),
                m.rung.frames.to_string(),
                m.rung.antialias.to_string(),
                m.triangles.to_string(),
                format!("{:.6}", m.errors.one_minus_iou),
                format!("{:.4}", m.errors.boundary_pixels),
                format!("{:.6}", m.errors.silhouette_one_minus_iou),
                format!("{:.4}", m.errors.silhouette_pixels),
                format!("{:.4}", m.errors.max_normal_degrees),
                format!("{:.4}", m.errors.mean_normal_degrees),
                format!("{:.3}", 1e3 * m.frame_seconds),
            ]
        }),
    )
}

/// One row per size and rung, over all views, with the Pareto front marked.
pub fn summary(summaries: &[Summary]) -> String {
    table(
        [
            "size",
            "preset",
            "density",
            "frames",
            "antialias",
            "triangles",
            "mean_one_minus_iou",
            "worst_one_minus_iou",
            "mean_boundary_px",
            "worst_boundary_px",
            "worst_silhouette_one_minus_iou",
            "worst_silhouette_px",
            "max_normal_deg",
            "mean_normal_deg",
            "frame_ms",
            "pareto",
        ],
        summaries.iter().map(|s| {
            [
                s.size.to_string(),
                preset_label(s.rung.preset()),
                s.rung.density.to_string(),
                s.rung.frames.to_string(),
                s.rung.antialias.to_string(),
                s.triangles.to_string(),
                format!("{:.6}", s.mean_one_minus_iou),
                format!("{:.6}", s.worst_one_minus_iou),
                format!("{:.4}", s.mean_boundary_pixels),
                format!("{:.4}", s.worst_boundary_pixels),
                format!("{:.6}", s.worst_silhouette_one_minus_iou),
                format!("{:.4}", s.worst_silhouette_pixels),
                format!("{:.4}", s.max_normal_degrees),
                format!("{:.4}", s.mean_normal_degrees),
                format!("{:.3}", 1e3 * s.frame_seconds),
                s.pareto.to_string(),
            ]
        }),
    )
}

/// One row per tessellation density.
pub fn mesh_errors(errors: &[MeshError]) -> String {
    table(
        [
            "segments_per_span",
            "triangles",
            "max_position_error",
            "max_normal_deg",
            "tessellate_ms",
        ],
        errors.iter().map(|e| {
            [
                e.segments.to_string(),
                e.triangles.to_string(),
                format!("{:.3e}", e.max_position_error),
                format!("{:.4}", e.max_normal_degrees),
                format!("{:.3}", 1e3 * e.tessellate_seconds),
            ]
        }),
    )
}

/// One row per frame mode.
pub fn frame_costs(costs: &[FrameCost]) -> String {
    table(
        ["frames", "exact_frames", "gbuffer_ns_per_pixel", "frame_ms"],
        costs.iter().map(|c| {
            [
                c.frames.to_string(),
                c.exact_frames.to_string(),
                format!("{:.1}", c.gbuffer_ns_per_pixel),
                format!("{:.3}", 1e3 * c.frame_seconds),
            ]
        }),
    )
}

/// One row per timed scaling configuration.
pub fn scaling(points: &[ScalingPoint]) -> String {
    table(
        ["series", "preset", "x", "triangles", "frame_ms"],
        points.iter().map(|p| {
            [
                p.series.name().into(),
                p.preset.into(),
                p.x.to_string(),
                p.triangles.to_string(),
                format!("{:.3}", 1e3 * p.frame_seconds),
            ]
        }),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_follow_the_header_comma_separated_one_per_line() {
        let text = table(
            ["a", "b"],
            [["1".to_string(), "x y".to_string()]].into_iter(),
        );
        assert_eq!(text, "a,b\n1,x y\n");
    }
}
