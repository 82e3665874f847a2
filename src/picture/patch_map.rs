//! The patch map: a model as a camera sees it, each patch in its own flat colour shaded lightly
//! by `N·V`, the seams between patches drawn, and each visible patch labelled with its name.

use std::sync::Arc;

use glam::{Vec3, Vec4};
use image::{Rgba, RgbaImage};

use super::label_placement::{place_labels, LabelRequest, NO_REGION};
use super::text::{
    block_size, draw_block, draw_label, fit_text, label_size, LabelStyle, PixelRect,
};
use crate::formats::image_encoding::patch_colour;
use crate::geom::PatchLibrary;
use crate::highlight::Light;
use crate::render::{
    Antialias, Aovs, Camera, PatchLook, RenderError, Renderer, Scene, Settings, Tone,
};
use crate::toon::CelRamp;

/// The map's background, where no patch is.
pub const MAP_BACKGROUND: Rgba<u8> = Rgba([236, 236, 232, 255]);

/// The colour of the seams between patches and of the silhouette.
pub const SEAM: Rgba<u8> = Rgba([28, 28, 32, 255]);

/// A drawn patch map, with where each label went.
#[derive(Clone, Debug)]
pub struct PatchMap {
    pub image: RgbaImage,
    /// The patch index under each pixel, row by row from the top, [`NO_REGION`] where none.
    pub patch_ids: Vec<u32>,
    /// One label per visible patch.
    pub labels: Vec<MapLabel>,
    /// The box of the parts' legend, when the model has parts.
    pub legend: Option<PixelRect>,
}

/// A patch's label on the map.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct MapLabel {
    /// The patch's index in the model.
    pub patch: usize,
    pub text: String,
    /// A pixel of the patch the label stands for, inside `rect`.
    pub anchor: (u32, u32),
    /// The label's box, inside the image.
    pub rect: PixelRect,
}

/// The text each patch is labelled with: its name, with `instance_prefix` (`"teapot/"`, for a
/// shot of one instance) taken off the front.
#[must_use]
pub fn patch_labels(library: &PatchLibrary, instance_prefix: Option<&str>) -> Vec<String> {
    library
        .patches
        .iter()
        .map(|patch| strip(&patch.name, instance_prefix))
        .collect()
}

fn strip(name: &str, prefix: Option<&str>) -> String {
    prefix
        .and_then(|prefix| name.strip_prefix(prefix))
        .unwrap_or(name)
        .to_owned()
}

/// The legend of the model's parts, one line each: the part's name, a colon and its patches' labels
/// ([`patch_labels`]), numbers in increasing runs written `24-27`. `instance_prefix` is taken
/// off the front of part and patch names alike, and a part's own instance (`car/` of
/// `car/glass`) off its patches' names.
#[must_use]
pub fn part_legend(library: &PatchLibrary, instance_prefix: Option<&str>) -> Vec<String> {
    let labels = patch_labels(library, instance_prefix);
    library
        .groups
        .iter()
        .map(|group| {
            let part = strip(&group.name, instance_prefix);
            // A part of one instance among several lists its patches without the instance.
            let instance = part
                .rsplit_once('/')
                .map(|(instance, _)| format!("{instance}/"));
            let names: Vec<&str> = group
                .patches
                .iter()
                .map(|&p| {
                    let label = labels[p].as_str();
                    instance
                        .as_deref()
                        .and_then(|i| label.strip_prefix(i))
                        .unwrap_or(label)
                })
                .collect();
            let numbers: Option<Vec<u64>> = names.iter().map(|n| n.parse().ok()).collect();
            let patches = match numbers {
                Some(numbers) => number_runs(&numbers),
                None => names.join(" "),
            };
            format!("{part}: {patches}")
        })
        .collect()
}

