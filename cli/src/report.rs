//! `glint render --report FILE.jsonl`: one JSON line per frame written, for a farm's
//! dashboards — what was written, from which inputs, how long each stage took, how much memory
//! the process has held, and where it ran.

use std::collections::BTreeMap;
use std::io::Write;
use std::path::Path;
use std::time::Duration;

use anyhow::Context;
use serde::Serialize;

use glint::job::RenderJob;
use glint::render::RenderStats;

/// One line of the report.
#[derive(Serialize)]
struct Line {
    frame: i64,
    path: String,
    fingerprint: Option<String>,
    /// The frame from start to written, seconds.
    seconds: f64,
    /// Each stage that ran, seconds.
    stages: BTreeMap<&'static str, f64>,
    /// The most memory the process has held so far (its peak resident set), bytes; `null` where
    /// the system does not say.
    peak_memory_bytes: Option<u64>,
    host: String,
}

/// Appends frame `frame`'s line to the report at `report` (created if missing): one write of
/// one line, so that tasks appending to one report on a shared disk do not interleave lines.
pub(super) fn append(
    report: &Path,
    job: &RenderJob,
    frame: i64,
    stats: &RenderStats,
    took: Duration,
) -> anyhow::Result<()> {
    let line = Line {
        frame,
        path: job.frame_path(frame).display().to_string(),
        fingerprint: job.fingerprint(frame).map(|f| f.0),
        seconds: took.as_secs_f64(),
        stages: stats
            .ran_stages()
            .map(|(stage, s)| (stage.name(), s.seconds))
            .collect(),
        peak_memory_bytes: peak_memory_bytes(),
        host: glint::formats::atomic::host_name(),
    };
    let mut text = serde_json::to_string(&line)?;
    text.push('\n');
    let mut file = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(report)
        .with_context(|| format!("cannot open the report {}", report.display()))?;
    file.write_all(text.as_bytes())
        .with_context(|| format!("cannot write the report {}", report.display()))
}

/// The process's peak resident set (`VmHWM` of `/proc/self/status`, Linux), bytes.
fn peak_memory_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib * 1024)
}
