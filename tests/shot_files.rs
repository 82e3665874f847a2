//! Every shot in `shots/` loads, and renders at a small size.

use glint::render::Renderer;
use glint::scene::load_shot;

#[test]
fn every_shot_loads_and_renders_small() {
    let mut count = 0;
    for entry in std::fs::read_dir("shots").unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "ron") {
            continue;
        }
        count += 1;
        let shot = load_shot(&path).unwrap_or_else(|e| panic!("{e}"));
        let mut settings = shot.settings;
        settings.width = 64;
        settings.height = 48;
        let mut renderer = Renderer::new(&shot.library);
        for frame in [
            shot.frames.0,
            (shot.frames.0 + shot.frames.1) / 2,
            shot.frames.1,
        ] {
            let scene = shot.at(frame as f64).scene(&shot).unwrap();
            let image = renderer.render(&scene, &settings).unwrap();
            let covered = image.colour.iter().filter(|c| c.w > 0.0).count();
            assert!(
                covered > 64 * 48 / 50,
                "{}: frame {frame} shows almost nothing",
                path.display()
            );
            assert!(image.colour.iter().all(|c| c.is_finite()));
        }
    }
    assert!(count >= 4, "only {count} shots");
}
