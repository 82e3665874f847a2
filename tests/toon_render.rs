//! X-Toon through the renderer: the tone of the exact sphere against the analytic sphere, the
//! detail stage running only where asked, and shape detail that moves no silhouette and, at
//! w = 0, changes no byte.

use std::sync::Arc;

use glam::{DVec3, Vec3};
use glint::formats::image_encoding::colour_rgba8;
use glint::geom::{shapes, NamedPatch, PatchLibrary};
use glint::highlight::{Expr, Layer, Light, Op, PreparedExpr};
use glint::render::tessellate::Density;
use glint::render::{
    Aovs, Camera, FrameMode, PatchLook, Projection, RenderedFrame, Renderer, Scene, Settings,
    Stage, Tone,
};
use glint::toon::{
    Abstraction, CelRamp, DetailMap, HighlightFrame, ShapeDetail, ToonTexture, XToon,
};

use crate::common::{teapot, teapot_camera};

/// A texture whose colour is its own coordinates: red the tone coordinate `(n·l + 1)/2`, green
/// the detail D, at every texel centre. Bilinear lookups between the centres return the
/// coordinates themselves.
fn coordinate_texture(size: usize) -> Arc<ToonTexture> {
    let centre = |i: usize| (i as f32 + 0.5) / size as f32;
    let texels = (0..size)
        .flat_map(|j| (0..size).map(move |i| Vec3::new(centre(i), 1.0 - centre(j), 0.0)))
        .collect();
    Arc::new(ToonTexture::new(size, size, texels).unwrap())
}

fn highlight() -> PreparedExpr {
    Expr::Layer(Layer::new(
        vec![Op::Translate {
            alpha: 0.1,
            beta: 0.05,
        }],
        0.06,
        [1.0, 1.0, 1.0],
    ))
    .prepare()
    .unwrap()
}

fn light() -> Light {
    Light::Directional {
        towards: Vec3::new(0.3, -0.6, 0.75).normalize(),
    }
}

fn render(library: &Arc<PatchLibrary>, looks: Vec<PatchLook>, camera: Camera) -> RenderedFrame {
    let scene = Scene {
        library,
        looks,
        camera,
        light: light(),
        outlines: None,
        aovs: Aovs {
            matte: true,
            patch_id: true,
            ..Aovs::default()
        },
        materials: Vec::new(),
    };
    let settings = Settings {
        density: Density::PerSpan { u: 6, v: 6 },
        frames: FrameMode::Exact,
        ..Settings::preview(200, 150)
    };
    let frame = Renderer::new(Arc::clone(library))
        .render(&scene, &settings)
        .unwrap();
    assert!(
        frame.colour.iter().all(|c| c.is_finite()),
        "a NaN or infinite pixel"
    );
    frame
}

/// An X-Toon look on every patch: a depth map, the given shape detail and a highlight.
fn xtoon_looks(library: &PatchLibrary, shape: Option<ShapeDetail>) -> Vec<PatchLook> {
    let built = shape
        .as_ref()
        .map(|s| s.abstraction.build(library).unwrap());
    let tone = XToon {
        detail: DetailMap::Depth { z_min: 9.0, r: 1.4 },
        invert: false,
        shape,
    }
    .prepare(coordinate_texture(16), built.as_ref())
    .unwrap();
    (0..library.patches.len())
        .map(|_| PatchLook {
            designed_light: None,
            lines: None,
            tone: Tone::XToon(tone.clone()),
            highlight: Some(highlight()),
        })
        .collect()
}

fn cel_looks(library: &PatchLibrary) -> Vec<PatchLook> {
    (0..library.patches.len())
        .map(|_| PatchLook {
            designed_light: None,
            lines: None,
            tone: Tone::Cel(CelRamp::two_tone(Vec3::splat(0.2), Vec3::splat(0.7), 0.0)),
            highlight: Some(highlight()),
        })
        .collect()
}

