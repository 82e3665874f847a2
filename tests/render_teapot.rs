//! The teapot through the whole renderer: no cracks from any side, finite G-buffer channels,
//! stages that run only when used, and output independent of the thread count.

use std::sync::Arc;

use glam::Vec3;
use glint::formats::image_encoding::colour_rgba8;
use glint::geom::PatchLibrary;
use glint::highlight::{Expr, Layer, Light, Op};
use glint::render::tessellate::Density;
use glint::render::{
    Aovs, Camera, Outlines, PatchLook, Projection, Renderer, Scene, Settings, Stage, Tone,
};
use glint::toon::CelRamp;

use crate::common::teapot;

fn camera_at(azimuth_degrees: f32, elevation_degrees: f32) -> Camera {
    let (a, e) = (azimuth_degrees.to_radians(), elevation_degrees.to_radians());
    let target = Vec3::new(0.0, 0.0, 1.5);
    Camera {
        eye: target + 9.0 * Vec3::new(e.cos() * a.cos(), e.cos() * a.sin(), e.sin()),
        target,
        up: Vec3::Z,
        projection: Projection::Perspective {
            fov_y_degrees: 35.0,
        },
        near: 0.1,
        far: 50.0,
    }
}

fn scene<'a>(
    library: &'a PatchLibrary,
    camera: Camera,
    highlight: bool,
    outlines: bool,
    aovs: Aovs,
) -> Scene<'a> {
    let expr = Expr::Layer(Layer::new(
        vec![Op::Scale {
            delta: 0.5,
            axis: Default::default(),
        }],
        0.05,
        [1.0, 1.0, 1.0],
    ))
    .prepare()
    .unwrap();
    Scene {
        library,
        looks: (0..library.patches.len())
            .map(|_| PatchLook {
                designed_light: None,
                lines: None,
                tone: Tone::Cel(CelRamp::two_tone(Vec3::splat(0.2), Vec3::splat(0.7), 0.0)),
                highlight: highlight.then(|| expr.clone()),
            })
            .collect(),
        camera,
        light: Light::Directional {
            towards: Vec3::new(0.4, -0.5, 0.8).normalize(),
        },
        outlines: outlines.then_some(Outlines {
            width: 2.0,
            colour: Vec3::ZERO,
            crease_degrees: 60.0,
            patch_borders: true,
        }),
        aovs,
        materials: Vec::new(),
    }
}

fn settings(size: u32) -> Settings {
    Settings {
        density: Density::ScreenTolerance { pixels: 0.5 },
        ..Settings::preview(size, size)
    }
}

/// The uncovered pixels of a `size × size` image that no path of uncovered pixels (4-connected)
/// links to the image border, in enclosed regions of fewer than 64 pixels: cracks of any
/// length and shape, one pixel or more wide. (The background seen through the handle is one
/// region of hundreds of pixels; a gap where two parts meet at a grazing angle opens to the
/// background around the teapot.)
fn small_holes(size: u32, covered: impl Fn(u32, u32) -> bool) -> Vec<(u32, u32)> {
    let n = size as usize;
    let mut outside = vec![false; n * n];
    let mut stack: Vec<(u32, u32)> = (0..size)
        .flat_map(|k| [(k, 0), (k, size - 1), (0, k), (size - 1, k)])
        .collect();
    while let Some((x, y)) = stack.pop() {
        let i = y as usize * n + x as usize;
        if outside[i] || covered(x, y) {
            continue;
        }
        outside[i] = true;
        if x > 0 {
            stack.push((x - 1, y));
        }
        if y > 0 {
            stack.push((x, y - 1));
        }
        if x + 1 < size {
            stack.push((x + 1, y));
        }
        if y + 1 < size {
            stack.push((x, y + 1));
        }
    }
    // The enclosed regions, each by a flood fill of its own.
    let mut seen = outside.clone();
    let mut holes = Vec::new();
    for start in 0..n * n {
        let (x0, y0) = ((start % n) as u32, (start / n) as u32);
        if seen[start] || covered(x0, y0) {
            continue;
        }
        let mut region = Vec::new();
        let mut stack = vec![(x0, y0)];
        while let Some((x, y)) = stack.pop() {
            let i = y as usize * n + x as usize;
            if seen[i] || covered(x, y) {
                continue;
            }
            seen[i] = true;
            region.push((x, y));
            stack.extend([(x - 1, y), (x + 1, y), (x, y - 1), (x, y + 1)]);
        }
        if region.len() < 64 {
            holes.extend(region);
        }
    }
    holes
}

