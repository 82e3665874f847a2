//! Helpers shared by the test modules: running the binary, loading the shipped models.

pub mod ball_shot;
pub mod http;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::Arc;

use glint::formats::load_patches;
use glint::geom::PatchLibrary;

/// The repository's root folder, where `patches/`, `shots/` and `textures/` are.
pub fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the command line crate sits in a folder of the repository")
}

/// A file of the repository, by its path from the root.
pub fn repo_file(path: &str) -> PathBuf {
    root().join(path)
}

/// The `glint` binary as a command, run in the repository's root folder.
pub fn glint() -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_glint"));
    command.current_dir(root());
    command
}

/// Runs `glint` with `args` in the repository's root folder and returns what it did.
pub fn glint_with(args: &[&str]) -> Output {
    glint().args(args).output().expect("the glint binary runs")
}

/// What a command wrote to standard error, as text.
pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// The Utah teapot: 32 bicubic Bezier patches.
pub fn teapot() -> Arc<PatchLibrary> {
    Arc::new(load_patches(&repo_file("patches/teapot.bpt")).expect("the shipped teapot loads"))
}

/// The teapot from the front right and above, filling most of a 16:9 frame (the frame
/// benchmarks' view).
pub fn teapot_camera() -> glint::render::Camera {
    glint::render::Camera {
        eye: glam::Vec3::new(5.5, -7.0, 4.5),
        target: glam::Vec3::new(0.0, 0.0, 1.4),
        up: glam::Vec3::Z,
        projection: glint::render::Projection::Perspective {
            fov_y_degrees: 30.0,
        },
        near: 0.1,
        far: 100.0,
    }
}

/// Runs a documented command line (`glint …`) with `sh` in `dir`, `glint` being the binary
/// under test, and returns what it did.
pub fn run_documented(dir: &Path, command: &str) -> Output {
    let binary = env!("CARGO_BIN_EXE_glint");
    let line = command.replacen("glint", &format!("'{binary}'"), 1);
    Command::new("sh")
        .current_dir(dir)
        .arg("-c")
        .arg(&line)
        .output()
        .expect("sh runs")
}

/// The 8-connected components of the pixels `on` marks: per pixel its component (or
/// `usize::MAX`), and their sizes.
pub fn labels(on: &[bool], (w, h): (usize, usize)) -> (Vec<usize>, Vec<usize>) {
    let mut label = vec![usize::MAX; on.len()];
    let mut sizes = Vec::new();
    for start in 0..on.len() {
        if !on[start] || label[start] != usize::MAX {
            continue;
        }
        let id = sizes.len();
        let mut size = 0;
        let mut stack = vec![start];
        label[start] = id;
        while let Some(p) = stack.pop() {
            size += 1;
            let (x, y) = ((p % w) as i64, (p / w) as i64);
            for dy in -1..=1 {
                for dx in -1..=1 {
                    let (nx, ny) = (x + dx, y + dy);
                    if nx < 0 || ny < 0 || nx >= w as i64 || ny >= h as i64 {
                        continue;
                    }
                    let q = ny as usize * w + nx as usize;
                    if on[q] && label[q] == usize::MAX {
                        label[q] = id;
                        stack.push(q);
                    }
                }
            }
        }
        sizes.push(size);
    }
    (label, sizes)
}

/// The coverage-weighted centroid of a matte `width` pixels wide, pixel `(i, j)`'s centre at
/// `(i, j)`, and the matte's total coverage.
pub fn matte_centroid_of(matte: &[f32], width: u32) -> ((f64, f64), f64) {
    let (mut sum, mut sx, mut sy) = (0.0, 0.0, 0.0);
    for (i, &m) in matte.iter().enumerate() {
        let (x, y) = (f64::from(i as u32 % width), f64::from(i as u32 / width));
        sum += f64::from(m);
        sx += f64::from(m) * x;
        sy += f64::from(m) * y;
    }
    ((sx / sum, sy / sum), sum)
}

/// A bilinear patch named `name`, with the prim's metadata `meta` (`""` for none) and its
/// children `inside`, as USDA: the unit square at z = 0, its corners row by row.
pub fn flat_patch(name: &str, meta: &str, inside: &str) -> String {
    format!(
        r#"def NurbsPatch "{name}" {meta}
{{
    int uVertexCount = 2
    int vVertexCount = 2
    int uOrder = 2
    int vOrder = 2
    double[] uKnots = [0, 0, 1, 1]
    double[] vKnots = [0, 0, 1, 1]
    point3f[] points = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (1, 1, 0)]
{inside}
}}
"#
    )
}
