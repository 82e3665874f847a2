//! A shade entry's numbers as parameter paths (`shade[N].stack[J].alpha`, `shade[N].mask.…`):
//! keyed with `glint key`, read back by loading the shot, refused with the nearest valid path
//! when they name no track, checked against the operation's range, and varied by `glint sheet`.

use std::path::{Path, PathBuf};
use std::process::Output;

use glint::highlight::{Mask, Op, ShadeStack};
use glint::shot::load_shot;

use crate::common::{repo_file, stderr};

/// A shot of the ball with one shade entry (a translation, a squaring, a mask) and `extra`
/// written after it in the `shade` list, written into `dir`.
fn write_shot(dir: &Path, extra: &str) -> PathBuf {
    let text = format!(
        r#"Shot(
    resolution: (64, 48),
    frames: (1, 21),
    fps: 24,
    output: "out/ball.####.png",
    instances: [(name: "ball", file: "{model}", material: "blue")],
    materials: {{ "blue": Cel(base: (0.04, 0.07, 0.2), bands: [(0.3, (0.3, 0.5, 0.9))]) }},
    camera: (eye: (0.0, -6.0, 1.0), target: (0.0, 0.0, 0.0), projection: Orthographic(height: 2.4)),
    light: Directional(towards: (0.35, -1.0, 0.45)),
    shade: [
        (
            patches: "ball/*",
            stack: [Translate(alpha: 0.1, beta: 0.0), Square(sigma: 0.2, n: 2.0)],
            mask: Some((u: (0.25, 0.9), v: (0.0, 1.0), feather: 0.05)),
        ),{extra}
    ],
)
"#,
        model = repo_file("patches/sphere.ron").display()
    );
    let path = dir.join("ball.ron");
    std::fs::write(&path, text).unwrap();
    path
}

/// Runs `glint ARGS` in `dir`.
fn glint_in(dir: &Path, args: &[&str]) -> Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_glint"))
        .current_dir(dir)
        .args(args)
        .output()
        .unwrap()
}

fn assert_exit(out: &Output, code: i32) {
    assert_eq!(
        out.status.code(),
        Some(code),
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        stderr(out)
    );
}

/// Shade entry `entry` of the shot at `path`, read at `frame`.
fn shade_at(path: &Path, entry: usize, frame: f64) -> ShadeStack {
    let shot = load_shot(path).unwrap_or_else(|e| panic!("{e}"));
    shot.at(frame).shade[entry].clone()
}

/// Linear interpolation between keys `(f0, v0)` and `(f1, v1)` at `f`.
fn between((f0, v0): (f64, f32), (f1, v1): (f64, f32), f: f64) -> f32 {
    v0 + (v1 - v0) * ((f - f0) / (f1 - f0)) as f32
}

#[test]
fn keys_written_land_in_the_file_and_read_back_at_their_frames() {
    let dir = tempfile::tempdir().unwrap();
    let shot = write_shot(dir.path(), "");
    let file = shot.to_str().unwrap();
    let keys: [(&str, &[(f64, f32)]); 5] = [
        ("shade[0].stack[0].alpha", &[(1.0, 0.05), (21.0, 0.45)]),
        ("shade[0].stack[0].beta", &[(11.0, -0.2)]),
        ("shade[0].stack[1].sigma", &[(1.0, 0.1), (11.0, 0.6)]),
        ("shade[0].mask.u[1]", &[(1.0, 0.6), (21.0, 0.95)]),
        ("shade[0].mask.feather", &[(5.0, 0.125)]),
    ];
    for (path, track) in keys {
        for &(frame, value) in track {
            let out = glint_in(
                dir.path(),
                &[
                    "key",
                    file,
                    "--at",
                    path,
                    "--frame",
                    &frame.to_string(),
                    "--value",
                    &value.to_string(),
                ],
            );
            assert_exit(&out, 0);
        }
    }
    // n set as a constant.
    let out = glint_in(
        dir.path(),
        &["key", file, "--at", "shade[0].stack[1].n", "--value", "3.5"],
    );
    assert_exit(&out, 0);
    let text = std::fs::read_to_string(&shot).unwrap();
    assert!(
        text.contains("alpha: [(1, 0.05), (21, 0.45)]"),
        "the keys are written where alpha was:\n{text}"
    );
    for frame in [1.0, 4.0, 11.0, 16.5, 21.0] {
        let shade = shade_at(&shot, 0, frame);
        let Op::Translate { alpha, beta } = shade.stack[0] else {
            panic!("{:?}", shade.stack[0]);
        };
        let Op::Square { sigma, n, .. } = shade.stack[1] else {
            panic!("{:?}", shade.stack[1]);
        };
        let Some(Mask { u, v, feather }) = shade.mask else {
            panic!("the mask is kept");
        };
        let expected_alpha = between((1.0, 0.05), (21.0, 0.45), frame);
        let expected_sigma = if frame >= 11.0 {
            0.6
        } else {
            between((1.0, 0.1), (11.0, 0.6), frame)
        };
        let near = |a: f32, b: f32| (a - b).abs() < 1e-6;
        assert!(near(alpha, expected_alpha), "frame {frame}: α {alpha}");
        assert!(near(beta, -0.2), "frame {frame}: β {beta}");
        assert!(near(sigma, expected_sigma), "frame {frame}: σ {sigma}");
        assert!(near(n, 3.5), "frame {frame}: n {n}");
        let expected_u1 = between((1.0, 0.6), (21.0, 0.95), frame);
        assert!(
            near(u.0, 0.25) && near(u.1, expected_u1),
            "frame {frame}: {u:?}"
        );
        assert!(near(v.0, 0.0) && near(v.1, 1.0), "frame {frame}: {v:?}");
        assert!(near(feather, 0.125), "frame {frame}: feather {feather}");
    }
}

