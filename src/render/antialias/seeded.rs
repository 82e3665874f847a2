//! The K × K samples of a marked pixel found from the surface points around it, by
//! Newton steps along each sample's ray instead of rasterization.

use glam::{Mat4, Vec2};
use rayon::prelude::*;

use super::near_border::NearBorder;
use super::resolved::Resolved;
use crate::geom::PatchLibrary;
use crate::highlight::Footprint;
use crate::render::gbuffer::{Evaluate, GBuffer, Texel, EMPTY, UNFILLED};
use crate::render::neighbourhood::around;
use crate::render::probe::{landed_depth, uv_slopes};
use crate::render::raster::Viewport;
use crate::render::scene::Scene;
use crate::render::settings::FrameMode;
use crate::render::shade::{shade, Edges, ShadeBuffers};
use crate::render::xtoon_tone::Views;

/// Pixels drawn together: the samples of one batch, and their candidates, are all the memory
/// the path holds (about 2 MB at 4 × 4 samples).
const BATCH_PIXELS: usize = 1024;

/// The relative spread of view depth among the texels of one patch around a pixel beyond which
/// the patch folds over itself there (one sheet in front of another): such a pixel is left to
/// rasterization, which sees every sheet.
const FOLD: f32 = 0.05;

/// What the path needs of the frame.
pub(in crate::render) struct SeedInput<'a> {
    pub library: &'a PatchLibrary,
    pub scene: &'a Scene<'a>,
    pub view_projection: Mat4,
    /// The one-sample G-buffer: its (u, v) are where the samples start from.
    pub gbuffer: &'a GBuffer,
    /// Per texel of `gbuffer`, its footprint from the edge-width stage, when edges are analytic.
    pub footprints: Option<&'a [Footprint]>,
    /// The image in pixels.
    pub image: Viewport,
    /// Samples per pixel side.
    pub k: u32,
}

/// Whether pixel `pixel` can be drawn from the surfaces its neighbourhood shows: some pixel of
/// its 3 × 3 neighbourhood is covered, no patch among them folds over itself there (the view
/// depths of its texels spread by more than [`FOLD`]), and where one of the nine is not covered
/// (a silhouette), no side of a patch's domain passes within [`BORDER_PIXELS`] of the pixel's
/// centre on screen, nor a collapsed one within [`POLE_PIXELS`] (`near_border`, built with
/// those reaches).
///
/// A silhouette near a patch's border is left to rasterization: there a patch seen edge-on may
/// cover a sliver of the pixel that no centre of the nine sees (the flat top of a knob, one
/// patch, above its side, another), and only the mesh knows it is there. Such a sliver is
/// bounded by the border it meets the other patch along, which passes within a pixel of the
/// box. Away from borders, and inside a surface, what no centre sees is what the marking of the
/// pixels cannot see either.
///
/// The distance is the projected border's own, not one taken from the slope of (u, v): toward a
/// silhouette the surface turns away and (u, v) changes ever faster from one pixel to the next,
/// so that any side of the domain within a few pixels' worth of that slope would count, though
/// it lies far off on screen or behind the silhouette.
///
/// The edges of a trim are not borders here: patches are joined along the sides of their
/// domains, and a trim's loop is where a patch ends, cut, as a hole's rim. A sample beyond it
/// lands on the part cut away, is dropped, and sees what lies behind, as in the rasterizer;
/// on the trimmed plate and capped sphere the coverage is the same as when trim edges went to
/// the tiles (soft IoU 0.99946 and 0.99965 against the analytic shapes either way), at the cost
/// of a sample's fraction of a pixel where a patch seen edge-on would continue a trim edge.
#[must_use]
pub(in crate::render) fn seedable(
    gbuffer: &GBuffer,
    scene: &Scene,
    near_border: &NearBorder,
    pixel: usize,
) -> bool {
    let size = (gbuffer.width as usize, gbuffer.height as usize);
    let (eye, forward) = (scene.camera.eye, scene.camera.forward());
    let mut seen: [(u32, f32, f32); 9] = [(EMPTY, 0.0, 0.0); 9];
    let (mut patches, mut empty) = (0, false);
    for n in around(pixel, size) {
        let Some(t) = gbuffer.texel(n) else {
            empty = true;
            continue;
        };
        let depth = (t.position - eye).dot(forward);
        match seen[..patches].iter_mut().find(|s| s.0 == t.patch) {
            Some(s) => (s.1, s.2) = (s.1.min(depth), s.2.max(depth)),
            None => {
                seen[patches] = (t.patch, depth, depth);
                patches += 1;
            }
        }
    }
    let flat = seen[..patches]
        .iter()
        .all(|&(_, near, far)| near > 0.0 && far - near <= FOLD * near);
    let (x, y) = ((pixel % size.0) as u32, (pixel / size.0) as u32);
    patches > 0 && flat && (!empty || !near_border.at(x, y))
}