#[test]
fn small_holes_are_found_whatever_their_shape() {
    // A covered square with a one-pixel dot, a crack two pixels long, a diagonal crack, and
    // a 10 × 10 window (a hole of 100 pixels, not a crack); an open notch at the border.
    let size = 40;
    let holes: Vec<(u32, u32)> = vec![(5, 5), (10, 5), (11, 5), (15, 15), (16, 16), (17, 17)];
    let covered = |x: u32, y: u32| {
        let inside = (2..38).contains(&x) && (2..38).contains(&y);
        let window = (20..30).contains(&x) && (20..30).contains(&y);
        let notch = x == 2 && y == 8;
        inside && !window && !notch && !holes.contains(&(x, y))
    };
    let mut found = small_holes(size, covered);
    found.sort_by_key(|&(x, y)| (y, x));
    let mut expected = holes.clone();
    expected.sort_by_key(|&(x, y)| (y, x));
    assert_eq!(found, expected);
}

#[test]
fn no_cracks_and_finite_channels_from_twelve_angles() {
    let library = teapot();
    let mut renderer = Renderer::new(Arc::clone(&library));
    let all = Aovs {
        matte: true,
        patch_id: true,
        depth: true,
        normal: true,
        uv: true,
        n_dot_h: true,
        n_dot_l: true,
        outline: true,
    };
    let size = 256;
    for k in 0..12 {
        let camera = camera_at(30.0 * k as f32 + 7.0, [-35.0, 10.0, 45.0, 80.0][k % 4]);
        let frame = renderer
            .render(&scene(&library, camera, true, false, all), &settings(size))
            .unwrap();
        let ids = frame.aovs.patch_id.as_ref().unwrap();
        let covered = |x: u32, y: u32| ids[(y * size + x) as usize] != u32::MAX;
        let cracks = small_holes(size, covered);
        assert!(
            cracks.is_empty(),
            "view {k}: uncovered pixels enclosed by the teapot: {cracks:?}"
        );
        assert!(
            ids.iter().filter(|&&i| i != u32::MAX).count() > 2000,
            "view {k}: teapot in view"
        );
        let a = &frame.aovs;
        assert!(a
            .depth
            .as_ref()
            .unwrap()
            .iter()
            .all(|d| d.is_finite() || *d == f32::INFINITY));
        assert!(a.normal.as_ref().unwrap().iter().all(|n| n.is_finite()));
        assert!(a.uv.as_ref().unwrap().iter().all(|uv| uv.is_finite()));
        assert!(a
            .matte
            .as_ref()
            .unwrap()
            .iter()
            .all(|m| (0.0..=1.0).contains(m)));
        assert!(a
            .n_dot_h
            .as_ref()
            .unwrap()
            .iter()
            .all(|x| (-1.0..=1.0).contains(x)));
        // Without shade stacks the tone reads the scene's light: N·L' is the normal's N·L,
        // but where a pixel's samples straddle a silhouette or a fold.
        let light = Vec3::new(0.4, -0.5, 0.8).normalize();
        let normals = a.normal.as_ref().unwrap();
        let n_dot_l = a.n_dot_l.as_ref().unwrap();
        let (mut near, mut on) = (0, 0);
        for (p, &id) in ids.iter().enumerate() {
            if id != u32::MAX {
                on += 1;
                near += usize::from((n_dot_l[p] - normals[p].dot(light)).abs() < 0.01);
            }
        }
        assert!(
            near * 100 >= on * 97,
            "view {k}: N·L' is N·L at {near} of {on} pixels"
        );
        assert!(frame.colour.iter().all(|c| c.is_finite()));
    }
}

