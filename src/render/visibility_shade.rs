//! Shading straight from the visibility buffer, for a plan whose only effect is the cel tone
//! over interpolated frames ([`Surfaces::Visibility`](super::plan::Surfaces::Visibility)): at
//! each covered pixel the tone of the vertex normal interpolated there and turned toward the
//! viewer — the normal and the colour a texel with interpolated frames gets.
//!
//! Most triangles lie inside one band of their ramp. Those are found once per triangle, by
//! bounding `N·L` over the triangle ([`uniform_tone`]), and their pixels take the band's colour
//! with no work of their own; the others are shaded pixel by pixel.

use glam::{Vec3, Vec4};
use rayon::prelude::*;

use super::facing::facing_normal;
use super::gbuffer::{EMPTY, PIXELS_PER_JOB};
use super::raster::{interpolate, VisibilityBuffer};
use super::scene::{Scene, Tone};
use super::shade::cel_tone;
use super::tessellate::Mesh;
use crate::highlight::Light;

/// Shades every pixel of `visibility`, a raster of `mesh`: the tone at each covered pixel
/// ([`pixel_tone`]), taken once per triangle where it is the same over the whole triangle.
/// Returns the colour image (alpha 1 on surfaces, 0 on the background).
pub fn shade_visibility(visibility: &VisibilityBuffer, mesh: &Mesh, scene: &Scene) -> Vec<Vec4> {
    let to_eye = bounds_tones(scene).then(|| vertex_to_eye(mesh, scene));
    // Alpha 0: the tone varies over the triangle.
    let uniform: Vec<Vec4> = (0..mesh.triangles.len())
        .into_par_iter()
        .with_min_len(PIXELS_PER_JOB)
        .map(|t| {
            uniform_tone(mesh, to_eye.as_deref(), scene, t).map_or(Vec4::ZERO, |c| c.extend(1.0))
        })
        .collect();
    let pixel = |i: usize, triangle: u32| {
        if triangle == EMPTY {
            return Vec4::ZERO;
        }
        let colour = uniform[triangle as usize];
        if colour.w > 0.0 {
            colour
        } else {
            pixel_tone(visibility, mesh, scene, i).extend(1.0)
        }
    };
    // A few pixels per item, so that the work of each is inlined into a loop of its own.
    let mut colour = visibility
        .triangle
        .par_chunks(PIXELS_PER_ITEM)
        .enumerate()
        .with_min_len(PIXELS_PER_JOB / PIXELS_PER_ITEM)
        .map(|(item, triangles)| {
            let start = item * PIXELS_PER_ITEM;
            std::array::from_fn(|k| {
                triangles
                    .get(k)
                    .map_or(Vec4::ZERO, |&triangle| pixel(start + k, triangle))
            })
        })
        .collect::<Vec<[Vec4; PIXELS_PER_ITEM]>>()
        .into_flattened();
    colour.truncate(visibility.triangle.len());
    colour
}

/// Pixels shaded together by [`shade_visibility`].
const PIXELS_PER_ITEM: usize = 8;

/// Whether [`uniform_tone`] bounds `N·L` over triangles, and so needs the directions to the
/// eye: under a directional light, when some patch has a cel ramp with bands.
fn bounds_tones(scene: &Scene) -> bool {
    matches!(scene.light, Light::Directional { .. })
        && scene
            .looks
            .iter()
            .any(|look| matches!(&look.tone, Tone::Cel(ramp) if !ramp.bands.is_empty()))
}

/// The unit direction from each vertex of `mesh` toward the eye (zero at the eye).
fn vertex_to_eye(mesh: &Mesh, scene: &Scene) -> Vec<Vec3> {
    mesh.positions
        .par_iter()
        .with_min_len(PIXELS_PER_JOB)
        .map(|&p| scene.camera.eye_direction(p).normalize_or_zero())
        .collect()
}

/// The tone at pixel `i` of `visibility`, which a triangle covers: `ramp(N·L)` with N the
/// vertex normal interpolated at the pixel and turned toward the viewer. Not inlined: few
/// pixels need it, and the loop over all of them stays small.
#[inline(never)]
fn pixel_tone(visibility: &VisibilityBuffer, mesh: &Mesh, scene: &Scene, i: usize) -> Vec3 {
    let (triangle, b) = (visibility.triangle[i] as usize, visibility.barycentric[i]);
    let [i0, i1, i2] = mesh.triangles[triangle].map(|k| k as usize);
    let p = &mesh.positions;
    let position = interpolate(b, p[i0], p[i1], p[i2]);
    let n = interpolate(b, mesh.normals[i0], mesh.normals[i1], mesh.normals[i2]);
    let normal = facing_normal(n, scene.camera.eye_direction(position));
    cel_tone(scene, mesh.triangle_patch[triangle], position, normal)
}

