//! USD time samples: a deforming patch's points between samples are the linear mix of the
//! samples written in the file (read out of its text here, independently of glint's parser), held
//! before the first and after the last; a time-sampled rotateZ turns a patch in angle; every
//! refusal of time samples is one located line, exit 2.

use glam::DVec3;
use glint::formats::{load_model, load_patches, parse_usda_motion};

use crate::common::{flat_patch, glint_with as glint, repo_file, stderr};

/// The text of `patches/flag.usda`, written by `scripts/usd/author_animated.py`.
pub(crate) fn flag_text() -> String {
    std::fs::read_to_string(repo_file("patches/flag.usda")).unwrap()
}

/// The numbers in `text`, a run of `(x, y, z)` tuples, three by three.
pub(crate) fn tuples(text: &str) -> Vec<DVec3> {
    let numbers: Vec<f64> = text
        .split(|c: char| matches!(c, '(' | ')' | ',' | '[' | ']') || c.is_whitespace())
        .filter(|s| !s.is_empty())
        .map(|s| {
            s.parse::<f64>()
                .unwrap_or_else(|_| panic!("{s:?} is no number"))
        })
        .collect();
    assert_eq!(numbers.len() % 3, 0);
    numbers
        .chunks(3)
        .map(|c| DVec3::new(c[0], c[1], c[2]))
        .collect()
}

/// The samples of the time-sampled attribute whose line starts with `head` (e.g.
/// `point3f[] points.timeSamples = {`) in `text`: each line `time: value,` up to the closing
/// `}`, as the time and the value's text.
pub(crate) fn samples_after<'a>(text: &'a str, head: &str) -> Vec<(f64, &'a str)> {
    let start = text.find(head).unwrap_or_else(|| panic!("no {head:?}")) + head.len();
    let mut out = Vec::new();
    for line in text[start..].lines() {
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        if line == "}" {
            break;
        }
        let (time, value) = line.split_once(':').unwrap();
        out.push((
            time.trim().parse::<f64>().unwrap(),
            value.trim().trim_end_matches(','),
        ));
    }
    out
}

/// USD's `points` (u fastest, `nu` along u) in glint's control-point order (`i · nv + j`).
pub(crate) fn in_net_order(points: &[DVec3], nu: usize, nv: usize) -> Vec<DVec3> {
    let mut out = Vec::new();
    for i in 0..nu {
        for j in 0..nv {
            out.push(points[j * nu + i]);
        }
    }
    out
}

/// The value at `t` of samples `(time, value)`, linear between the two around it, the ends held.
pub(crate) fn mix_at(samples: &[(f64, Vec<DVec3>)], t: f64) -> Vec<DVec3> {
    if t <= samples[0].0 {
        return samples[0].1.clone();
    }
    if t >= samples[samples.len() - 1].0 {
        return samples[samples.len() - 1].1.clone();
    }
    let k = samples.iter().position(|(time, _)| *time > t).unwrap();
    let ((t0, a), (t1, b)) = (&samples[k - 1], &samples[k]);
    let s = (t - t0) / (t1 - t0);
    a.iter().zip(b).map(|(p, q)| *p + (*q - *p) * s).collect()
}

pub(crate) fn largest_gap(a: &[DVec3], b: &[DVec3]) -> f64 {
    assert_eq!(a.len(), b.len());
    a.iter()
        .zip(b)
        .map(|(p, q)| (*p - *q).abs().max_element())
        .fold(0.0, f64::max)
}

pub(crate) fn patch_index(library: &glint::geom::PatchLibrary, name: &str) -> usize {
    library
        .patches
        .iter()
        .position(|p| p.name == name)
        .unwrap_or_else(|| panic!("no patch {name}"))
}

