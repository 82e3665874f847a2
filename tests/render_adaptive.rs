//! Adaptive anti-aliasing: the frame at one sample a pixel, with k × k samples averaged into
//! just the pixels whose colour can be wrong — silhouettes, lines, highlight and tone edges —
//! tile by tile.

use std::sync::Arc;

use glam::{Vec3, Vec4};
use glint::accuracy::{AnalyticSphere, ClosedForm};
use glint::geom::PatchLibrary;
use glint::highlight::{Expr, Layer, Light, Op};
use glint::render::{
    Antialias, Aovs, FrameMode, Outlines, PatchLook, Projection, RenderedFrame, Renderer, Scene,
    Settings, Stage, Tone,
};
use glint::toon::CelRamp;

use crate::common::{teapot, teapot_camera};

/// A two-tone blue cel look with no highlight and the outlines' lines.
fn blue() -> PatchLook {
    PatchLook {
        designed_light: None,
        lines: None,
        tone: Tone::Cel(CelRamp::two_tone(
            Vec3::new(0.2, 0.25, 0.5),
            Vec3::new(0.4, 0.55, 0.9),
            0.1,
        )),
        highlight: None,
    }
}

fn teapot_scene(library: &PatchLibrary, outlines: bool) -> Scene<'_> {
    let highlight = Expr::Layer(Layer::new(
        vec![
            Op::Translate {
                alpha: 0.15,
                beta: 0.05,
            },
            Op::Rotate { degrees: 25.0 },
        ],
        0.06,
        [1.0, 1.0, 1.0],
    ))
    .prepare()
    .unwrap();
    Scene {
        library,
        looks: (0..library.patches.len())
            .map(|_| PatchLook {
                designed_light: None,
                highlight: Some(highlight.clone()),
                ..blue()
            })
            .collect(),
        camera: teapot_camera(),
        light: Light::Directional {
            towards: Vec3::new(0.3, -0.6, 0.75).normalize(),
        },
        outlines: outlines.then_some(Outlines {
            width: 2.0,
            colour: Vec3::ZERO,
            crease_degrees: 60.0,
            patch_borders: false,
        }),
        aovs: Aovs {
            matte: true,
            ..Aovs::default()
        },
        materials: Vec::new(),
    }
}

fn with(antialias: Antialias) -> Settings {
    Settings {
        antialias,
        ..Settings::final_quality(200, 120)
    }
}

/// A frame of `scene` from a fresh renderer with the `final` settings but `antialias`.
fn render(library: &Arc<PatchLibrary>, scene: &Scene, antialias: Antialias) -> RenderedFrame {
    Renderer::new(Arc::clone(library))
        .render(scene, &with(antialias))
        .unwrap()
}

#[test]
fn only_supersampled_pixels_leave_the_one_sample_frame_and_they_smooth_its_edges() {
    let library = teapot();
    for outlines in [false, true] {
        let scene = teapot_scene(&library, outlines);
        let render = |antialias| render(&library, &scene, antialias);
        let (one, adaptive) = (render(Antialias::Analytic), render(Antialias::Adaptive(4)));
        assert!(!one.stats.ran(Stage::Supersample));
        let supersampled = adaptive.stats[Stage::Supersample].pixels;
        let changed = one
            .colour
            .iter()
            .zip(&adaptive.colour)
            .filter(|(a, b)| a != b)
            .count() as u64;
        // The unmarked pixels are the one-sample frame's, bit for bit.
        assert!(
            0 < changed && changed <= supersampled,
            "{changed} of {supersampled}"
        );
        assert!(supersampled < 200 * 120 / 2, "{supersampled}");
        // At one sample the silhouette is hard (the lines' own edges are anti-aliased at
        // any sampling); adaptively it is anti-aliased.
        let partial = |colour: &[Vec4]| colour.iter().filter(|c| c.w > 0.0 && c.w < 1.0).count();
        if !outlines {
            assert_eq!(partial(&one.colour), 0);
        }
        assert!(
            partial(&adaptive.colour) > 100,
            "{}",
            partial(&adaptive.colour)
        );
        // The same samples as a fresh renderer's, frame after frame.
        let mut renderer = Renderer::new(Arc::clone(&library));
        let settings = with(Antialias::Adaptive(4));
        let first = renderer.render(&scene, &settings).unwrap();
        let again = renderer.render(&scene, &settings).unwrap();
        assert_eq!(first.colour, adaptive.colour);
        assert_eq!(again.colour, adaptive.colour);
        assert_eq!(again.aovs, adaptive.aovs);
    }
}