/// How far from a silhouette pixel's centre, in pixels on screen, the side of a patch's domain
/// must pass for the silhouette to be drawn from the surfaces around it ([`seedable`]).
pub(in crate::render) const BORDER_PIXELS: f32 = 3.0;

/// How far from a silhouette pixel's centre, in pixels on screen, a collapsed side (a pole)
/// must lie for the silhouette to be drawn from the surfaces around it. (u, v) turns about a
/// pole, and a start moved from a texel by its slope can miss every sample the surface covers:
/// on the sphere at 256 × 256 with its pole at the top of its outline, the half-covered pixels
/// 4 to 5 pixels beside the pole came out empty.
pub(in crate::render) const POLE_PIXELS: f32 = 12.0;

/// Whether every pixel of the 3 × 3 neighbourhood of `pixel` (inside the image) is covered.
fn covered_around(gbuffer: &GBuffer, pixel: u32) -> bool {
    let size = (gbuffer.width as usize, gbuffer.height as usize);
    around(pixel as usize, size).all(|n| gbuffer.slot[n] != EMPTY)
}

/// One candidate for a sample: the sample and the texel it starts from.
#[derive(Clone, Copy, Debug, Default)]
struct Candidate {
    /// The sample's index in the batch: `pixel_in_batch · k² + sy · k + sx`.
    sample: u32,
    /// The seed texel's index in the one-sample G-buffer.
    seed: u32,
}

/// A covered pixel around a marked one, as a start for its samples.
#[derive(Clone, Copy, Debug, Default)]
struct Seed {
    /// Its texel's index in the one-sample G-buffer.
    slot: u32,
    patch: u32,
    /// Its centre in pixels.
    centre: Vec2,
    /// The change of its (u, v) per pixel along x and y ([`uv_slopes`]; zero where none).
    slopes: (Vec2, Vec2),
    /// Whether the eye sees only the back of its patch among the seeds ([`Texel::back`]): a
    /// start from it looks for that side alone. Where it sees both, the patch folds over about
    /// the pixel, and a start that lands on the back may have crossed to the far sheet.
    back_only: bool,
}

/// The covered pixels of a marked pixel's 3 × 3 neighbourhood, and how many patches they show.
#[derive(Clone, Copy, Debug, Default)]
struct Seeds {
    seeds: [Seed; 9],
    count: usize,
    patches: usize,
}

impl Seeds {
    /// The seeds around `pixel` in `gbuffer`.
    fn around(gbuffer: &GBuffer, pixel: u32) -> Self {
        let w = gbuffer.width as usize;
        let mut seeds = Self::default();
        for n in around(pixel as usize, (w, gbuffer.height as usize)) {
            let slot = gbuffer.slot[n];
            if slot == EMPTY {
                continue;
            }
            let Texel { patch, back, .. } = gbuffer.texels[slot as usize];
            if seeds.seeds[..seeds.count].iter().all(|s| s.patch != patch) {
                seeds.patches += 1;
            }
            let (along_x, along_y) = uv_slopes(gbuffer, slot);
            seeds.seeds[seeds.count] = Seed {
                slot,
                patch,
                centre: Vec2::new((n % w) as f32, (n / w) as f32) + 0.5,
                slopes: (along_x.unwrap_or(Vec2::ZERO), along_y.unwrap_or(Vec2::ZERO)),
                back_only: back,
            };
            seeds.count += 1;
        }
        // `back_only` held each seed's own side; it becomes whether every seed of its patch is
        // on the back, once a pixel rather than once a sample.
        let seen = seeds.seeds;
        for seed in &mut seeds.seeds[..seeds.count] {
            seed.back_only = seen[..seeds.count]
                .iter()
                .all(|s| s.patch != seed.patch || s.back_only);
        }
        seeds
    }

