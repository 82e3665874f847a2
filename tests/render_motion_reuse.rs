//! A frame where one instance moved rigidly evaluates that instance's grids, intersection
//! lines and silhouettes again and keeps the others': two teapots, one driving and turning, the other still.
//! Whatever is kept, the frames are a fresh renderer's bytes.

use std::sync::Arc;

use glint::render::tessellate::Density;
use glint::render::{RenderedFrame, Renderer, Settings};
use glint::shot::{load_shot_text, Shot};

use crate::common::repo_file;

/// Patches of the Utah teapot.
const TEAPOT_PATCHES: usize = 32;

/// Two teapots side by side, seen from the front: `still` stays, `driving` moves along y and
/// turns about z from frame 1 to 4. A small highlight on every patch and the shot's outlines,
/// intersections included (each teapot's spout and handle pass through its body).
const TWO_TEAPOTS: &str = r#"Shot(
    resolution: (160, 90),
    frames: (1, 4),
    fps: 24,
    output: "two_teapots.####.png",
    includes: ["looks/studio.ron"],
    instances: [
        (name: "still", file: "../patches/teapot.bpt", material: "porcelain",
         transform: (translate: (-2.2, 0, 0))),
        (name: "driving", file: "../patches/teapot.bpt", material: "clay",
         transform: (translate: [(1, (2.2, 0, 0)), (4, (2.2, 0.6, 0))],
                     degrees: [(1, 0), (4, 30)])),
    ],
    camera: (eye: (0, -14, 6), target: (0, 0, 1.2), projection: Perspective(fov_y_degrees: 32.0)),
    light: Directional(towards: (-0.35, -0.55, 0.75)),
    highlights: [
        (patches: "*", expr: Layer((stack: [], epsilon: 0.02, colour: (1, 1, 1)))),
    ],
    render: (
        preset: Final,
        outlines: (width: 1.5, colour: (0.05, 0.04, 0.1), crease_degrees: 70.0),
    ),
)"#;

fn two_teapots() -> Shot {
    load_shot_text(&repo_file("shots/two_teapots.ron"), TWO_TEAPOTS.to_string()).unwrap()
}

/// The shot's settings at its small size, with `density`.
fn settings(shot: &Shot, density: Density) -> Settings {
    Settings {
        density,
        ..shot.settings_with(None, None)
    }
}

/// Frame `frame` of `shot` rendered by `renderer`.
fn render(renderer: &mut Renderer, shot: &Shot, frame: i64, settings: &Settings) -> RenderedFrame {
    let state = shot.at(frame as f64);
    let scene = state.scene(shot).unwrap();
    renderer.render(&scene, settings).unwrap()
}

/// The colour and every AOV of two frames, bit for bit.
fn assert_same_output(kept: &RenderedFrame, fresh: &RenderedFrame, what: &str) {
    let bits = |f: &RenderedFrame| {
        f.colour
            .iter()
            .flat_map(|c| c.to_array().map(f32::to_bits))
            .collect::<Vec<_>>()
    };
    assert!(bits(kept) == bits(fresh), "{what}: colours differ");
    assert!(kept.aovs == fresh.aovs, "{what}: AOVs differ");
}

#[test]
fn only_the_moving_teapot_s_grids_and_intersections_are_made_again() {
    let shot = two_teapots();
    assert_eq!(shot.library.patches.len(), 2 * TEAPOT_PATCHES);
    // Fixed segment counts: the still teapot's grids are cut alike in every frame.
    let settings = settings(&shot, Density::PerSpan { u: 4, v: 4 });
    let mut renderer = Renderer::new(Arc::clone(&shot.library));
    let first = render(&mut renderer, &shot, 1, &settings);
    assert_eq!(first.stats.grids_evaluated, 2 * TEAPOT_PATCHES);
    assert_eq!(first.stats.intersection_pairs_kept, 0);
    assert!(first.stats.intersection_pairs_tested > 0);
    for frame in 2..=4 {
        let kept = render(&mut renderer, &shot, frame, &settings);
        let s = &kept.stats;
        assert!(s.tessellation_rebuilt, "frame {frame}");
        assert_eq!(
            (s.grids_evaluated, s.grids_kept),
            (TEAPOT_PATCHES, TEAPOT_PATCHES),
            "frame {frame}"
        );
        // Every pair of the still teapot's patches: 32 · 31 / 2.
        assert_eq!(
            s.intersection_pairs_kept,
            TEAPOT_PATCHES * (TEAPOT_PATCHES - 1) / 2,
            "frame {frame}"
        );
        // The driving teapot's spout and handle still pass through its body.
        assert!(s.intersection_pairs_tested > 0, "frame {frame}");
        // The still teapot's silhouettes are kept under the camera that holds.
        assert_eq!(s.silhouettes_kept, TEAPOT_PATCHES, "frame {frame}");
        let fresh = render(
            &mut Renderer::new(Arc::clone(&shot.library)),
            &shot,
            frame,
            &settings,
        );
        assert_eq!(fresh.stats.intersection_pairs_kept, 0);
        assert_same_output(&kept, &fresh, &format!("frame {frame}"));
    }
}