#[test]
fn a_look_library_names_its_own_shade_entries() {
    let dir = tempfile::tempdir().unwrap();
    let looks = dir.path().join("looks.ron");
    std::fs::write(
        &looks,
        r#"Looks(
    shade: [(patches: "ball/*", stack: [Rotate(degrees: 10.0), Translate(alpha: 0.0, beta: 0.0)])],
)
"#,
    )
    .unwrap();
    let shot = write_shot(dir.path(), "");
    let text = std::fs::read_to_string(&shot).unwrap().replace(
        "    instances:",
        "    includes: [\"looks.ron\"],\n    instances:",
    );
    std::fs::write(&shot, text).unwrap();
    let out = glint_in(
        dir.path(),
        &[
            "key",
            "looks.ron",
            "--at",
            "shade[0].stack[1].beta",
            "--frame",
            "6",
            "--value",
            "0.35",
        ],
    );
    assert_exit(&out, 0);
    let out = glint_in(
        dir.path(),
        &[
            "key",
            "looks.ron",
            "--at",
            "shade[0].stack[0].degrees",
            "--value",
            "-25",
        ],
    );
    assert_exit(&out, 0);
    // The include's entries come first: its entry is the shot's shade entry 0.
    let loaded = load_shot(&shot).unwrap();
    assert_eq!(
        loaded.shade_written(0).map(|(f, i)| (f.to_path_buf(), i)),
        Some((looks.clone(), 0))
    );
    let shade = loaded.at(6.0).shade[0].clone();
    assert_eq!(
        shade.stack,
        vec![
            Op::Rotate { degrees: -25.0 },
            Op::Translate {
                alpha: 0.0,
                beta: 0.35
            }
        ]
    );
}

/// `glint key FILE --at PATH --value 0.5` must fail with exit 2 and one line naming the file and
/// suggesting `nearest`, leaving the file as it was.
fn assert_refused(dir: &Path, file: &Path, written: &str, reason: &str, nearest: Option<&str>) {
    let before = std::fs::read_to_string(file).unwrap();
    let out = glint_in(
        dir,
        &[
            "key",
            file.to_str().unwrap(),
            "--at",
            written,
            "--value",
            "0.5",
        ],
    );
    assert_exit(&out, 2);
    let message = stderr(&out);
    assert_eq!(message.lines().count(), 1, "{message}");
    assert!(
        message.starts_with(&format!("error: {}: ", file.display())),
        "{message}"
    );
    assert!(message.contains(reason), "{written}: {message}");
    if let Some(nearest) = nearest {
        assert!(
            message.contains(&format!("the nearest valid path is `{nearest}`")),
            "{written}: {message}"
        );
        let text = std::fs::read_to_string(file).unwrap();
        glint::shot::parse_param_path(&text, nearest)
            .unwrap_or_else(|e| panic!("the suggested path {nearest} is valid: {e}"));
    }
    assert_eq!(std::fs::read_to_string(file).unwrap(), before);
}

#[test]
fn a_path_to_a_missing_entry_or_operation_is_refused_with_the_nearest_valid_path() {
    let dir = tempfile::tempdir().unwrap();
    let shot = write_shot(
        dir.path(),
        r#"
        (patches: "ball/*", stack: [Scale(delta: 0.5, axis: U)]),"#,
    );
    let cases = [
        (
            "shade[2].stack[0].alpha",
            "this file has 2 shade entries, shade[0] to shade[1], so no shade[2]",
            "shade[0].stack[0].alpha",
        ),
        (
            "shade[0].stack[2].alpha",
            "shade[0]'s stack has 2 operation(s), numbered from 0, so no stack[2]",
            "shade[0].stack[0].alpha",
        ),
        (
            "shade[0].stack[1].alphx",
            "unknown `alphx`",
            "shade[0].stack[0].alpha",
        ),
        (
            "shade[0].stack[1].beta",
            "shade[0].stack[1] is a Square, which has no `beta`",
            "shade[0].stack[0].beta",
        ),
        (
            "shade[1].stack[0].axis",
            "shade[1].stack[0]'s axis is `U` or `V`, which has no number",
            // Five edits from either `shade[1].stack[0].delta` or this, the first written.
            "shade[0].stack[0].alpha",
        ),
        (
            "shade[1].mask.feather",
            "shade[1] has no mask",
            "shade[0].mask.feather",
        ),
    ];
    for (written, reason, nearest) in cases {
        assert_refused(dir.path(), &shot, written, reason, Some(nearest));
    }
    // A file without shade entries.
    let plain = dir.path().join("plain.ron");
    let text = std::fs::read_to_string(&shot).unwrap();
    let start = text.find("    shade: [").unwrap();
    let end = start + text[start..].find("\n    ],\n").unwrap() + "\n    ],\n".len();
    std::fs::write(&plain, format!("{}{}", &text[..start], &text[end..])).unwrap();
    assert_refused(
        dir.path(),
        &plain,
        "shade[0].stack[0].alpha",
        "this file has no shade entry, so no shade[0]",
        None,
    );
}

