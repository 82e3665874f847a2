//! Pictures for people: `glint patches --map` (the patch map of a model or a shot) and
//! `glint sheet` (tiles of frames or variants in one PNG), through the API and the binary.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::process::Output;

use image::{Rgba, RgbaImage};

use glint::formats::image_encoding::patch_colour;
use glint::picture::patch_map::{MAP_BACKGROUND, SEAM};
use glint::picture::sheet::SHEET_BACKGROUND;
use glint::picture::{
    part_legend, patch_labels, render_patch_map, try_three_quarter_camera, PatchMap, PixelRect,
    SheetLayout,
};
use glint::render::Settings;
use glint::shot::{load_shot, Preset};

use crate::common::{glint_with, repo_file, stderr, teapot};

fn succeed(args: &[&str]) -> Output {
    let out = glint_with(args);
    assert_eq!(out.status.code(), Some(0), "{args:?}: {}", stderr(&out));
    out
}

fn png(path: &Path) -> RgbaImage {
    image::open(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .to_rgba8()
}

fn text(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// The boxes drawn over the map: every label and the legend.
fn boxes(map: &PatchMap) -> Vec<PixelRect> {
    map.labels
        .iter()
        .map(|l| l.rect)
        .chain(map.legend)
        .collect()
}

fn in_any(boxes: &[PixelRect], x: u32, y: u32) -> bool {
    boxes.iter().any(|b| b.contains(i64::from(x), i64::from(y)))
}

#[test]
fn the_teapot_map_gives_each_visible_patch_its_own_colour_and_a_label_on_it() {
    let teapot = teapot();
    let (width, height) = (400, 300);
    let camera = try_three_quarter_camera(&teapot, 4.0 / 3.0).unwrap();
    let labels = patch_labels(&teapot, None);
    let legend = part_legend(&teapot, None);
    let map = render_patch_map(
        &teapot,
        camera,
        &Settings::preview(width, height),
        &labels,
        &legend,
    )
    .unwrap();
    let ids = &map.patch_ids;
    let visible: BTreeSet<u32> = ids.iter().copied().filter(|&i| i != u32::MAX).collect();
    // The three-quarter view shows most of the model.
    assert!(visible.len() >= 20, "{visible:?}");
    let palette: BTreeSet<[u8; 3]> = visible.iter().map(|&i| patch_colour(i)).collect();
    assert_eq!(
        palette.len(),
        visible.len(),
        "two visible patches share a colour"
    );

    // Each patch's pixels (off the seams and the boxes) are its own colour, shaded: their mean
    // is nearer a multiple of its palette colour than of any other visible patch's.
    let covered = boxes(&map);
    let mut sums: BTreeMap<u32, ([f64; 3], f64)> = BTreeMap::new();
    for (x, y, p) in map.image.enumerate_pixels() {
        let id = ids[(y * width + x) as usize];
        if in_any(&covered, x, y) {
            continue;
        }
        if id == u32::MAX {
            assert_eq!(*p, MAP_BACKGROUND, "({x}, {y})");
            continue;
        }
        if *p == SEAM {
            continue;
        }
        let entry = sums.entry(id).or_default();
        for c in 0..3 {
            entry.0[c] += f64::from(p[c]);
        }
        entry.1 += 1.0;
    }
    let off_line = |mean: [f64; 3], colour: [u8; 3]| {
        let c = colour.map(f64::from);
        let k = (mean[0] * c[0] + mean[1] * c[1] + mean[2] * c[2])
            / (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
        (0..3).map(|i| (mean[i] - k * c[i]).powi(2)).sum::<f64>()
    };
    for (&id, &(sum, n)) in &sums {
        let mean = sum.map(|s| s / n);
        let nearest = visible
            .iter()
            .min_by(|&&a, &&b| {
                off_line(mean, patch_colour(a)).total_cmp(&off_line(mean, patch_colour(b)))
            })
            .unwrap();
        assert_eq!(*nearest, id, "patch {id} looks like patch {nearest}");
    }

    // One label per visible patch, naming it, standing on one of its pixels, inside the image
    // and drawn in ink; none over the legend.
    let labelled: BTreeSet<u32> = map.labels.iter().map(|l| l.patch as u32).collect();
    assert_eq!(labelled, visible);
    let legend = map.legend.expect("the teapot has parts");
    for label in &map.labels {
        assert_eq!(label.text, teapot.patches[label.patch].name);
        let (x, y) = label.anchor;
        assert_eq!(ids[(y * width + x) as usize], label.patch as u32);
        let r = label.rect;
        assert!(r.contains(i64::from(x), i64::from(y)));
        assert!(r.x >= 0 && r.y >= 0);
        assert!(r.x + i64::from(r.width) <= i64::from(width));
        assert!(r.y + i64::from(r.height) <= i64::from(height));
        assert!(!r.overlaps(&legend), "{label:?}");
        let ink = (r.y..r.y + i64::from(r.height))
            .flat_map(|y| (r.x..r.x + i64::from(r.width)).map(move |x| (x, y)))
            .filter(|&(x, y)| map.image.get_pixel(x as u32, y as u32)[0] < 60)
            .count();
        assert!(ink >= 8, "{label:?} has {ink} ink pixels");
    }

    // The binary draws the same map.
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("maps/teapot.png");
    let listing = succeed(&[
        "patches",
        "patches/teapot.bpt",
        "--map",
        text(&out),
        "--size",
        "400x300",
    ]);
    assert!(String::from_utf8_lossy(&listing.stdout).contains("32 patches, 7 parts"));
    assert_eq!(png(&out), map.image);
}

#[test]
fn a_shot_map_is_seen_through_the_shot_camera_at_the_frame() {
    let dir = tempfile::tempdir().unwrap();
    let shot_path = repo_file("shots/teapot_turntable.ron");
    let map_at = |frame: &str| {
        let out = dir.path().join(format!("map.{frame}.png"));
        succeed(&[
            "patches",
            text(&shot_path),
            "--map",
            text(&out),
            "--frame",
            frame,
            "--size",
            "320x180",
        ]);
        png(&out)
    };
    let map = map_at("48");
    succeed(&[
        "render",
        text(&shot_path),
        "--frames",
        "48",
        "--size",
        "320x180",
        "--preset",
        "preview",
        "--aov",
        "patch_id",
        "--out",
        text(&dir.path().join("f.##.png")),
    ]);
    let ids = image::open(dir.path().join("f.48.patch_id.png"))
        .unwrap()
        .to_luma16();

    // The map as the API draws it with the shot's camera at frame 48: the binary's is the same,
    // and its patch ids are the rendered frame's.
    let shot = load_shot(&shot_path).unwrap();
    let prefix = Some("teapot/");
    let drawn = render_patch_map(
        &shot.library,
        shot.at(48.0).camera,
        &shot.settings_with(Some(Preset::Preview), Some((320, 180))),
        &patch_labels(&shot.library, prefix),
        &part_legend(&shot.library, prefix),
    )
    .unwrap();
    assert_eq!(drawn.image, map);
    let rendered: Vec<u32> = ids
        .pixels()
        .map(|p| {
            if p[0] == 65_535 {
                u32::MAX
            } else {
                u32::from(p[0])
            }
        })
        .collect();
    let differing = drawn
        .patch_ids
        .iter()
        .zip(&rendered)
        .filter(|(a, b)| a != b)
        .count();
    assert_eq!(differing, 0, "of {} pixels", rendered.len());
    // Labels drop the one instance's name.
    assert!(drawn.labels.iter().all(|l| !l.text.contains('/')));

    // Outside the labels and the legend, the map's silhouette is the rendered frame's.
    let covered = boxes(&drawn);
    let mut compared = 0;
    for (x, y, p) in map.enumerate_pixels() {
        if in_any(&covered, x, y) {
            continue;
        }
        let background = ids.get_pixel(x, y)[0] == 65_535;
        assert_eq!(*p == MAP_BACKGROUND, background, "({x}, {y})");
        compared += usize::from(!background);
    }
    assert!(compared > 1000, "{compared}");

    // Another frame, another view; no --frame is the first frame.
    assert_ne!(map_at("1"), map);
    let first = dir.path().join("map.first.png");
    succeed(&[
        "patches",
        text(&shot_path),
        "--map",
        text(&first),
        "--size",
        "320x180",
    ]);
    assert_eq!(png(&first), map_at("1"));
}

#[test]
fn map_options_that_cannot_be_met_exit_2_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("maps/m.png");
    for (args, says) in [
        (
            vec![
                "patches",
                "patches/teapot.bpt",
                "--map",
                text(&out),
                "--frame",
                "3",
            ],
            "patch file",
        ),
        (
            vec![
                "patches",
                "shots/crescent.ron",
                "--map",
                text(&out),
                "--frame",
                "500",
            ],
            "outside the shot's frame range 1-72",
        ),
        (
            vec!["patches", "patches/teapot.bpt", "--frame", "3"],
            "--map",
        ),
        (
            vec![
                "patches",
                "patches/teapot.bpt",
                "--map",
                text(&out),
                "--size",
                "0x10",
            ],
            "size",
        ),
    ] {
        let result = glint_with(&args);
        assert_eq!(result.status.code(), Some(2), "{args:?}");
        assert!(
            stderr(&result).contains(says),
            "{args:?}: {}",
            stderr(&result)
        );
        assert!(result.stdout.is_empty(), "{args:?}");
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            0,
            "{args:?}"
        );
    }
}

#[test]
fn a_sheet_over_time_holds_each_frame_as_rendered_alone_with_its_caption() {
    let dir = tempfile::tempdir().unwrap();
    let sheet_path = dir.path().join("sheets/ops.png");
    let shot = "shots/sphere_ops.ron";
    let frames = [1, 30, 61];
    succeed(&[
        "sheet",
        shot,
        "--frames",
        "1,30,61",
        "--tile",
        "96x64",
        "--out",
        text(&sheet_path),
    ]);
    succeed(&[
        "render",
        shot,
        "--frames",
        "1,30,61",
        "--size",
        "96x64",
        "--preset",
        "preview",
        "--aov",
        "none",
        "--out",
        text(&dir.path().join("f.####.png")),
    ]);
    let sheet = png(&sheet_path);
    // Three tiles: a 2 × 2 grid, 4 pixels between cells and around them, a 12-pixel caption
    // strip (8-pixel glyphs and 2 pixels of padding) under each tile.
    assert_eq!(
        sheet.dimensions(),
        (4 + 2 * (96 + 4), 4 + 2 * (64 + 12 + 4))
    );
    let captions: Vec<String> = frames.iter().map(|f| format!("frame {f}")).collect();
    let layout = SheetLayout::new(&captions, (96, 64), None).unwrap();
    assert_eq!((layout.columns, layout.rows), (2, 2));
    let mut strips = Vec::new();
    for (i, frame) in frames.iter().enumerate() {
        let alone = png(&dir.path().join(format!("f.{frame:04}.png")));
        let (x0, y0) = layout.tile_origin(i);
        assert_eq!(
            (x0, y0),
            (4 + (i as u32 % 2) * 100, 4 + (i as u32 / 2) * 80)
        );
        for (x, y, p) in alone.enumerate_pixels() {
            assert_eq!(
                sheet.get_pixel(x0 + x, y0 + y),
                p,
                "frame {frame} at ({x}, {y})"
            );
        }
        // The caption: ink under the tile, and a different picture for each frame's number.
        let strip: Vec<Rgba<u8>> = (0..12)
            .flat_map(|y| (0..96).map(move |x| (x, y)))
            .map(|(x, y)| *sheet.get_pixel(x0 + x, y0 + 64 + y))
            .collect();
        assert!(strip.iter().filter(|p| p[0] < 60 && p[3] == 255).count() > 40);
        strips.push(strip);
    }
    assert!(strips[0] != strips[1] && strips[1] != strips[2]);
    // The fourth cell is empty.
    let (x0, y0) = layout.tile_origin(3);
    assert_eq!(*sheet.get_pixel(x0 + 48, y0 + 32), SHEET_BACKGROUND);
    // The frames differ, so the comparison above tells tiles apart.
    assert_ne!(
        png(&dir.path().join("f.0001.png")),
        png(&dir.path().join("f.0061.png"))
    );

    // --columns 3: one row.
    succeed(&[
        "sheet",
        shot,
        "--frames",
        "1,30,61",
        "--tile",
        "96x64",
        "--columns",
        "3",
        "--out",
        text(&sheet_path),
    ]);
    assert_eq!(png(&sheet_path).dimensions(), (4 + 3 * 100, 4 + 80));
}

#[test]
fn a_cropped_sheet_shows_the_rectangle_drawn_again_at_the_tile_size() {
    let dir = tempfile::tempdir().unwrap();
    let sheet_path = dir.path().join("crop.png");
    let shot = "shots/sphere_ops.ron";
    // 60 × 40 of the 480 × 480 frame at tiles of 180 × 120: three times as many pixels.
    succeed(&[
        "sheet",
        shot,
        "--frames",
        "30",
        "--crop",
        "200,150,60,40",
        "--tile",
        "180x120",
        "--out",
        text(&sheet_path),
    ]);
    succeed(&[
        "render",
        shot,
        "--frames",
        "30",
        "--size",
        "1440x1440",
        "--preset",
        "preview",
        "--aov",
        "none",
        "--out",
        text(&dir.path().join("big.####.png")),
    ]);
    let sheet = png(&sheet_path);
    let big = png(&dir.path().join("big.0030.png"));
    let layout = SheetLayout::new(&["frame 30".to_string()], (180, 120), None).unwrap();
    let (x0, y0) = layout.tile_origin(0);
    let mut differ = 0;
    for y in 0..120 {
        for x in 0..180 {
            assert_eq!(
                sheet.get_pixel(x0 + x, y0 + y),
                big.get_pixel(600 + x, 450 + y),
                "({x}, {y})"
            );
            differ += usize::from(big.get_pixel(600 + x, 450 + y) != big.get_pixel(600, 450));
        }
    }
    assert!(
        differ > 100,
        "the rectangle shows something: {differ} pixels differ"
    );
    // Without --tile, tiles are 320 wide at the crop's shape.
    succeed(&[
        "sheet",
        shot,
        "--frames",
        "1",
        "--crop",
        "0,0,160,120",
        "--out",
        text(&sheet_path),
    ]);
    let (w, h) = png(&sheet_path).dimensions();
    assert_eq!(w, 4 + 320 + 4);
    assert!(h > 4 + 240, "{h}");
}

#[test]
fn sheet_tiles_default_to_320_pixels_wide_at_the_shot_aspect() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("tt.png");
    // The turntable is 640 × 360: tiles of 320 × 180; a caption fits at scale 2 (20 pixels).
    succeed(&[
        "sheet",
        "shots/teapot_turntable.ron",
        "--frames",
        "1",
        "--out",
        text(&out),
    ]);
    assert_eq!(png(&out).dimensions(), (4 + 320 + 4, 4 + 180 + 20 + 4));
}

