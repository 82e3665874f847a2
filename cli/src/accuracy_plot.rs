//! The error–time plot of a sweep as SVG: one colour per image size, every rung a point (filled
//! on the Pareto front, which is joined by a line), the presets labelled.

use plotters::prelude::*;

use glint::accuracy::sweep::Summary;

/// One colour per image size, distinct on white.
const COLOURS: [RGBColor; 4] = [
    RGBColor(214, 39, 40),
    RGBColor(31, 119, 180),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
];

/// The smallest 1 − IoU drawn: lower values sit on the axis (log scale).
const FLOOR: f64 = 1e-5;

/// The SVG text of the plot of the worst view's 1 − IoU against frame time (both logarithmic).
pub fn error_against_time(summaries: &[Summary]) -> Result<String, String> {
    let mut svg = String::new();
    draw(summaries, &mut svg).map_err(|e| format!("drawing the plot: {e}"))?;
    Ok(svg)
}

fn draw(summaries: &[Summary], svg: &mut String) -> Result<(), Box<dyn std::error::Error>> {
    let error = |s: &Summary| s.worst_one_minus_iou.max(FLOOR);
    let time = |s: &Summary| 1e3 * s.frame_seconds;
    let range = |values: Vec<f64>| {
        let (lo, hi) = values.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
        if lo.is_finite() && hi > lo {
            (lo / 1.5)..(hi * 1.5)
        } else {
            0.1..10.0
        }
    };
    let x_range = range(summaries.iter().map(time).collect());
    let y_range = range(summaries.iter().map(error).collect());
    let mut sizes: Vec<u32> = summaries.iter().map(|s| s.size).collect();
    sizes.sort_unstable();
    sizes.dedup();

    let root = SVGBackend::with_string(svg, (900, 620)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            "Accuracy ladder on the analytic sphere: error against time",
            ("sans-serif", 20),
        )
        .margin(12)
        .x_label_area_size(44)
        .y_label_area_size(70)
        .build_cartesian_2d(x_range.log_scale(), y_range.log_scale())?;
    chart
        .configure_mesh()
        .x_desc("time per frame (ms, median)")
        .y_desc("1 − IoU (worst view)")
        .light_line_style(WHITE)
        .x_label_formatter(&|&x| {
            if x >= 1.0 {
                format!("{x:.0}")
            } else {
                format!("{x:.2}")
            }
        })
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .draw()?;

    for (index, &size) in sizes.iter().enumerate() {
        let colour = COLOURS[index % COLOURS.len()].to_rgba();
        let of_size: Vec<&Summary> = summaries.iter().filter(|s| s.size == size).collect();
        chart
            .draw_series(of_size.iter().map(|s| {
                let style = if s.pareto {
                    colour.filled()
                } else {
                    colour.stroke_width(1)
                };
                Circle::new((time(s), error(s)), 3, style)
            }))?
            .label(format!("{size} × {size} (filled: Pareto front)"))
            .legend(move |(x, y)| Circle::new((x, y), 4, colour.filled()));
        let mut front: Vec<(f64, f64)> = of_size
            .iter()
            .filter(|s| s.pareto)
            .map(|s| (time(s), error(s)))
            .collect();
        front.sort_by(|a, b| a.0.total_cmp(&b.0));
        chart.draw_series(LineSeries::new(front, colour.stroke_width(2)))?;
        chart.draw_series(of_size.iter().filter_map(|s| {
            let preset = s.rung.preset()?;
            Some(
                EmptyElement::at((time(s), error(s)))
                    + Cross::new((0, 0), 6, BLACK.stroke_width(2))
                    + Text::new(preset, (6, -16), ("sans-serif", 14)),
            )
        }))?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .position(SeriesLabelPosition::UpperRight)
        .draw()?;
    root.present()?;
    Ok(())
}