#[test]
fn xtoon_on_the_exact_sphere_matches_the_analytic_sphere() {
    const SIZE: u32 = 96;
    const TEXELS: usize = 32;
    let library = Arc::new(PatchLibrary {
        patches: vec![NamedPatch {
            name: "sphere".into(),
            trim: None,
            surface: shapes::sphere(DVec3::ZERO, 1.0).unwrap(),
        }],
        groups: Vec::new(),
    });
    let (z_min, r) = (4.1_f32, 1.2_f32);
    let tone = XToon {
        detail: DetailMap::Depth { z_min, r },
        invert: false,
        shape: None,
    }
    .prepare(coordinate_texture(TEXELS), None)
    .unwrap();
    let half_height = 1.2;
    let camera = Camera {
        eye: Vec3::new(0.0, -5.0, 0.0),
        target: Vec3::ZERO,
        up: Vec3::Z,
        projection: Projection::Orthographic {
            height: 2.0 * half_height,
        },
        near: 0.5,
        far: 20.0,
    };
    let l = Vec3::new(0.5, -0.6, 0.62).normalize();
    let scene = Scene {
        library: &library,
        looks: vec![PatchLook {
            designed_light: None,
            lines: None,
            tone: Tone::XToon(tone),
            highlight: None,
        }],
        camera,
        light: Light::Directional { towards: l },
        outlines: None,
        aovs: Aovs::default(),
        materials: Vec::new(),
    };
    let settings = Settings {
        density: Density::PerSpan { u: 8, v: 8 },
        frames: FrameMode::Refined,
        ..Settings::preview(SIZE, SIZE)
    };
    let frame = Renderer::new(Arc::clone(&library))
        .render(&scene, &settings)
        .unwrap();
    let edge = 0.5 / TEXELS as f32;
    let mut checked = 0;
    for y in 0..SIZE {
        for x in 0..SIZE {
            // The pixel's ray hits the unit sphere at (X, −√(1 − X² − Z²), Z).
            let ndc = |i: u32| 2.0 * (i as f32 + 0.5) / SIZE as f32 - 1.0;
            let (px, pz) = (ndc(x) * half_height, -ndc(y) * half_height);
            let rho2 = px * px + pz * pz;
            if rho2 > 0.95 {
                continue;
            }
            let p = Vec3::new(px, -(1.0 - rho2).sqrt(), pz);
            let depth = p.y + 5.0;
            let d = 1.0 - (depth / z_min).ln() / r.ln();
            let want_red = ((p.dot(l) + 1.0) / 2.0).clamp(edge, 1.0 - edge);
            let want_green = d.clamp(edge, 1.0 - edge);
            let c = frame.colour[(y * SIZE + x) as usize];
            assert_eq!(c.w, 1.0, "pixel ({x}, {y}) not covered");
            assert!(
                (c.x - want_red).abs() < 2e-4 && (c.y - want_green).abs() < 2e-4,
                "pixel ({x}, {y}): {c} against ({want_red}, {want_green})"
            );
            checked += 1;
        }
    }
    assert!(checked > 4000, "{checked}");
    assert_eq!(frame.stats.xtoon_pixels, frame.stats[Stage::Shade].pixels);
}

#[test]
fn a_scene_without_xtoon_does_no_detail_work() {
    let library = teapot();
    let frame = render(&library, cel_looks(&library), teapot_camera());
    assert_eq!(frame.stats.xtoon_pixels, 0);
    assert!(!frame.stats.ran(Stage::Detail));
    assert_eq!(frame.stats[Stage::Detail].pixels, 0);
    assert!(frame.stats[Stage::Shade].pixels > 0);
}

#[test]
fn the_detail_stage_counts_the_pixels_of_xtoon_patches() {
    let library = teapot();
    let mut looks = cel_looks(&library);
    let xtoon = xtoon_looks(&library, None);
    // The body patches (4–11) with X-Toon, the rest cel.
    looks[4..12].clone_from_slice(&xtoon[4..12]);
    let frame = render(&library, looks, teapot_camera());
    let ids = frame.aovs.patch_id.as_ref().unwrap();
    let on_body = ids.iter().filter(|&&p| (4..12).contains(&p)).count() as u64;
    assert!(on_body > 1000);
    assert_eq!(frame.stats.xtoon_pixels, on_body);
    // No highlight uses an abstracted frame: the tone is computed within the shade stage, with
    // no stage of its own.
    assert!(!frame.stats.ran(Stage::Detail));
    assert_eq!(frame.stats[Stage::Detail].pixels, 0);
}

