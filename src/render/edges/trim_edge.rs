//! Trim edges for adaptive anti-aliasing: the pixels about the rim of a trimmed patch whose
//! colour one sample on each side of the rim gives, weighted by the rim's cover of the box.

use glam::{DVec2, Mat4, Vec2, Vec4};
use rayon::prelude::*;
use std::sync::atomic::{AtomicU8, Ordering};

use super::band_edge::{band_clear_of_box, JUMP};
use super::edge_width::{signed_values_of, SignedValues};
use super::highlight_edge::{highlights_clear_of_box, SMOOTH_BEND};
use crate::geom::PatchLibrary;
use crate::math::{BoxQuadratic, LevelCrossing};
use crate::render::colour::{premultiplied, straight};
use crate::render::gbuffer::{Evaluate, GBuffer, Texel, EMPTY, UNFILLED};
use crate::render::neighbourhood::around;
use crate::render::probe::landed_depth;
use crate::render::probe::{away_from_borders, uv_slopes};
use crate::render::scene::{Scene, Tone};
use crate::render::settings::FrameMode;
use crate::render::shade::Shaded;

/// What the trim edges of a frame draw at one sample.
#[derive(Clone, Debug, Default)]
pub(in crate::render) struct TrimEdges {
    /// Per pixel of the image, whether it lies about a trim's rim and its colour is right as
    /// drawn at one sample ([`find_trim_edges`]).
    pub drawn: Vec<bool>,
    /// The pixels among them a rim crosses.
    pub crossed: Vec<Crossed>,
    /// NURBS frames evaluated.
    pub frames: u64,
    /// The candidate pixels judged: those about a rim.
    pub judged: u64,
}

/// A pixel a trim's rim crosses, drawn from one sample on each side of it.
#[derive(Clone, Copy, Debug)]
pub(in crate::render) struct Crossed {
    pub pixel: u32,
    /// The fraction of the box the trimmed patch keeps.
    pub cover: f32,
    /// The trimmed patch at the pixel's centre, on its ray (on a part the trim may cut away).
    pub kept: Texel,
    /// What the cut part shows at the pixel's centre, on its ray: the surface behind, or
    /// nothing (the background).
    pub beyond: Option<Texel>,
    /// The trim's signed distance over the box, as its cover was taken.
    pub rim: BoxQuadratic,
}

/// A candidate drawn right: where the rim crosses it, what its cut part shows at the centre
/// (`None` inside: the background), and the trimmed patch's samples at its nine centres.
type DrawnCandidate = (Option<Option<Texel>>, [usize; 9]);

/// A pixel whose 3 × 3 neighbourhood shows two things: the trimmed patch `front`, and `other`
/// (a patch behind it, or [`EMPTY`] for the background).
#[derive(Clone, Copy, Debug)]
struct Candidate {
    pixel: u32,
    front: u32,
    other: u32,
}

/// Per pixel of `gbuffer`'s image, whether the rim of a trimmed patch lies about it and its
/// colour is right as drawn at one sample; the pixels the rim crosses, with the samples on
/// each side that [`composite`] draws them from. `None` where no patch of the scene is trimmed
/// (or the image is narrower than three pixels).
///
/// A pixel not yet drawn right (`drawn`, per texel) whose 3 × 3 neighbourhood, inside the
/// image, shows exactly a trimmed patch P with a cel tone and one other thing — the
/// background, or a patch Q with a cel tone behind P, none of P's texels there within three
/// pixels of its domain's side — is tried. Each surface is taken at the nine centres: where a
/// centre shows it, its texel; elsewhere the point where the centre's ray meets it, found by a
/// probe from its nearest texel (`GBuffer::evaluate_frames`, refined). The trim's signed
/// distance `f` in (u, v) is taken at P's nine points
/// ([`Trim::try_signed_distance`](crate::geom::Trim::try_signed_distance), positive where it
/// keeps P); against the background, where P keeps more than the rim's reach at each of its
/// own texels about the pixel, its outline ends it there and the pixel fails before P is
/// sought off them. The pixel is drawn right when:
///
/// - P meets every centre's ray, and the quadratic of `f` over the box
///   ([`BoxQuadratic`]) stays on one side of 0 over it, or crosses it straight within
///   [`SMOOTH_BEND`] and [`JUMP`] ([`BoxQuadratic::crossing`]); its cover of the box
///   ([`BoxQuadratic::coverage_above`]) is P's share of the pixel;
/// - each centre shows P where `f > 0` there and the other thing where `f ≤ 0`, or either
///   within [`RIM_SLACK`] of the rim;
/// - over the part P covers, P's highlight and band edges are clear of the box (the
///   quadratics of their values at P's nine points, as
///   [`highlight_edges`](super::highlight_edge::highlight_edges) and
///   [`band_edges`](super::band_edge::band_edges) take them); over the rest, Q meets every
///   centre's ray behind P, its own trim keeps the whole box, and its edges are clear of it.
///
/// Where the rim crosses the box, P's own texels among the nine are found again on their rays
/// (the G-buffer's frames may be interpolated, a few hundredths of a pixel off) and the cover
/// taken again from them; the pixel's colour is then P's at the centre over its cover and the
/// other thing's over the rest ([`composite`]). Elsewhere it is the centre's own. An uncovered
/// pixel whose nine are all uncovered, beside crossed pixels with the background beyond, is
/// drawn right too where each of their rims, carried to its box
/// ([`BoxQuadratic::moved_to`]), stays on the cut side over it.
#[must_use]
pub(in crate::render) fn find_trim_edges(
    gbuffer: &GBuffer,
    scene: &Scene,
    view_projection: Mat4,
    drawn: &[bool],
) -> Option<TrimEdges> {
    let library = scene.library;
    let (w, h) = (gbuffer.width as usize, gbuffer.height as usize);
    if !library.patches.iter().any(|p| p.trim.is_some()) || w < 3 || h < 3 {
        return None;
    }
    let candidates = candidates(gbuffer, scene, drawn);
    let mut edges = TrimEdges {
        drawn: vec![false; w * h],
        judged: candidates.len() as u64,
        ..TrimEdges::default()
    };
    if candidates.is_empty() {
        return Some(edges);
    }
    let mut asked = Asked::of(&candidates, (w, h));
    asked.by_patch(library.patches.len());
    let mut samples = Samples::start(gbuffer, library, &asked.wanted);
    let outline = ended_by_outline(gbuffer, &candidates, &asked, &samples);
    let view = (scene, view_projection);
    edges.frames = samples.seek_off_patch(gbuffer, view, (&candidates, &outline), &asked);
    let signed = signed_values_of(&samples.probes, scene);
    let judged = (candidates.as_slice(), outline.as_slice(), &asked, &signed);
    let crossings = judge(gbuffer, scene, judged, &samples, &mut edges.drawn);
    settle_crossings(
        gbuffer,
        view,
        &crossings,
        (&mut samples, &signed),
        &mut edges,
    );
    draw_beside_crossed(gbuffer, &mut edges);
    Some(edges)
}