#[test]
fn a_deforming_patch_between_samples_is_the_linear_mix_of_the_written_samples() {
    let text = flag_text();
    let written: Vec<(f64, Vec<DVec3>)> = samples_after(&text, "points.timeSamples = {")
        .into_iter()
        .map(|(t, v)| (t, in_net_order(&tuples(v), 5, 4)))
        .collect();
    assert_eq!(
        written.len(),
        3,
        "the fixture samples the cloth three times"
    );
    let model = load_model(&repo_file("patches/flag.usda")).unwrap();
    let motion = model.motion.as_ref().expect("the flag moves");
    let cloth = patch_index(&model.library, "flag/cloth");
    for t in [1.0, 1.5, 3.7, 11.999, 12.0, 12.25, 17.5, 23.9, 24.0] {
        let gap = largest_gap(&motion.points_at(cloth, t), &mix_at(&written, t));
        assert!(gap <= 1e-12, "at time code {t}: {gap:e}");
    }
    // Held before the first sample and after the last.
    for (t, k) in [(-50.0, 0), (0.999, 0), (24.001, 2), (1e9, 2)] {
        let gap = largest_gap(&motion.points_at(cloth, t), &written[k].1);
        assert!(gap <= 1e-12, "at time code {t}: {gap:e}");
    }
    // The library holds the cloth at its earliest sample.
    let library: Vec<DVec3> = model.library.patches[cloth]
        .surface
        .control_points()
        .collect();
    assert!(largest_gap(&library, &written[0].1) <= 1e-12);
    // A surface made from the points at a time is the mix, too.
    let at = motion.points_at(cloth, 6.0);
    let surface = model.library.patches[cloth]
        .surface
        .try_with_points(&at)
        .unwrap();
    let made: Vec<DVec3> = surface.control_points().collect();
    assert!(largest_gap(&made, &mix_at(&written, 6.0)) <= 1e-12);
}

#[test]
fn the_layer_s_time_codes_and_samples_are_read() {
    let model = load_model(&repo_file("patches/flag.usda")).unwrap();
    let motion = model.motion.unwrap();
    let codes = motion.time_codes();
    assert_eq!(codes.per_second, 24.0);
    assert_eq!(codes.frames_per_second, Some(24.0));
    assert_eq!(codes.start, Some(1.0));
    assert_eq!(codes.end, Some(24.0));
    let cloth = patch_index(&model.library, "flag/cloth");
    let vane = patch_index(&model.library, "flag/turn/vane");
    let mut moving = motion.moving().to_vec();
    moving.sort_unstable();
    let mut expected = vec![cloth, vane];
    expected.sort_unstable();
    assert_eq!(moving, expected);
    assert_eq!(motion.sample_times(), &[1.0, 12.0, 24.0]);
}

#[test]
fn a_time_sampled_rotate_turns_the_patch_in_angle() {
    let text = flag_text();
    let angles: Vec<(f64, f64)> = samples_after(&text, "xformOp:rotateZ.timeSamples = {")
        .into_iter()
        .map(|(t, v)| (t, v.parse::<f64>().unwrap()))
        .collect();
    assert_eq!(angles.len(), 2);
    let ((t0, a0), (t1, a1)) = (angles[0], angles[1]);
    let model = load_model(&repo_file("patches/flag.usda")).unwrap();
    let motion = model.motion.unwrap();
    let vane = patch_index(&model.library, "flag/turn/vane");
    // The vane's points as written (under `def NurbsPatch "vane"`), u fastest.
    let vane_text = &text[text.find("def NurbsPatch \"vane\"").unwrap()..];
    let head = "points = [";
    let start = vane_text.find(head).unwrap() + head.len() - 1;
    let end = start + vane_text[start..].find(']').unwrap() + 1;
    let written = in_net_order(&tuples(&vane_text[start..end]), 2, 4);
    // Each point turns about z by the angle interpolated between the samples: its distance
    // from the axis stays, which a mix of the turned points would not keep.
    for t in [t0 - 5.0, t0, 4.0, 12.5, 20.0, t1, t1 + 5.0] {
        let s = ((t - t0) / (t1 - t0)).clamp(0.0, 1.0);
        let angle = (a0 + (a1 - a0) * s).to_radians();
        let (sin, cos) = angle.sin_cos();
        let turned: Vec<DVec3> = written
            .iter()
            .map(|p| DVec3::new(cos * p.x - sin * p.y, sin * p.x + cos * p.y, p.z))
            .collect();
        let at = motion.points_at(vane, t);
        let gap = largest_gap(&at, &turned);
        assert!(gap <= 1e-12, "at {t}: {gap:e}");
        // The far corner's angle about the pole, directly.
        let p = at[0];
        let expected = DVec3::new(-cos, -sin, 0.0);
        assert!(
            (p.truncate().normalize() - expected.truncate()).length() <= 1e-12,
            "at {t}: {p}"
        );
    }
}