#[test]
fn sheets_that_cannot_be_made_exit_2_and_write_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("sheets/s.png");
    let o = text(&out);
    for (args, says) in [
        (
            vec![
                "sheet",
                "shots/crescent.ron",
                "--frames",
                "1-70",
                "--out",
                o,
            ],
            "70 tiles are more than the 64",
        ),
        (
            vec![
                "sheet",
                "shots/crescent.ron",
                "--frames",
                "1",
                "--crop",
                "400,400,100,50",
                "--out",
                o,
            ],
            "leaves the shot's 480×480 image",
        ),
        (
            vec![
                "sheet",
                "shots/crescent.ron",
                "--frames",
                "1",
                "--crop",
                "0,0,100,50",
                "--tile",
                "200x200",
                "--out",
                o,
            ],
            "does not have the shape of --crop's 100×50",
        ),
        (
            vec![
                "sheet",
                "shots/crescent.ron",
                "--frames",
                "1",
                "--crop",
                "10,10,2,2",
                "--out",
                o,
            ],
            "beyond 16384 pixels a side",
        ),
        (
            vec![
                "sheet",
                "shots/crescent.ron",
                "--frames",
                "1",
                "--crop",
                "10,10,0,2",
                "--out",
                o,
            ],
            "expected X,Y,W,H",
        ),
        (
            vec![
                "sheet",
                "shots/crescent.ron",
                "--frames",
                "70-80",
                "--out",
                o,
            ],
            "frame 73 is outside the shot's frame range 1-72",
        ),
        (
            vec![
                "sheet",
                "shots/crescent.ron",
                "--vary",
                "a=1,2,3,4,5,6,7,8",
                "--vary",
                "b=1,2,3,4,5,6,7,8,9",
                "--out",
                o,
            ],
            "72 variants (8 × 9), more than the 64",
        ),
        (
            vec![
                "sheet",
                "shots/crescent.ron",
                "--vary",
                "a=1",
                "--vary",
                "a=2",
                "--out",
                o,
            ],
            "given twice",
        ),
        (
            vec![
                "sheet",
                "shots/crescent.ron",
                "--vary",
                "a=(1, 2",
                "--out",
                o,
            ],
            "'(' is not closed",
        ),
        (
            vec![
                "sheet",
                "shots/crescent.ron",
                "--frame",
                "36",
                "--vary",
                "highlights[0].layers[1].stack[1].alpah=0.1,0.3",
                "--out",
                o,
            ],
            "the nearest valid path is `highlights[0].layers[1].stack[1].alpha`",
        ),
        (
            vec![
                "sheet",
                "shots/crescent.ron",
                "--frames",
                "1",
                "--columns",
                "0",
                "--out",
                o,
            ],
            "--columns must be at least 1",
        ),
        (vec!["sheet", "shots/crescent.ron", "--out", o], "--frames"),
        (
            vec![
                "sheet",
                "shots/crescent.ron",
                "--frames",
                "1,2",
                "--tile",
                "9000x10",
                "--out",
                o,
            ],
            "over the 16384",
        ),
    ] {
        let result = glint_with(&args);
        assert_eq!(
            result.status.code(),
            Some(2),
            "{args:?}: {}",
            stderr(&result)
        );
        assert!(
            stderr(&result).contains(says),
            "{args:?}: {}",
            stderr(&result)
        );
        assert_eq!(
            std::fs::read_dir(dir.path()).unwrap().count(),
            0,
            "{args:?}"
        );
    }
}