/// What pixel `n` of `gbuffer` shows: its patch, or [`EMPTY`].
#[must_use]
fn patch_shown(gbuffer: &GBuffer, n: usize) -> u32 {
    let slot = gbuffer.slot[n];
    if slot == EMPTY {
        EMPTY
    } else {
        gbuffer.texels[slot as usize].patch
    }
}

/// The candidates ([`candidate`]) among the pixels of `gbuffer` not yet `drawn` right (per
/// texel).
///
/// A candidate's nine show its trimmed patch P beside another thing, so some texel of P
/// among them has the other thing in its own nine: its neighbourhood is not all on its
/// patch, and it is not drawn right. The candidates lie within the 3 × 3 neighbourhoods of
/// such texels, and are tried in pixel order.
fn candidates(gbuffer: &GBuffer, scene: &Scene, drawn: &[bool]) -> Vec<Candidate> {
    let library = scene.library;
    let (w, h) = (gbuffer.width as usize, gbuffer.height as usize);
    let beside_other: Vec<u32> = drawn
        .par_iter()
        .enumerate()
        .filter(|&(_, &d)| !d)
        .map(|(slot, _)| &gbuffer.texels[slot])
        .filter(|t| {
            trimmed(scene, t.patch)
                && cel(scene, t.patch)
                && around(t.pixel as usize, (w, h)).any(|n| patch_shown(gbuffer, n) != t.patch)
        })
        .map(|t| t.pixel)
        .collect();
    let mut near = vec![false; w * h];
    let mut nearby: Vec<u32> = Vec::new();
    for &pixel in &beside_other {
        for n in around(pixel as usize, (w, h)) {
            if !near[n] {
                near[n] = true;
                nearby.push(n as u32);
            }
        }
    }
    nearby.sort_unstable();
    // Per texel, whether it lies away from its domain's sides (`away_from_borders`) once asked:
    // 0 not yet, 1 away, 2 near.
    let away: Vec<AtomicU8> = (0..gbuffer.texels.len())
        .map(|_| AtomicU8::new(0))
        .collect();
    let away_from_sides = |slot: u32| match away[slot as usize].load(Ordering::Relaxed) {
        1 => true,
        2 => false,
        _ => {
            let is_away = away_from_borders(gbuffer, library, slot);
            away[slot as usize].store(if is_away { 1 } else { 2 }, Ordering::Relaxed);
            is_away
        }
    };
    nearby
        .par_iter()
        .filter_map(|&p| candidate(gbuffer, scene, drawn, &away_from_sides, p as usize))
        .collect()
}

/// The samples the candidates ask for, each surface at each pixel once.
struct Asked {
    /// Per pixel, 1 + the index of its entry in `entries` (0 for none).
    at: Vec<u32>,
    /// Up to two (surface, sample) pairs a pixel, ([`EMPTY`], [`EMPTY`]) for none.
    entries: Vec<[(u32, u32); 2]>,
    /// Per sample: its pixel, its surface, and the candidate that asked for it.
    wanted: Vec<(usize, u32, usize)>,
}

