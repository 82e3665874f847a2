//! How much memory rendering a frame takes, estimated before rendering: what a farm task should
//! request, and what the memory ceiling refuses.

use crate::render::{Antialias, FrameMode, Settings};
use crate::shot::Aov;

/// Bytes held per sample of the whole-image buffers while a frame renders (its G-buffer entry,
/// visibility and shading, the resolved colour and the images written, shared out): with
/// interpolated frames, measured as 80 B a pixel at `preview`; with exact or refined frames,
/// which keep each sample's frame, about 80 B a sample under 4 × 4 supersampling and 110 B a
/// pixel at `final` (adaptive, one sample a pixel); 150 B covers smaller frames, where the
/// fixed costs weigh more — the teapot turntable (README, farm section).
fn bytes_per_sample(frames: FrameMode) -> u64 {
    match frames {
        FrameMode::Interpolated => 90,
        FrameMode::Exact | FrameMode::Refined => 150,
    }
}

/// Bytes a mesh vertex holds over a frame (position, normal, tangent, (u, v), its share of the
/// triangles, and their projected and facing forms): 177 B measured on the teapot at 256
/// segments per span (2.1 M vertices, 388 MB peak at 64×64), rounded up.
const BYTES_PER_VERTEX: u64 = 200;

/// What the process holds before the first frame: code, the model, its mesh.
const BASE_BYTES: u64 = 64 << 20;

/// What each worker holds while it supersamples a tile under adaptive anti-aliasing: a window
/// of at most (16 · 8 + apron)² samples at about 250 B each at 8 × 8, rounded up; at 4 × 4 a
/// quarter of it. The batch of pixels drawn from the points around them (1024 pixels' samples
/// with their candidates, about 650 B a sample at most: 42 MB at 8 × 8) takes as much once
/// more.
const TILE_BYTES_PER_SAMPLE_SIDE: u64 = 1 << 20;

/// Bytes a pixel holds for an AOV while its frame renders and is written (its image, the
/// shading it keeps, its PNG and its layer of the EXR), rounded up from the teapot turntable
/// at `final`, 3840 × 2160: the matte adds 164 MB (20 B a pixel), the normal 281 MB (34 B: it
/// also has the one-sample pass refine its frames, as `uv`, `depth` and `N·H` do), all seven
/// 955 MB (115 B); `N·L'` reads the frames the tone is shaded with, and adds 65 MB (8 B) to the
/// seven.
fn aov_bytes_per_pixel(aov: Aov) -> u64 {
    match aov {
        Aov::Normal | Aov::Uv | Aov::Depth | Aov::NDotH => 36,
        Aov::Matte | Aov::PatchId | Aov::NDotL | Aov::Outline => 24,
    }
}

/// The peak memory of rendering one frame with `settings`, the AOVs `aovs` and a mesh of
/// `vertices` vertices, an upper estimate from measured peaks (the README's farm table):
/// `64 MiB + pixels × samples × (90 B interpolated, 150 B exact or refined) + vertices × 200 B`,
/// plus per pixel 36 B for each AOV that reads the pixels' frames and 24 B for each other;
/// and under adaptive anti-aliasing `K²` MiB more per worker thread for its tile, and once more
/// for the batch of samples drawn without tiles.
#[must_use]
pub fn estimate_peak_bytes(settings: &Settings, aovs: &[Aov], vertices: u64) -> u64 {
    image_bytes(settings, aovs)
        .saturating_add(BASE_BYTES)
        .saturating_add(vertices.saturating_mul(BYTES_PER_VERTEX))
}

/// The part of [`estimate_peak_bytes`] that grows with the image (and the workers' tiles).
fn image_bytes(settings: &Settings, aovs: &[Aov]) -> u64 {
    let pixels = u64::from(settings.width) * u64::from(settings.height);
    let aov_bytes: u64 = aovs.iter().map(|&aov| aov_bytes_per_pixel(aov)).sum();
    let samples = u64::from(settings.samples_per_side()).pow(2);
    let tiles = match settings.antialias {
        Antialias::None | Antialias::Analytic | Antialias::Supersample(_) => 0,
        Antialias::Adaptive(k) => {
            let workers = match settings.threads {
                0 => std::thread::available_parallelism().map_or(1, |n| n.get()),
                n => n,
            };
            u64::from(k).pow(2) * TILE_BYTES_PER_SAMPLE_SIDE * (workers as u64 + 1)
        }
    };
    pixels * (samples * bytes_per_sample(settings.frames) + aov_bytes) + tiles
}