#[test]
fn unused_stages_do_no_work_and_used_ones_do() {
    let library = teapot();
    let mut renderer = Renderer::new(Arc::clone(&library));
    let camera = camera_at(20.0, 25.0);
    let plain = renderer
        .render(
            &scene(&library, camera, false, false, Aovs::default()),
            &settings(128),
        )
        .unwrap()
        .stats;
    assert!(plain[Stage::Shade].pixels > 0 && plain[Stage::Rasterize].pixels > 0);
    assert_eq!(plain[Stage::Shade].pixels, plain[Stage::Rasterize].pixels);
    assert!(
        !plain.ran(Stage::GBuffer),
        "the tone alone is shaded straight from the visibility buffer"
    );
    assert_eq!(plain[Stage::GBuffer].pixels, 0);
    assert_eq!(plain.highlight_pixels, 0);
    for stage in [
        Stage::Detail,
        Stage::EdgeWidths,
        Stage::Outline,
        Stage::Aov,
        Stage::Resolve,
    ] {
        assert!(!plain.ran(stage), "{stage}");
        assert_eq!(plain[stage].pixels, 0, "{stage}");
    }
    assert_eq!(plain.exact_frames, 0, "preview interpolates frames");

    let aovs = Aovs {
        matte: true,
        ..Aovs::default()
    };
    let full = renderer
        .render(&scene(&library, camera, true, true, aovs), &settings(128))
        .unwrap()
        .stats;
    assert_eq!(full[Stage::GBuffer].pixels, full[Stage::Rasterize].pixels);
    assert_eq!(full.highlight_pixels, full[Stage::Shade].pixels);
    assert!(full[Stage::Outline].pixels > 0);
    assert_eq!(full[Stage::Aov].pixels, 128 * 128);
    assert!(
        !full.tessellation_rebuilt,
        "same camera and density: the cached mesh serves"
    );
}

#[test]
fn shading_straight_from_the_visibility_buffer_gives_the_g_buffer_image() {
    let library = teapot();
    let mut renderer = Renderer::new(Arc::clone(&library));
    for (k, camera) in [camera_at(20.0, 25.0), camera_at(200.0, -30.0)]
        .into_iter()
        .enumerate()
    {
        let direct = scene(&library, camera, false, false, Aovs::default());
        // Asking for an AOV makes the frame build the G-buffer; the colour must not change.
        let depth = Aovs {
            depth: true,
            ..Aovs::default()
        };
        let through_texels = scene(&library, camera, false, false, depth);
        let a = renderer.render(&direct, &settings(160)).unwrap();
        let b = renderer.render(&through_texels, &settings(160)).unwrap();
        assert!(!a.stats.ran(Stage::GBuffer), "view {k}");
        assert!(b.stats[Stage::GBuffer].pixels > 2000, "view {k}");
        assert_eq!(
            a.stats[Stage::Shade].pixels,
            b.stats[Stage::Shade].pixels,
            "view {k}"
        );
        assert!(a.colour == b.colour, "view {k}: the two paths shade alike");
    }
}

#[test]
fn thread_count_does_not_change_the_output_bytes() {
    let library = teapot();
    let camera = camera_at(-40.0, 30.0);
    let scene = scene(&library, camera, true, true, Aovs::default());
    let images: Vec<Vec<u8>> = [1, 2, 3]
        .iter()
        .map(|&threads| {
            let settings = Settings {
                threads,
                ..Settings::final_quality(160, 120)
            };
            colour_rgba8(
                &Renderer::new(Arc::clone(&library))
                    .render(&scene, &settings)
                    .unwrap()
                    .colour,
            )
        })
        .collect();
    assert!(images[0] == images[1] && images[1] == images[2]);
}