impl Asked {
    /// The samples: each surface a candidate needs at each of its nine centres, once. Per
    /// pixel, 1 + the index of its entry in `asked` (0 for none: the pages of an image of
    /// zeros not written to are never touched), which holds up to two (surface, sample) pairs.
    fn of(candidates: &[Candidate], (w, h): (usize, usize)) -> Self {
        let mut asked_at = vec![0u32; w * h];
        let mut asked: Vec<[(u32, u32); 2]> = Vec::new();
        let mut wanted: Vec<(usize, u32, usize)> = Vec::new();
        for candidate in candidates {
            for n in around(candidate.pixel as usize, (w, h)) {
                for surface in [candidate.front, candidate.other] {
                    if surface == EMPTY {
                        continue;
                    }
                    if asked_at[n] == 0 {
                        asked.push([(EMPTY, EMPTY); 2]);
                        asked_at[n] = asked.len() as u32;
                    }
                    let entry = &mut asked[asked_at[n] as usize - 1];
                    if entry.iter().any(|e| e.0 == surface) {
                        continue;
                    }
                    // A third surface asked of one pixel is not sampled: its candidate fails.
                    if let Some(free) = entry.iter_mut().find(|e| e.0 == EMPTY) {
                        *free = (surface, wanted.len() as u32);
                        wanted.push((n, surface, candidate.pixel as usize));
                    }
                }
            }
        }
        Self {
            at: asked_at,
            entries: asked,
            wanted,
        }
    }

    /// The samples patch by patch, each patch's in the order asked: as asked, the two surfaces
    /// of a pixel alternate, and the probes and signed values below, taken a run of one patch
    /// at a time, would find runs of one. Each patch's run starts after the runs of those
    /// before it (a counting sort) among the `patches`.
    fn by_patch(&mut self, patches: usize) {
        let wanted = &self.wanted;
        let mut next = vec![0u32; patches];
        for &(_, surface, _) in wanted {
            next[surface as usize] += 1;
        }
        let mut first = 0;
        for count in &mut next {
            (*count, first) = (first, first + *count);
        }
        let mut renumbered = vec![0u32; wanted.len()];
        for (at, &(_, surface, _)) in renumbered.iter_mut().zip(wanted) {
            *at = next[surface as usize];
            next[surface as usize] += 1;
        }
        for entry in self.entries.iter_mut().flatten().filter(|e| e.0 != EMPTY) {
            entry.1 = renumbered[entry.1 as usize];
        }
        let mut by_patch = vec![(0, 0, 0); wanted.len()];
        for (&at, &sample) in renumbered.iter().zip(wanted) {
            by_patch[at as usize] = sample;
        }
        self.wanted = by_patch;
    }

    /// The sample asked of `surface` at pixel `n`.
    fn entry(&self, n: usize, surface: u32) -> Option<usize> {
        let entry = self.entries.get((self.at[n] as usize).checked_sub(1)?)?;
        entry.iter().find(|e| e.0 == surface).map(|e| e.1 as usize)
    }
}

/// The samples asked for, as probes, with their trims.
struct Samples {
    probes: Vec<Texel>,
    /// Per probe, the reach of (u, v) over a pixel there ([`start`]).
    uv_reach: Vec<f64>,
    /// Per probe, whether it is on its pixel's ray: its pixel's own texel, or a probe found
    /// there.
    landed: Vec<bool>,
    /// The probes started off their pixel's own texel, to be moved onto their rays.
    foreign: Vec<usize>,
    /// Per probe, its trim's signed distance and the reach it was sought within.
    trim: Vec<Option<(f64, f64)>>,
}

impl Samples {
    /// A centre that shows the surface is its own sample; another is the surface found on the
    /// centre's ray from the surface's nearest texel (a probe). The own samples' trims now;
    /// those off the patch once they are on their rays.
    fn start(gbuffer: &GBuffer, library: &PatchLibrary, wanted: &[(usize, u32, usize)]) -> Self {
        let started: Vec<Option<(Texel, f64, bool)>> = wanted
            .par_iter()
            .map(|&(n, surface, pixel)| start(gbuffer, library, pixel, n, surface))
            .collect();
        let mut probes: Vec<Texel> = Vec::with_capacity(started.len());
        let mut uv_reach: Vec<f64> = Vec::with_capacity(started.len());
        let mut landed: Vec<bool> = Vec::with_capacity(started.len());
        let mut foreign: Vec<u32> = Vec::new();
        for (k, start) in started.into_iter().enumerate() {
            // Without a start (not reached: a candidate's surfaces are seen about it) the
            // sample is missing, as one whose ray misses its surface.
            let (texel, reach, own, found) = match start {
                Some((texel, reach, own)) => (texel, reach, own, true),
                None => (UNFILLED, 0.0, true, false),
            };
            if !own {
                foreign.push(k as u32);
            }
            probes.push(texel);
            uv_reach.push(reach);
            landed.push(own && found);
        }
        let foreign: Vec<usize> = foreign.into_iter().map(|k| k as usize).collect();
        let mut off_patch = vec![false; probes.len()];
        for &k in &foreign {
            off_patch[k] = true;
        }
        let trim: Vec<Option<(f64, f64)>> = probes
            .par_iter()
            .zip(&uv_reach)
            .zip(&off_patch)
            .map(|((t, &uv_reach), &off)| {
                if off {
                    None
                } else {
                    trim_at(library, t, uv_reach)
                }
            })
            .collect();
        Self {
            probes,
            uv_reach,
            landed,
            foreign,
            trim,
        }
    }