#[test]
fn a_layer_without_time_samples_has_no_motion_and_load_patches_is_the_model_s_library() {
    let still = load_model(&repo_file("patches/sphere.usda")).unwrap();
    assert!(still.motion.is_none());
    let flag = repo_file("patches/flag.usda");
    let library = load_patches(&flag).unwrap();
    let model = load_model(&flag).unwrap();
    assert_eq!(library.patches.len(), model.library.patches.len());
    for (a, b) in library.patches.iter().zip(&model.library.patches) {
        let (a, b): (Vec<DVec3>, Vec<DVec3>) = (
            a.surface.control_points().collect(),
            b.surface.control_points().collect(),
        );
        assert_eq!(a, b);
    }
}

/// A bilinear patch on the unit square whose points are time-sampled by `samples` (the lines
/// inside `points.timeSamples = { … }`), under `/rig`, which has the xformOps `ops`.
fn sheet(samples: &str, ops: &str, extra: &str) -> String {
    format!(
        r#"#usda 1.0
(
    timeCodesPerSecond = 30
    upAxis = "Z"
)

def Xform "rig"
{{
{ops}
    def NurbsPatch "sheet"
    {{
        int uVertexCount = 2
        int vVertexCount = 2
        int uOrder = 2
        int vOrder = 2
        double[] uKnots = [0, 0, 1, 1]
        double[] vKnots = [0, 0, 1, 1]
{extra}
        point3f[] points.timeSamples = {{
{samples}
        }}
    }}
}}
"#
    )
}

const TWO_SAMPLES: &str = "            1: [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)],\n            10: [(0, 0, 1), (1, 0, 1), (0, 1, 1), (1, 1, 1)],";

#[test]
fn samples_written_out_of_order_are_sorted_and_a_repeated_time_keeps_the_last() {
    let samples = "            10: [(0, 0, 9), (1, 0, 9), (0, 1, 9), (1, 1, 9)],\n            1: [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)],\n            10: [(0, 0, 1), (1, 0, 1), (0, 1, 1), (1, 1, 1)],";
    let text = sheet(samples, "", "");
    let (library, motion) = parse_usda_motion(&text, "sheet.usda").unwrap();
    let motion = motion.unwrap();
    assert_eq!(motion.sample_times(), &[1.0, 10.0]);
    assert_eq!(motion.time_codes().per_second, 30.0);
    assert_eq!(motion.time_codes().start, None);
    // z runs from 0 at time code 1 to 1 (the last written at 10) at time code 10.
    for t in [1.0, 4.0, 10.0] {
        let z = (t - 1.0) / 9.0;
        for p in motion.points_at(0, t) {
            assert!((p.z - z).abs() <= 1e-12, "at {t}: {p}");
        }
    }
    assert!(library.patches[0]
        .surface
        .control_points()
        .all(|p| p.z == 0.0));
}

#[test]
fn a_patch_under_still_transforms_in_a_moving_layer_does_not_move() {
    let plank = flat_patch("plank", "", "");
    let still = format!(
        "def Xform \"post\"\n{{\n    double3 xformOp:translate = (3, 0, 0)\n    uniform token[] xformOpOrder = [\"xformOp:translate\"]\n{plank}}}\n"
    );
    let text = sheet(TWO_SAMPLES, "", "") + &still;
    let (library, motion) = parse_usda_motion(&text, "sheet.usda").unwrap();
    let motion = motion.expect("the sheet moves");
    assert_eq!(library.patches[1].name, "post/plank");
    assert_eq!(motion.moving(), &[0]);
    let placed: Vec<DVec3> = library.patches[1].surface.control_points().collect();
    assert_eq!(placed[3], DVec3::new(4.0, 1.0, 0.0));
    for t in [1.0, 5.5, 10.0] {
        assert_eq!(motion.points_at(1, t), placed, "at time code {t}");
    }
}