#[test]
fn zero_shape_weight_reproduces_the_plain_render_byte_for_byte() {
    let library = teapot();
    let plain = render(&library, xtoon_looks(&library, None), teapot_camera());
    for abstraction in [
        Abstraction::Sphere,
        Abstraction::Ellipsoid,
        Abstraction::Cylinder,
        Abstraction::Smoothed { iterations: 2 },
    ] {
        let shape = ShapeDetail {
            abstraction,
            weight: 0.0,
            highlight_frame: HighlightFrame::Abstracted,
        };
        let zero = render(
            &library,
            xtoon_looks(&library, Some(shape)),
            teapot_camera(),
        );
        assert!(
            colour_rgba8(&zero.colour) == colour_rgba8(&plain.colour),
            "{abstraction:?}"
        );
        assert_eq!(zero.colour, plain.colour, "{abstraction:?}");
        assert_eq!(zero.aovs.matte, plain.aovs.matte, "{abstraction:?}");
    }
}

#[test]
fn shape_detail_moves_no_silhouette_and_the_highlight_frame_is_a_choice() {
    let library = teapot();
    let plain = render(&library, xtoon_looks(&library, None), teapot_camera());
    let alpha = |f: &RenderedFrame| f.colour.iter().map(|c| c.w).collect::<Vec<f32>>();
    let with = |highlight_frame| {
        let shape = ShapeDetail {
            abstraction: Abstraction::Ellipsoid,
            weight: 1.0,
            highlight_frame,
        };
        render(
            &library,
            xtoon_looks(&library, Some(shape)),
            teapot_camera(),
        )
    };
    let (abstracted, true_frame) = (with(HighlightFrame::Abstracted), with(HighlightFrame::True));
    for frame in [&abstracted, &true_frame] {
        // The same pixels covered, by the same patches: silhouettes stay.
        assert_eq!(alpha(frame), alpha(&plain));
        assert_eq!(frame.aovs.patch_id, plain.aovs.patch_id);
        // The tone follows the ellipsoid's normals.
        let changed = frame
            .colour
            .iter()
            .zip(&plain.colour)
            .filter(|(a, b)| (a.x - b.x).abs() > 0.05)
            .count();
        assert!(changed > 1000, "{changed}");
    }
    // In the true frame the designed highlight is the plain render's; in the abstracted frame
    // it moves with the abstracted normals.
    assert_eq!(true_frame.aovs.matte, plain.aovs.matte);
    let moved = abstracted
        .aovs
        .matte
        .as_ref()
        .unwrap()
        .iter()
        .zip(plain.aovs.matte.as_ref().unwrap())
        .filter(|(a, b)| a != b)
        .count();
    assert!(moved > 50, "{moved}");
    // The abstracted highlight frames need the tone to run ahead of the shade pass; outside
    // the highlights it gives the tone the shade pass computes as it goes.
    assert!(abstracted.stats.ran(Stage::Detail));
    assert!(!true_frame.stats.ran(Stage::Detail));
    assert_eq!(
        abstracted.stats[Stage::Detail].pixels,
        abstracted.stats.xtoon_pixels
    );
    assert_eq!(abstracted.stats.xtoon_pixels, true_frame.stats.xtoon_pixels);
    let mattes = abstracted.aovs.matte.as_ref().unwrap().iter();
    let unlit = mattes
        .zip(true_frame.aovs.matte.as_ref().unwrap())
        .map(|(a, b)| *a == 0.0 && *b == 0.0);
    let mut compared = 0;
    for ((a, b), unlit) in abstracted.colour.iter().zip(&true_frame.colour).zip(unlit) {
        if unlit {
            assert_eq!(a, b);
            compared += 1;
        }
    }
    assert!(compared > 10_000, "{compared}");
}