#[test]
fn a_sheet_of_variants_holds_each_value_as_the_edited_shot_renders_it() {
    let dir = tempfile::tempdir().unwrap();
    let sheet_path = dir.path().join("variants.png");
    let alpha = "highlights[0].layers[1].stack[1].alpha";
    let values = ["0.2", "0.45"];
    succeed(&[
        "sheet",
        "shots/crescent.ron",
        "--frame",
        "36",
        "--vary",
        &format!("{alpha}={}", values.join(",")),
        "--tile",
        "96x96",
        "--out",
        text(&sheet_path),
    ]);
    let sheet = png(&sheet_path);
    let captions: Vec<String> = values.iter().map(|v| format!("alpha={v}")).collect();
    let layout = SheetLayout::new(&captions, (96, 96), None).unwrap();
    // Each tile against the shot edited by `glint key` and rendered alone.
    let shots = dir.path().join("shots");
    std::fs::create_dir_all(&shots).unwrap();
    let copy = shots.join("crescent.ron");
    let mut tiles = Vec::new();
    for (i, value) in values.iter().enumerate() {
        let original = std::fs::read_to_string(crate::common::repo_file("shots/crescent.ron"))
            .unwrap()
            .replace(
                "../patches/",
                &format!("{}/", crate::common::repo_file("patches").display()),
            );
        std::fs::write(&copy, original).unwrap();
        succeed(&["key", text(&copy), "--at", alpha, "--value", value]);
        let frame = dir.path().join(format!("v{i}.#.png"));
        succeed(&[
            "render",
            text(&copy),
            "--frames",
            "36",
            "--size",
            "96x96",
            "--preset",
            "preview",
            "--aov",
            "none",
            "--out",
            text(&frame),
        ]);
        let alone = png(&dir.path().join(format!("v{i}.36.png")));
        let (x0, y0) = layout.tile_origin(i);
        for (x, y, p) in alone.enumerate_pixels() {
            assert_eq!(
                sheet.get_pixel(x0 + x, y0 + y),
                p,
                "alpha {value} at ({x}, {y})"
            );
        }
        tiles.push(alone);
    }
    assert_ne!(tiles[0], tiles[1], "the two values give different pictures");
}