/// The most vertices a mesh may have beside a frame of `settings` with the AOVs `aovs` within
/// `ceiling` bytes.
#[must_use]
pub fn max_mesh_vertices(settings: &Settings, aovs: &[Aov], ceiling: u64) -> u64 {
    ceiling.saturating_sub(BASE_BYTES.saturating_add(image_bytes(settings, aovs)))
        / BYTES_PER_VERTEX
}

/// The frames of `frames` the memory of a job is estimated at: at most 16, evenly spaced,
/// the first and last among them. The mesh of a screen tolerance changes with the view; a
/// frame between these whose mesh is larger than the ceiling allows is refused when it comes
/// ([`Renderer::set_max_mesh_vertices`](crate::render::Renderer::set_max_mesh_vertices)).
#[must_use]
pub fn sampled_frames(frames: &[i64]) -> Vec<i64> {
    const MOST: usize = 16;
    if frames.len() <= MOST {
        return frames.to_vec();
    }
    (0..MOST)
        .map(|k| frames[k * (frames.len() - 1) / (MOST - 1)])
        .collect()
}

/// The memory ceiling when none is given: three quarters of the memory this process may use —
/// the machine's (`MemTotal` in `/proc/meminfo`), or its control group's limit
/// (`/sys/fs/cgroup/memory.max`) where that is lower — or 4 GiB where neither can be read.
#[must_use]
pub fn default_memory_ceiling() -> u64 {
    let total = std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|text| {
            let line = text.lines().find(|l| l.starts_with("MemTotal:"))?;
            let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
            kib.checked_mul(1024)
        });
    let group = std::fs::read_to_string("/sys/fs/cgroup/memory.max")
        .ok()
        .and_then(|text| text.trim().parse::<u64>().ok());
    let usable = match (total, group) {
        (Some(t), Some(g)) => t.min(g),
        (Some(m), None) | (None, Some(m)) => m,
        (None, None) => return 4 << 30,
    };
    usable / 4 * 3
}

/// `bytes` for people: `512 MB`, `2.6 GB` (powers of 1000).
#[must_use]
pub fn bytes_text(bytes: u64) -> String {
    let b = bytes as f64;
    if b >= 1e9 {
        format!("{:.1} GB", b / 1e9)
    } else {
        format!("{:.0} MB", (b / 1e6).max(1.0))
    }
}