/// Numbers written with each run of consecutive ones shortened: `0-3 8 10-11`.
#[must_use]
pub fn number_runs(numbers: &[u64]) -> String {
    let mut runs: Vec<(u64, u64)> = Vec::new();
    for &n in numbers {
        match runs.last_mut() {
            Some((_, end)) if *end + 1 == n => *end = n,
            _ => runs.push((n, n)),
        }
    }
    runs.iter()
        .map(|&(a, b)| {
            if a == b {
                a.to_string()
            } else {
                format!("{a}-{b}")
            }
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// The scale labels are drawn at on an image `width × height`: 2 from 400 pixels on the
/// shorter side, 1 below.
#[must_use]
pub fn map_label_scale(width: u32, height: u32) -> u32 {
    if width.min(height) >= 400 {
        2
    } else {
        1
    }
}

/// Renders `library` as `camera` sees it at `settings`' size and tessellation (without
/// supersampling: a patch id is a pixel's central sample), and draws its map with `labels`
/// (one per patch, [`patch_labels`]) and `legend` ([`part_legend`]).
pub fn render_patch_map(
    library: &Arc<PatchLibrary>,
    camera: Camera,
    settings: &Settings,
    labels: &[String],
    legend: &[String],
) -> Result<PatchMap, RenderError> {
    let mut settings = *settings;
    settings.antialias = Antialias::None;
    let plain = PatchLook {
        designed_light: None,
        lines: None,
        tone: Tone::Cel(CelRamp {
            base: Vec3::splat(0.5),
            bands: Vec::new(),
        }),
        highlight: None,
    };
    let scene = Scene {
        library,
        looks: vec![plain; library.patches.len()],
        camera,
        light: Light::Directional {
            towards: -camera.forward(),
        },
        outlines: None,
        aovs: Aovs {
            patch_id: true,
            normal: true,
            depth: true,
            ..Aovs::default()
        },
        materials: Vec::new(),
    };
    let frame = Renderer::new(Arc::clone(library)).render(&scene, &settings)?;
    let pixels = frame.colour.len();
    // The scene asked for these three; an image missing is drawn as background.
    let a = frame.aovs;
    let ids = a.patch_id.unwrap_or_else(|| vec![NO_REGION; pixels]);
    let normals = a.normal.unwrap_or_else(|| vec![Vec3::ZERO; pixels]);
    let depth = a.depth.unwrap_or_else(|| vec![f32::INFINITY; pixels]);
    Ok(draw_patch_map(
        MapPixels {
            width: frame.width,
            height: frame.height,
            ids,
            normals: &normals,
            depth: &depth,
        },
        &camera,
        labels,
        legend,
    ))
}

/// What the map is drawn from: per pixel, row by row from the top, the patch index
/// ([`NO_REGION`] on the background), the shading normal and the NDC depth.
pub struct MapPixels<'a> {
    pub width: u32,
    pub height: u32,
    pub ids: Vec<u32>,
    pub normals: &'a [Vec3],
    pub depth: &'a [f32],
}

/// Draws the map of `pixels`, rendered through `camera`.
///
/// A patch pixel is its flat colour ([`patch_colour`]) times `0.55 + 0.45·|N·V|`, where `V`
/// is [`Camera::toward_eye`] at the pixel's point (its NDC position and depth taken back
/// through the inverse view-projection): faces turned to the eye are bright, grazing ones
/// darker. A patch pixel with a 4-neighbour of another patch or of the background is a seam.
/// The legend (when there are lines) goes in the corner where it hides the fewest patch
/// pixels (the first of top left, top right, bottom left, bottom right on a tie), 4 pixels in;
/// the labels are placed around it by [`place_labels`]; both at [`map_label_scale`].
#[must_use]
pub fn draw_patch_map(
    pixels: MapPixels<'_>,
    camera: &Camera,
    labels: &[String],
    legend: &[String],
) -> PatchMap {
    let MapPixels {
        width,
        height,
        ids,
        normals,
        depth,
    } = pixels;
    let (w, h) = (width as usize, height as usize);
    let inverse = camera
        .view_projection(width as f32 / height as f32)
        .inverse();
    let mut image = RgbaImage::from_pixel(width, height, MAP_BACKGROUND);
    for y in 0..h {
        for x in 0..w {
            let i = y * w + x;
            let id = ids[i];
            if id == NO_REGION {
                continue;
            }
            let differs = |j: usize| ids[j] != id;
            let seam = (x > 0 && differs(i - 1))
                || (x + 1 < w && differs(i + 1))
                || (y > 0 && differs(i - w))
                || (y + 1 < h && differs(i + w));
            let colour = if seam {
                SEAM
            } else {
                let ndc = Vec4::new(
                    2.0 * (x as f32 + 0.5) / width as f32 - 1.0,
                    1.0 - 2.0 * (y as f32 + 0.5) / height as f32,
                    depth[i],
                    1.0,
                );
                let point = inverse * ndc;
                let point = point.truncate() / point.w;
                let facing = normals[i]
                    .normalize_or_zero()
                    .dot(camera.toward_eye(point))
                    .abs();
                let shade = 0.55 + 0.45 * if facing.is_finite() { facing } else { 1.0 };
                let [r, g, b] = patch_colour(id);
                let lit = |c: u8| (f32::from(c) * shade).round() as u8;
                Rgba([lit(r), lit(g), lit(b), 255])
            };
            image.put_pixel(x as u32, y as u32, colour);
        }
    }
    let style = LabelStyle::dark_on_light(map_label_scale(width, height));
    let requests: Vec<LabelRequest> = labels
        .iter()
        .enumerate()
        .map(|(patch, text)| LabelRequest {
            region: patch as u32,
            size: label_size(text, &style),
        })
        .collect();
    let legend = (!legend.is_empty()).then(|| {
        let lines: Vec<String> = legend
            .iter()
            .map(|line| fit_text(line, width.saturating_sub(8), &style))
            .collect();
        let lines: Vec<&str> = lines.iter().map(String::as_str).collect();
        let rect = legend_corner(&ids, (width, height), block_size(&lines, &style));
        draw_block(&mut image, &lines, (rect.x, rect.y), &style)
    });
    let labels = place_labels(&ids, (width, height), &requests, legend.as_slice())
        .into_iter()
        .map(|p| {
            let patch = p.region as usize;
            let text = labels[patch].clone();
            draw_label(&mut image, &text, (p.rect.x, p.rect.y), &style);
            MapLabel {
                patch,
                text,
                anchor: p.anchor,
                rect: p.rect,
            }
        })
        .collect();
    PatchMap {
        image,
        patch_ids: ids,
        labels,
        legend,
    }
}

/// The box of `size` 4 pixels in from the corner of the image where it covers the fewest
/// pixels of patches: top left, top right, bottom left or bottom right, the first on a tie.
fn legend_corner(ids: &[u32], (width, height): (u32, u32), size: (u32, u32)) -> PixelRect {
    let margin = 4;
    let (right, bottom) = (
        i64::from(width) - i64::from(size.0) - margin,
        i64::from(height) - i64::from(size.1) - margin,
    );
    let corners = [
        (margin, margin),
        (right, margin),
        (margin, bottom),
        (right, bottom),
    ];
    let covered = |rect: &PixelRect| {
        let (x0, y0) = (rect.x.max(0) as u32, rect.y.max(0) as u32);
        let x1 = (rect.x + i64::from(rect.width)).clamp(0, i64::from(width)) as u32;
        let y1 = (rect.y + i64::from(rect.height)).clamp(0, i64::from(height)) as u32;
        (y0..y1)
            .flat_map(|y| (x0..x1).map(move |x| (x, y)))
            .filter(|&(x, y)| ids[(y * width + x) as usize] != NO_REGION)
            .count()
    };
    corners
        .iter()
        .map(|&(x, y)| PixelRect {
            x: x.max(0),
            y: y.max(0),
            width: size.0,
            height: size.1,
        })
        .min_by_key(covered)
        .unwrap_or(PixelRect {
            x: 0,
            y: 0,
            width: size.0,
            height: size.1,
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{shapes, NamedPatch, PatchGroup};

    fn library(names: &[&str], groups: &[(&str, &[usize])]) -> PatchLibrary {
        let surface = shapes::plane(1.0, 1.0).unwrap();
        PatchLibrary {
            patches: names
                .iter()
                .map(|n| NamedPatch {
                    name: (*n).into(),
                    trim: None,
                    surface: surface.clone(),
                })
                .collect(),
            groups: groups
                .iter()
                .map(|(name, patches)| PatchGroup {
                    name: (*name).into(),
                    patches: patches.to_vec(),
                })
                .collect(),
        }
    }

    #[test]
    fn labels_are_names_and_the_legend_lists_each_part() {
        let lib = library(&["0", "1", "2", "3"], &[("lid", &[0, 1, 3]), ("top", &[1])]);
        assert_eq!(patch_labels(&lib, None), ["0", "1", "2", "3"]);
        assert_eq!(part_legend(&lib, None), ["lid: 0-1 3", "top: 1"]);
        let shot = library(
            &["teapot/0", "teapot/1", "car/windshield", "car/rear"],
            &[("teapot/lid", &[0, 1]), ("car/glass", &[2, 3])],
        );
        assert_eq!(
            patch_labels(&shot, None),
            ["teapot/0", "teapot/1", "car/windshield", "car/rear"]
        );
        assert_eq!(
            part_legend(&shot, None),
            ["teapot/lid: 0-1", "car/glass: windshield rear"]
        );
        let one = library(&["teapot/0", "teapot/1"], &[("teapot/lid", &[0, 1])]);
        assert_eq!(patch_labels(&one, Some("teapot/")), ["0", "1"]);
        assert_eq!(part_legend(&one, Some("teapot/")), ["lid: 0-1"]);
    }

    #[test]
    fn the_legend_takes_the_emptiest_corner() {
        // Patches fill the left half of a 20 × 10 image: the legend goes top right.
        let ids: Vec<u32> = (0..10)
            .flat_map(|_| (0..20).map(|x| if x < 10 { 0 } else { NO_REGION }))
            .collect();
        let rect = legend_corner(&ids, (20, 10), (6, 3));
        assert_eq!((rect.x, rect.y), (10, 4));
    }

    #[test]
    fn seams_shading_and_background_follow_the_ids() {
        // An 8 × 4 image: background in column 0, patch 1 in columns 1–4, patch 2 in 5–7.
        let ids: Vec<u32> = (0..4)
            .flat_map(|_| (0..8).map(|x| [NO_REGION, 1, 1, 1, 1, 2, 2, 2][x]))
            .collect();
        let camera = Camera {
            eye: Vec3::new(0.0, 0.0, 5.0),
            target: Vec3::ZERO,
            up: Vec3::Y,
            projection: crate::render::Projection::Orthographic { height: 2.0 },
            near: 1.0,
            far: 10.0,
        };
        // Patch 2 faces the eye, patch 1 turns 60° away.
        let normals: Vec<Vec3> = ids
            .iter()
            .map(|&id| match id {
                1 => Vec3::new(60f32.to_radians().sin(), 0.0, 60f32.to_radians().cos()),
                _ => Vec3::Z,
            })
            .collect();
        let depth = vec![0.5; ids.len()];
        let map = draw_patch_map(
            MapPixels {
                width: 8,
                height: 4,
                ids: ids.clone(),
                normals: &normals,
                depth: &depth,
            },
            &camera,
            &[],
            &[],
        );
        let px = |x: u32, y: u32| *map.image.get_pixel(x, y);
        assert_eq!(px(0, 2), MAP_BACKGROUND);
        // The silhouette and the line between the patches are seams; the image border is not.
        assert_eq!((px(1, 2), px(4, 2), px(5, 2)), (SEAM, SEAM, SEAM));
        // Facing the eye: the flat colour; turned 60° away: darker by 0.45 (1 − cos 60°).
        let [r, g, b] = patch_colour(2);
        assert_eq!(px(7, 0), Rgba([r, g, b, 255]));
        assert_eq!(px(6, 3), Rgba([r, g, b, 255]));
        let [r, g, b] = patch_colour(1);
        let shade = |c: u8| (f32::from(c) * (1.0 - 0.45 * 0.5)).round() as u8;
        assert_eq!(px(2, 0), Rgba([shade(r), shade(g), shade(b), 255]));
        assert_eq!(px(3, 3), px(2, 0));
        assert_eq!(map.patch_ids, ids);
    }
}
