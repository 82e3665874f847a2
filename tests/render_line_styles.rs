//! Line styles per patch: each patch's lines take its own width and colour, a line two patches
//! share (where they pass through each other) is drawn by the wider style that draws its kind,
//! and a kind no patch draws is not drawn.

use std::sync::Arc;

use glam::{DVec3, Vec2, Vec3, Vec4};
use glint::geom::{shapes, NamedPatch, PatchLibrary};
use glint::highlight::Light;
use glint::render::{
    Aovs, Camera, LineKind, LineKinds, LineStyle, Outlines, PatchLook, Projection, Renderer, Scene,
    Settings, Tone,
};
use glint::toon::CelRamp;

const WIDTH: u32 = 320;
const HEIGHT: u32 = 160;
/// World units seen from the image's top to its bottom: 50 pixels per unit.
const VIEW_HEIGHT: f32 = 3.2;

/// Two unit spheres centred at `(±x, 0, 0)`.
fn two_spheres(x: f64) -> Arc<PatchLibrary> {
    let sphere = |name: &str, at: f64| NamedPatch {
        name: name.into(),
        trim: None,
        surface: shapes::sphere(DVec3::new(at, 0.0, 0.0), 1.0).unwrap(),
    };
    Arc::new(PatchLibrary {
        patches: vec![sphere("left", -x), sphere("right", x)],
        groups: Vec::new(),
    })
}

/// Where world point `(x, z)` of the plane y = 0 lands on the image, seen from −y.
fn on_image(x: f32, z: f32) -> Vec2 {
    let scale = HEIGHT as f32 / VIEW_HEIGHT;
    Vec2::new(
        0.5 * WIDTH as f32 + x * scale,
        0.5 * HEIGHT as f32 - z * scale,
    )
}

/// The outline AOV (straight alpha) of the spheres seen from −y, patch k's lines in
/// `styles[k]` (None: the outlines' own, 1.5 px black).
fn lines(library: &Arc<PatchLibrary>, styles: &[Option<LineStyle>]) -> Vec<Vec4> {
    let scene = Scene {
        library,
        looks: styles
            .iter()
            .map(|&lines| PatchLook {
                designed_light: None,
                tone: Tone::Cel(CelRamp::two_tone(
                    Vec3::new(0.2, 0.3, 0.5),
                    Vec3::new(0.5, 0.6, 0.9),
                    0.2,
                )),
                highlight: None,
                lines,
            })
            .collect(),
        camera: Camera {
            eye: Vec3::new(0.0, -10.0, 0.0),
            target: Vec3::ZERO,
            up: Vec3::Z,
            projection: Projection::Orthographic {
                height: VIEW_HEIGHT,
            },
            near: 0.1,
            far: 100.0,
        },
        light: Light::Directional {
            towards: Vec3::new(0.3, -0.5, 0.8).normalize(),
        },
        outlines: Some(Outlines {
            width: 1.5,
            colour: Vec3::ZERO,
            crease_degrees: 60.0,
            patch_borders: false,
        }),
        aovs: Aovs {
            outline: true,
            ..Aovs::default()
        },
        materials: Vec::new(),
    };
    let frame = Renderer::new(Arc::clone(library))
        .render(&scene, &Settings::preview(WIDTH, HEIGHT))
        .unwrap();
    frame.aovs.outline.unwrap()
}

/// The image's alpha bilinearly at `p` (pixel centres at half-integers), 0 outside.
fn alpha_at(image: &[Vec4], p: Vec2) -> f32 {
    let (w, h) = (WIDTH as usize, HEIGHT as usize);
    let q = p - 0.5;
    let (x0, y0) = (q.x.floor(), q.y.floor());
    let (fx, fy) = (q.x - x0, q.y - y0);
    let at = |x: f32, y: f32| {
        if x < 0.0 || y < 0.0 || x >= w as f32 || y >= h as f32 {
            0.0
        } else {
            image[y as usize * w + x as usize].w
        }
    };
    let top = at(x0, y0) * (1.0 - fx) + at(x0 + 1.0, y0) * fx;
    let bottom = at(x0, y0 + 1.0) * (1.0 - fx) + at(x0 + 1.0, y0 + 1.0) * fx;
    top * (1.0 - fy) + bottom * fy
}

/// The ink across the line at `centre`, along `across` (unit): its integral (the line's width)
/// from `reach` pixels before to `reach` after.
fn width_across(image: &[Vec4], centre: Vec2, across: Vec2, reach: f32) -> f32 {
    let step = 0.05;
    let mut s = -reach;
    let mut sum = 0.0;
    while s <= reach {
        sum += alpha_at(image, centre + across * s) * step;
        s += step;
    }
    sum
}