#[test]
fn a_pixel_wholly_under_ink_is_not_supersampled_and_the_rest_still_are() {
    let library = teapot();
    let lined = teapot_scene(&library, true);
    // With a matte to write, every marked pixel is supersampled, inked or not (the matte
    // under the ink is still the surface's); without one, a pixel the lines cover wholly
    // shows only ink, and is left at one sample.
    let with_matte = render(&library, &lined, Antialias::Adaptive(4));
    let no_aovs = Scene {
        aovs: Aovs::default(),
        ..lined.clone()
    };
    let without = render(&library, &no_aovs, Antialias::Adaptive(4));
    let (all, left) = (
        with_matte.stats[Stage::Supersample].pixels,
        without.stats[Stage::Supersample].pixels,
    );
    assert!(0 < left && left < all, "{left} of {all} supersampled");
}

#[test]
fn the_supersampled_silhouette_follows_the_surface_not_the_mesh() {
    // Refined frames grow the coverage past the mesh's chords onto the surface, so a coarse
    // and a fine tessellation give nearly the same alpha; exact frames keep the mesh's.
    let library = teapot();
    let scene = teapot_scene(&library, false);
    let alpha = |pixels: f32, frames: FrameMode| -> Vec<f32> {
        let settings = Settings {
            density: glint::render::tessellate::Density::ScreenTolerance { pixels },
            frames,
            ..with(Antialias::Adaptive(4))
        };
        let frame = Renderer::new(Arc::clone(&library))
            .render(&scene, &settings)
            .unwrap();
        frame.colour.iter().map(|c| c.w).collect()
    };
    let difference =
        |a: &[f32], b: &[f32]| -> f32 { a.iter().zip(b).map(|(a, b)| (a - b).abs()).sum() };
    let fine = alpha(0.05, FrameMode::Refined);
    let refined = difference(&alpha(1.0, FrameMode::Refined), &fine);
    let exact = difference(
        &alpha(1.0, FrameMode::Exact),
        &alpha(0.05, FrameMode::Exact),
    );
    assert!(
        refined < 0.5 * exact,
        "refined {refined} against exact {exact}"
    );
}

#[test]
fn adaptive_samples_agree_with_supersampling_every_pixel() {
    // The marked pixels' samples — found from the refined points around them inside a surface,
    // rasterized in tiles at silhouettes and where lines reach — against every pixel rasterized
    // at the same 4 × 4 samples.
    let library = teapot();
    for outlines in [false, true] {
        let scene = teapot_scene(&library, outlines);
        let render = |antialias| render(&library, &scene, antialias);
        let (adaptive, every) = (
            render(Antialias::Adaptive(4)),
            render(Antialias::Supersample(4)),
        );
        let edge = every
            .colour
            .iter()
            .filter(|c| c.w > 0.0 && c.w < 1.0)
            .count() as f32;
        let alpha: Vec<f32> = adaptive
            .colour
            .iter()
            .zip(&every.colour)
            .map(|(a, b)| (a.w - b.w).abs())
            .collect();
        let matte = |f: &RenderedFrame| f.aovs.matte.clone().unwrap();
        let mattes: Vec<f32> = matte(&adaptive)
            .iter()
            .zip(&matte(&every))
            .map(|(a, b)| (a - b).abs())
            .collect();
        // Each difference at most `most` anywhere, and summed over the image at most
        // `per_edge` per pixel of the silhouette.
        let within = |what: &str, differences: &[f32], most: f32, per_edge: f32| {
            let largest = differences.iter().copied().fold(0.0, f32::max);
            let sum = differences.iter().sum::<f32>();
            assert!(largest <= most, "outlines {outlines}: {what} {largest}");
            assert!(
                sum <= per_edge * edge,
                "outlines {outlines}: {what} {sum} over {edge} edge pixels"
            );
        };
        // Coverage: a sample row at most anywhere (the sliver of a surface no centre sees), and
        // a few hundredths of a pixel over the silhouette's length.
        within("alpha", &alpha, 0.25, 0.03);
        // The highlight: within a fifth of a pixel's coverage anywhere.
        within("matte", &mattes, 0.2, 0.03);
    }
}