#[test]
fn a_value_out_of_its_operations_range_is_refused_at_its_place() {
    let dir = tempfile::tempdir().unwrap();
    let shot = write_shot(dir.path(), "");
    let before = std::fs::read_to_string(&shot).unwrap();
    // σ ∈ [0, 1]; a mask's feather ≥ 0; n > 0.
    for (path, value) in [
        ("shade[0].stack[1].sigma", "1.5"),
        ("shade[0].mask.feather", "-0.1"),
        ("shade[0].stack[1].n", "0"),
    ] {
        let out = glint_in(
            dir.path(),
            &[
                "key",
                shot.to_str().unwrap(),
                "--at",
                path,
                "--frame",
                "3",
                "--value",
                value,
            ],
        );
        assert_exit(&out, 2);
        let message = stderr(&out);
        assert_eq!(message.lines().count(), 1, "{message}");
        // FILE:LINE:COL: … at the shade entry.
        let located = format!("error: {}:", shot.display());
        let rest = message
            .strip_prefix(&located)
            .unwrap_or_else(|| panic!("{message}"));
        let mut fields = rest.splitn(3, ':');
        let line: usize = fields.next().unwrap().parse().unwrap();
        let col: usize = fields.next().unwrap().parse().unwrap();
        let shade_line = before.lines().position(|l| l.contains("shade: [")).unwrap() + 1;
        assert!(line > shade_line && col > 0, "{message}");
        assert_eq!(std::fs::read_to_string(&shot).unwrap(), before);
    }
}

#[test]
fn key_help_and_list_name_the_shade_paths() {
    let dir = tempfile::tempdir().unwrap();
    let shot = write_shot(dir.path(), "");
    let help = glint_in(dir.path(), &["key", "--help"]);
    assert_exit(&help, 0);
    let help = String::from_utf8_lossy(&help.stdout).into_owned();
    assert!(help.contains("shade[0].stack[0].alpha"), "{help}");
    assert!(help.contains("shade[N].mask.u[I]"), "{help}");
    let out = glint_in(dir.path(), &["key", shot.to_str().unwrap(), "--list"]);
    assert_exit(&out, 0);
    let listed = String::from_utf8_lossy(&out.stdout).into_owned();
    for line in [
        "shade[0].stack[0].alpha = 0.1",
        "shade[0].stack[0].beta = 0.0",
        "shade[0].stack[1].sigma = 0.2",
        "shade[0].stack[1].n = 2.0",
        "shade[0].mask.u[0] = 0.25",
        "shade[0].mask.u[1] = 0.9",
        "shade[0].mask.v[1] = 1.0",
        "shade[0].mask.feather = 0.05",
    ] {
        assert!(listed.lines().any(|l| l == line), "{line}:\n{listed}");
    }
}

#[test]
fn a_sheet_varies_a_shade_number() {
    let dir = tempfile::tempdir().unwrap();
    let shot = write_shot(dir.path(), "");
    let sheet = dir.path().join("sheet.png");
    let out = glint_in(
        dir.path(),
        &[
            "sheet",
            shot.to_str().unwrap(),
            "--frame",
            "1",
            "--vary",
            "shade[0].stack[0].alpha=0.0,0.8",
            "--tile",
            "64x48",
            "--out",
            sheet.to_str().unwrap(),
        ],
    );
    assert_exit(&out, 0);
    let image = image::open(&sheet).unwrap().to_rgba8();
    // Two tiles side by side, each with its caption strip beneath: the translated light moves
    // the band edge, so the two tiles' pixels differ.
    let gap = glint::picture::sheet::SHEET_GAP;
    let (w, h) = image.dimensions();
    assert_eq!(w, 2 * (64 + gap) + gap, "{w}×{h}");
    let tile = |x0: u32| -> Vec<[u8; 4]> {
        (0..48)
            .flat_map(|y| (0..64).map(move |x| (x, y)))
            .map(|(x, y)| image.get_pixel(x0 + x, gap + y).0)
            .collect()
    };
    let (a, b) = (tile(gap), tile(2 * gap + 64));
    let differing = a.iter().zip(&b).filter(|(p, q)| p != q).count();
    assert!(differing > 20, "only {differing} pixels differ");
}