    /// Fills `candidates` and `texels` (one per patch per sample, `k² · patches` of each) for
    /// pixel `j` of the batch, at `pixel`: each sample's start on each patch is that patch's
    /// seed nearest the sample, its (u, v) moved by the seed's slopes to the sample's offset.
    fn fill(
        &self,
        input: &SeedInput,
        (j, pixel): (usize, u32),
        candidates: &mut [Candidate],
        texels: &mut [Texel],
    ) {
        let (k, w) = (input.k, input.image.width);
        let full_width = w * k;
        let (px, py) = (pixel % w, pixel / w);
        let mut out = candidates.iter_mut().zip(texels.iter_mut());
        for s in 0..k * k {
            let (sx, sy) = (s % k, s / k);
            let centre = Vec2::new(
                px as f32 + (sx as f32 + 0.5) / k as f32,
                py as f32 + (sy as f32 + 0.5) / k as f32,
            );
            let global = (py * k + sy) * full_width + px * k + sx;
            // The nearest seed of each patch: (patch, distance², its index in `seeds`).
            let mut nearest = [(EMPTY, 0f32, 0usize); 9];
            let mut patches = 0;
            for (i, seed) in self.seeds[..self.count].iter().enumerate() {
                let d = centre.distance_squared(seed.centre);
                match nearest[..patches].iter_mut().find(|n| n.0 == seed.patch) {
                    Some(n) if d < n.1 => (n.1, n.2) = (d, i),
                    Some(_) => {}
                    None => {
                        nearest[patches] = (seed.patch, d, i);
                        patches += 1;
                    }
                }
            }
            for &(_, _, i) in &nearest[..patches] {
                let Some((candidate, texel)) = out.next() else {
                    return;
                };
                let seed = &self.seeds[i];
                let t = input.gbuffer.texels[seed.slot as usize];
                let domain = input.library.patches[t.patch as usize].surface.domain();
                let offset = centre - seed.centre;
                let uv = t.uv + (seed.slopes.0 * offset.x + seed.slopes.1 * offset.y);
                *candidate = Candidate {
                    sample: j as u32 * k * k + s,
                    seed: seed.slot,
                };
                *texel = Texel {
                    pixel: global,
                    uv: Vec2::new(
                        uv.x.clamp(domain.u.0 as f32, domain.u.1 as f32),
                        uv.y.clamp(domain.v.0 as f32, domain.v.1 as f32),
                    ),
                    back: seed.back_only,
                    ..t
                };
            }
        }
    }
}

/// The memory of the seeded path, kept from one batch to the next.
#[derive(Default)]
pub(in crate::render) struct Buffers {
    shading: ShadeBuffers,
    seeds: Vec<Seeds>,
    candidates: Vec<Candidate>,
    texels: Vec<Texel>,
    /// Per sample of the batch, the nearest candidate that landed on its ray: (depth, index).
    chosen: Vec<Option<(f32, u32)>>,
    /// The samples chosen, as a G-buffer, and their footprints.
    samples: GBuffer,
    footprints: Vec<Footprint>,
}

/// Draws each of `pixels` at `input.k × input.k` samples and returns their averages, the pixels
/// it could not draw, and the frames evaluated.
///
/// Each sample is tried from each patch its pixel's 3 × 3 neighbourhood shows, starting from
/// that patch's texel nearest the sample, its (u, v) moved by the texel's slope
/// ([`uv_slopes`]): the start is refined onto the sample's ray ([`GBuffer::evaluate_frames`]
/// with refined frames, within a probe's evaluations) and kept when the point it lands on
/// projects within 0.05 samples of the sample's centre ([`landed_depth`]) on a part of the
/// patch its trim keeps; of the points kept, the nearest covers the sample. A pixel inside a
/// surface with a sample that none covers is given back.
/// The samples are shaded with their seed's footprint over the sample (a `k`-th of the
/// pixel's), and a pixel takes the mean of its samples as the rasterized tiles do
/// ([`Resolved::average`]).
pub(in crate::render) fn draw(
    input: &SeedInput,
    views: &Views,
    pixels: &[u32],
    buffers: &mut Buffers,
) -> Drawn {
    let mut drawn = Drawn {
        resolved: Vec::with_capacity(pixels.len()),
        failed: Vec::new(),
        frames: 0,
    };
    for batch in pixels.chunks(BATCH_PIXELS) {
        let out = (&mut drawn.resolved, &mut drawn.failed);
        drawn.frames += draw_batch(input, views, batch, buffers, out);
    }
    drawn
}

