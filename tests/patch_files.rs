//! Every model shipped in `patches/` loads and evaluates, and the hand-made car panels keep the
//! properties they are there to exercise.

use std::sync::Arc;

use std::path::PathBuf;

use glint::formats::load_patches;
use glint::geom::{GridEvaluator, PatchLibrary};

/// Every model in `patches/` (not the parts files beside them, which name their groups).
fn patch_files() -> Vec<PathBuf> {
    let dir = crate::common::root().join("patches");
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| !p.to_string_lossy().ends_with(".parts.ron"))
        .collect();
    files.sort();
    files
}

fn load(name: &str) -> PatchLibrary {
    let path = crate::common::root().join("patches").join(name);
    load_patches(&path).unwrap()
}

#[test]
fn every_shipped_model_loads_with_finite_unit_normals() {
    let files = patch_files();
    assert!(files.len() >= 4, "{files:?}");
    for file in files {
        let lib = load_patches(&file).unwrap_or_else(|e| panic!("{e}"));
        assert!(!lib.patches.is_empty(), "{}", file.display());
        for patch in &lib.patches {
            let grid = GridEvaluator::uniform(&patch.surface, 17, 17);
            for i in 0..17 {
                for j in 0..17 {
                    let f = grid.frame(i, j);
                    assert!(
                        (f.normal.length() - 1.0).abs() < 1e-12,
                        "{} patch {}",
                        file.display(),
                        patch.name
                    );
                }
            }
        }
    }
}

#[test]
fn car_panels_are_rational_with_non_uniform_knots_and_c1_joints() {
    let car = load("car_panels.ron");
    let names: Vec<&str> = car.patches.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(
        names,
        ["hood", "windshield", "roof", "rear_window", "trunk"]
    );
    for patch in &car.patches {
        let s = &patch.surface;
        let spans: Vec<f64> = s
            .knots_u()
            .knots()
            .windows(2)
            .map(|w| w[1] - w[0])
            .filter(|d| *d > 0.0)
            .collect();
        assert!(
            spans.iter().any(|d| (d - spans[0]).abs() > 1e-9),
            "{spans:?}"
        );
        assert!((0..s.count_u()).any(|i| s.control_point(i, 0).1 != 1.0));
        // Outward: the normal at the middle of each panel points up.
        assert!(s.frame(0.5, 0.5).normal.z > 0.5, "{}", patch.name);
    }
    for pair in car.patches.windows(2) {
        let (front, back) = (&pair[0].surface, &pair[1].surface);
        for k in 0..=20 {
            let u = k as f64 / 20.0;
            let (a, b) = (front.derivs(u, 1.0, 1), back.derivs(u, 0.0, 1));
            let what = format!("{} / {} at u = {u}", pair[0].name, pair[1].name);
            assert!((a.point - b.point).length() < 1e-12, "position, {what}");
            assert!((a.su - b.su).length() < 1e-12, "Su, {what}");
            assert!((a.sv - b.sv).length() < 1e-12, "Sv, {what}");
        }
    }
}

/// The ```ron block of docs/patch-format.md.
fn documented_example() -> String {
    let path = crate::common::root().join("docs/patch-format.md");
    let doc = std::fs::read_to_string(path).unwrap();
    let start = doc.find("```ron\n").unwrap() + "```ron\n".len();
    let end = start + doc[start..].find("```").unwrap();
    doc[start..end].to_owned()
}

#[test]
fn documented_example_parses_into_every_kind_of_surface() {
    let lib = glint::formats::parse_patch_ron(&documented_example(), "patch-format.md").unwrap();
    let names: Vec<&str> = lib.patches.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["ball", "can", "ring", "floor", "tile", "panel"]);
    let ball = &lib.find("ball").unwrap().surface;
    let centre = glam::DVec3::new(0.0, 0.0, 2.0);
    assert!(((ball.point(0.3, 0.6) - centre).length() - 1.0).abs() < 1e-12);
    let tile = &lib.find("tile").unwrap().surface;
    assert_eq!((tile.knots_u().degree(), tile.knots_v().degree()), (1, 1));
    let panel = &lib.find("panel").unwrap().surface;
    assert_eq!(panel.control_point(1, 0).1, 0.7);
}

