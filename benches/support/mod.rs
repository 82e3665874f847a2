//! Shared by the benchmarks: a summary of speed ratios between functions measured in the same
//! run, read back from criterion's estimates.

use std::path::PathBuf;

/// criterion's median time per iteration (ns) for `group/function`, from this run's estimates.
fn median_ns(group: &str, function: &str) -> Option<f64> {
    let target =
        std::env::var_os("CARGO_TARGET_DIR").map_or_else(|| PathBuf::from("target"), PathBuf::from);
    let path = target
        .join("criterion")
        .join(group.replace('/', "_"))
        .join(function)
        .join("new/estimates.json");
    let text = std::fs::read_to_string(path).ok()?;
    let json: serde_json::Value = serde_json::from_str(&text).ok()?;
    json["median"]["point_estimate"].as_f64()
}

/// Prints, for each `(group, numerator, denominator)`, the time ratio numerator / denominator
/// of the medians measured in this run, with both medians.
pub fn print_ratios(title: &str, rows: &[(&str, &str, &str)]) {
    println!("\n{title}");
    println!(
        "{:<34} {:>14} {:>14} {:>10}",
        "group", "numerator", "denominator", "ratio"
    );
    for &(group, numerator, denominator) in rows {
        match (median_ns(group, numerator), median_ns(group, denominator)) {
            (Some(a), Some(b)) => println!(
                "{group:<34} {:>11.3} ms {:>11.3} ms {:>10.2}   ({numerator} / {denominator})",
                a / 1e6,
                b / 1e6,
                a / b
            ),
            _ => println!("{group:<34} (not measured in this run)"),
        }
    }
}