    /// The sample asked of `surface` at pixel `n` where it landed on its ray.
    fn find(&self, asked: &Asked, n: usize, surface: u32) -> Option<usize> {
        asked.entry(n, surface).filter(|&k| self.landed[k])
    }

    /// The probes off their pixel's own texel that the `candidates` not ended by their
    /// `outline` ask for, moved onto their rays ([`onto_rays`]) and their trims taken there;
    /// the others are not sought, and are left out of `foreign`. Returns the frames evaluated.
    fn seek_off_patch(
        &mut self,
        gbuffer: &GBuffer,
        (scene, view_projection): (&Scene, Mat4),
        (candidates, outline): (&[Candidate], &[bool]),
        asked: &Asked,
    ) -> u64 {
        let (w, h) = (gbuffer.width as usize, gbuffer.height as usize);
        let mut sought = vec![false; self.probes.len()];
        for (c, _) in candidates.iter().zip(outline).filter(|(_, &o)| !o) {
            for n in around(c.pixel as usize, (w, h)) {
                for surface in [c.front, c.other] {
                    if let Some(k) = asked.entry(n, surface).filter(|_| surface != EMPTY) {
                        sought[k] = true;
                    }
                }
            }
        }
        let foreign: Vec<usize> = std::mem::take(&mut self.foreign)
            .into_iter()
            .filter(|&k| sought[k])
            .collect();
        let (found, frames) =
            onto_rays(gbuffer, scene, view_projection, &mut self.probes, &foreign);
        for (&k, found) in foreign.iter().zip(found) {
            self.landed[k] = found;
        }
        let library = scene.library;
        let found_trims: Vec<Option<(f64, f64)>> = foreign
            .par_iter()
            .map(|&k| trim_at(library, &self.probes[k], self.uv_reach[k]))
            .collect();
        for (&k, value) in foreign.iter().zip(found_trims) {
            self.trim[k] = value;
        }
        self.foreign = foreign;
        frames
    }
}

/// Per probe `t`, its trim's signed distance and the reach it was sought within: `TRIM_REACH`
/// times `uv_reach`, the reach of (u, v) over a pixel there.
#[must_use]
fn trim_at(library: &PatchLibrary, t: &Texel, uv_reach: f64) -> Option<(f64, f64)> {
    let Some(trim) = &library.patches[t.patch as usize].trim else {
        return Some((f64::INFINITY, f64::INFINITY));
    };
    // Without a reach (no slope of (u, v) to take it from) the rim cannot be placed.
    let reach = TRIM_REACH * uv_reach;
    if reach.is_nan() || reach <= 0.0 {
        return None;
    }
    let (u, v) = (f64::from(t.uv.x), f64::from(t.uv.y));
    Some((trim.try_signed_distance(u, v, reach)?, reach))
}

/// Per candidate, whether its outline ends it: a candidate against the background where the
/// trimmed patch keeps, at each of its own texels about the pixel, more than the rim's reach
/// (four pixels): the rim cannot reach the background's centres, a pixel or so away, and what
/// ends the patch there is its outline. The judgement would fail; its samples off the patch
/// are not sought.
fn ended_by_outline(
    gbuffer: &GBuffer,
    candidates: &[Candidate],
    asked: &Asked,
    samples: &Samples,
) -> Vec<bool> {
    let (w, h) = (gbuffer.width as usize, gbuffer.height as usize);
    candidates
        .par_iter()
        .map(|c| {
            c.other == EMPTY
                && around(c.pixel as usize, (w, h)).all(|n| {
                    if patch_shown(gbuffer, n) != c.front {
                        return true;
                    }
                    let Some(k) = asked.entry(n, c.front) else {
                        return false;
                    };
                    matches!(samples.trim[k], Some((d, reach)) if d >= reach)
                })
        })
        .collect()
}

/// A pixel the rim crosses: the pixel, what its cut part shows at the centre (`None`: the
/// background), and the trimmed patch's samples at its nine centres.
type Crossing = (u32, Option<Texel>, [usize; 9]);

