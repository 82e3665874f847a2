//! Chains: pieces joined end to end into lines, along which visibility is decided as a whole,
//! so that a line neither breaks into dots nor keeps stray ones where a nearer surface almost
//! touches it.

use crate::render::FastMap;

use glam::DVec3;

use super::occlusion::Occluders;
use super::piece::{OnScreen, Piece};
use super::stroke::Capsule;
use super::visible::DepthTest;

/// Samples along a line are at most this many pixels apart.
const STEP: f32 = 0.5;

/// The most samples one piece is cut into (only a piece reaching far outside the image is
/// longer than this many steps).
const MOST_SAMPLES: f32 = 16384.0;

/// A hidden stretch of a line shorter than this (pixels), between two visible ones, is drawn:
/// no surface nearer than the line is that thin on the image and worth a gap in it.
const SHORTEST_GAP: f32 = 3.0;

/// A visible stretch of a line shorter than this (pixels), hidden on both sides, is not drawn:
/// it would be a dot.
const SHORTEST_STROKE: f32 = 2.0;

/// Pieces joined end to end into one line.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Chain {
    /// `(piece, reversed)` in order along the line, consecutive pieces sharing an end point.
    pub pieces: Vec<(usize, bool)>,
    /// Whether the line closes on itself: its last piece ends where its first begins.
    pub closed: bool,
}

/// The pieces joined into chains. Ends closer than [`SAME_POINT`] of the model's extent are
/// one point: two patches find the silhouette's crossing of the seam they share each on its
/// own surface, a rounding error apart. A chain stops where three or more pieces meet; every
/// piece is in one chain.
#[must_use]
pub(crate) fn chains(pieces: &[Piece]) -> Vec<Chain> {
    let point_ids = same_points(pieces);
    let key = |p: usize, end: usize| point_ids[2 * p + end];
    // The ends at each point, `(piece, end)`: those of point `i` at `at[first[i]..first[i + 1]]`.
    let points = point_ids.iter().max().map_or(0, |&m| m + 1);
    let mut first = vec![0usize; points + 1];
    for &id in &point_ids {
        first[id + 1] += 1;
    }
    for i in 0..points {
        first[i + 1] += first[i];
    }
    let mut filled = first.clone();
    let mut at = vec![(0usize, 0usize); point_ids.len()];
    for (k, &id) in point_ids.iter().enumerate() {
        at[filled[id]] = (k / 2, k % 2);
        filled[id] += 1;
    }
    let ends_at = |id: usize| &at[first[id]..first[id + 1]];
    let mut used = vec![false; pieces.len()];
    // The piece continuing a line from the end point of `(piece, end)`, if exactly one other
    // piece ends there and it is unused: `(piece, end it enters by)`.
    let next = |used: &[bool], piece: usize, end: usize| -> Option<(usize, usize)> {
        match *ends_at(key(piece, end)) {
            [a, b] => {
                let other = if a.0 == piece { b } else { a };
                (other.0 != piece && !used[other.0]).then_some(other)
            }
            _ => None,
        }
    };
    let mut out = Vec::new();
    for start in 0..pieces.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let mut forward = vec![(start, false)];
        let mut end = (start, 1);
        while let Some((piece, entered)) = next(&used, end.0, end.1) {
            used[piece] = true;
            forward.push((piece, entered == 1));
            end = (piece, 1 - entered);
        }
        let mut backward = Vec::new();
        let mut end = (start, 0);
        while let Some((piece, entered)) = next(&used, end.0, end.1) {
            used[piece] = true;
            backward.push((piece, entered == 0));
            end = (piece, 1 - entered);
        }
        backward.reverse();
        backward.extend(forward);
        // The point the line starts from and the one it ends at.
        let start = backward[0];
        let finish = backward[backward.len() - 1];
        let closed = backward.len() > 1
            && key(start.0, usize::from(start.1)) == key(finish.0, usize::from(!finish.1));
        out.push(Chain {
            pieces: backward,
            closed,
        });
    }
    out
}

/// Ends of pieces closer than this, relative to the model's extent, are the same point.
const SAME_POINT: f64 = 1e-7;

