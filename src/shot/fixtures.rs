//! Fixtures of the unit tests of `shot`: shot texts to read and edit, parameter paths from
//! their text.

use super::ParamPath;

/// A shot written in several styles: comments, keys on lines of their own and on one line, a
/// Boolean of two layers with a mask and a feather, an entry picking patches by a list.
pub(crate) const STYLED_SHOT: &str = r#"// A shot.
Shot(
    resolution: (64, 48),
    frames: (1, 24),
    fps: 24,
    output: "out.####.png",
    instances: [(name: "ball", file: "sphere.ron", material: "m")],
    materials: {
        "m": Cel(base: (0.1, 0.1, 0.1), bands: [(0.0, (0.5, 0.5, 0.5))]),
    },
    camera: (
        eye: (0.0, -6.0, 0.0), // front
        target: (0.0, 0.0, 0.0),
        projection: Orthographic(height: 2.4),
    ),
    light: Directional(
        towards: [
            (1, (0.0, -1.0, 0.0)), // from the front
            (24, (1.0, 0.0, 0.0)),
        ],
    ),
    highlights: [
        (
            patches: "ball/*",
            expr: Subtract(
                Layer((stack: [Scale(delta: 0.5, axis: Angle(30.0))], epsilon: 0.08, colour: (1.0, 0.9, 0.6))),
                Layer((
                    stack: [Translate(alpha: [(1, 0.6), (24, 0.15)], beta: 0.0)],
                    epsilon: 0.08,
                    colour: (1.0, 1.0, 1.0),
                    feather: Some(0.01),
                    mask: (u: (0.0, 0.5), v: (0.0, 1.0), feather: 0.1),
                )),
            ),
        ),
        (patches: ["ball/a", "ball/b"], expr: Layer((stack: [], epsilon: 0.01, colour: (1, 1, 1)))),
    ],
)
"#;

/// A minimal shot: frames 1–24 of one ball (`sphere.ron`, material "m") under a camera on the z
/// axis and a light along it, with `highlights` (a list, as written) as its highlights.
pub(crate) fn shot_with_highlights(highlights: &str) -> String {
    format!(
        r#"Shot(
    frames: (1, 24),
    fps: 24,
    output: "out.####.png",
    resolution: (64, 64),
    camera: (eye: (0.0, 0.0, 5.0), target: (0.0, 0.0, 0.0), projection: Perspective(fov_y_degrees: 30.0)),
    light: Directional(towards: (0.0, 0.0, -1.0)),
    instances: [(name: "ball", file: "sphere.ron", material: "m")],
    materials: {{"m": Cel(base: (0.1, 0.1, 0.1), bands: [(0.0, (0.5, 0.5, 0.5))])}},
    highlights: {highlights},
)"#
    )
}

/// `written` read as a parameter path; panics when it does not read.
pub(crate) fn param_path(written: &str) -> ParamPath {
    written.parse().unwrap_or_else(|e| panic!("{e}"))
}