#[test]
fn documented_parts_examples_read_as_written() {
    let path = crate::common::root().join("docs/patch-format.md");
    let doc = std::fs::read_to_string(path).unwrap();
    let blocks: Vec<&str> = doc
        .split("```ron\n")
        .skip(1)
        .map(|b| &b[..b.find("```").unwrap()])
        .collect();
    assert_eq!(blocks.len(), 3);
    let lib = glint::formats::parse_patch_ron(blocks[1], "patch-format.md").unwrap();
    assert_eq!(lib.group("paint").unwrap().patches, [0, 1]);
    assert_eq!(lib.group("front").unwrap().patches, [0]);
    let dir = tempfile::tempdir().unwrap();
    let parts = dir.path().join("teapot.parts.ron");
    std::fs::write(&parts, blocks[2]).unwrap();
    let teapot = crate::common::teapot();
    let groups = glint::formats::parts::read_parts_file(&parts, &teapot.patches, &[]).unwrap();
    for group in &groups {
        assert_eq!(Some(group), teapot.group(&group.name), "as shipped");
    }
}

/// A camera framing a model: its control points' bounding sphere seen from the front-right,
/// above.
fn framing_camera(library: &PatchLibrary) -> glint::render::Camera {
    use glam::{DVec3, Vec3};
    let points: Vec<DVec3> = library.control_points().collect();
    let (lo, hi) = points
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
            (lo.min(*p), hi.max(*p))
        });
    let centre = ((lo + hi) * 0.5).as_vec3();
    let radius = ((hi - lo).length() * 0.5) as f32;
    glint::render::Camera {
        eye: centre + Vec3::new(1.0, -1.6, 0.9).normalize() * radius * 3.5,
        target: centre,
        up: Vec3::Z,
        projection: glint::render::Projection::Perspective {
            fov_y_degrees: 40.0,
        },
        near: 0.01 * radius,
        far: 10.0 * radius,
    }
}

#[test]
fn every_shipped_model_renders() {
    use glint::highlight::{Expr, Layer, Light};
    use glint::render::{Aovs, PatchLook, Renderer, Scene, Settings, Tone};
    use glint::toon::CelRamp;
    let highlight = Expr::Layer(Layer::new(vec![], 0.1, [1.0, 1.0, 1.0]))
        .prepare()
        .unwrap();
    for file in patch_files() {
        let library = Arc::new(load_patches(&file).unwrap());
        let camera = framing_camera(&library);
        let scene = Scene {
            library: &library,
            looks: library
                .patches
                .iter()
                .map(|_| PatchLook {
                    designed_light: None,
                    lines: None,
                    tone: Tone::Cel(CelRamp::two_tone(
                        glam::Vec3::splat(0.2),
                        glam::Vec3::splat(0.7),
                        0.0,
                    )),
                    highlight: Some(highlight.clone()),
                })
                .collect(),
            camera,
            // A light at the eye: the highlight sits where the model faces the camera, which
            // every model does somewhere.
            light: Light::Directional {
                towards: (camera.eye - camera.target).normalize(),
            },
            outlines: None,
            aovs: Aovs {
                matte: true,
                ..Aovs::default()
            },
            materials: Vec::new(),
        };
        let frame = Renderer::new(Arc::clone(&library))
            .render(&scene, &Settings::preview(96, 96))
            .unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        let covered = frame.colour.iter().filter(|c| c.w > 0.0).count();
        assert!(
            covered > 200,
            "{}: {covered} pixels covered",
            file.display()
        );
        assert!(
            frame.colour.iter().all(|c| c.is_finite()),
            "{}",
            file.display()
        );
        let lit = frame
            .aovs
            .matte
            .unwrap()
            .iter()
            .filter(|&&m| m > 0.5)
            .count();
        assert!(lit > 0, "{}: the highlight shows somewhere", file.display());
    }
}

/// The volume a model's frames enclose, `(1/3) Σ ∫∫ P·N |Su × Sv| du dv` over its patches (the
/// divergence theorem with the field P/3), by the midpoint rule on `m × m` cells: positive when
/// the normals face out of a closed model.
fn enclosed_volume(library: &PatchLibrary, m: usize) -> f64 {
    let mut volume = 0.0;
    for patch in &library.patches {
        let s = &patch.surface;
        let (u, v) = (s.domain().u, s.domain().v);
        let (hu, hv) = ((u.1 - u.0) / m as f64, (v.1 - v.0) / m as f64);
        for i in 0..m {
            for j in 0..m {
                let (a, b) = (u.0 + (i as f64 + 0.5) * hu, v.0 + (j as f64 + 0.5) * hv);
                let d = s.derivs(a, b, 1);
                let f = s.frame(a, b);
                volume += f.point.dot(f.normal) * d.su.cross(d.sv).length() * hu * hv / 3.0;
            }
        }
    }
    volume
}