/// The colour of the most inked pixel within `reach` of `centre`.
fn colour_near(image: &[Vec4], centre: Vec2, reach: i32) -> Vec3 {
    let (cx, cy) = (centre.x as i32, centre.y as i32);
    let mut best = Vec4::ZERO;
    for y in cy - reach..=cy + reach {
        for x in cx - reach..=cx + reach {
            let p = image[y as usize * WIDTH as usize + x as usize];
            if p.w > best.w {
                best = p;
            }
        }
    }
    best.truncate()
}

#[test]
fn each_patch_s_lines_take_its_own_width_and_colour() {
    let library = two_spheres(1.4);
    let red = Vec3::new(1.0, 0.0, 0.0);
    let image = lines(&library, &[Some(LineStyle::new(4.0, red)), None]);
    let radius = HEIGHT as f32 / VIEW_HEIGHT;
    for (sphere, x, width, colour) in [(0, -1.4f32, 4.0f32, red), (1, 1.4, 1.5, Vec3::ZERO)] {
        let centre = on_image(x, 0.0);
        for k in 0..36 {
            let a = (k as f32 * 10.0 + 3.0).to_radians();
            let out = Vec2::new(a.cos(), a.sin());
            // Where the two outlines face each other they are 40 px apart: far enough.
            let at = centre + out * radius;
            let measured = width_across(&image, at, out, 3.0 * width);
            assert!(
                (measured - width).abs() <= 0.25,
                "sphere {sphere} at {}°: {measured} px wide, not {width}",
                k * 10 + 3
            );
            let seen = colour_near(&image, at, 1);
            assert!(
                seen.distance(colour) < 1e-3,
                "sphere {sphere} at {}°: colour {seen}",
                k * 10 + 3
            );
        }
    }
}

#[test]
fn the_line_two_patches_share_is_drawn_by_the_wider_style_that_draws_it() {
    // Overlapping spheres pass through each other along the circle x = 0, y² + z² = 0.64, whose
    // near half is seen as the segment x = 0, |z| ≤ 0.8, between the outer outlines.
    let library = two_spheres(0.6);
    let (red, blue) = (Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 0.0, 1.0));
    let wide = LineStyle::new(3.0, red);
    let narrow = LineStyle::new(1.5, blue);
    let no_intersections =
        LineKinds::of(&[LineKind::Silhouette, LineKind::Crease, LineKind::Border]);
    let cases = [
        ("both draw it", [wide, narrow], Some((3.0, red))),
        (
            "only the narrow one draws it",
            [
                LineStyle {
                    kinds: no_intersections,
                    ..wide
                },
                narrow,
            ],
            Some((1.5, blue)),
        ),
        (
            "neither draws it",
            [
                LineStyle {
                    kinds: no_intersections,
                    ..wide
                },
                LineStyle {
                    kinds: no_intersections,
                    ..narrow
                },
            ],
            None,
        ),
    ];
    for (name, styles, expected) in cases {
        let image = lines(&library, &styles.map(Some));
        for z in [-0.5f32, -0.25, 0.0, 0.25, 0.5] {
            let at = on_image(0.0, z);
            let measured = width_across(&image, at, Vec2::X, 8.0);
            match expected {
                Some((width, colour)) => {
                    assert!(
                        (measured - width).abs() <= 0.3,
                        "{name}, z = {z}: {measured} px wide, not {width}"
                    );
                    let seen = colour_near(&image, at, 1);
                    assert!(seen.distance(colour) < 1e-3, "{name}, z = {z}: {seen}");
                }
                None => assert_eq!(measured, 0.0, "{name}, z = {z}: ink where none is drawn"),
            }
        }
        // The outer outlines are drawn in every case, each in its sphere's style.
        let left = width_across(&image, on_image(-1.6, 0.0), Vec2::X, 8.0);
        let right = width_across(&image, on_image(1.6, 0.0), Vec2::X, 8.0);
        assert!(
            (left - 3.0).abs() <= 0.25 && (right - 1.5).abs() <= 0.25,
            "{name}: {left} {right}"
        );
    }
}

#[test]
fn a_patch_that_draws_no_silhouette_leaves_its_outline_bare() {
    let library = two_spheres(1.4);
    let borders_only = LineStyle {
        kinds: LineKinds::of(&[LineKind::Border]),
        ..LineStyle::new(2.0, Vec3::ZERO)
    };
    let image = lines(&library, &[Some(borders_only), None]);
    let radius = HEIGHT as f32 / VIEW_HEIGHT;
    for k in 0..12 {
        let out = Vec2::from_angle((k as f32 * 30.0).to_radians());
        let left = width_across(&image, on_image(-1.4, 0.0) + out * radius, out, 6.0);
        let right = width_across(&image, on_image(1.4, 0.0) + out * radius, out, 6.0);
        assert_eq!(left, 0.0, "the left sphere draws no silhouette");
        assert!((right - 1.5).abs() <= 0.25, "{right}");
    }
}