/// Judges each of the `candidates` not ended by their `outline` ([`find_trim_edges`]) and
/// marks those drawn right in `drawn` (per pixel); the pixels the rim crosses: (pixel, what
/// lies beyond, the trimmed patch's samples).
fn judge(
    gbuffer: &GBuffer,
    scene: &Scene,
    (candidates, outline, asked, signed): (&[Candidate], &[bool], &Asked, &SignedValues),
    samples: &Samples,
    drawn: &mut [bool],
) -> Vec<Crossing> {
    let (w, h) = (gbuffer.width as usize, gbuffer.height as usize);
    let probes = &samples.probes;
    let find = |n: usize, surface: u32| samples.find(asked, n, surface);
    let judged: Vec<Option<DrawnCandidate>> = candidates
        .par_iter()
        .zip(outline)
        .map(|(candidate, &outline)| {
            if outline {
                return None;
            }
            let pixel = candidate.pixel as usize;
            let mut front = [0usize; 9];
            for (slot, n) in front.iter_mut().zip(around(pixel, (w, h))) {
                *slot = find(n, candidate.front)?;
            }
            let surface = |probes_of: &[usize; 9]| Surface {
                probes,
                signed,
                trim: &samples.trim,
                indices: *probes_of,
            };
            let front_surface = surface(&front);
            let cover = front_surface.kept_cover()?;
            // Each centre sees the trimmed patch where its trim keeps it, the other thing where
            // it does not, or either within `RIM_SLACK` of the rim.
            for (k, n) in around(pixel, (w, h)).enumerate() {
                let (distance, reach) = front_surface.trim_value(k)?;
                let seen = patch_shown(gbuffer, n);
                let on_rim = distance.abs() * TRIM_REACH < RIM_SLACK * reach;
                let expected = if distance > 0.0 {
                    candidate.front
                } else {
                    candidate.other
                };
                if !(seen == expected || on_rim) {
                    return None;
                }
            }
            if cover > 0.0 && !front_surface.clear_of_box(scene) {
                return None;
            }
            let beyond = if candidate.other == EMPTY || cover == 1.0 {
                None
            } else {
                let mut behind = [0usize; 9];
                for (slot, n) in behind.iter_mut().zip(around(pixel, (w, h))) {
                    *slot = find(n, candidate.other)?;
                }
                let behind_surface = surface(&behind);
                let behind_everywhere =
                    (0..9).all(|k| probes[behind[k]].depth > probes[front[k]].depth);
                if !(behind_everywhere
                    && behind_surface.kept_cover() == Some(1.0)
                    && behind_surface.clear_of_box(scene))
                {
                    return None;
                }
                Some(probes[behind[4]])
            };
            // A pixel the rim crosses, with what its cut part shows at the centre.
            let crossing = (cover > 0.0 && cover < 1.0).then_some(beyond);
            Some((crossing, front))
        })
        .collect();
    let mut crossings = Vec::new();
    for (candidate, judged) in candidates.iter().zip(judged) {
        if let Some((crossing, front)) = judged {
            drawn[candidate.pixel as usize] = true;
            if let Some(beyond) = crossing {
                crossings.push((candidate.pixel, beyond, front));
            }
        }
    }
    crossings
}

/// Where the rim crosses a pixel, the trimmed patch's own texels about it are found again
/// on their rays (the G-buffer's may be interpolated from the mesh, a few hundredths of a
/// pixel off), and the cover taken again from them: each of the `crossings` that keeps a
/// crossing rim is one of `edges.crossed`, the others are not drawn right.
fn settle_crossings(
    gbuffer: &GBuffer,
    (scene, view_projection): (&Scene, Mat4),
    crossings: &[Crossing],
    (samples, signed): (&mut Samples, &SignedValues),
    edges: &mut TrimEdges,
) {
    let mut settle = vec![false; samples.probes.len()];
    for &k in crossings.iter().flat_map(|(_, _, front)| front) {
        settle[k] = true;
    }
    for &k in &samples.foreign {
        settle[k] = false;
    }
    let settled: Vec<usize> = (0..samples.probes.len()).filter(|&k| settle[k]).collect();
    let (found, frames) = onto_rays(
        gbuffer,
        scene,
        view_projection,
        &mut samples.probes,
        &settled,
    );
    edges.frames += frames;
    let library = scene.library;
    let settled_trims: Vec<Option<(f64, f64)>> = settled
        .par_iter()
        .zip(found)
        .map(|(&k, found)| {
            found
                .then(|| trim_at(library, &samples.probes[k], samples.uv_reach[k]))
                .flatten()
        })
        .collect();
    for (&k, value) in settled.iter().zip(settled_trims) {
        samples.trim[k] = value;
    }
    let crossed: Vec<Option<Crossed>> = crossings
        .par_iter()
        .map(|&(pixel, beyond, front)| {
            let surface = Surface {
                probes: &samples.probes,
                signed,
                trim: &samples.trim,
                indices: front,
            };
            match surface.kept_cover_and_rim() {
                Some((cover, Some(rim))) => Some(Crossed {
                    pixel,
                    cover,
                    kept: samples.probes[front[4]],
                    beyond,
                    rim,
                }),
                Some((_, None)) | None => None,
            }
        })
        .collect();
    for (&(pixel, _, _), crossed) in crossings.iter().zip(crossed) {
        match crossed {
            Some(crossed) => edges.crossed.push(crossed),
            None => edges.drawn[pixel as usize] = false,
        }
    }
}

