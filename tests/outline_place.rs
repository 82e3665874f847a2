//! `glint place` with a drawn layer: the translation puts the outline's point (0, 0) on the
//! surface point under the pixel, so the rendered matte of a point-symmetric outline is
//! centred there, and the placement's residual on that patch is a centre.

use std::path::Path;

use glint::job::{LayerChoice, Overrides, RenderJob};
use glint::shot::Aov;

use crate::common::repo_file;

const SIZE: (u32, u32) = (320, 240);

/// A four-pointed glint of corners, point-symmetric about (0, 0), tips 0.09 out.
const GLINT: &str = "Outline([(0.0, 0.09), (0.02, 0.02), (0.09, 0.0), (0.02, -0.02), \
                     (0.0, -0.09), (-0.02, -0.02), (-0.09, 0.0), (-0.02, 0.02)])";

/// The sphere under an orthographic camera with the glint translated by (α, β).
fn shot(dir: &Path, alpha: f32, beta: f32) -> std::path::PathBuf {
    let text = format!(
        r#"Shot(
    resolution: ({w}, {h}),
    frames: (1, 1),
    fps: 24,
    output: "out/drawn.####.png",
    instances: [(name: "m", file: "{model}", material: "grey")],
    materials: {{ "grey": Cel(base: (0.1, 0.1, 0.1), bands: [(0.0, (0.5, 0.5, 0.5))]) }},
    camera: (eye: (0.5, -6.0, 1.0), target: (0.0, 0.0, 0.0), projection: Orthographic(height: 2.6)),
    light: Directional(towards: (0.3, -1.0, 0.5)),
    highlights: [(patches: "m/*", expr: Layer((
        stack: [Translate(alpha: {alpha}, beta: {beta})],
        epsilon: 0.05,
        colour: (1.0, 1.0, 1.0),
        shape: {GLINT},
    )))],
    render: (preset: Final),
)"#,
        w = SIZE.0,
        h = SIZE.1,
        model = repo_file("patches/sphere.ron").display(),
    );
    let path = dir.join(format!("drawn_{alpha}_{beta}.ron"));
    std::fs::write(&path, text).unwrap();
    path
}

fn job(path: &Path) -> RenderJob {
    let overrides = Overrides {
        aovs: Some(vec![Aov::Matte]),
        ..Overrides::default()
    };
    RenderJob::load(path, &overrides).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The centroid of the matte within 30 pixels of `at`, in pixel centres, checking that the
/// blob lies wholly inside that window.
fn centroid(matte: &[f32], at: (f64, f64)) -> (f64, f64) {
    let (mut sum, mut sx, mut sy, mut rim) = (0.0, 0.0, 0.0, 0.0_f64);
    for y in 0..SIZE.1 {
        for x in 0..SIZE.0 {
            let (cx, cy) = (f64::from(x), f64::from(y));
            let d = (cx - at.0).hypot(cy - at.1);
            let m = f64::from(matte[(y * SIZE.0 + x) as usize]);
            if d <= 30.0 {
                sum += m;
                sx += m * cx;
                sy += m * cy;
                if d > 28.5 {
                    rim = rim.max(m);
                }
            }
        }
    }
    assert!(sum > 4.0, "no glint near {at:?}: {sum} pixels");
    assert!(
        rim == 0.0,
        "the glint near {at:?} is larger than the window"
    );
    (sx / sum, sy / sum)
}

#[test]
fn place_puts_a_drawn_outlines_centre_on_the_pixel() {
    let dir = tempfile::tempdir().unwrap();
    let start = shot(dir.path(), 0.0, 0.0);
    let mut placing = job(&start);
    for pixel in [(160.0, 120.0), (131.0, 98.0), (188.0, 141.0)] {
        let placed = placing.place(1.0, pixel, LayerChoice::default()).unwrap();
        // The residual on the patch under the pixel is a centre, and the glint shows there.
        let own = placed
            .residuals
            .iter()
            .find(|r| r.patch == placed.patch)
            .expect("a residual for the patch under the pixel");
        assert!(own.nearest < 1e-4 && own.covered, "{pixel:?}: {own:?}");
        let solved = shot(dir.path(), placed.translation.x, placed.translation.y);
        let image = job(&solved).render_frame(1.0).unwrap();
        let matte = image.aovs.matte.as_ref().unwrap();
        let (x, y) = centroid(matte, pixel);
        let miss = (x - pixel.0).hypot(y - pixel.1);
        assert!(
            miss < 1.0,
            "{pixel:?}: the glint's centroid ({x}, {y}) is {miss} px off"
        );
    }
}
