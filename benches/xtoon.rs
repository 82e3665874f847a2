//! What X-Toon costs: the teapot at 1280×720 with an X-Toon tone on every patch against the same
//! frame with a plain cel ramp, measured side by side in the same run, frame by frame in turn — a depth (LOA) map, a
//! highlight map, and the depth map with ellipsoid and smoothed shape detail. Exact frames, no
//! designed highlights, no outlines: the tone is most of the shading work. The GPU shader of
//! the X-Toon paper (Barla, Thollot & Markosian 2006) ran at 1.19 times the plain toon shader's
//! frame time.
//! Run with `cargo bench --bench xtoon`; it prints each variant's frame time by stage, then the
//! ratios.

#[path = "support/frames.rs"]
mod frames;
#[path = "support/teapot.rs"]
mod teapot;

use frames::Variant;

use std::path::Path;
use std::sync::Arc;

use glam::Vec3;
use glint::formats::{load_patches, read_toon_texture};
use glint::geom::PatchLibrary;
use glint::highlight::Light;
use glint::render::tessellate::Density;
use glint::render::{Aovs, FrameMode, PatchLook, Scene, Settings, Tone};
use glint::toon::{Abstraction, CelRamp, DetailMap, HighlightFrame, ShapeDetail, XToon};

/// Rounds of frames measured.
const ROUNDS: usize = 100;

fn scene(library: &PatchLibrary, tone: Tone) -> Scene<'_> {
    Scene {
        library,
        looks: (0..library.patches.len())
            .map(|_| PatchLook {
                designed_light: None,
                lines: None,
                tone: tone.clone(),
                highlight: None,
            })
            .collect(),
        camera: teapot::camera(),
        light: Light::Directional {
            towards: Vec3::new(0.3, -0.6, 0.75).normalize(),
        },
        outlines: None,
        aovs: Aovs::default(),
        materials: Vec::new(),
    }
}

fn xtoon(
    library: &PatchLibrary,
    texture: &str,
    detail: DetailMap,
    shape: Option<ShapeDetail>,
) -> Tone {
    let texture = Arc::new(read_toon_texture(&Path::new("textures").join(texture)).unwrap());
    let built = shape
        .as_ref()
        .map(|s| s.abstraction.build(library).unwrap());
    Tone::XToon(
        XToon {
            detail,
            invert: false,
            shape,
        }
        .prepare(texture, built.as_ref())
        .unwrap(),
    )
}

fn main() {
    let library = Arc::new(load_patches(Path::new("patches/teapot.bpt")).unwrap());
    let depth = DetailMap::Depth { z_min: 9.0, r: 1.3 };
    let shape = |abstraction| {
        Some(ShapeDetail {
            abstraction,
            weight: 0.5,
            highlight_frame: HighlightFrame::Abstracted,
        })
    };
    let variants = [
        (
            "cel",
            Tone::Cel(CelRamp::two_tone(
                Vec3::new(0.2, 0.25, 0.5),
                Vec3::new(0.4, 0.55, 0.9),
                0.1,
            )),
        ),
        (
            "xtoon_depth",
            xtoon(&library, "abstraction.png", depth.clone(), None),
        ),
        (
            "xtoon_highlight",
            xtoon(
                &library,
                "plastic_highlight.png",
                DetailMap::Highlight { s: 12.0 },
                None,
            ),
        ),
        (
            "xtoon_ellipsoid",
            xtoon(
                &library,
                "abstraction.png",
                depth.clone(),
                shape(Abstraction::Ellipsoid),
            ),
        ),
        (
            "xtoon_smoothed",
            xtoon(
                &library,
                "abstraction.png",
                depth,
                shape(Abstraction::Smoothed { iterations: 4 }),
            ),
        ),
    ];
    let settings = Settings {
        density: Density::PerSpan { u: 12, v: 12 },
        frames: FrameMode::Exact,
        ..Settings::preview(teapot::WIDTH, teapot::HEIGHT)
    };
    let scenes: Vec<(&'static str, Scene)> = variants
        .iter()
        .map(|(name, tone)| (*name, scene(&library, tone.clone())))
        .collect();
    let mut renders: Vec<Variant> = scenes
        .iter()
        .map(|(name, scene)| Variant::render(name, &library, scene, &settings))
        .collect();
    let measured = frames::measure(&mut renders, ROUNDS);
    measured.print_frames("teapot, 1280×720: frame time by stage");
    measured.print_ratios(
        "frame-time ratios to the plain cel ramp",
        &[
            ("xtoon_depth", "cel"),
            ("xtoon_highlight", "cel"),
            ("xtoon_ellipsoid", "cel"),
            ("xtoon_smoothed", "cel"),
        ],
    );
}