/// An uncovered pixel whose nine are all uncovered, beside pixels the rim crosses, shows
/// the background when each of their rims, carried over to its box, stays cut over it: per
/// crossed pixel, the neighbours it tries and whether its rim stays cut over each. Those every
/// crossed pixel beside them draws right are drawn right.
fn draw_beside_crossed(gbuffer: &GBuffer, edges: &mut TrimEdges) {
    let (w, h) = (gbuffer.width as usize, gbuffer.height as usize);
    let tried: Vec<(u32, bool)> = edges
        .crossed
        .par_iter()
        .filter(|c| c.beyond.is_none())
        .flat_map_iter(|crossed| {
            let c = crossed.pixel as usize;
            around(c, (w, h))
                .filter(move |&n| n != c)
                .filter(|&n| {
                    let (x, y) = (n % w, n / w);
                    x > 0 && y > 0 && x + 1 < w && y + 1 < h && !edges.drawn[n]
                })
                .map(move |n| {
                    let empty = around(n, (w, h)).all(|m| patch_shown(gbuffer, m) == EMPTY);
                    let d = |a: usize, b: usize| a as f32 - b as f32;
                    let moved = crossed.rim.moved_to(d(n % w, c % w), d(n / w, c / w));
                    let cut = moved.centre + moved.reach() < 0.0;
                    (n as u32, empty && cut)
                })
        })
        .collect();
    // 0 untried, 1 drawn right by every crossed pixel so far, 2 not.
    let mut beside = vec![0u8; w * h];
    for &(n, right) in &tried {
        let b = &mut beside[n as usize];
        *b = if right && *b != 2 { 1 } else { 2 };
    }
    for (drawn, &b) in edges.drawn.iter_mut().zip(&beside) {
        *drawn |= b == 1;
    }
}

/// The pixel `pixel`'s candidacy ([`find_trim_edges`]): not drawn right yet, inside the image by a
/// pixel, its nine showing a trimmed patch with a cel tone and one other thing, the
/// background or a patch with a cel tone whose texels all lie behind the trimmed patch's, and
/// the trimmed patch's texels there away from its domain's sides (`away_from_sides`, per slot).
fn candidate(
    gbuffer: &GBuffer,
    scene: &Scene,
    drawn: &[bool],
    away_from_sides: &impl Fn(u32) -> bool,
    pixel: usize,
) -> Option<Candidate> {
    let (w, h) = (gbuffer.width as usize, gbuffer.height as usize);
    let (x, y) = (pixel % w, pixel / w);
    if x == 0 || y == 0 || x + 1 >= w || y + 1 >= h {
        return None;
    }
    if gbuffer.slot[pixel] != EMPTY && drawn[gbuffer.slot[pixel] as usize] {
        return None;
    }
    // The two things seen (what the pixel shows, and another), before their depths.
    let own = patch_shown(gbuffer, pixel);
    let mut other = None;
    for n in around(pixel, (w, h)) {
        let seen = patch_shown(gbuffer, n);
        if seen == own || other == Some(seen) {
            continue;
        }
        if other.is_some() {
            return None;
        }
        other = Some(seen);
    }
    let other = other?;
    // Each thing's nearest and farthest depth.
    let mut seen = [
        (own, f32::INFINITY, f32::NEG_INFINITY),
        (other, f32::INFINITY, f32::NEG_INFINITY),
    ];
    for n in around(pixel, (w, h)) {
        let Some(t) = gbuffer.texel(n) else {
            continue;
        };
        let s = if t.patch == own {
            &mut seen[0]
        } else {
            &mut seen[1]
        };
        s.1 = s.1.min(t.depth);
        s.2 = s.2.max(t.depth);
    }
    let (front, other) = match (seen[0].0, seen[1].0) {
        (EMPTY, p) | (p, EMPTY) => (p, EMPTY),
        // Both patches: the nearer in front, wholly.
        _ if seen[0].2 < seen[1].1 => (seen[0].0, seen[1].0),
        _ if seen[1].2 < seen[0].1 => (seen[1].0, seen[0].0),
        _ => return None,
    };
    let other_ok = other == EMPTY || cel(scene, other);
    if !(trimmed(scene, front) && cel(scene, front) && other_ok) {
        return None;
    }
    // Beside the side of its domain, a patch ends there, not at its trim.
    let inside = around(pixel, (w, h))
        .all(|n| patch_shown(gbuffer, n) != front || away_from_sides(gbuffer.slot[n]));
    inside.then_some(Candidate {
        pixel: pixel as u32,
        front,
        other,
    })
}

/// Whether `patch` of `scene` has a trim.
fn trimmed(scene: &Scene, patch: u32) -> bool {
    scene.library.patches[patch as usize].trim.is_some()
}

/// Whether `patch` of `scene` has a cel tone.
fn cel(scene: &Scene, patch: u32) -> bool {
    matches!(scene.looks[patch as usize].tone, Tone::Cel(_))
}

/// Moves each of the `probes` numbered in `which` onto its pixel's ray in the image of
/// `gbuffer` (`GBuffer::evaluate_frames`, refined, within a probe's evaluations) and sets its
/// depth where it lands there ([`landed_depth`]); a probe that does not land keeps the
/// frame it was given. Per probe of `which`, whether it landed, and the frames evaluated.
fn onto_rays(
    gbuffer: &GBuffer,
    scene: &Scene,
    view_projection: Mat4,
    probes: &mut [Texel],
    which: &[usize],
) -> (Vec<bool>, u64) {
    let mut searched: Vec<Texel> = which.iter().map(|&k| probes[k]).collect();
    let size = (gbuffer.width, gbuffer.height);
    let frames = GBuffer::evaluate_frames(
        &mut searched,
        scene.library,
        &scene.camera,
        view_projection,
        size,
        FrameMode::Refined,
        Evaluate::QuickProbe,
    );
    let found = which
        .iter()
        .zip(searched)
        .map(|(&k, mut t)| {
            let depth = landed_depth(view_projection, t.position, t.pixel, size);
            if let Some(depth) = depth {
                t.depth = depth;
                probes[k] = t;
            }
            depth.is_some()
        })
        .collect();
    (found, frames)
}