/// How far inside a band, in `N·L`, a triangle's bounds must lie for its tone to be taken once
/// for all its pixels; also the least cosine between a corner's normal and the direction to
/// the eye from any corner. Rounding moves the per-pixel values far less.
const MARGIN: f32 = 1e-4;

/// The cel tone of triangle `t` when it is the same at every point of it, else `None`;
/// `to_eye[k]` is the unit direction from vertex k toward the eye, needed only when the ramp
/// has bands (a ramp of one colour is uniform under any light); without it, such a triangle
/// is shaded per pixel.
///
/// At barycentrics `b`, the pixel's normal is `m = Σ b_i n_i`, normalized and turned toward the
/// viewer, with `n_i` the unit corner normals. Its side is the sign of
/// `m·(e − p) = Σ_i Σ_j b_i b_j n_i·(e − p_j)` (`e − p_j` toward the eye from corner j), the
/// same over the triangle when all nine terms share it: `s = ±1`. With a directional light L
/// and `d_i = s n_i·L`, `N·L = Σ b_i d_i / |m|`, where `|m|² = Σ b_i b_j n_i·n_j` lies between
/// `c`, the least `n_i·n_j`, and 1. So `N·L` lies in `[lo, hi]`: `lo` the least `d_i`, divided
/// by `√c` when negative; `hi` the largest, divided by `√c` when positive. The tone is uniform
/// when `[lo − MARGIN, hi + MARGIN]` lies in one band of the patch's ramp.
///
/// `None` for an X-Toon patch and, on a ramp with bands, for a point light (L varies over the
/// triangle), a corner normal not unit, corner normals 90° or more apart, or a side not clear
/// of the eye by [`MARGIN`].
fn uniform_tone(mesh: &Mesh, to_eye: Option<&[Vec3]>, scene: &Scene, t: usize) -> Option<Vec3> {
    let Tone::Cel(ramp) = &scene.looks[mesh.triangle_patch[t] as usize].tone else {
        return None;
    };
    if ramp.bands.is_empty() {
        return Some(ramp.base);
    }
    let (Light::Directional { towards }, Some(to_eye)) = (scene.light, to_eye) else {
        return None;
    };
    let corners = mesh.triangles[t].map(|k| k as usize);
    let n = corners.map(|k| mesh.normals[k]);
    // NaN is not unit.
    if !n.iter().all(|n| (n.length_squared() - 1.0).abs() <= 1e-5) {
        return None;
    }
    let v = corners.map(|k| to_eye[k]);
    let cosines = n.map(|n| Vec3::new(n.dot(v[0]), n.dot(v[1]), n.dot(v[2])));
    let least_cosine = cosines[0].min(cosines[1]).min(cosines[2]).min_element();
    let most_cosine = cosines[0].max(cosines[1]).max(cosines[2]).max_element();
    let side = if least_cosine > MARGIN {
        1.0
    } else if most_cosine < -MARGIN {
        -1.0
    } else {
        return None;
    };
    let c = n[0].dot(n[1]).min(n[1].dot(n[2])).min(n[2].dot(n[0]));
    if c <= MARGIN {
        return None;
    }
    let d = n.map(|n| side * n.dot(towards));
    let (least, most) = (d[0].min(d[1]).min(d[2]), d[0].max(d[1]).max(d[2]));
    let widen = |x: f32| x / c.sqrt();
    let lo = if least < 0.0 { widen(least) } else { least };
    let hi = if most > 0.0 { widen(most) } else { most };
    ramp.uniform_between(lo - MARGIN, hi + MARGIN)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::formats::load_patches;
    use crate::render::fixtures::clip_space;
    use crate::render::raster::{rasterize, RasterOptions, Viewport};
    use crate::render::scene::{Aovs, PatchLook};
    use crate::render::tessellate::{Density, Tessellator};
    use crate::render::{Camera, Projection};
    use crate::toon::CelRamp;

    /// Per triangle and per pixel give the same colours, byte for byte, on the teapot from
    /// several sides, with its normals as tessellated and reversed (every triangle seen from
    /// its back), under both projections, and with one-colour ramps on half the patches under
    /// a point light; and both ways are taken.
    #[test]
    fn triangles_of_one_tone_shade_as_their_pixels_do() {
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("patches/teapot.bpt");
        let library = load_patches(&path).unwrap();
        let ramp = CelRamp {
            base: Vec3::new(0.1, 0.1, 0.2),
            bands: vec![
                (-0.3, Vec3::new(0.3, 0.3, 0.5)),
                (0.2, Vec3::new(0.5, 0.5, 0.8)),
                (0.7, Vec3::new(0.9, 0.9, 1.0)),
            ],
        };
        let flat = CelRamp {
            base: Vec3::new(0.6, 0.2, 0.1),
            bands: Vec::new(),
        };
        // Not a whole number of items of pixels.
        let (width, height) = (161, 119);
        let mut tessellator = Tessellator::new(library.clone());
        // Pixels shaded by triangle and by pixel, under the directional and the point light.
        let (mut per_triangle, mut per_pixel) = ([0, 0], [0, 0]);
        for (k, eye) in [
            Vec3::new(5.5, -7.0, 4.5),
            Vec3::new(-6.0, 2.0, 1.0),
            Vec3::new(0.5, 0.5, 9.0),
        ]
        .into_iter()
        .enumerate()
        {
            let projection = if k == 1 {
                Projection::Orthographic { height: 5.0 }
            } else {
                Projection::Perspective {
                    fov_y_degrees: 35.0,
                }
            };
            let camera = Camera {
                eye,
                target: Vec3::new(0.0, 0.0, 1.4),
                up: Vec3::Z,
                projection,
                near: 0.1,
                far: 100.0,
            };
            let view_projection = camera.view_projection(width as f32 / height as f32);
            let (mesh, _) = tessellator.mesh(
                Density::PerSpan { u: 6, v: 6 },
                view_projection,
                width,
                height,
            );
            let mut reversed = mesh.clone();
            for n in &mut reversed.normals {
                *n = -*n;
            }
            let clip = clip_space(mesh, view_projection);
            let viewport = Viewport { width, height };
            let (visibility, _) =
                rasterize(viewport, &clip, &mesh.triangles, &RasterOptions::default());
            // The last view: a point light, and the even patches in one colour.
            let last = k == 2;
            let scene = Scene {
                library: &library,
                looks: (0..library.patches.len())
                    .map(|patch| PatchLook {
                        designed_light: None,
                        lines: None,
                        tone: Tone::Cel(if last && patch % 2 == 0 {
                            flat.clone()
                        } else {
                            ramp.clone()
                        }),
                        highlight: None,
                    })
                    .collect(),
                camera,
                light: if last {
                    Light::Point {
                        position: Vec3::new(4.0, -3.0, 6.0),
                    }
                } else {
                    Light::Directional {
                        towards: Vec3::new(0.3, -0.6, 0.75).normalize(),
                    }
                },
                outlines: None,
                aovs: Aovs::default(),
                materials: Vec::new(),
            };
            for mesh in [mesh, &reversed] {
                let colour = shade_visibility(&visibility, mesh, &scene);
                assert_eq!(colour.len(), visibility.triangle.len());
                let to_eye = vertex_to_eye(mesh, &scene);
                for (i, &triangle) in visibility.triangle.iter().enumerate() {
                    if triangle == EMPTY {
                        assert_eq!(colour[i], Vec4::ZERO);
                        continue;
                    }
                    let want = pixel_tone(&visibility, mesh, &scene, i).extend(1.0);
                    assert_eq!(colour[i], want, "pixel {i}");
                    match uniform_tone(mesh, Some(&to_eye), &scene, triangle as usize) {
                        Some(_) => per_triangle[usize::from(last)] += 1,
                        None => per_pixel[usize::from(last)] += 1,
                    }
                }
            }
        }
        assert!(
            per_triangle[0] > per_pixel[0] && per_pixel[0] > 0,
            "directional light: {} pixels by triangle, {} by pixel",
            per_triangle[0],
            per_pixel[0]
        );
        assert!(
            per_triangle[1] > 0 && per_pixel[1] > 0,
            "point light: {} pixels by triangle, {} by pixel",
            per_triangle[1],
            per_pixel[1]
        );
    }
}
