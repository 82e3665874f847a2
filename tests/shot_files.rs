//! Every shot in `shots/` loads, and renders at a small size.

use std::sync::Arc;

use glint::render::Renderer;
use glint::shot::load_shot;

/// What a shot is there to show, from its header comment: whether its camera moves (so its
/// silhouettes change from first to last frame), and what else changes over the shot.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Shows {
    /// The highlight changes while the camera and the light stay.
    AnimatedHighlight,
    /// The light moves: the tone changes, the silhouettes stay.
    MovingLight,
    /// The camera moves: the silhouettes change.
    MovingCamera,
    /// The shading changes (a keyed tone, shape detail or line style), the silhouettes stay.
    AnimatedShading,
    /// A model moves, turns or deforms while the camera stays: the silhouettes change.
    MovingModel,
}

fn purpose(name: &str) -> Shows {
    match name {
        "sphere_ops" | "crescent" | "drawn_shapes" => Shows::AnimatedHighlight,
        "teapot_light_orbit" | "shade_design" => Shows::MovingLight,
        "teapot_turntable"
        | "teapot_rising_camera"
        | "xtoon_abstraction"
        | "xtoon_aerial_perspective"
        | "xtoon_metal"
        | "xtoon_receding_shadows"
        | "speaker"
        | "car_doors" => Shows::MovingCamera,
        "xtoon_backlight" | "xtoon_plastic" | "xtoon_shape_teapot" | "xtoon_shape_torus"
        | "line_styles" => Shows::AnimatedShading,
        "teapot_lid_opens" | "car_drive" | "usd_flag" | "line_kinds" => Shows::MovingModel,
        _ => panic!("shots/{name}.ron: say here what it shows"),
    }
}

#[test]
fn every_shot_loads_and_renders_small_and_shows_what_it_is_for() {
    let mut count = 0;
    for entry in std::fs::read_dir(crate::common::repo_file("shots")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "ron") {
            continue;
        }
        count += 1;
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        let shows = purpose(&name);
        let shot = load_shot(&path).unwrap_or_else(|e| panic!("{e}"));
        let mut settings = shot.settings;
        settings.width = 64;
        settings.height = 48;
        let mut renderer = Renderer::new(Arc::clone(&shot.library));
        let mut frames = Vec::new();
        for frame in [
            shot.frames.0,
            (shot.frames.0 + shot.frames.1) / 2,
            shot.frames.1,
        ] {
            let state = shot.at(frame as f64);
            let mut scene = state.scene(&shot).unwrap();
            scene.aovs.matte = true;
            scene.aovs.patch_id = true;
            let image = renderer.render(&scene, &settings).unwrap();
            let covered = image.colour.iter().filter(|c| c.w > 0.0).count();
            assert!(
                covered > 64 * 48 / 50,
                "{}: frame {frame} shows almost nothing",
                path.display()
            );
            assert!(image.colour.iter().all(|c| c.is_finite()));
            // Only what the shot calls for runs: X-Toon detail only in the X-Toon shots.
            let xtoon = name.starts_with("xtoon_");
            assert_eq!(image.stats.xtoon_pixels > 0, xtoon, "{}", path.display());
            frames.push(image);
        }
        let what = format!("{}: {shows:?}", path.display());
        let ids = |k: usize| frames[k].aovs.patch_id.clone().unwrap();
        let matte = |k: usize| frames[k].aovs.matte.clone().unwrap();
        let colour = |k: usize| frames[k].colour.clone();
        let silhouettes_stay = ids(0) == ids(1) && ids(1) == ids(2);
        let moving_silhouettes = matches!(shows, Shows::MovingCamera | Shows::MovingModel);
        assert_eq!(silhouettes_stay, !moving_silhouettes, "{what}");
        // Only the shots there to show a moving model move one.
        assert_eq!(shot.moves(), shows == Shows::MovingModel, "{what}");
        match shows {
            Shows::AnimatedHighlight => {
                assert!(matte(0) != matte(1) || matte(1) != matte(2), "{what}");
                assert!((0..3).any(|k| matte(k).iter().any(|&m| m > 0.5)), "{what}");
            }
            Shows::MovingLight | Shows::AnimatedShading => {
                assert!(colour(0) != colour(1) && colour(1) != colour(2), "{what}");
            }
            Shows::MovingCamera | Shows::MovingModel => {}
        }
    }
    assert!(count >= 4, "only {count} shots");
}