#[test]
fn a_cel_frame_finds_its_edges_on_interpolated_frames_and_draws_them_refined() {
    // With the matte alone, the one-sample pass interpolates frames; asking for the depth AOV,
    // which reads each pixel's refined point, makes it refine every pixel. The frames then
    // differ in the work, not in what they show: refined frames change a cel colour only near
    // an edge, and those pixels are drawn again from refined samples either way.
    let library = teapot();
    let scene = teapot_scene(&library, false);
    let mut reading = scene.clone();
    reading.aovs.depth = true;
    let flat = render(&library, &scene, Antialias::Adaptive(4));
    let read = render(&library, &reading, Antialias::Adaptive(4));
    // The frames spared are the one-sample pass's, one per covered pixel (and a few more
    // where a grazing ray is refined twice).
    let covered = read.stats[Stage::GBuffer].pixels as i64;
    let spared = read.stats.exact_frames as i64 - flat.stats.exact_frames as i64;
    assert!(
        (spared - covered).abs() <= covered / 10,
        "{spared} frames spared, {covered} pixels covered"
    );
    // Where an edge only grazes a pixel, which pixels the contrast marks can differ by one: a
    // pixel may differ by one sample of its 16 (a sixteenth of the largest contrast in the
    // scene, white highlight on blue), and only a few pixels may differ at all. (Where the lid
    // and the body end side by side, the pixels drawn again are those whose (u, v) lie near
    // the ends, which refining moves by a hair: a few more of them may differ.)
    let differences: Vec<f32> = flat
        .colour
        .iter()
        .zip(&read.colour)
        .map(|(a, b)| (*a - *b).abs().max_element())
        .collect();
    let largest = differences.iter().copied().fold(0.0, f32::max);
    assert!(largest <= 1.0 / 16.0 + 1e-4, "{largest}");
    let differing = differences.iter().filter(|&&d| d > 2.0 / 255.0).count() as i64;
    assert!(differing <= covered / 500, "{differing} pixels differ");
}

/// `scene` rendered at `size × size` with `final`'s settings but `antialias`.
fn final_with(
    library: &Arc<PatchLibrary>,
    scene: &Scene,
    size: u32,
    antialias: Antialias,
) -> RenderedFrame {
    let settings = Settings {
        antialias,
        ..Settings::final_quality(size, size)
    };
    Renderer::new(Arc::clone(library))
        .render(scene, &settings)
        .unwrap()
}