#[test]
fn knots_whose_samples_agree_are_read_and_a_default_loses_to_samples() {
    let extra = "        double[] uRange.timeSamples = {\n            1: (0, 1),\n            5: (0, 1),\n        }\n        point3f[] points = [(5, 5, 5), (6, 5, 5), (5, 6, 5), (6, 6, 5)]";
    let text = sheet(TWO_SAMPLES, "", extra);
    let (library, motion) = parse_usda_motion(&text, "sheet.usda").unwrap();
    assert!(motion.is_some());
    assert!(library.patches[0]
        .surface
        .control_points()
        .all(|p| p.z == 0.0 && p.x <= 1.0));
}

/// A file that is refused: `text`, refused at the first `at`, saying each of `says`.
struct Refusal {
    name: &'static str,
    text: String,
    at: &'static str,
    says: &'static [&'static str],
}

fn refusals() -> Vec<Refusal> {
    let xform = |ops: &str| format!("    {ops}\n");
    vec![
        Refusal {
            name: "a points sample of the wrong count",
            text: sheet(
                "            1: [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)],\n            7: [(0, 0, 1), (1, 0, 1), (0, 1, 1)],",
                "",
                "",
            ),
            at: "7: [",
            says: &["/rig/sheet", "`points` has 3 points", "2 × 2 = 4"],
        },
        Refusal {
            name: "time-sampled point weights",
            text: sheet(
                TWO_SAMPLES,
                "",
                "        double[] pointWeights.timeSamples = {\n            1: [1, 1, 1, 1],\n        }",
            ),
            at: "pointWeights.timeSamples",
            says: &["`pointWeights` is time-sampled"],
        },
        Refusal {
            name: "knots whose samples differ",
            text: sheet(
                TWO_SAMPLES,
                "",
                "        double[] vKnots.timeSamples = {\n            1: [0, 0, 1, 1],\n            3: [0, 0, 2, 2],\n        }",
            ),
            at: "3: [0, 0, 2, 2]",
            says: &["`vKnots`", "time codes 1 and 3 differ"],
        },
        Refusal {
            name: "orders whose samples differ",
            text: sheet(
                TWO_SAMPLES,
                "",
                "        int uOrder.timeSamples = {\n            1: 2,\n            2: 3,\n        }",
            ),
            at: "2: 3",
            says: &["`uOrder`", "changes over time"],
        },
        Refusal {
            name: "counts whose samples differ",
            text: sheet(
                TWO_SAMPLES,
                "",
                "        int vVertexCount.timeSamples = {\n            1: 2,\n            4: 3,\n        }",
            ),
            at: "4: 3",
            says: &["`vVertexCount`", "changes over time"],
        },
        Refusal {
            name: "ranges whose samples differ",
            text: sheet(
                TWO_SAMPLES,
                "",
                "        double2 vRange.timeSamples = {\n            1: (0, 1),\n            8: (0, 0.5),\n        }",
            ),
            at: "8: (0, 0.5)",
            says: &["`vRange`", "time codes 1 and 8 differ"],
        },
        Refusal {
            name: "a time code that is not finite",
            text: sheet(
                "            1: [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)],\n            inf: [(0, 0, 1), (1, 0, 1), (0, 1, 1), (1, 1, 1)],",
                "",
                "",
            ),
            at: "inf: [",
            says: &["time code", "not a finite number"],
        },
        Refusal {
            name: "a sampled value that is not finite",
            text: sheet(
                "            1: [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)],\n            6: [(0, 0, 1), (1, 0, nan), (0, 1, 1), (1, 1, 1)],",
                "",
                "",
            ),
            at: "6: [",
            says: &["`points` must hold finite numbers"],
        },
        Refusal {
            name: "a sampled angle that is not finite",
            text: sheet(
                TWO_SAMPLES,
                &xform("double xformOp:rotateZ.timeSamples = {\n        1: 0,\n        5: inf,\n    }\n    uniform token[] xformOpOrder = [\"xformOp:rotateZ\"]"),
                "",
            ),
            at: "5: inf",
            says: &["/rig", "`xformOp:rotateZ` must be 1 finite number"],
        },
        Refusal {
            name: "a sampled scale passing through 0",
            text: sheet(
                TWO_SAMPLES,
                &xform("double3 xformOp:scale.timeSamples = {\n        1: (1, 1, 1),\n        5: (-1, 1, 1),\n    }\n    uniform token[] xformOpOrder = [\"xformOp:scale\"]"),
                "",
            ),
            at: "5: (-1, 1, 1)",
            says: &["`xformOp:scale` flattens the prim between time codes 1 and 5"],
        },
        Refusal {
            name: "a blocked sample",
            text: sheet(
                "            1: [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)],\n            2: None,",
                "",
                "",
            ),
            at: "None,",
            says: &["blocked"],
        },
        Refusal {
            name: "a spline",
            text: sheet(
                TWO_SAMPLES,
                &xform("double xformOp:rotateZ.spline = {\n        1: 0,\n    }"),
                "",
            ),
            at: "xformOp:rotateZ.spline",
            says: &["`xformOp:rotateZ` is animated by a spline"],
        },
        Refusal {
            // Points within 0.02 of the origin, moved 2·10⁶ along x at time code 5: the bound
            // `a·|P| + b` (here `b = √3 · 2·10⁶`, the node's linear bound times its move) is
            // past 10⁶ by the move alone.
            name: "a sampled move that may carry a point beyond the coordinates glint evaluates",
            text: sheet(
                "            1: [(0, 0, 0), (0.01, 0, 0), (0, 0.01, 0), (0.01, 0.01, 0)],\n            10: [(0, 0, 0.01), (0.01, 0, 0.01), (0, 0.01, 0.01), (0.01, 0.01, 0.01)],",
                &xform("double3 xformOp:translate.timeSamples = {\n        1: (0, 0, 0),\n        5: (2000000, 0, 0),\n    }\n    uniform token[] xformOpOrder = [\"xformOp:translate\"]"),
                "",
            ),
            at: "def NurbsPatch",
            says: &[
                "/rig/sheet",
                "may carry a control point as far as 3.4641",
                "e6, beyond ±1e6",
            ],
        },
        Refusal {
            // Points 1000 from the origin, scaled up to 2000 times by time code 5: the bound
            // `a·|P| + b` passes 10⁶ by the product of the scale's bound and the points'
            // reach, where neither alone comes near it.
            name: "a sampled scale that may carry a point beyond the coordinates glint evaluates",
            text: sheet(
                "            1: [(0, 0, 0), (1000, 0, 0), (0, 1000, 0), (1000, 1000, 0)],\n            10: [(0, 0, 1), (1000, 0, 1), (0, 1000, 1), (1000, 1000, 1)],",
                &xform("double3 xformOp:scale.timeSamples = {\n        1: (1, 1, 1),\n        5: (2000, 2000, 2000),\n    }\n    uniform token[] xformOpOrder = [\"xformOp:scale\"]"),
                "",
            ),
            at: "def NurbsPatch",
            says: &["/rig/sheet", "may carry a control point as far as", "beyond ±1e6"],
        },
        Refusal {
            name: "time codes per second of 0",
            text: sheet(TWO_SAMPLES, "", "")
                .replacen("timeCodesPerSecond = 30", "timeCodesPerSecond = 0", 1),
            at: "0\n    upAxis",
            says: &["`timeCodesPerSecond` is 0"],
        },
    ]
}

#[test]
fn every_refusal_of_time_samples_is_one_located_line_and_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    for case in refusals() {
        let path = dir.path().join("sheet.usda");
        std::fs::write(&path, &case.text).unwrap();
        let out = glint(&["patches", path.to_str().unwrap()]);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{}: {err}", case.name);
        assert_eq!(err.lines().count(), 1, "{}: {err}", case.name);
        let offset = case
            .text
            .find(case.at)
            .unwrap_or_else(|| panic!("{}: {:?} not in the text", case.name, case.at));
        let (line, col) = glint::formats::ron_location::position_of(&case.text, offset);
        let place = format!("sheet.usda:{line}:{col}: ");
        assert!(
            err.contains(&place),
            "{}: expected {place} in {err}",
            case.name
        );
        for says in case.says {
            assert!(
                err.contains(says),
                "{}: expected {says:?} in {err}",
                case.name
            );
        }
        // And through the library, the same place.
        let e = load_model(&path).unwrap_err().to_string();
        assert!(e.contains(&place), "{}: {e}", case.name);
    }
}
