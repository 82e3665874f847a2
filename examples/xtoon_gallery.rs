//! Each X-Toon effect family on the teapot and the torus, through the Rust API: one sheet of
//! panels per family and model, read left to right.
//!
//! - levels of abstraction, receding shadows, aerial perspective: the camera dollies away
//!   (zooming in to keep the framing), so only the depth map changes the tone;
//! - depth of field: the focus point moves from the front to the back;
//! - plastic highlight, metallic flare, backlight: the light turns;
//! - shape detail: the true shape, then the sphere, ellipsoid, cylinder and smoothed
//!   abstractions at w = 1.
//!
//! `cargo run --release --example xtoon_gallery -- [OUT_DIR]` (default `out/xtoon`); textures
//! are read from `textures/`.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::{Vec3, Vec4};
use glint::formats::image_encoding::colour_rgba8;
use glint::formats::png::{write_png, PngLayout};
use glint::formats::{load_patches, read_toon_texture};
use glint::geom::PatchLibrary;
use glint::highlight::Light;
use glint::render::{
    Aovs, Camera, Outlines, PatchLook, Projection, Renderer, Scene, Settings, Tone,
};
use glint::toon::{Abstraction, DetailMap, HighlightFrame, ShapeDetail, ToonTexture, XToon};

const PANEL: (u32, u32) = (360, 270);

/// A model and how to look at it.
struct Model {
    name: &'static str,
    library: Arc<PatchLibrary>,
    target: Vec3,
    /// Unit direction from the target to the eye.
    toward_eye: Vec3,
    /// Eye distances of the dolly; the first is the close-up.
    distances: [f32; 3],
    /// Field of view at the first distance, in degrees.
    fov: f32,
    /// Depth map z_min: the close-up's nearest point.
    z_min: f32,
}

/// One panel: the tone, the camera distance (index into the dolly) and the light.
struct Panel {
    tone: XToon,
    distance: usize,
    light: Vec3,
}

fn camera(model: &Model, distance: usize) -> Camera {
    let d = model.distances[distance];
    // Keep the framing: the view height at the target stays the close-up's.
    let height = 2.0 * model.distances[0] * (0.5 * model.fov.to_radians()).tan();
    Camera {
        eye: model.target + d * model.toward_eye,
        target: model.target,
        up: Vec3::Z,
        projection: Projection::Perspective {
            fov_y_degrees: (2.0 * (0.5 * height / d).atan()).to_degrees(),
        },
        near: 0.1,
        far: 200.0,
    }
}

fn render(model: &Model, texture: &Arc<ToonTexture>, panel: &Panel) -> anyhow::Result<Vec<Vec4>> {
    let shape = panel
        .tone
        .shape
        .as_ref()
        .map(|s| s.abstraction.build(&model.library))
        .transpose()?;
    let tone = panel.tone.prepare(Arc::clone(texture), shape.as_ref())?;
    let scene = Scene {
        library: &model.library,
        looks: (0..model.library.patches.len())
            .map(|_| PatchLook {
                designed_light: None,
                lines: None,
                tone: Tone::XToon(tone.clone()),
                highlight: None,
            })
            .collect(),
        camera: camera(model, panel.distance),
        light: Light::Directional {
            towards: panel.light.normalize(),
        },
        outlines: Some(Outlines {
            width: 1.5,
            colour: Vec3::splat(0.03),
            crease_degrees: 70.0,
            patch_borders: false,
        }),
        aovs: Aovs::default(),
        materials: Vec::new(),
    };
    let settings = Settings::final_quality(PANEL.0, PANEL.1);
    Ok(Renderer::new(Arc::clone(&model.library))
        .render(&scene, &settings)?
        .colour)
}

/// Panels side by side over white, as one PNG.
fn write_sheet(path: &Path, panels: &[Vec<Vec4>]) -> anyhow::Result<()> {
    let (w, h) = (PANEL.0 as usize, PANEL.1 as usize);
    let width = w * panels.len();
    let mut sheet = vec![Vec4::ONE; width * h];
    for (k, panel) in panels.iter().enumerate() {
        for y in 0..h {
            for x in 0..w {
                let c = panel[y * w + x];
                let over_white = c.truncate() * c.w + Vec3::ONE * (1.0 - c.w);
                sheet[y * width + k * w + x] = over_white.extend(1.0);
            }
        }
    }
    write_png(
        path,
        width as u32,
        h as u32,
        PngLayout::Rgba8,
        &colour_rgba8(&sheet),
    )?;
    println!("wrote {}", path.display());
    Ok(())
}

fn xtoon(detail: DetailMap) -> XToon {
    XToon {
        detail,
        invert: false,
        shape: None,
    }
}