#[test]
fn a_band_edge_straight_across_a_pixel_is_drawn_at_one_sample_with_its_area() {
    // The unit sphere lit from the side, black below n·l = 0.2 and white above: the terminator
    // is a smooth curve across the disc. Where it crosses a pixel inside the disc the pixel
    // takes the box's area of the lit side at one sample, as the analytic sphere ray-cast at
    // 16 × 16 rays a pixel says: as close as 4 × 4 samples of every pixel come, on average and
    // at worst (where the edge bends, or meets the silhouette, the pixel is supersampled).
    let size = 256u32;
    let library = AnalyticSphere::library();
    let camera = AnalyticSphere::new(Projection::Perspective {
        fov_y_degrees: 26.0,
    })
    .camera();
    let towards = Vec3::new(1.0, -0.4, 0.5).normalize();
    let sphere = AnalyticSphere::seen_by(camera, towards);
    let threshold = 0.2;
    let scene = |bands: bool| Scene {
        library: &library,
        looks: vec![PatchLook {
            designed_light: None,
            lines: None,
            tone: Tone::Cel(CelRamp::two_tone(
                Vec3::ZERO,
                if bands { Vec3::ONE } else { Vec3::ZERO },
                threshold,
            )),
            highlight: None,
        }],
        camera,
        light: Light::Directional { towards },
        outlines: None,
        aovs: Aovs::default(),
        materials: Vec::new(),
    };
    let render = |scene: &Scene, antialias| final_with(&library, scene, size, antialias);
    // Per pixel, of 16 × 16 rays: the fraction that meet the sphere, and that meet it lit.
    let k = 16u32;
    let truth: Vec<(f32, f32)> = (0..size * size)
        .map(|i| {
            let (px, py) = ((i % size) as f32, (i / size) as f32);
            let (mut hit, mut lit) = (0u32, 0u32);
            for s in 0..k * k {
                let x = px + ((s % k) as f32 + 0.5) / k as f32;
                let y = py + ((s / k) as f32 + 0.5) / k as f32;
                if let Some(p) = sphere.hit(size, x, y) {
                    hit += 1;
                    lit += u32::from(p.normalize().as_vec3().dot(towards) >= threshold);
                }
            }
            let all = (k * k) as f32;
            (hit as f32 / all, lit as f32 / all)
        })
        .collect();
    // The pixels inside the disc that the terminator crosses.
    let crossed: Vec<usize> = (0..truth.len())
        .filter(|&i| truth[i].0 == 1.0 && truth[i].1 > 0.0 && truth[i].1 < 1.0)
        .collect();
    assert!(crossed.len() > 150, "{} pixels", crossed.len());
    let errors = |frame: &RenderedFrame| -> (f32, f32) {
        let e: Vec<f32> = crossed
            .iter()
            .map(|&i| (frame.colour[i].x * frame.colour[i].w - truth[i].1).abs())
            .collect();
        (
            e.iter().sum::<f32>() / e.len() as f32,
            e.iter().copied().fold(0.0, f32::max),
        )
    };
    let banded = scene(true);
    let adaptive = render(&banded, Antialias::Adaptive(4));
    let every = render(&banded, Antialias::Supersample(4));
    let (mean, worst) = errors(&adaptive);
    let (every_mean, every_worst) = errors(&every);
    assert!(
        mean <= every_mean && worst <= every_worst,
        "one sample: mean {mean}, worst {worst}; 4 × 4 samples: mean {every_mean}, worst \
         {every_worst}"
    );
    // And they were drawn at one sample: the band adds few pixels to those supersampled at
    // the silhouette.
    let plain = render(&scene(false), Antialias::Adaptive(4));
    let added = adaptive.stats[Stage::Supersample].pixels as i64
        - plain.stats[Stage::Supersample].pixels as i64;
    assert!(
        added * 4 < crossed.len() as i64,
        "{added} more supersampled for {} crossed",
        crossed.len()
    );
}