/// The sample of `patch` on the ray of pixel `n`, about candidate `pixel`, with the reach of
/// (u, v) over a pixel there and whether it is the texel of `n` itself: that texel when it
/// shows the patch, else the start of a probe, the patch's texel in `pixel`'s neighbourhood
/// nearest `n` with its (u, v) moved by its slopes to `n` and held in the patch's domain;
/// `None` where the neighbourhood does not show the patch.
fn start(
    gbuffer: &GBuffer,
    library: &PatchLibrary,
    pixel: usize,
    n: usize,
    patch: u32,
) -> Option<(Texel, f64, bool)> {
    let (w, h) = (gbuffer.width as usize, gbuffer.height as usize);
    let reach = |(x, y): (Option<Vec2>, Option<Vec2>)| {
        let (x, y) = (x.unwrap_or_default(), y.unwrap_or_default());
        0.5 * f64::from(x.length() + y.length())
    };
    if let Some(t) = gbuffer.texel(n).filter(|t| t.patch == patch) {
        return Some((*t, reach(uv_slopes(gbuffer, gbuffer.slot[n])), true));
    }
    let at = |p: usize| DVec2::new((p % w) as f64, (p / w) as f64);
    let seed = around(pixel, (w, h))
        .filter(|&m| gbuffer.texel(m).is_some_and(|t| t.patch == patch))
        .min_by(|&a, &b| {
            at(a)
                .distance_squared(at(n))
                .total_cmp(&at(b).distance_squared(at(n)))
        })
        .map(|m| gbuffer.slot[m]);
    let slot = seed?;
    let t = gbuffer.texels[slot as usize];
    // Where the neighbourhood shows both sides of the patch (it folds over there), a probe that
    // lands on the back may have crossed to the far sheet ([`Texel::back`]).
    let back = around(pixel, (w, h))
        .filter_map(|m| gbuffer.texel(m))
        .all(|m| m.patch != patch || m.back);
    let slopes = uv_slopes(gbuffer, slot);
    let (along_x, along_y) = slopes;
    let offset = (at(n) - at(t.pixel as usize)).as_vec2();
    let uv = t.uv + along_x.unwrap_or_default() * offset.x + along_y.unwrap_or_default() * offset.y;
    let domain = library.patches[patch as usize].surface.domain();
    let texel = Texel {
        pixel: n as u32,
        uv: Vec2::new(
            uv.x.clamp(domain.u.0 as f32, domain.u.1 as f32),
            uv.y.clamp(domain.v.0 as f32, domain.v.1 as f32),
        ),
        back,
        ..t
    };
    Some((texel, reach(slopes), false))
}

/// One surface at the nine centres about a pixel: its probes, by index.
struct Surface<'a> {
    probes: &'a [Texel],
    signed: &'a SignedValues<'a>,
    /// Per probe, its trim's signed distance and the reach it was sought within.
    trim: &'a [Option<(f64, f64)>],
    indices: [usize; 9],
}