/// What [`draw`] did.
pub(in crate::render) struct Drawn {
    /// The pixels drawn, averaged.
    pub resolved: Vec<Resolved>,
    /// The pixels inside a surface (their neighbourhood covered) some sample of which met no
    /// surface from any start: a surface no centre sees, or a search that strayed. They are
    /// left to rasterization.
    pub failed: Vec<u32>,
    /// NURBS frames evaluated.
    pub frames: u64,
}

fn draw_batch(
    input: &SeedInput,
    views: &Views,
    pixels: &[u32],
    buffers: &mut Buffers,
    (resolved, failed): (&mut Vec<Resolved>, &mut Vec<u32>),
) -> u64 {
    let (k, image, gbuffer) = (input.k, input.image, input.gbuffer);
    let per_pixel = (k * k) as usize;
    let full = (image.width * k, image.height * k);
    let Buffers {
        shading,
        seeds,
        candidates,
        texels,
        chosen,
        samples,
        footprints,
    } = buffers;

    // The candidates: per sample, the nearest texel of each patch around its pixel, each
    // pixel's written in place at its offset (k² per patch its neighbourhood shows).
    pixels
        .par_iter()
        .map(|&pixel| Seeds::around(gbuffer, pixel))
        .collect_into_vec(seeds);
    // Pixel j's candidates are `first[j]..first[j + 1]`.
    let mut first = Vec::with_capacity(pixels.len() + 1);
    first.push(0);
    for s in seeds.iter() {
        first.push(first.last().copied().unwrap_or(0) + s.patches * per_pixel);
    }
    let total = first.last().copied().unwrap_or(0);
    candidates.resize(total, Candidate::default());
    texels.resize(total, UNFILLED);
    let mut pieces = Vec::with_capacity(pixels.len());
    let (mut rest_c, mut rest_t) = (&mut candidates[..], &mut texels[..]);
    for s in seeds.iter() {
        let n = s.patches * per_pixel;
        let (c, more_c) = std::mem::take(&mut rest_c).split_at_mut(n);
        let (t, more_t) = std::mem::take(&mut rest_t).split_at_mut(n);
        pieces.push((c, t));
        (rest_c, rest_t) = (more_c, more_t);
    }
    pieces
        .into_par_iter()
        .zip(seeds.par_iter())
        .zip(pixels.par_iter())
        .enumerate()
        .for_each(|(j, (((c, t), s), &pixel))| s.fill(input, (j, pixel), c, t));
    let mut frames = probe(input, texels, full, Evaluate::QuickProbe);

    // Per sample, the nearest candidate that landed on its ray on a part of its patch the trim
    // keeps, pixel by pixel.
    chosen.clear();
    chosen.resize(pixels.len() * per_pixel, None);
    chosen
        .par_chunks_mut(per_pixel)
        .zip(first.par_windows(2))
        .enumerate()
        .for_each(|(j, (chosen, range))| {
            for index in range[0]..range[1] {
                let t = &texels[index];
                let Some(depth) = landed_depth(input.view_projection, t.position, t.pixel, full)
                else {
                    continue;
                };
                let slot = &mut chosen[candidates[index].sample as usize - j * per_pixel];
                if slot.is_some_and(|(nearest, _)| depth >= nearest) {
                    continue;
                }
                let patch = &input.library.patches[t.patch as usize];
                // One that landed where the patch is trimmed away lets the sample see past it.
                if patch.keeps(f64::from(t.uv.x), f64::from(t.uv.y)) {
                    *slot = Some((depth, index as u32));
                }
            }
        });

    frames += retry_beside_landed(input, pixels, candidates, texels, chosen);

    // The samples as a G-buffer k wide, one k × k block per pixel down it.
    samples.width = k;
    samples.height = k * pixels.len() as u32;
    samples.slot.clear();
    samples.slot.resize(chosen.len(), EMPTY);
    samples.texels.clear();
    footprints.clear();
    for (s, choice) in chosen.iter().enumerate() {
        let Some((depth, index)) = *choice else {
            continue;
        };
        samples.slot[s] = samples.texels.len() as u32;
        samples.texels.push(Texel {
            pixel: s as u32,
            depth,
            ..texels[index as usize]
        });
        let seed = candidates[index as usize].seed as usize;
        let footprint = input.footprints.map_or(Footprint::HARD, |f| f[seed]);
        footprints.push(Footprint {
            x: footprint.x / k as f32,
            y: footprint.y / k as f32,
        });
    }
    let shaded = shade(
        samples,
        input.scene,
        views,
        None,
        Edges {
            widths: input.footprints.map(|_| footprints.as_slice()),
            bands: None,
            highlights: None,
            settled: None,
            signed: None,
        },
        shading,
    );

    for (j, &pixel) in pixels.iter().enumerate() {
        let range = j * per_pixel..(j + 1) * per_pixel;
        if chosen[range.clone()].iter().any(Option::is_none) && covered_around(gbuffer, pixel) {
            failed.push(pixel);
            continue;
        }
        resolved.push(Resolved::average(pixel, &shaded, range));
    }
    frames
}