#[test]
fn a_highlight_edge_across_a_pixel_is_drawn_at_one_sample_with_its_area() {
    // The unit sphere with a crescent: a highlight with a smaller one cut from it off its
    // centre. Where one layer's edge crosses a pixel inside the disc, the pixel takes the box's
    // area of the crescent at one sample (from the quadratic of the layer's inside value over
    // the pixel), as the analytic sphere ray-cast at 16 × 16 rays a pixel says: on average
    // within a quarter of what 4 × 4 samples of every pixel come to (0.0025 against 0.023 of
    // a pixel), and few of those pixels are supersampled.
    let size = 256u32;
    let library = AnalyticSphere::library();
    let view = AnalyticSphere::new(Projection::Perspective {
        fov_y_degrees: 26.0,
    });
    let layer = |stack, epsilon| Box::new(Expr::Layer(Layer::new(stack, epsilon, [1.0; 3])));
    let described = Expr::Subtract(
        layer(vec![], 0.12),
        layer(
            vec![Op::Translate {
                alpha: 0.2,
                beta: 0.1,
            }],
            0.06,
        ),
    );
    let crescent = described.prepare().unwrap();
    let aovs = Aovs {
        matte: true,
        ..Aovs::default()
    };
    let scene = view.scene(&library, &crescent, aovs);
    let render = |scene: &Scene, antialias| final_with(&library, scene, size, antialias);
    // The truth from the closed form, not from the renderer's own highlight code.
    let truth = view.coverage(&ClosedForm::try_new(&described).unwrap(), size, 16);
    // The pixels wholly on the sphere (its four corners are: the disc is convex) that an edge
    // of the crescent crosses.
    let on_sphere = |i: u32| {
        let (x, y) = ((i % size) as f32, (i / size) as f32);
        [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)]
            .iter()
            .all(|(dx, dy)| view.hit(size, x + dx, y + dy).is_some())
    };
    let crossed: Vec<usize> = (0..size * size)
        .filter(|&i| {
            let t = truth[i as usize];
            t > 0.0 && t < 1.0 && on_sphere(i)
        })
        .map(|i| i as usize)
        .collect();
    assert!(crossed.len() > 100, "{} pixels", crossed.len());
    let mean_error = |frame: &RenderedFrame| -> f32 {
        let matte = frame.aovs.matte.as_ref().unwrap();
        crossed
            .iter()
            .map(|&i| (matte[i] - truth[i]).abs())
            .sum::<f32>()
            / crossed.len() as f32
    };
    let adaptive = render(&scene, Antialias::Adaptive(4));
    let every = render(&scene, Antialias::Supersample(4));
    let (one, sixteen) = (mean_error(&adaptive), mean_error(&every));
    assert!(
        one * 4.0 < sixteen,
        "one sample: mean {one}; 4 × 4 samples: mean {sixteen}"
    );
    // And they were drawn at one sample: the crescent adds few pixels to those supersampled at
    // the silhouette.
    let none = Expr::Layer(Layer::new(vec![], 1e-6, [1.0; 3]))
        .prepare()
        .unwrap();
    let plain = render(&view.scene(&library, &none, aovs), Antialias::Adaptive(4));
    let added = adaptive.stats[Stage::Supersample].pixels as i64
        - plain.stats[Stage::Supersample].pixels as i64;
    assert!(
        added * 4 < crossed.len() as i64,
        "{added} more supersampled for {} crossed",
        crossed.len()
    );
}

