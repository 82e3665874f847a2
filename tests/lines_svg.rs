//! Lines as SVG on a real shot: each stroke where the frame draws its line, a few long paths
//! per part, and `--svg` files that are written, stamped and checked like a frame's others.

use glint::job::{Overrides, RenderJob, FINGERPRINT_KEY};
use glint::render::{LineKind, VectorLines};
use glint::shot::Aov;

use crate::common::{glint_with, repo_file, stderr};

/// Points along each stroke of `lines`, at most half a pixel apart, with its width there.
fn samples(lines: &VectorLines) -> Vec<(glam::Vec2, f32)> {
    let mut out = Vec::new();
    for s in &lines.strokes {
        let n = s.points.len();
        let segments = if s.closed { n } else { n - 1 };
        for k in 0..segments.max(1) {
            let (a, b) = (s.points[k], s.points[(k + 1) % n]);
            let (wa, wb) = (s.widths[k], s.widths[(k + 1) % n]);
            let steps = (a.distance(b) / 0.5).ceil().max(1.0) as usize;
            for i in 0..steps {
                let t = i as f32 / steps as f32;
                out.push((a.lerp(b, t), wa + (wb - wa) * t));
            }
        }
    }
    out
}

#[test]
fn on_the_turntable_every_stroke_runs_on_the_drawn_lines_in_a_few_paths_a_part() {
    let overrides = Overrides {
        frames: Some(vec![1, 9, 17]),
        size: Some((480, 270)),
        aovs: Some(vec![Aov::Outline]),
        ..Overrides::default()
    };
    let mut job = RenderJob::load(&repo_file("shots/teapot_turntable.ron"), &overrides).unwrap();
    let (w, h) = (480usize, 270usize);
    for frame in [1, 9, 17] {
        let image = job.render_frame(frame as f64).unwrap();
        let lines = image.lines.as_deref().unwrap();
        let alpha: Vec<f32> = image
            .aovs
            .outline
            .as_ref()
            .unwrap()
            .iter()
            .map(|c| c.w)
            .collect();
        // A drawn line pixel: at least half covered. A stroke's centre point is on the drawn
        // lines when such a pixel lies within half a pixel of it.
        let drawn_near = |p: glam::Vec2| {
            let (x0, y0) = (p.x.floor() as i64, p.y.floor() as i64);
            (-1..=1).any(|dy| {
                (-1..=1).any(|dx| {
                    let (x, y) = (x0 + dx, y0 + dy);
                    if x < 0 || y < 0 || x >= w as i64 || y >= h as i64 {
                        return false;
                    }
                    let nearest = glam::Vec2::new(
                        p.x.clamp(x as f32, x as f32 + 1.0),
                        p.y.clamp(y as f32, y as f32 + 1.0),
                    );
                    alpha[y as usize * w + x as usize] >= 0.5 && nearest.distance(p) <= 0.5
                })
            })
        };
        // Taper tips thinner than a pixel draw no half-covered pixel; they are left out.
        let points: Vec<_> = samples(lines)
            .into_iter()
            .filter(|&(_, w)| w >= 1.0)
            .collect();
        let on = points.iter().filter(|&&(p, _)| drawn_near(p)).count();
        let share = on as f64 / points.len() as f64;
        assert!(
            share >= 0.99,
            "frame {frame}: {on} of {} stroke points on the drawn lines",
            points.len()
        );
        // Each part's silhouette is a few long paths, not one per piece of the mesh.
        for (p, part) in lines.parts.iter().enumerate() {
            let paths: Vec<_> = lines
                .strokes
                .iter()
                .filter(|s| s.kind == LineKind::Silhouette && s.part as usize == p)
                .filter(|s| s.uniform_width().is_some())
                .collect();
            let points: usize = paths.iter().map(|s| s.points.len()).sum();
            println!(
                "frame {frame}: {part}: {} silhouette paths, {points} points",
                paths.len()
            );
            assert!(
                paths.len() <= 8,
                "frame {frame}: {part}: {} paths",
                paths.len()
            );
        }
    }
}

#[test]
fn svg_files_are_written_stamped_and_verified_like_the_frame_s_others() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out/ls.####.png");
    let shot = repo_file("shots/line_styles.ron");
    let args = |command: &'static str| {
        vec![
            command.to_string(),
            shot.display().to_string(),
            "--frames".into(),
            "1-2".into(),
            "--size".into(),
            "160x90".into(),
            "--preset".into(),
            "preview".into(),
            "--out".into(),
            out.display().to_string(),
            "--svg".into(),
        ]
    };
    let run = |mut a: Vec<String>, extra: &[&str]| {
        a.extend(extra.iter().map(|s| s.to_string()));
        glint_with(&a.iter().map(String::as_str).collect::<Vec<_>>())
    };
    let rendered = run(args("render"), &["--quiet"]);
    assert_eq!(rendered.status.code(), Some(0), "{}", stderr(&rendered));
    let svg = dir.path().join("out/ls.0001.svg");
    let text = std::fs::read_to_string(&svg).unwrap();
    assert!(text.contains("viewBox=\"0 0 160 90\""));
    assert!(text.contains(&format!("<metadata data-key=\"{FINGERPRINT_KEY}\">")));
    assert!(text.contains("<g id=\"silhouette\""));
    let verified = run(args("verify"), &[]);
    assert_eq!(verified.status.code(), Some(0), "{}", stderr(&verified));
    // A truncated SVG is found, and only that frame is to render again.
    std::fs::write(&svg, &text[..text.len() / 2]).unwrap();
    let verified = run(args("verify"), &[]);
    let said = String::from_utf8_lossy(&verified.stdout).into_owned() + &stderr(&verified);
    assert_ne!(verified.status.code(), Some(0));
    assert!(said.contains("ls.0001.svg"), "{said}");
    assert!(!said.contains("ls.0002.svg"), "{said}");
    // --skip-existing renders it again, and the frame is whole once more.
    let resumed = run(args("render"), &["--quiet", "--skip-existing"]);
    assert_eq!(resumed.status.code(), Some(0), "{}", stderr(&resumed));
    assert_eq!(std::fs::read_to_string(&svg).unwrap(), text);
    // An output folder that cannot be made: refused in one line, exit 2, nothing written.
    let blocked = tempfile::tempdir().unwrap();
    std::fs::write(blocked.path().join("blocker"), b"a file").unwrap();
    let mut a = args("render");
    let at = a.len() - 2;
    a[at] = blocked
        .path()
        .join("blocker/ls.####.png")
        .display()
        .to_string();
    let refused = run(a.clone(), &["--quiet"]);
    assert_eq!(refused.status.code(), Some(2), "{}", stderr(&refused));
    assert_eq!(
        stderr(&refused).trim().lines().count(),
        1,
        "{}",
        stderr(&refused)
    );
    // Something that is not a file where an SVG goes: that frame fails (exit 1) and its colour
    // is not written, so the frame is not taken for whole; the frame before it is.
    std::fs::remove_file(blocked.path().join("blocker")).unwrap();
    std::fs::create_dir_all(blocked.path().join("blocker/ls.0002.svg")).unwrap();
    let failed = run(a, &["--quiet"]);
    assert_eq!(failed.status.code(), Some(1), "{}", stderr(&failed));
    assert!(
        stderr(&failed).contains("ls.0002.svg"),
        "{}",
        stderr(&failed)
    );
    assert!(blocked.path().join("blocker/ls.0001.png").is_file());
    assert!(
        !blocked.path().join("blocker/ls.0002.png").exists(),
        "no partial frame"
    );
}