/// The `ron` code blocks of a document, in order.
fn ron_blocks(doc: &str) -> Vec<&str> {
    doc.split("```ron\n")
        .skip(1)
        .map(|block| &block[..block.find("```").unwrap()])
        .collect()
}

#[test]
fn the_documented_example_and_look_library_load_and_render() {
    let doc = std::fs::read_to_string(crate::common::repo_file("docs/shot-format.md")).unwrap();
    let blocks = ron_blocks(&doc);
    let example = blocks[0];
    let looks = blocks.iter().find(|b| b.starts_with("Looks(")).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let shots = dir.path().join("shots");
    std::fs::create_dir_all(shots.join("looks")).unwrap();
    std::fs::write(shots.join("looks/studio.ron"), looks).unwrap();
    std::fs::write(shots.join("looks/more_looks.ron"), "Looks()").unwrap();
    let patches = concat!(env!("CARGO_MANIFEST_DIR"), "/../patches/");
    let textures = concat!(env!("CARGO_MANIFEST_DIR"), "/../textures/");
    std::fs::write(
        shots.join("example.ron"),
        example
            .replace("../patches/", patches)
            .replace("../textures/", textures),
    )
    .unwrap();
    let shot = load_shot(&shots.join("example.ron")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(shot.library.patches.len(), 34);
    assert_eq!(
        shot.frame_path(7),
        shots.join("out/example/example.0007.png")
    );
    let mut settings = shot.settings_with(None, Some((64, 36)));
    settings.antialias = glint::render::Antialias::None;
    let state = shot.at(24.5);
    let scene = state.scene(&shot).unwrap();
    let image = Renderer::new(Arc::clone(&shot.library))
        .render(&scene, &settings)
        .unwrap();
    assert!(image.aovs.matte.unwrap().iter().any(|&m| m > 0.5));
}

/// The `ron` block of `doc` that follows the heading `heading`.
fn block_after<'a>(doc: &'a str, heading: &str) -> &'a str {
    let section = &doc[doc.find(heading).unwrap_or_else(|| panic!("no {heading}"))..];
    ron_blocks(section)[0]
}

#[test]
fn the_documented_moving_and_animated_instances_load_as_written() {
    let doc = std::fs::read_to_string(crate::common::repo_file("docs/shot-format.md")).unwrap();
    let patches = concat!(env!("CARGO_MANIFEST_DIR"), "/../patches/");
    let dir = tempfile::tempdir().unwrap();
    let shot = |instance: &str| {
        format!(
            r#"Shot(resolution: (32, 18), frames: (1, 48), fps: 24, output: "o.####.png",
    instances: [{}],
    materials: {{"porcelain": Cel(base: (0.5, 0.5, 0.5)), "clay": Cel(base: (0.5, 0.2, 0.1))}},
    camera: (eye: (0, -9, 4), target: (0, 0, 1), projection: Perspective(fov_y_degrees: 30)),
    light: Directional(towards: (0, -1, 1)))"#,
            instance.replace("../patches/", patches)
        )
    };
    let moving = block_after(&doc, "### Moving instances and parts");
    let loaded = glint::shot::load_shot_text(&dir.path().join("a.ron"), shot(moving))
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(loaded.moves());
    // The teapot drives and turns as a rigid whole, which keeps the distance between any two of
    // its points; the cover (knob and lid) turns about its hinge between frames 12 and 36 only,
    // which changes the distance from a lid point to a body point then, and not before.
    let gap = |frame: f64| -> f64 {
        let library = loaded.library_at(frame);
        let point = |patch: usize| library.patches[patch].surface.point(0.5, 0.5);
        point(24).distance(point(4))
    };
    assert!(
        (gap(1.0) - gap(12.0)).abs() < 1e-9,
        "{} {}",
        gap(1.0),
        gap(12.0)
    );
    assert!(
        (gap(36.0) - gap(12.0)).abs() > 0.5,
        "{} {}",
        gap(36.0),
        gap(12.0)
    );
    assert!(loaded.library_at(24.0).patches[4] != loaded.library_at(1.0).patches[4]);
    let usd = block_after(&doc, "### Animated USD layers");
    let animated = glint::shot::load_shot_text(&dir.path().join("b.ron"), shot(usd))
        .unwrap_or_else(|e| panic!("{e}"));
    assert!(animated.moves());
}