/// Seen square from −y, a sphere's silhouette is the meridian circle y = 0, and half of it runs
/// along the seam where the patch's domain wraps around: there `N·(P − E)` is rounding alone,
/// and its sign on the two sides of the seam depends on where the sphere is. The line must be
/// whole wherever it is.
#[test]
fn a_silhouette_along_a_seam_is_whole_wherever_the_rounding_falls() {
    for x in [-1.4f64, -1.1, -0.7, 0.0, 0.3, 0.9, 1.4] {
        let sphere = shapes::sphere(DVec3::new(x, 0.0, 0.0), 1.0).unwrap();
        let library = Arc::new(PatchLibrary {
            patches: vec![NamedPatch {
                name: "ball".into(),
                trim: None,
                surface: sphere,
            }],
            groups: Vec::new(),
        });
        let image = lines(&library, &[None]);
        let centre = on_image(x as f32, 0.0);
        let radius = HEIGHT as f32 / VIEW_HEIGHT;
        for k in 0..72 {
            let out = Vec2::from_angle((k as f32 * 5.0).to_radians());
            let width = width_across(&image, centre + out * radius, out, 5.0);
            assert!(
                (width - 1.5).abs() <= 0.25,
                "sphere at x = {x}, {}° round: {width} px wide",
                k * 5
            );
        }
    }
}

/// A shot's `lines` entries restyle the patches they pick — by part or by material — field by
/// field, later entries over earlier ones, over the outlines' own style; each field is a track.
#[test]
fn a_shot_s_line_entries_restyle_the_parts_they_pick_field_by_field() {
    let text = r#"Shot(
    resolution: (64, 36), frames: (1, 11), fps: 24, output: "out/l.####.png",
    instances: [
        (name: "pot", file: "../patches/teapot.bpt", material: "porcelain"),
        (name: "ball", file: "../patches/sphere.ron", material: "clay"),
    ],
    materials: {
        "porcelain": Cel(base: (0.1, 0.1, 0.3), bands: []),
        "clay": Cel(base: (0.3, 0.1, 0.1), bands: []),
    },
    camera: (eye: (0.0, -9.0, 4.0), target: (0.0, 0.0, 1.0), projection: Perspective(fov_y_degrees: 35.0)),
    light: Directional(towards: (0.3, -1.0, 0.4)),
    lines: [
        (patches: "pot/spout", width: [(1, 1.0), (11, 5.0)], colour: (1.0, 0.0, 0.0)),
        (material: "clay", kinds: [Silhouette], taper: 6.0),
        (patches: ["pot/spout", "pot/lid"], colour: (0.0, 1.0, 0.0)),
    ],
    render: (preset: Preview, outlines: (width: [(1, 2.0), (11, 3.0)], colour: (0.0, 0.0, 0.2))),
)"#;
    let path = crate::common::root().join("shots/line_styles.ron");
    let shot = glint::shot::load_shot_text(&path, text.to_string()).unwrap();
    let names: Vec<&str> = shot
        .library
        .patches
        .iter()
        .map(|p| p.name.as_str())
        .collect();
    let index = |name: &str| {
        names
            .iter()
            .position(|&n| n == name)
            .unwrap_or_else(|| panic!("no {name} in {names:?}"))
    };
    let state = shot.at(6.0);
    let scene = state.scene(&shot).unwrap();
    let style = |name: &str| scene.looks[index(name)].lines.unwrap();
    // Halfway through both width tracks.
    let outlines = scene.outlines.unwrap();
    assert_eq!(outlines.width, 2.5);
    let plain = style("pot/0");
    assert_eq!(plain, LineStyle::new(2.5, Vec3::new(0.0, 0.0, 0.2)));
    // The spout: its own width, and the last entry's colour over the first's.
    assert_eq!(style("pot/16"), LineStyle::new(3.0, Vec3::Y));
    // The lid: the last entry's colour alone.
    assert_eq!(style("pot/24"), LineStyle::new(2.5, Vec3::Y));
    // The clay ball: silhouettes only, tapered, in the outlines' width and colour.
    let ball = style("ball/sphere");
    assert_eq!(
        ball,
        LineStyle {
            kinds: LineKinds::of(&[LineKind::Silhouette]),
            taper: 6.0,
            ..plain
        }
    );
}