fn main() -> anyhow::Result<()> {
    let out = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "out/xtoon".into()),
    );
    std::fs::create_dir_all(&out)?;
    let texture = |name: &str| -> anyhow::Result<Arc<ToonTexture>> {
        Ok(Arc::new(read_toon_texture(
            &Path::new("textures").join(format!("{name}.png")),
        )?))
    };
    let models = [
        Model {
            name: "teapot",
            library: Arc::new(load_patches(Path::new("patches/teapot.bpt"))?),
            target: Vec3::new(0.2, 0.0, 1.5),
            toward_eye: Vec3::new(5.5, -7.0, 4.5).normalize(),
            distances: [10.0, 20.0, 36.0],
            fov: 34.0,
            z_min: 8.0,
        },
        Model {
            name: "torus",
            library: Arc::new(load_patches(Path::new("patches/torus.ron"))?),
            target: Vec3::ZERO,
            toward_eye: Vec3::new(0.3, -1.0, 0.8).normalize(),
            distances: [4.0, 8.0, 15.0],
            fov: 40.0,
            z_min: 3.0,
        },
    ];
    let key = Vec3::new(0.3, -0.6, 0.75);
    for model in &models {
        let depth = DetailMap::Depth {
            z_min: model.z_min,
            r: 3.5,
        };
        let dolly = |tone: &XToon| -> Vec<Panel> {
            (0..3)
                .map(|distance| Panel {
                    tone: tone.clone(),
                    distance,
                    light: key,
                })
                .collect()
        };
        let turning = |tone: &XToon, lights: [Vec3; 3]| -> Vec<Panel> {
            lights
                .iter()
                .map(|&light| Panel {
                    tone: tone.clone(),
                    distance: 0,
                    light,
                })
                .collect()
        };
        // The focus point on the line of sight, from in front of the model to behind it.
        let focus = |offset: f32| {
            let eye = model.target + model.distances[0] * model.toward_eye;
            (eye + (model.distances[0] + offset) * -model.toward_eye).to_array()
        };
        let dof = |offset: f32| Panel {
            tone: xtoon(DetailMap::DepthOfField {
                focus: focus(offset),
                z_min: 0.05 * model.distances[0],
                r: 6.0,
            }),
            distance: 0,
            light: key,
        };
        let shape = |abstraction: Option<Abstraction>| Panel {
            tone: XToon {
                detail: DetailMap::NearSilhouette { r: 0.0 },
                invert: false,
                shape: abstraction.map(|abstraction| ShapeDetail {
                    abstraction,
                    weight: 1.0,
                    highlight_frame: HighlightFrame::Abstracted,
                }),
            },
            distance: 0,
            light: key,
        };
        let sheets: Vec<(&str, &str, Vec<Panel>)> = vec![
            ("abstraction", "abstraction", dolly(&xtoon(depth.clone()))),
            (
                "receding_shadows",
                "receding_shadows",
                dolly(&xtoon(depth.clone())),
            ),
            (
                "aerial_perspective",
                "aerial_perspective",
                dolly(&xtoon(depth)),
            ),
            (
                "depth_of_field",
                "abstraction",
                vec![
                    dof(-0.1 * model.distances[0]),
                    dof(0.0),
                    dof(0.1 * model.distances[0]),
                ],
            ),
            (
                "plastic_highlight",
                "plastic_highlight",
                turning(
                    &xtoon(DetailMap::Highlight { s: 10.0 }),
                    [key, Vec3::new(0.9, -0.5, 0.5), Vec3::new(-0.2, -0.4, 1.0)],
                ),
            ),
            (
                "metal_flare",
                "metal_flare",
                turning(
                    &xtoon(DetailMap::Highlight { s: 4.0 }),
                    [Vec3::new(0.9, -0.2, 0.2), key, Vec3::new(-0.6, -0.9, 0.4)],
                ),
            ),
            (
                "backlight",
                "backlight",
                turning(
                    &xtoon(DetailMap::NearSilhouette { r: 1.0 }),
                    [Vec3::new(-0.8, 0.6, 0.4), Vec3::new(0.0, 0.3, 1.0), key],
                ),
            ),
            (
                "shape_detail",
                "abstraction",
                vec![
                    shape(None),
                    shape(Some(Abstraction::Sphere)),
                    shape(Some(Abstraction::Ellipsoid)),
                    shape(Some(Abstraction::Cylinder)),
                    shape(Some(Abstraction::Smoothed { iterations: 10 })),
                ],
            ),
        ];
        for (sheet, texture_name, panels) in sheets {
            let texture = texture(texture_name)?;
            let images = panels
                .iter()
                .map(|p| render(model, &texture, p))
                .collect::<anyhow::Result<Vec<_>>>()?;
            write_sheet(&out.join(format!("{}_{sheet}.png", model.name)), &images)?;
        }
    }
    Ok(())
}
