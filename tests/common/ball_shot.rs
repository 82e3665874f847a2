//! The one-frame shot of the ball in `sphere.ron` beside it, which the tests of editing a shot
//! while it is watched or reloaded write and rewrite.

use std::path::Path;

/// A one-frame shot of the ball, seen from the front and a little above through an
/// orthographic camera, lit from the front left, with one unstacked highlight layer.
pub struct BallShot<'a> {
    /// The image's width and height.
    pub size: (u32, u32),
    /// The highlight's width ε.
    pub epsilon: f32,
    /// The ramp's lit colour, as RON text.
    pub lit: &'a str,
    /// An include file, if any.
    pub include: Option<&'a str>,
    /// The render preset, if the shot names one.
    pub preset: Option<&'a str>,
}

impl BallShot<'_> {
    /// The shot's text.
    pub fn text(&self) -> String {
        let (width, height) = self.size;
        let (epsilon, lit) = (self.epsilon, self.lit);
        let includes = self
            .include
            .map_or_else(String::new, |i| format!("\n    includes: [{i:?}],"));
        let render = self
            .preset
            .map_or_else(String::new, |p| format!("\n    render: (preset: {p}),"));
        format!(
            r#"Shot(
    resolution: ({width}, {height}),
    frames: (1, 1),
    fps: 24,
    output: "out/ball.#.png",{includes}
    instances: [(name: "ball", file: "sphere.ron", material: "blue")],
    materials: {{ "blue": Cel(base: (0.04, 0.07, 0.2), bands: [(0.05, {lit})]) }},
    camera: (eye: (0.0, -6.0, 1.0), target: (0.0, 0.0, 0.0), projection: Orthographic(height: 2.4)),
    light: Directional(towards: (0.35, -1.0, 0.45)),
    highlights: [(patches: "ball/*", expr: Layer((stack: [], epsilon: {epsilon}, colour: (1.0, 1.0, 1.0))))],{render}
)
"#
        )
    }
}

/// Saves `text` at `path` as an editor does: a new file beside it renamed over it.
pub fn save_as_an_editor_does(path: &Path, text: &str) {
    let name = path.file_name().unwrap().to_string_lossy();
    let temporary = path.with_file_name(format!(".{name}.swp"));
    std::fs::write(&temporary, text).unwrap();
    std::fs::rename(&temporary, path).unwrap();
}