#[test]
fn a_gap_thinner_than_a_pixel_between_two_patches_that_end_there_is_drawn_with_its_area() {
    // Two plates of one colour, seen straight on through an orthographic camera 200 px across
    // 2.4 units, side by side with a gap of 0.4 px between them that lies between the centres
    // of pixel columns 99 and 100: each of the two columns is 0.2 px of gap.
    use glint::geom::{NamedPatch, NurbsSurface};
    let pixel = 2.4 / 200.0;
    let gap = 0.4 * pixel;
    let plate = |x0: f64, x1: f64| {
        let points = vec![
            vec![
                glam::DVec3::new(x0, -1.0, 0.0),
                glam::DVec3::new(x0, 1.0, 0.0),
            ],
            vec![
                glam::DVec3::new(x1, -1.0, 0.0),
                glam::DVec3::new(x1, 1.0, 0.0),
            ],
        ];
        let knots = vec![0.0, 0.0, 1.0, 1.0];
        NurbsSurface::new(1, 1, knots.clone(), knots, &points, None).unwrap()
    };
    let library = Arc::new(PatchLibrary {
        patches: [
            ("left", plate(-1.0, -0.5 * gap)),
            ("right", plate(0.5 * gap, 1.0)),
        ]
        .into_iter()
        .map(|(name, surface)| NamedPatch {
            name: name.into(),
            trim: None,
            surface,
        })
        .collect(),
        groups: Vec::new(),
    });
    let scene = Scene {
        library: &library,
        looks: vec![blue(), blue()],
        camera: glint::render::Camera {
            eye: Vec3::new(0.0, 0.0, 5.0),
            target: Vec3::ZERO,
            up: Vec3::Y,
            projection: Projection::Orthographic { height: 2.4 },
            near: 0.1,
            far: 100.0,
        },
        light: Light::Directional {
            towards: Vec3::new(0.2, 0.3, 0.9).normalize(),
        },
        outlines: None,
        aovs: Aovs::default(),
        materials: Vec::new(),
    };
    let frame = Renderer::new(Arc::clone(&library))
        .render(&scene, &Settings::final_quality(200, 200))
        .unwrap();
    // Away from the plates' ends, the two columns take 0.8 of a pixel each, the 4 × 4 samples
    // of the pixel within one column of samples (a quarter), the columns beside them all.
    for y in 20..180 {
        for x in 97..103 {
            let alpha = frame.colour[y * 200 + x].w;
            let truth = if x == 99 || x == 100 { 0.8 } else { 1.0 };
            assert!(
                (alpha - truth).abs() <= 0.06,
                "pixel ({x}, {y}): alpha {alpha}, truth {truth}"
            );
        }
    }
}

#[test]
fn a_silhouette_beside_a_pole_takes_each_sample_the_sphere_covers() {
    // The sphere seen from a little above its equator: its north pole lies at or near the top
    // of its outline, where (u, v) turns fast about it. Each of a silhouette pixel's 4 × 4
    // samples is covered where the analytic sphere's ray at that sample hits it (the
    // reference counted at the same samples), but for a sample or two within a hair of the
    // outline, where the mesh or a search may go either way. Started from the texels around
    // it alone, a pixel beside the pole came out empty where half of it is covered.
    let library = AnalyticSphere::library();
    let highlight = Expr::Layer(Layer::new(
        vec![Op::Rotate { degrees: 0.0 }],
        0.05,
        [1.0; 3],
    ))
    .prepare()
    .unwrap();
    let size = 256;
    for height in [0.3f32, 0.5, 0.8, 1.0, 1.2, 1.4, 1.6, 2.0, 2.5] {
        let sphere = AnalyticSphere::seen_by(
            glint::render::Camera {
                eye: Vec3::new(0.4, -4.0, height),
                target: Vec3::ZERO,
                up: Vec3::Z,
                projection: Projection::Perspective {
                    fov_y_degrees: 35.0,
                },
                near: 0.1,
                far: 100.0,
            },
            Vec3::new(0.3, -0.5, 0.8),
        );
        let scene = sphere.scene(&library, &highlight, Aovs::default());
        let c = sphere.camera().view_projection(1.0) * glam::Vec4::new(0.0, 0.0, 1.0, 1.0);
        eprintln!(
            "pole at {} {}",
            (c.x / c.w + 1.0) * 128.0,
            (1.0 - c.y / c.w) * 128.0
        );
        let frame = Renderer::new(Arc::clone(&library))
            .render(&scene, &Settings::final_quality(size, size))
            .unwrap();
        let truth = sphere.mattes(&highlight, size, 4, 4).silhouette;
        let off: Vec<(usize, f32, f32)> = frame
            .colour
            .iter()
            .zip(&truth)
            .enumerate()
            .filter(|(_, (c, &t))| (c.w - t).abs() > 1.5 / 16.0)
            .map(|(i, (c, &t))| (i, c.w, t))
            .collect();
        let far_off = off.iter().any(|&(_, a, t)| (a - t).abs() > 2.5 / 16.0);
        assert!(off.len() <= 1 && !far_off, "eye height {height}: {off:?}");
    }
}