/// Per end of each piece (`2 k + end`), an id shared by the ends within [`SAME_POINT`] of one
/// another, the ids counting up from 0. Ends that are bit for bit the same point (most joins:
/// both triangles of an edge compute its crossing alike) share an id at once; an end no other
/// matches exactly — a loose end, where a seam between patches cut the line — then takes the
/// id of the first loose end met within that distance, looked for in the 27 grid cells around
/// it (cells that wide).
fn same_points(pieces: &[Piece]) -> Vec<usize> {
    let ends: Vec<DVec3> = pieces.iter().flat_map(|p| p.ends).collect();
    // Ends sorted by their bits: equal points side by side, numbered in order.
    let bits = |k: usize| ends[k].to_array().map(f64::to_bits);
    let mut order: Vec<usize> = (0..ends.len()).collect();
    order.sort_unstable_by_key(|&k| bits(k));
    let mut ids = vec![0usize; ends.len()];
    let mut distinct = 0;
    for (n, &k) in order.iter().enumerate() {
        if n > 0 && bits(order[n - 1]) != bits(k) {
            distinct += 1;
        }
        ids[k] = distinct;
    }
    let mut uses = vec![0u32; distinct + usize::from(!ends.is_empty())];
    for &id in &ids {
        uses[id] += 1;
    }
    let extent = ends
        .iter()
        .fold(1.0f64, |m, p| m.max(p.abs().max_element()));
    let tolerance = SAME_POINT * extent;
    let cell = |p: DVec3| (p / tolerance).floor().as_i64vec3();
    let mut filed: FastMap<glam::I64Vec3, Vec<(DVec3, usize)>> = FastMap::default();
    for (k, &point) in ends.iter().enumerate() {
        if uses[ids[k]] != 1 {
            continue;
        }
        let home = cell(point);
        let mut found = None;
        'search: for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let near = home + glam::I64Vec3::new(dx, dy, dz);
                    if let Some(&(_, id)) = filed
                        .get(&near)
                        .and_then(|list| list.iter().find(|(q, _)| q.distance(point) <= tolerance))
                    {
                        found = Some(id);
                        break 'search;
                    }
                }
            }
        }
        match found {
            Some(id) => ids[k] = id,
            None => filed.entry(home).or_default().push((point, ids[k])),
        }
    }
    ids
}

/// One sample along a chain: its piece (in the chain's list), its fraction along the piece in
/// the chain's direction, its distance along the chain in pixels, and whether it shows.
#[derive(Clone, Copy, Debug)]
struct Sample {
    piece: usize,
    t: f32,
    at: f32,
    shows: bool,
}

/// Per piece on the image, the occlusion level of each of its samples: the piece cut into
/// `n + 1` samples at most [`STEP`] apart (both ends included, from its first end), each 0
/// where it shows against `depth`; elsewhere, with `hidden` (the surfaces in front and the
/// most levels drawn), the number of surfaces in front of it, at least 1 (the depth test found
/// one), up to `most + 1`; without, [`BEYOND`].
#[must_use]
pub(crate) fn sample_piece(
    on: &OnScreen,
    depth: &DepthTest,
    hidden: Option<(&Occluders, u32)>,
) -> Vec<u8> {
    let n = samples_along(on);
    (0..=n)
        .map(|i| {
            let t = i as f32 / n as f32;
            let (point, z, reach) = (on.point(t), on.depth(t), on.reach_at(t));
            let shows = match (on.open_on, on.inside) {
                (Some(patch), _) => depth.shows_open(point, z, reach, patch),
                (None, true) => depth.shows_on_surface(point, z, reach),
                (None, false) => depth.shows(point, z, reach),
            };
            match (shows, hidden) {
                (true, _) => 0,
                (false, Some((occluders, most))) => {
                    occluders.in_front(point, z, most).clamp(1, most + 1) as u8
                }
                (false, None) => BEYOND,
            }
        })
        .collect()
}

/// The occlusion level of a sample hidden behind more surfaces than any style draws.
pub(crate) const BEYOND: u8 = u8::MAX;

/// How many steps a piece is cut into.
fn samples_along(on: &OnScreen) -> u32 {
    (on.length() / STEP).ceil().clamp(1.0, MOST_SAMPLES) as u32
}

/// What one chain draws: its capsules in order, the piece each draws, and its stretches.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Drawn {
    pub capsules: Vec<Capsule>,
    /// Per capsule, the piece it draws (its index in the frame's pieces).
    pub pieces: Vec<u32>,
    /// The visible stretches, each a run of `capsules` drawn one after another along the
    /// line, and whether it is the whole of a closed line (no end).
    pub stretches: Vec<(std::ops::Range<usize>, bool)>,
}