#[test]
fn closed_models_face_outward() {
    use std::f64::consts::PI;
    // The unit sphere, and the torus of radii 1 and 0.35: 2π² R r².
    let sphere = enclosed_volume(&load("sphere.ron"), 64);
    assert!((sphere / (4.0 * PI / 3.0) - 1.0).abs() < 1e-3, "{sphere}");
    let torus = enclosed_volume(&load("torus.ron"), 64);
    assert!(
        (torus / (2.0 * PI * PI * 0.35 * 0.35) - 1.0).abs() < 1e-3,
        "{torus}"
    );
    // The teapot is closed but for where the spout and handle meet the body: each patch's
    // normal faces out, so the whole encloses a positive volume, most of it the body's.
    let teapot = crate::common::teapot();
    let volume = enclosed_volume(&teapot, 16);
    assert!(volume > 20.0, "{volume}");
    // Each part alone, closed by the others, adds a share of the same sign or nearly none.
    for (k, patch) in teapot.patches.iter().enumerate() {
        let one = PatchLibrary {
            patches: vec![patch.clone()],
            groups: Vec::new(),
        };
        let share = enclosed_volume(&one, 16);
        assert!(
            share > -0.05 * volume,
            "patch {k} ({}): {share} of {volume}",
            patch.name
        );
    }
}

/// Patch edges of a model as `(patch, edge, points)`, `edge` 0: v = 0, 1: u = 1, 2: v = 1,
/// 3: u = 0, with 9 points along each; collapsed edges left out.
type PatchEdge = (usize, usize, Vec<(f64, f64)>);

fn patch_edges(library: &PatchLibrary) -> Vec<PatchEdge> {
    let mut edges = Vec::new();
    for (p, patch) in library.patches.iter().enumerate() {
        let s = &patch.surface;
        let (u, v) = (s.domain().u, s.domain().v);
        for e in 0..4 {
            let params: Vec<(f64, f64)> = (0..=8)
                .map(|k| {
                    let t = k as f64 / 8.0;
                    let (a, b) = (u.0 + t * (u.1 - u.0), v.0 + t * (v.1 - v.0));
                    [(a, v.0), (u.1, b), (a, v.1), (u.0, b)][e]
                })
                .collect();
            let first = s.point(params[0].0, params[0].1);
            if params
                .iter()
                .all(|&(a, b)| (s.point(a, b) - first).length() < 1e-9)
            {
                continue;
            }
            edges.push((p, e, params));
        }
    }
    edges
}

/// The shared edges modelled as creases, by file name and patch pair: the speaker's dust cap
/// sits in its cone at an angle.
const CREASES: &[(&str, usize, usize)] = &[("speaker.usda", 6, 7)];

#[test]
fn normals_agree_across_every_shared_patch_edge() {
    for file in patch_files() {
        let library = load_patches(&file).unwrap();
        let edges = patch_edges(&library);
        let surface = |p: usize| &library.patches[p].surface;
        let mut shared = 0;
        for (a, (p, e, along)) in edges.iter().enumerate() {
            for (q, f, other) in &edges[a + 1..] {
                if (p, e) == (q, f) {
                    continue;
                }
                let ends = |r: usize, params: &[(f64, f64)]| -> Vec<glam::DVec3> {
                    params
                        .iter()
                        .map(|&(a, b)| surface(r).point(a, b))
                        .collect()
                };
                let (mine, mut theirs) = (ends(*p, along), ends(*q, other));
                let mut other = other.clone();
                let same = |x: &[glam::DVec3], y: &[glam::DVec3]| {
                    x.iter().zip(y).all(|(m, t)| (*m - *t).length() < 1e-9)
                };
                if !same(&mine, &theirs) {
                    theirs.reverse();
                    other.reverse();
                    if !same(&mine, &theirs) {
                        continue;
                    }
                }
                shared += 1;
                let crease = CREASES
                    .iter()
                    .any(|&(name, a, b)| file.ends_with(name) && (a, b) == (*p, *q));
                if crease {
                    continue;
                }
                for (&(u0, v0), &(u1, v1)) in along.iter().zip(&other) {
                    let (n0, n1) = (
                        surface(*p).frame(u0, v0).normal,
                        surface(*q).frame(u1, v1).normal,
                    );
                    assert!(
                        n0.dot(n1) > 0.99,
                        "{}: patch {p} edge {e} at ({u0}, {v0}) vs patch {q} edge {f}: {n0} vs {n1}",
                        file.display()
                    );
                }
            }
        }
        println!("{}: {shared} shared edges", file.display());
        // The car doors are separate panels with shut lines between them: no edge is shared.
        let separate = file.ends_with("car_doors.usda");
        assert!(
            shared > 0 || library.patches.len() == 1 || separate,
            "{}",
            file.display()
        );
    }
}