/// Reads a memory size as `--max-memory` takes it: a number of bytes with an optional unit —
/// `K`, `M`, `G`, `T` (powers of 1024, with or without a trailing `B` or `iB`) — such as
/// `512M`, `8G` or `1.5GiB`.
pub fn parse_memory_size(text: &str) -> Result<u64, String> {
    let t = text.trim();
    let split = t.find(|c: char| c.is_ascii_alphabetic()).unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let scale: u64 = match unit.to_ascii_uppercase().as_str() {
        "" | "B" => 1,
        "K" | "KB" | "KIB" => 1 << 10,
        "M" | "MB" | "MIB" => 1 << 20,
        "G" | "GB" | "GIB" => 1 << 30,
        "T" | "TB" | "TIB" => 1 << 40,
        _ => {
            return Err(format!(
                "\"{text}\" is no memory size: the unit must be K, M, G or T"
            ))
        }
    };
    let value: f64 = number
        .trim()
        .parse()
        .map_err(|_| format!("\"{text}\" is no memory size: write a number and a unit, like 8G"))?;
    let bytes = value * scale as f64;
    if !(bytes.is_finite() && bytes >= 1.0 && bytes < 2f64.powi(63)) {
        return Err(format!(
            "\"{text}\" is no memory size: it must be at least 1 byte"
        ));
    }
    Ok(bytes as u64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::tessellate::Density;

    #[test]
    fn the_estimate_covers_the_measured_peaks() {
        // Peaks measured with /usr/bin/time on the teapot (32 one-span patches; README, farm
        // section). Its mesh at a screen tolerance has at most 32 · 65² vertices; at 256 and
        // 128 segments per span 32 · 257² and 32 · 129².
        let dense = |mut s: Settings, n| {
            s.density = Density::PerSpan { u: n, v: n };
            s
        };
        let mesh = |n: u64| 32 * (n + 1) * (n + 1);
        for (settings, vertices, measured) in [
            (
                Settings {
                    antialias: crate::render::Antialias::Supersample(4),
                    ..Settings::final_quality(1920, 1080)
                },
                mesh(64),
                2_600_000_000u64,
            ),
            (Settings::final_quality(640, 360), mesh(64), 125_000_000),
            (Settings::final_quality(1920, 1080), mesh(64), 300_000_000),
            (Settings::final_quality(3840, 2160), mesh(64), 815_000_000),
            (Settings::preview(1920, 1080), mesh(64), 200_000_000),
            (Settings::preview(3840, 2160), mesh(64), 665_000_000),
            (
                dense(Settings::preview(64, 64), 256),
                mesh(256),
                388_000_000,
            ),
            (
                dense(Settings::preview(64, 64), 128),
                mesh(128),
                140_000_000,
            ),
        ] {
            let estimate = estimate_peak_bytes(&settings, &[], vertices);
            assert!(
                estimate >= measured,
                "{settings:?}: {estimate} < {measured}"
            );
            assert!(
                estimate < measured * 2,
                "{settings:?}: {estimate} is far above {measured}"
            );
        }
    }

    #[test]
    fn the_estimate_covers_the_measured_peaks_with_aovs() {
        // The teapot turntable at `final`, 3840 × 2160, measured with /usr/bin/time: the matte
        // alone, the normal alone, all but `N·L'`, and all eight. The estimate adds each AOV's
        // own cost, so it counts the frames refined for several of them more than once.
        let mesh = 32 * 65 * 65;
        let settings = Settings::final_quality(3840, 2160);
        for (aovs, measured) in [
            (vec![Aov::Matte], 910_000_000u64),
            (vec![Aov::Normal], 1_030_000_000),
            (
                Aov::ALL.into_iter().filter(|&a| a != Aov::NDotL).collect(),
                1_700_000_000,
            ),
            (Aov::ALL.to_vec(), 1_630_000_000),
        ] {
            let estimate = estimate_peak_bytes(&settings, &aovs, mesh);
            assert!(estimate >= measured, "{aovs:?}: {estimate} < {measured}");
            assert!(estimate < measured * 21 / 10, "{aovs:?}: {estimate}");
        }
    }

    #[test]
    fn the_room_left_for_the_mesh_is_what_the_estimate_allows() {
        let settings = Settings::preview(640, 360);
        let ceiling = 1 << 30;
        let most = max_mesh_vertices(&settings, &[], ceiling);
        assert!(estimate_peak_bytes(&settings, &[], most) <= ceiling);
        assert!(estimate_peak_bytes(&settings, &[], most + 1) > ceiling);
        let matte = max_mesh_vertices(&settings, &[Aov::Matte], ceiling);
        assert!(estimate_peak_bytes(&settings, &[Aov::Matte], matte) <= ceiling);
        assert!(matte < most);
        assert_eq!(
            max_mesh_vertices(&Settings::final_quality(4096, 4096), &[], ceiling),
            0
        );
        // Adaptive samples take tiles per worker, not K² times the image.
        let adaptive = |k, threads| Settings {
            antialias: Antialias::Adaptive(k),
            threads,
            ..Settings::final_quality(1920, 1080)
        };
        let (four, eight) = (
            estimate_peak_bytes(&adaptive(4, 2), &[], 0),
            estimate_peak_bytes(&adaptive(8, 2), &[], 0),
        );
        assert_eq!(eight - four, 3 * (64 - 16) * TILE_BYTES_PER_SAMPLE_SIDE);
        assert_eq!(
            estimate_peak_bytes(&adaptive(4, 8), &[], 0) - four,
            6 * 16 * TILE_BYTES_PER_SAMPLE_SIDE
        );
    }

    #[test]
    fn sampled_frames_keep_the_ends_and_at_most_sixteen() {
        let frames: Vec<i64> = (1..=1000).collect();
        let sampled = sampled_frames(&frames);
        assert_eq!(sampled.len(), 16);
        assert_eq!((sampled[0], sampled[15]), (1, 1000));
        assert!(sampled.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(sampled_frames(&[3, 9]), vec![3, 9]);
    }

    #[test]
    fn memory_sizes_read_with_their_units() {
        assert_eq!(parse_memory_size("512M"), Ok(512 << 20));
        assert_eq!(parse_memory_size("8G"), Ok(8 << 30));
        assert_eq!(parse_memory_size("1.5GiB"), Ok(3 << 29));
        assert_eq!(parse_memory_size("4096"), Ok(4096));
        assert_eq!(parse_memory_size("2 tb"), Ok(2 << 40));
        for bad in ["", "G", "-1G", "8X", "nanG", "1e30T", "0"] {
            assert!(parse_memory_size(bad).is_err(), "{bad}");
        }
    }
}