/// The capsules that draw the stretches of one chain where `draws` says its samples are drawn,
/// given their piece and occlusion level — where they show, or where they are hidden behind
/// few enough surfaces (`screen[k]` is piece k's place on the image, None off it, and
/// `levels[k]` its samples' occlusion levels from [`sample_piece`]).
/// Along the chain, hidden stretches shorter than [`SHORTEST_GAP`] between visible ones are
/// drawn, and visible stretches shorter than [`SHORTEST_STROKE`] between hidden ones are not.
/// Each drawn stretch narrows toward its ends over its pieces' taper; the point where a
/// closed chain closes is not an end.
#[must_use]
pub(crate) fn visible_capsules(
    line: &Chain,
    screen: &[Option<OnScreen>],
    levels: &[Vec<u8>],
    draws: impl Fn(usize, u8) -> bool,
) -> Drawn {
    let chain = &line.pieces[..];
    let mut samples: Vec<Sample> = Vec::new();
    let mut travelled = 0.0;
    for (k, &(piece, reversed)) in chain.iter().enumerate() {
        let Some(on) = &screen[piece] else {
            // Off the image or behind the eye: a break in the line.
            samples.push(Sample {
                piece: k,
                t: 0.0,
                at: travelled,
                shows: false,
            });
            continue;
        };
        let length = on.length();
        let n = samples_along(on);
        for i in 0..=n {
            let t = i as f32 / n as f32;
            let own = if reversed { n - i } else { i };
            samples.push(Sample {
                piece: k,
                t,
                at: travelled + length * t,
                shows: draws(piece, levels[piece][own as usize]),
            });
        }
        travelled += length;
    }
    // Runs of equal visibility: (first sample, last sample, shows).
    let mut runs: Vec<(usize, usize, bool)> = Vec::new();
    for (i, s) in samples.iter().enumerate() {
        match runs.last_mut() {
            Some(run) if run.2 == s.shows => run.1 = i,
            _ => runs.push((i, i, s.shows)),
        }
    }
    let span = |run: &(usize, usize, bool)| samples[run.1].at - samples[run.0].at;
    for r in 1..runs.len().saturating_sub(1) {
        if !runs[r].2
            && span(&runs[r]) < SHORTEST_GAP
            && screen_all(&samples, screen, chain, runs[r])
        {
            runs[r].2 = true;
        }
    }
    let mut drawn = Drawn::default();
    let mut r = 0;
    while r < runs.len() {
        if !runs[r].2 {
            r += 1;
            continue;
        }
        // Merge the visible runs now adjacent.
        let (first, mut last) = (runs[r].0, runs[r].1);
        while r + 1 < runs.len() && runs[r + 1].2 {
            r += 1;
            last = runs[r].1;
        }
        r += 1;
        // A short stretch between hidden ones is a dot; one at an end of the chain may go on
        // in the next chain (where a seam cut the line), and stays.
        let inside = first > 0 && last + 1 < samples.len();
        if inside && samples[last].at - samples[first].at < SHORTEST_STROKE {
            continue;
        }
        let ends = Ends {
            first: !(line.closed && first == 0),
            last: !(line.closed && last + 1 == samples.len()),
        };
        let start = drawn.capsules.len();
        draw_stretch(&samples[first..=last], ends, chain, screen, &mut drawn);
        let whole_loop = !ends.first && !ends.last;
        drawn
            .stretches
            .push((start..drawn.capsules.len(), whole_loop));
    }
    drawn
}

/// Which ends of a drawn stretch are ends of the line (where it narrows over its taper).
#[derive(Clone, Copy, Debug)]
struct Ends {
    first: bool,
    last: bool,
}

/// Whether every piece a run of samples lies on is on the image (a gap across a piece off it
/// is not filled).
fn screen_all(
    samples: &[Sample],
    screen: &[Option<OnScreen>],
    chain: &[(usize, bool)],
    (first, last, _): (usize, usize, bool),
) -> bool {
    samples[first..=last]
        .iter()
        .all(|s| screen[chain[s.piece].0].is_some())
}