impl Surface<'_> {
    /// The probe at centre `k` (row by row, the pixel's own at 4).
    fn at(&self, k: usize) -> &Texel {
        &self.probes[self.indices[k]]
    }

    /// The trim's signed distance at centre `k` and the reach it was sought within
    /// ([`Trim::try_signed_distance`](crate::geom::Trim::try_signed_distance); infinite on an
    /// untrimmed patch); `None` where the search was refused.
    fn trim_value(&self, k: usize) -> Option<(f64, f64)> {
        self.trim[self.indices[k]]
    }

    /// The fraction of the box the surface's trim keeps: 1 or 0 where its rim stays clear of
    /// the box, the quadratic's cover where the rim crosses it straight enough, `None`
    /// otherwise (a bend, a jump, a corner, or a rim too near to tell from its reach).
    fn kept_cover(&self) -> Option<f32> {
        self.kept_cover_and_rim().map(|(cover, _)| cover)
    }

    /// [`kept_cover`](Self::kept_cover), and the quadratic of the trim's signed distance over
    /// the box where its rim is near enough to be taken from it.
    fn kept_cover_and_rim(&self) -> Option<(f32, Option<BoxQuadratic>)> {
        let mut f = [[0.0f64; 3]; 3];
        let mut beyond_reach = false;
        for (k, value) in f.iter_mut().flatten().enumerate() {
            let (distance, reach) = self.trim_value(k)?;
            *value = distance;
            beyond_reach |= distance.abs() >= reach;
        }
        let (centre, reach) = self.trim_value(4)?;
        if centre == f64::INFINITY {
            return Some((1.0, None));
        }
        // A value at its reach is farther than the search looked: the rim is far from that
        // centre, and the quadratic would not follow it. Clear when far from the pixel's own.
        if beyond_reach {
            let clear = centre.abs() > 0.5 * reach;
            return clear.then_some((if centre > 0.0 { 1.0 } else { 0.0 }, None));
        }
        let q = BoxQuadratic::through(&f.map(|row| row.map(|v| v as f32)));
        let spread = q.reach();
        if !(spread.is_finite() && q.centre.is_finite()) {
            return None;
        }
        let cover = if q.centre - spread > 0.0 {
            1.0
        } else if q.centre + spread < 0.0 {
            0.0
        } else {
            match q.crossing(0.0, SMOOTH_BEND, JUMP)? {
                LevelCrossing::Straight => q.coverage_above(0.0),
                LevelCrossing::Bent => return None,
            }
        };
        Some((cover, Some(q)))
    }

    /// Whether the surface's highlight edges and its cel tone's band edges are clear of the
    /// box, from their values at the nine probes.
    fn clear_of_box(&self, scene: &Scene) -> bool {
        let t = self.at(4);
        let Tone::Cel(ramp) = &scene.looks[t.patch as usize].tone else {
            return false;
        };
        let n_dot_l = std::array::from_fn(|y| {
            std::array::from_fn(|x| {
                let t = self.at(3 * y + x);
                scene.tone_n_dot_l(t.patch, &t.frame, t.uv, t.position)
            })
        });
        let layers = &self.signed.layers[t.patch as usize];
        band_clear_of_box(ramp, &n_dot_l)
            && highlights_clear_of_box(layers, |j| {
                std::array::from_fn(|y| {
                    std::array::from_fn(|x| self.signed.at(self.indices[3 * y + x], j))
                })
            })
    }
}

/// How far, in multiples of the box's reach in (u, v), the trim's rim is looked for about each
/// of the nine centres: a rim that crosses the box lies within about one of every centre.
const TRIM_REACH: f64 = 4.0;

/// How near the rim, in pixels (as the box's reach in (u, v) measures them), a centre may show
/// either side of it ([`find_trim_edges`]). The rasterizer tests the trim at the (u, v) the mesh's
/// triangles interpolate, and a centre the exact trim keeps just inside the rim may show the
/// other thing: over five frames of the speaker at 1280 × 720 under `final`, 602 of the 606
/// centres that did lay within 0.1 pixels of the rim (the other 4 beyond 0.3), and on the car
/// panels all 188 within 0.01. Only the trimmed patch and the other thing are seen about a
/// candidate, and both are sampled at every centre, so the pixel takes the rim's place from
/// the exact trim, not from the mesh.
const RIM_SLACK: f64 = 0.125;

/// Draws the pixels of `edges` a rim crosses in `shaded`: the premultiplied mix
/// `cover · kept + (1 − cover) · beyond` of the colours (and the matte and `N·H`) of the two
/// samples at the pixel's centre, shaded as `shade` shades ([`find_trim_edges`]); nothing beyond is
/// the background, transparent.
pub(in crate::render) fn composite(
    edges: &TrimEdges,
    shade: impl FnOnce(&GBuffer) -> Shaded,
    shaded: &mut Shaded,
) {
    if edges.crossed.is_empty() {
        return;
    }
    // Two pixels a crossed one, side by side: its kept sample, then what lies beyond.
    let mut samples = GBuffer {
        width: 2,
        height: edges.crossed.len() as u32,
        slot: vec![EMPTY; 2 * edges.crossed.len()],
        texels: Vec::with_capacity(2 * edges.crossed.len()),
    };
    for (j, crossed) in edges.crossed.iter().enumerate() {
        for (side, texel) in [Some(crossed.kept), crossed.beyond].into_iter().enumerate() {
            if let Some(texel) = texel {
                samples.slot[2 * j + side] = samples.texels.len() as u32;
                samples.texels.push(Texel {
                    pixel: (2 * j + side) as u32,
                    ..texel
                });
            }
        }
    }
    let two = shade(&samples);
    for (j, crossed) in edges.crossed.iter().enumerate() {
        let (a, b) = (2 * j, 2 * j + 1);
        let c = crossed.cover;
        let p = crossed.pixel as usize;
        let colour: Vec4 =
            premultiplied(two.colour[a]) * c + premultiplied(two.colour[b]) * (1.0 - c);
        shaded.colour[p] = straight(colour);
        if let (Some(matte), Some(m)) = (shaded.matte.as_mut(), two.matte.as_ref()) {
            matte[p] = m[a] * c + m[b] * (1.0 - c);
        }
        if let (Some(n_dot_h), Some(n)) = (shaded.n_dot_h.as_mut(), two.n_dot_h.as_ref()) {
            n_dot_h[p] = n[a] * c + n[b] * (1.0 - c);
        }
        if let (Some(n_dot_l), Some(n)) = (shaded.n_dot_l.as_mut(), two.n_dot_l.as_ref()) {
            n_dot_l[p] = n[a] * c + n[b] * (1.0 - c);
        }
    }
}
