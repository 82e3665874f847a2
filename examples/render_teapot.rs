//! Drives the renderer from Rust: the Utah teapot, two-tone cel shading, a designed highlight
//! (stretched, squared, with a crescent cut) on the body, outlines, and AOVs as PNGs and EXR.
//!
//! `cargo run --release --example render_teapot -- [OUT_DIR]` (default `out/teapot`).

use std::path::PathBuf;

use glam::Vec3;
use glint::formats::load_patches;
use glint::formats::{write_frame_exr, write_pngs};
use glint::highlight::{Expr, Layer, Light, Op, SquareStyle};
use glint::render::{
    Aovs, Camera, Outlines, PatchLook, Projection, Renderer, Scene, Settings, Tone,
};
use glint::toon::CelRamp;

fn layer(stack: Vec<Op>, epsilon: f32) -> Layer {
    Layer::new(stack, epsilon, [1.0, 1.0, 0.95])
}

fn main() -> anyhow::Result<()> {
    let out = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "out/teapot".into()),
    );
    std::fs::create_dir_all(&out)?;
    let library = std::sync::Arc::new(load_patches(std::path::Path::new("patches/teapot.bpt"))?);

    // A squared highlight stretched along the body, with a shifted copy cut out of it.
    let body = Expr::Subtract(
        Box::new(Expr::Layer(layer(
            vec![
                Op::Scale {
                    delta: 0.6,
                    axis: Default::default(),
                },
                Op::Square {
                    sigma: 0.2,
                    n: 2.0,
                    style: SquareStyle::Tangent,
                },
            ],
            0.06,
        ))),
        Box::new(Expr::Layer(layer(
            vec![Op::Translate {
                alpha: 0.12,
                beta: 0.08,
            }],
            0.04,
        ))),
    )
    .prepare()?;
    let looks = (0..library.patches.len())
        .map(|i| PatchLook {
            designed_light: None,
            lines: None,
            tone: Tone::Cel(CelRamp::two_tone(
                Vec3::new(0.16, 0.25, 0.55),
                Vec3::new(0.35, 0.55, 0.95),
                0.1,
            )),
            // Body patches 4–11 carry the designed highlight; the others only their tone.
            highlight: (4..12).contains(&i).then(|| body.clone()),
        })
        .collect();
    let scene = Scene {
        library: &library,
        looks,
        camera: Camera {
            eye: Vec3::new(5.5, -7.0, 5.0),
            target: Vec3::new(0.0, 0.0, 1.4),
            up: Vec3::Z,
            projection: Projection::Perspective {
                fov_y_degrees: 35.0,
            },
            near: 0.1,
            far: 100.0,
        },
        light: Light::Directional {
            towards: Vec3::new(0.3, -0.6, 0.75).normalize(),
        },
        outlines: Some(Outlines {
            width: 2.0,
            colour: Vec3::new(0.02, 0.02, 0.05),
            crease_degrees: 60.0,
            patch_borders: false,
        }),
        aovs: Aovs {
            matte: true,
            patch_id: true,
            n_dot_h: true,
            ..Aovs::default()
        },
        materials: Vec::new(),
    };
    let mut renderer = Renderer::new(std::sync::Arc::clone(&library));
    let frame = renderer.render(&scene, &Settings::final_quality(960, 640))?;
    for path in write_pngs(&frame, &out.join("teapot.png"))? {
        println!("wrote {}", path.display());
    }
    write_frame_exr(&frame, &out.join("teapot.exr"), &[])?;
    println!("{}", serde_json::to_string_pretty(&frame.stats)?);
    println!("wrote {}", out.join("teapot.exr").display());
    Ok(())
}