/// Capsules along the samples of one visible stretch: one per piece it crosses, from the
/// stretch's first to its last fraction of that piece, of the piece's radius. Within a
/// piece's taper of an end of the line the radius is `r · s / taper`, `s` the distance along
/// the stretch to that end, and the capsules go sample to sample.
fn draw_stretch(
    stretch: &[Sample],
    ends: Ends,
    chain: &[(usize, bool)],
    screen: &[Option<OnScreen>],
    drawn: &mut Drawn,
) {
    let (start, finish) = (stretch[0].at, stretch[stretch.len() - 1].at);
    // The distance along the stretch to its nearer end that narrows.
    let to_end = |at: f32| {
        let from_first = if ends.first {
            at - start
        } else {
            f32::INFINITY
        };
        let to_last = if ends.last {
            finish - at
        } else {
            f32::INFINITY
        };
        from_first.min(to_last)
    };
    let mut i = 0;
    while i < stretch.len() {
        let k = stretch[i].piece;
        let mut j = i;
        while j + 1 < stretch.len() && stretch[j + 1].piece == k {
            j += 1;
        }
        let (piece, reversed) = chain[k];
        if let Some(on) = &screen[piece] {
            let before = drawn.capsules.len();
            let capsules = &mut drawn.capsules;
            let along = |t: f32| if reversed { 1.0 - t } else { t };
            let radius = |s: &Sample| on.radius * (to_end(s.at) / on.taper).min(1.0);
            let tapers =
                on.taper > 0.0 && (to_end(stretch[i].at).min(to_end(stretch[j].at)) < on.taper);
            if tapers {
                for w in stretch[i..=j].windows(2) {
                    capsules.push(on.capsule(
                        along(w[0].t),
                        along(w[1].t),
                        [radius(&w[0]), radius(&w[1])],
                    ));
                }
                if i == j {
                    let t = along(stretch[i].t);
                    capsules.push(on.capsule(t, t, [radius(&stretch[i]); 2]));
                }
            } else {
                capsules.push(on.capsule(along(stretch[i].t), along(stretch[j].t), [on.radius; 2]));
            }
            let added = drawn.capsules.len() - before;
            drawn
                .pieces
                .extend(std::iter::repeat_n(piece as u32, added));
        }
        i = j + 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::line_style::LineKind;
    fn piece(a: [f64; 3], b: [f64; 3]) -> Piece {
        let (a, b) = (DVec3::from(a), DVec3::from(b));
        Piece {
            ends: [a, b],
            on_mesh: [a.as_vec3(), b.as_vec3()],
            opacity: 1.0,
            kind: LineKind::Silhouette,
            open: false,
            patches: [0, 0],
        }
    }

    #[test]
    fn pieces_sharing_ends_join_into_lines_that_stop_where_three_meet() {
        // A path a–b–c–d given out of order and with one piece reversed, a closed triangle,
        // and a star of three pieces meeting at the origin.
        let pieces = vec![
            piece([1.0, 0.0, 0.0], [2.0, 0.0, 0.0]),
            piece([3.0, 0.0, 0.0], [2.0, 0.0, 0.0]),
            piece([0.0, 0.0, 0.0], [1.0, 0.0, 0.0]),
            piece([0.0, 5.0, 0.0], [1.0, 5.0, 0.0]),
            piece([1.0, 5.0, 0.0], [0.0, 6.0, 0.0]),
            piece([0.0, 6.0, 0.0], [0.0, 5.0, 0.0]),
            piece([9.0, 9.0, 0.0], [9.0, 10.0, 0.0]),
            piece([9.0, 9.0, 0.0], [10.0, 9.0, 0.0]),
            piece([9.0, 9.0, 0.0], [8.0, 9.0, 0.0]),
        ];
        let chains = chains(&pieces);
        let mut lengths: Vec<(usize, bool)> =
            chains.iter().map(|c| (c.pieces.len(), c.closed)).collect();
        lengths.sort_unstable();
        // The path is open, the triangle closed, the star's arms three open lines.
        assert_eq!(
            lengths,
            vec![(1, false), (1, false), (1, false), (3, false), (3, true)]
        );
        // Along each chain, one piece's far end is the next one's near end.
        let end = |&(p, reversed): &(usize, bool), far: bool| {
            let e = pieces[p].ends;
            if reversed == far {
                e[0]
            } else {
                e[1]
            }
        };
        for chain in chains.iter().map(|c| &c.pieces) {
            for w in chain.windows(2) {
                assert_eq!(end(&w[0], true), end(&w[1], false), "{chain:?}");
            }
        }
    }

    /// The capsules of `pieces` joined into one chain, every sample shown, drawn in `style`
    /// through a view that maps (x, y) in [−1, 1]² onto a 200 px square.
    fn drawn(pieces: &[Piece], style: crate::render::LineStyle) -> Vec<Capsule> {
        drawn_without(pieces, style, None).capsules
    }

    /// [`drawn`], the piece `off` (if any) taken as off the image, with the stretches.
    fn drawn_without(
        pieces: &[Piece],
        style: crate::render::LineStyle,
        off: Option<usize>,
    ) -> Drawn {
        let screen: Vec<Option<OnScreen>> = pieces
            .iter()
            .enumerate()
            .map(|(k, p)| {
                p.on_screen(glam::Mat4::IDENTITY, (200, 200), &[style], 0)
                    .filter(|_| Some(k) != off)
            })
            .collect();
        let levels: Vec<Vec<u8>> = screen
            .iter()
            .map(|on| vec![0; on.as_ref().map_or(0, samples_along) as usize + 1])
            .collect();
        let lines = chains(pieces);
        assert_eq!(lines.len(), 1);
        visible_capsules(&lines[0], &screen, &levels, |_, level| level == 0)
    }

    /// A line from x = 20 px to 180 px along y = 100 px in eight pieces of 20 px, and a style
    /// 4 px wide that narrows over 10 px at its ends.
    fn tapering_line() -> (Vec<Piece>, crate::render::LineStyle) {
        let x = |k: usize| -0.8 + 0.2 * k as f64;
        let pieces = (0..8)
            .map(|k| piece([x(k), 0.0, 0.5], [x(k + 1), 0.0, 0.5]))
            .collect();
        let style = crate::render::LineStyle {
            taper: 10.0,
            ..crate::render::LineStyle::new(4.0, glam::Vec3::ZERO)
        };
        (pieces, style)
    }

    #[test]
    fn a_piece_off_the_image_breaks_the_line_into_two_that_each_end_there() {
        // The fifth piece (100 px to 120 px) off the image: however short the gap, it is not
        // bridged.
        let (open, style) = tapering_line();
        let drawn = drawn_without(&open, style, Some(4));
        assert_eq!(drawn.stretches.len(), 2);
        let expected = |px: f32| {
            let to_end = if px <= 100.0 {
                (px - 20.0).min(100.0 - px)
            } else {
                (px - 120.0).min(180.0 - px)
            };
            2.0 * (to_end / 10.0).min(1.0)
        };
        for c in &drawn.capsules {
            for (end, radius) in [(c.a, c.radii[0]), (c.b, c.radii[1])] {
                assert!(!(100.0 + 1e-3..120.0 - 1e-3).contains(&end.x), "{end}");
                assert!(
                    (radius - expected(end.x)).abs() < 1e-3,
                    "at {end}: {radius}, not {}",
                    expected(end.x)
                );
            }
        }
    }

    #[test]
    fn a_line_narrows_over_its_taper_at_its_ends_and_a_loop_nowhere() {
        let (open, style) = tapering_line();
        let capsules = drawn(&open, style);
        let expected = |px: f32| 2.0 * ((px - 20.0).min(180.0 - px) / 10.0).min(1.0);
        let mut narrowest = f32::INFINITY;
        for c in &capsules {
            for (end, radius) in [(c.a, c.radii[0]), (c.b, c.radii[1])] {
                assert!(
                    (radius - expected(end.x)).abs() < 1e-3,
                    "at {end}: {radius}, not {}",
                    expected(end.x)
                );
                narrowest = narrowest.min(radius);
            }
        }
        assert!(narrowest < 1e-3, "the ends come to a point");
        // The line is whole: its capsules cover it end to end.
        let covered: f32 = capsules.iter().map(|c| c.a.distance(c.b)).sum();
        assert!((covered - 160.0).abs() < 1e-3, "{covered}");

        // A square loop closes on itself: no end, no narrowing.
        let corners = [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]];
        let square: Vec<Piece> = (0..4)
            .map(|k| {
                let (a, b) = (corners[k], corners[(k + 1) % 4]);
                piece([a[0], a[1], 0.5], [b[0], b[1], 0.5])
            })
            .collect();
        for c in drawn(&square, style) {
            assert_eq!(c.radii, [2.0, 2.0]);
        }
    }
}