/// Tries again each sample of a silhouette pixel (one with an uncovered neighbour) that no start
/// reached, beside a sample of the pixel that one did: from where that sample landed, a `k`-th
/// of a pixel away, as a probe. A start from the texels around can be too far where (u, v)
/// turns fast (toward a pole, near the silhouette), and there a sample the surface covers
/// would be taken for one it misses. The starts that land are appended to `candidates` and
/// `texels` and chosen. Returns the frames evaluated.
fn retry_beside_landed(
    input: &SeedInput,
    pixels: &[u32],
    candidates: &mut Vec<Candidate>,
    texels: &mut Vec<Texel>,
    chosen: &mut [Option<(f32, u32)>],
) -> u64 {
    let (k, w) = (input.k, input.image.width);
    let per_pixel = (k * k) as usize;
    let full = (w * k, input.image.height * k);
    let first = texels.len();
    for (j, &pixel) in pixels.iter().enumerate() {
        if covered_around(input.gbuffer, pixel) {
            continue;
        }
        let block = &chosen[j * per_pixel..(j + 1) * per_pixel];
        for s in 0..k * k {
            if block[s as usize].is_some() {
                continue;
            }
            let (sx, sy) = (s % k, s / k);
            let beside = [
                (sx > 0).then(|| s - 1),
                (sx + 1 < k).then(|| s + 1),
                (sy > 0).then(|| s - k),
                (sy + 1 < k).then(|| s + k),
            ];
            let Some(from) = beside
                .into_iter()
                .flatten()
                .find_map(|n| block[n as usize].map(|(_, index)| index))
            else {
                continue;
            };
            let (px, py) = (pixel % w, pixel / w);
            let global = (py * k + sy) * full.0 + px * k + sx;
            candidates.push(Candidate {
                sample: j as u32 * k * k + s,
                seed: candidates[from as usize].seed,
            });
            texels.push(Texel {
                pixel: global,
                ..texels[from as usize]
            });
        }
    }
    if texels.len() == first {
        return 0;
    }
    let frames = probe(input, &mut texels[first..], full, Evaluate::Probe);
    for index in first..texels.len() {
        let t = &texels[index];
        let Some(depth) = landed_depth(input.view_projection, t.position, t.pixel, full) else {
            continue;
        };
        let patch = &input.library.patches[t.patch as usize];
        if patch.keeps(f64::from(t.uv.x), f64::from(t.uv.y)) {
            chosen[candidates[index].sample as usize] = Some((depth, index as u32));
        }
    }
    frames
}

/// Refines each of `texels` onto the ray of its sample in the `full` grid of samples, as a
/// probe of kind `evaluate` ([`GBuffer::evaluate_frames`] with refined frames); returns the
/// frames evaluated.
fn probe(input: &SeedInput, texels: &mut [Texel], full: (u32, u32), evaluate: Evaluate) -> u64 {
    GBuffer::evaluate_frames(
        texels,
        input.library,
        &input.scene.camera,
        input.view_projection,
        full,
        FrameMode::Refined,
        evaluate,
    )
}