#[test]
fn frames_with_an_adaptive_density_are_a_fresh_renderer_s_bytes() {
    // Under the screen tolerance the moving teapot's counts change and so may the still
    // one's: whatever is kept, the frame is the fresh renderer's.
    let shot = two_teapots();
    let settings = settings(&shot, Density::ScreenTolerance { pixels: 0.5 });
    let mut renderer = Renderer::new(Arc::clone(&shot.library));
    for frame in [1, 2, 4, 3] {
        let kept = render(&mut renderer, &shot, frame, &settings);
        let s = &kept.stats;
        assert_eq!(s.grids_evaluated + s.grids_kept, 2 * TEAPOT_PATCHES);
        let fresh = render(
            &mut Renderer::new(Arc::clone(&shot.library)),
            &shot,
            frame,
            &settings,
        );
        assert_same_output(&kept, &fresh, &format!("frame {frame}"));
    }
}

/// Two teapots, seen from the front: `still` stays; `driving` turns all along and drives from
/// beside it to right in front of it by frame 5, then waits while the camera steps aside
/// between frames 5 and 6 and holds.
const PASSING: &str = r#"Shot(
    resolution: (160, 90),
    frames: (1, 7),
    fps: 24,
    output: "passing.####.png",
    includes: ["looks/studio.ron"],
    instances: [
        (name: "still", file: "../patches/teapot.bpt", material: "porcelain",
         transform: (translate: (-2.2, 0, 0))),
        (name: "driving", file: "../patches/teapot.bpt", material: "clay",
         transform: (translate: [(1, (2.2, 0, 0)), (5, (-2.2, -3.5, 0)), (7, (-2.2, -3.5, 0))],
                     degrees: [(1, 0), (7, 60)])),
    ],
    camera: (
        eye: [(1, (0, -14, 6)), (5, (0, -14, 6)), (6, (1, -13, 6)), (7, (1, -13, 6))],
        target: (0, 0, 1.2),
        projection: Perspective(fov_y_degrees: 32.0),
    ),
    light: Directional(towards: (-0.35, -0.55, 0.75)),
    highlights: [
        (patches: "*", expr: Layer((stack: [], epsilon: 0.02, colour: (1, 1, 1)))),
    ],
    render: (
        preset: Final,
        outlines: (width: 1.5, colour: (0.05, 0.04, 0.1), crease_degrees: 70.0),
        aovs: [Matte, PatchId, Depth, Normal, Uv],
    ),
)"#;

#[test]
fn a_frame_where_one_teapot_moved_rasterizes_it_alone_and_gives_a_fresh_renderer_s_bytes() {
    let shot = load_shot_text(&repo_file("shots/passing.ron"), PASSING.to_string()).unwrap();
    // Fixed segment counts: both teapots are cut alike, into the same number of triangles.
    let settings = settings(&shot, Density::PerSpan { u: 4, v: 4 });
    let mut renderer = Renderer::new(Arc::clone(&shot.library));
    for frame in 1..=7 {
        let kept = render(&mut renderer, &shot, frame, &settings);
        let s = &kept.stats;
        let one_teapot = s.triangles / 2;
        // The first frame draws all; the second, where the driving teapot first moved, draws
        // the still one's visibility to keep and the driving one's over it; so does frame 6,
        // where the camera moved; the others draw the driving teapot alone.
        let drawn = match frame {
            1 | 2 | 6 => s.triangles,
            _ => one_teapot,
        };
        assert_eq!(s.triangles_rasterized, drawn, "frame {frame}");
        // Where both this frame and the one before drew over the same kept visibility, the
        // still teapot's texels whose visibility stayed are kept; at most its samples.
        let samples = u64::from(settings.samples_per_side().pow(2));
        let still_texels = kept.aovs.patch_id.as_ref().map(|ids| {
            ids.iter().filter(|&&id| id < TEAPOT_PATCHES as u32).count() as u64 * samples
        });
        match frame {
            1 | 2 | 6 => assert_eq!(s.texels_kept, 0, "frame {frame}"),
            _ => assert!(s.texels_kept > 0, "frame {frame}"),
        }
        if let Some(still) = still_texels {
            assert!(s.texels_kept <= still, "frame {frame}");
        }
        // The still teapot's silhouettes are kept from the frame before, except where the
        // camera moved or nothing was found before.
        let silhouettes_kept = match frame {
            1 | 6 => 0,
            _ => TEAPOT_PATCHES,
        };
        assert_eq!(s.silhouettes_kept, silhouettes_kept, "frame {frame}");
        let fresh = render(
            &mut Renderer::new(Arc::clone(&shot.library)),
            &shot,
            frame,
            &settings,
        );
        assert_eq!(
            fresh.stats.triangles_rasterized, s.triangles,
            "frame {frame}"
        );
        assert_same_output(&kept, &fresh, &format!("frame {frame}"));
    }
}
