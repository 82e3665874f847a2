//! A trimmed patch's kept region: closed loops in the (u, v) plane, a point kept when a ray from
//! it crosses them an odd number of times.

use glam::DVec2;
use thiserror::Error;

use super::Domain;
use crate::math::distance_to_segment;

/// The most loop segments a patch's trim may have, over all its loops.
pub const MAX_TRIM_SEGMENTS: usize = 1 << 20;

/// The most entries the rows of [`Trim`] hold (a segment counted once per row it crosses):
/// the rows get fewer when the loops would need more.
const MAX_ROW_ENTRIES: usize = 1 << 24;

/// Within this fraction of the domain's larger side, a segment lying along a side of the
/// domain is that side: it cuts nothing, since points are tested
/// [`INSET`] inside the domain ([`Trim::contains`]).
const ON_SIDE: f64 = 1e-9;

/// The most cells of its grid [`Trim::try_signed_distance`] searches.
pub const MOST_CELLS_SEARCHED: usize = 64;

/// How far inside the domain, as a fraction of its larger side, a point is moved before it is
/// tested: a point on the domain's edge (where a loop drawn along that edge would leave its
/// side to rounding) counts as the point just inside.
const INSET: f64 = 1e-7;

/// The kept part of a patch's domain: the points inside an odd number of the closed loops
/// (RenderMan's trim rule, which USD follows). The loops are polylines in (u, v); a consistent
/// set runs counter-clockwise around what it keeps and clockwise around what it cuts out, so
/// an outer loop runs counter-clockwise and a hole in it clockwise ([`Trim::new`] checks it).
#[derive(Clone, Debug, PartialEq)]
pub struct Trim {
    /// Each loop's points, the last equal to the first.
    loops: Vec<Vec<DVec2>>,
    domain: Domain,
    segments: Vec<Segment>,
    rows: Rows,
    cells: Cells,
}

/// One side of a loop.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Segment {
    a: DVec2,
    b: DVec2,
    /// It lies along a side of the domain.
    on_side: bool,
}

/// The segments by horizontal bands of the plane: `bands[r]` lists those whose v range meets
/// `[v0 + r h, v0 + (r + 1) h]`.
#[derive(Clone, Debug, PartialEq)]
struct Rows {
    v0: f64,
    height: f64,
    bands: Vec<Vec<u32>>,
}

/// The domain cut into a grid of cells, each with whether its centre is kept and the segments
/// that meet it (by their bounding boxes; those along a side of the domain left out): a point is
/// kept as the centre of its cell is, unless the way from the centre to it crosses a segment of
/// the cell an odd number of times.
#[derive(Clone, Debug, PartialEq)]
struct Cells {
    lo: DVec2,
    size: DVec2,
    columns: usize,
    rows: usize,
    /// Per cell (row-major), whether its centre is kept.
    kept: Vec<bool>,
    /// Per cell, its segments: `items[first[c]..first[c + 1]]`.
    first: Vec<u32>,
    items: Vec<u32>,
}

/// Where a part of the domain lies against a trim.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Region {
    /// All of it is kept.
    Kept,
    /// All of it is cut away.
    Cut,
    /// A loop crosses it: each point must be tested.
    Both,
}

/// Loops that do not make a trim.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum TrimError {
    #[error("trim loop {index} has a point that is not a finite number")]
    NotFinite { index: usize },
    #[error("trim loop {index} encloses no area")]
    Empty { index: usize },
    #[error(
        "trim loop {index} runs {runs} but lies inside {depth} other loop(s): an outer loop runs \
         counter-clockwise in (u, v) and a hole inside it clockwise — reverse the loop, or add \
         the loop around it (the patch's outer boundary)"
    )]
    Orientation {
        index: usize,
        runs: &'static str,
        depth: usize,
    },
    #[error("the trim has {count} segments, more than the {max} glint follows")]
    TooLarge { count: usize, max: usize },
}

impl Trim {
    /// The trim of a patch over `domain` by the closed polylines `loops` (each closed by its
    /// last point returning to its first; one that does not is closed). Refused: a point that
    /// is not finite, a loop with no area, more than [`MAX_TRIM_SEGMENTS`] segments, and a loop
    /// whose direction does not match its depth — counter-clockwise when inside an even number
    /// of the other loops, clockwise when inside an odd number — since then the two rules USD
    /// inherits from RenderMan (odd crossings, and the kept side to the left) disagree.
    pub fn new(loops: Vec<Vec<DVec2>>, domain: Domain) -> Result<Self, TrimError> {
        let mut closed = Vec::with_capacity(loops.len());
        for (index, mut points) in loops.into_iter().enumerate() {
            if points.iter().any(|p| !p.is_finite()) {
                return Err(TrimError::NotFinite { index });
            }
            if let (Some(&first), Some(&last)) = (points.first(), points.last()) {
                if first != last {
                    points.push(first);
                }
            }
            if signed_area(&points) == 0.0 {
                return Err(TrimError::Empty { index });
            }
            closed.push(points);
        }
        let count: usize = closed.iter().map(|l| l.len() - 1).sum();
        if count > MAX_TRIM_SEGMENTS {
            return Err(TrimError::TooLarge {
                count,
                max: MAX_TRIM_SEGMENTS,
            });
        }
        for (index, points) in closed.iter().enumerate() {
            let depth = closed
                .iter()
                .enumerate()
                .filter(|&(j, other)| j != index && crossings(other, points[0]) % 2 == 1)
                .count();
            let counter_clockwise = signed_area(points) > 0.0;
            if counter_clockwise != (depth % 2 == 0) {
                let runs = if counter_clockwise {
                    "counter-clockwise"
                } else {
                    "clockwise"
                };
                return Err(TrimError::Orientation { index, runs, depth });
            }
        }
        let side = (domain.u.1 - domain.u.0).max(domain.v.1 - domain.v.0);
        let near = |x: f64, edge: f64| (x - edge).abs() <= ON_SIDE * side;
        let along_side = |a: DVec2, b: DVec2| {
            [domain.u.0, domain.u.1]
                .iter()
                .any(|&e| near(a.x, e) && near(b.x, e))
                || [domain.v.0, domain.v.1]
                    .iter()
                    .any(|&e| near(a.y, e) && near(b.y, e))
        };
        let segments: Vec<Segment> = closed
            .iter()
            .flat_map(|l| l.windows(2))
            .map(|w| Segment {
                a: w[0],
                b: w[1],
                on_side: along_side(w[0], w[1]),
            })
            .collect();
        let rows = Rows::new(&segments);
        let mut trim = Self {
            loops: closed,
            domain,
            segments,
            rows,
            cells: Cells::default(),
        };
        trim.cells = Cells::new(&trim);
        Ok(trim)
    }

    /// The loops, each closed (its last point its first).
    #[must_use]
    pub fn loops(&self) -> &[Vec<DVec2>] {
        &self.loops
    }

    /// The domain the trim was made for.
    #[must_use]
    pub fn domain(&self) -> Domain {
        self.domain
    }

    /// The segments of the loops that cut the surface, each `[a, b]`: every one but those that
    /// lie along a side of the domain, where the patch ends anyway.
    pub fn edges(&self) -> impl Iterator<Item = [DVec2; 2]> + '_ {
        self.segments
            .iter()
            .filter(|s| !s.on_side)
            .map(|s| [s.a, s.b])
    }

    /// Whether (u, v) is kept: moved 10⁻⁷ of the domain's larger side inside the domain, it
    /// lies inside an odd number of loops. The count is found from the point's cell of a grid
    /// over the domain: the cell centre's, changed by each of the cell's segments the straight
    /// way from the centre to the point crosses.
    #[must_use]
    pub fn contains(&self, u: f64, v: f64) -> bool {
        let p = self.inset(DVec2::new(u, v));
        let c = &self.cells;
        let cell = c.index(p);
        let centre = c.centre(cell);
        let mut kept = c.kept[cell];
        for &i in &c.items[c.first[cell] as usize..c.first[cell + 1] as usize] {
            let s = &self.segments[i as usize];
            kept ^= crosses(centre, p, s.a, s.b);
        }
        kept
    }

    /// The distance in (u, v) from `(u, v)` to the nearest segment that cuts the surface,
    /// positive where the trim keeps the point and negative where it cuts it away
    /// ([`Trim::contains`]), and `±reach` when no such segment lies within `reach`. `None` where
    /// the square of side `2 reach` about the point covers more than [`MOST_CELLS_SEARCHED`]
    /// cells of the trim's grid, or the point or `reach` is not finite.
    ///
    /// Near a loop it changes as the distance from its polyline does: smoothly across the loop,
    /// and with a kink only on the inner side of a corner, where two segments are as near.
    #[must_use]
    pub fn try_signed_distance(&self, u: f64, v: f64, reach: f64) -> Option<f64> {
        if !(u.is_finite() && v.is_finite() && reach.is_finite() && reach >= 0.0) {
            return None;
        }
        let p = self.inset(DVec2::new(u, v));
        let c = &self.cells;
        let (x0, y0) = c.cell_of(p - reach);
        let (x1, y1) = c.cell_of(p + reach);
        if (x1 - x0 + 1) * (y1 - y0 + 1) > MOST_CELLS_SEARCHED {
            return None;
        }
        let mut nearest = reach;
        for y in y0..=y1 {
            for x in x0..=x1 {
                let cell = y * c.columns + x;
                for &i in &c.items[c.first[cell] as usize..c.first[cell + 1] as usize] {
                    let s = &self.segments[i as usize];
                    nearest = nearest.min(distance_to_segment(p, s.a, s.b));
                }
            }
        }
        Some(if self.contains(u, v) {
            nearest
        } else {
            -nearest
        })
    }

    /// [`Trim::contains`] by the crossings of the ray from the point towards +u (a segment
    /// crosses the line through v when exactly one of its ends lies above it), all counted.
    fn contains_by_rays(&self, p: DVec2) -> bool {
        let Some(band) = self.rows.band(p.y) else {
            return false;
        };
        let mut odd = false;
        for &i in band {
            let s = &self.segments[i as usize];
            if (s.a.y > p.y) != (s.b.y > p.y) {
                let x = s.a.x + (p.y - s.a.y) * (s.b.x - s.a.x) / (s.b.y - s.a.y);
                if x > p.x {
                    odd = !odd;
                }
            }
        }
        odd
    }

    /// Where the box `[lo, hi]` lies: [`Region::Both`] when a segment that cuts the surface
    /// meets it, else as its centre lies.
    #[must_use]
    pub fn region(&self, lo: DVec2, hi: DVec2) -> Region {
        let (first, last) = (self.rows.index(lo.y), self.rows.index(hi.y));
        let crossed = (first..=last).any(|r| {
            self.rows.bands[r].iter().any(|&i| {
                let s = &self.segments[i as usize];
                !s.on_side && segment_meets_box(s.a, s.b, lo, hi)
            })
        });
        if crossed {
            Region::Both
        } else if self.contains(0.5 * (lo.x + hi.x), 0.5 * (lo.y + hi.y)) {
            Region::Kept
        } else {
            Region::Cut
        }
    }

    /// The parts of the segment from `a` to `b` the trim keeps, as intervals `[t₀, t₁]` of
    /// `a + t (b − a)`, in order: the segment is cut where a loop crosses it (ends included),
    /// and each piece kept when its middle is ([`Trim::contains`]).
    #[must_use]
    pub fn kept_spans(&self, a: DVec2, b: DVec2) -> Vec<(f64, f64)> {
        match self.region(a.min(b), a.max(b)) {
            Region::Kept => return vec![(0.0, 1.0)],
            Region::Cut => return Vec::new(),
            Region::Both => {}
        }
        let d = b - a;
        let (first, last) = (self.rows.index(a.y.min(b.y)), self.rows.index(a.y.max(b.y)));
        let mut cuts = vec![0.0, 1.0];
        for r in first..=last {
            for &i in &self.rows.bands[r] {
                let s = &self.segments[i as usize];
                let e = s.b - s.a;
                let det = d.perp_dot(e);
                if s.on_side || det == 0.0 {
                    continue;
                }
                let t = (s.a - a).perp_dot(e) / det;
                let w = (s.a - a).perp_dot(d) / det;
                if (0.0..=1.0).contains(&t) && (0.0..=1.0).contains(&w) {
                    cuts.push(t);
                }
            }
        }
        cuts.sort_by(f64::total_cmp);
        cuts.dedup();
        let mut spans: Vec<(f64, f64)> = Vec::new();
        for w in cuts.windows(2) {
            let middle = a + d * (0.5 * (w[0] + w[1]));
            if w[1] > w[0] && self.contains(middle.x, middle.y) {
                match spans.last_mut() {
                    Some(last) if last.1 == w[0] => last.1 = w[1],
                    _ => spans.push((w[0], w[1])),
                }
            }
        }
        spans
    }

    /// `p` moved into the domain shrunk by [`INSET`] of its larger side.
    fn inset(&self, p: DVec2) -> DVec2 {
        let d = self.domain;
        let e = INSET * (d.u.1 - d.u.0).max(d.v.1 - d.v.0);
        DVec2::new(
            p.x.clamp(d.u.0 + e, d.u.1 - e),
            p.y.clamp(d.v.0 + e, d.v.1 - e),
        )
    }
}

impl Default for Cells {
    fn default() -> Self {
        Self {
            lo: DVec2::ZERO,
            size: DVec2::ONE,
            columns: 1,
            rows: 1,
            kept: vec![false],
            first: vec![0, 0],
            items: Vec::new(),
        }
    }
}

impl Cells {
    /// About one cell per segment that cuts (at most 256 a side) over the domain, fewer when
    /// the segments would fill more than [`MAX_ROW_ENTRIES`] entries; each centre's state by
    /// [`Trim::contains_by_rays`].
    fn new(trim: &Trim) -> Self {
        let d = trim.domain;
        let (lo, hi) = (DVec2::new(d.u.0, d.v.0), DVec2::new(d.u.1, d.v.1));
        let cutting: Vec<usize> = (0..trim.segments.len())
            .filter(|&i| !trim.segments[i].on_side)
            .collect();
        let mut side = ((4.0 * cutting.len() as f64).sqrt().ceil() as usize).clamp(1, 512);
        loop {
            let mut cells = Self {
                lo,
                size: (hi - lo) / side as f64,
                columns: side,
                rows: side,
                kept: Vec::new(),
                first: Vec::new(),
                items: Vec::new(),
            };
            let spans: Vec<(usize, [usize; 4])> = cutting
                .iter()
                .map(|&i| {
                    let s = &trim.segments[i];
                    let (a, b) = (cells.cell_of(s.a.min(s.b)), cells.cell_of(s.a.max(s.b)));
                    (i, [a.0, b.0, a.1, b.1])
                })
                .collect();
            let entries: usize = spans
                .iter()
                .map(|(_, [x0, x1, y0, y1])| (x1 - x0 + 1) * (y1 - y0 + 1))
                .sum();
            if entries > MAX_ROW_ENTRIES && side > 1 {
                side /= 2;
                continue;
            }
            let n = side * side;
            let mut count = vec![0u32; n + 1];
            for (_, [x0, x1, y0, y1]) in &spans {
                for y in *y0..=*y1 {
                    for x in *x0..=*x1 {
                        count[y * side + x + 1] += 1;
                    }
                }
            }
            for c in 0..n {
                count[c + 1] += count[c];
            }
            let mut fill = count.clone();
            cells.items = vec![0; entries];
            for &(i, [x0, x1, y0, y1]) in &spans {
                for y in y0..=y1 {
                    for x in x0..=x1 {
                        let slot = &mut fill[y * side + x];
                        cells.items[*slot as usize] = i as u32;
                        *slot += 1;
                    }
                }
            }
            cells.first = count;
            cells.kept = (0..n)
                .map(|c| trim.contains_by_rays(trim.inset(cells.centre(c))))
                .collect();
            return cells;
        }
    }

    /// The (column, row) of the cell holding `p`, clamped to the grid.
    fn cell_of(&self, p: DVec2) -> (usize, usize) {
        let at = |x: f64, lo: f64, size: f64, n: usize| {
            let k = ((x - lo) / size).floor();
            if k.is_nan() || k < 0.0 {
                0
            } else {
                (k as usize).min(n - 1)
            }
        };
        (
            at(p.x, self.lo.x, self.size.x, self.columns),
            at(p.y, self.lo.y, self.size.y, self.rows),
        )
    }

    /// The index of the cell holding `p`.
    fn index(&self, p: DVec2) -> usize {
        let (x, y) = self.cell_of(p);
        y * self.columns + x
    }

    /// The centre of cell `c`.
    fn centre(&self, c: usize) -> DVec2 {
        let (x, y) = (c % self.columns, c / self.columns);
        self.lo + self.size * DVec2::new(x as f64 + 0.5, y as f64 + 0.5)
    }
}

/// Whether the way from `c` to `p` crosses the segment from `a` to `b`: `a` and `b` lie on
/// opposite sides of the line through `c` and `p`, and `c` and `p` on opposite sides of the
/// segment's line, a point on a line counted on its positive side. So where the way passes
/// through a vertex two segments share, it crosses one of them if the loop goes on across and
/// both or neither if it turns back: the count's parity is right.
#[must_use]
fn crosses(c: DVec2, p: DVec2, a: DVec2, b: DVec2) -> bool {
    let side = |x: DVec2, y: DVec2, z: DVec2| (y - x).perp_dot(z - x) >= 0.0;
    side(c, p, a) != side(c, p, b) && side(a, b, c) != side(a, b, p)
}

impl Rows {
    /// About √n bands over the segments' v range, fewer when the segments would fill more
    /// than [`MAX_ROW_ENTRIES`] entries.
    fn new(segments: &[Segment]) -> Self {
        let (v0, v1) = segments.iter().fold((f64::MAX, f64::MIN), |(lo, hi), s| {
            (lo.min(s.a.y).min(s.b.y), hi.max(s.a.y).max(s.b.y))
        });
        let mut count = ((segments.len() as f64).sqrt().ceil() as usize).clamp(1, 4096);
        loop {
            let rows = Self {
                v0,
                height: ((v1 - v0) / count as f64).max(f64::MIN_POSITIVE),
                bands: vec![Vec::new(); count],
            };
            let entries: usize = segments.iter().map(|s| rows.span(s).count()).sum();
            if entries <= MAX_ROW_ENTRIES || count == 1 {
                let mut rows = rows;
                for (i, s) in segments.iter().enumerate() {
                    for r in rows.span(s) {
                        rows.bands[r].push(i as u32);
                    }
                }
                return rows;
            }
            count = (count / 2).max(1);
        }
    }

    /// The band of `v`, clamped to the bands there are.
    fn index(&self, v: f64) -> usize {
        let r = ((v - self.v0) / self.height).floor();
        if r.is_nan() || r < 0.0 {
            0
        } else {
            (r as usize).min(self.bands.len() - 1)
        }
    }

    /// The segments of the band holding `v`; None when `v` is outside every band.
    fn band(&self, v: f64) -> Option<&[u32]> {
        let top = self.v0 + self.height * self.bands.len() as f64;
        (self.v0..=top)
            .contains(&v)
            .then(|| self.bands[self.index(v)].as_slice())
    }

    /// The bands segment `s` meets.
    fn span(&self, s: &Segment) -> std::ops::RangeInclusive<usize> {
        self.index(s.a.y.min(s.b.y))..=self.index(s.a.y.max(s.b.y))
    }
}

/// The signed area of the closed polyline `points`, positive counter-clockwise:
/// `½ Σ (pᵢ − p₀) × (pᵢ₊₁ − p₀)`.
#[must_use]
fn signed_area(points: &[DVec2]) -> f64 {
    let origin = points.first().copied().unwrap_or_default();
    0.5 * points
        .windows(2)
        .map(|w| (w[0] - origin).perp_dot(w[1] - origin))
        .sum::<f64>()
}

/// How many segments of the closed polyline `points` the ray from `p` towards +u crosses.
#[must_use]
fn crossings(points: &[DVec2], p: DVec2) -> usize {
    points
        .windows(2)
        .filter(|w| {
            let (a, b) = (w[0], w[1]);
            (a.y > p.y) != (b.y > p.y) && a.x + (p.y - a.y) * (b.x - a.x) / (b.y - a.y) > p.x
        })
        .count()
}

/// Whether the segment from `a` to `b` meets the closed box `[lo, hi]`: their bounding boxes
/// overlap and the box's corners do not all lie strictly on one side of the segment's line.
#[must_use]
fn segment_meets_box(a: DVec2, b: DVec2, lo: DVec2, hi: DVec2) -> bool {
    if a.x.max(b.x) < lo.x || a.x.min(b.x) > hi.x || a.y.max(b.y) < lo.y || a.y.min(b.y) > hi.y {
        return false;
    }
    let d = b - a;
    let side = |c: DVec2| d.perp_dot(c - a);
    let corners = [
        side(lo),
        side(DVec2::new(hi.x, lo.y)),
        side(hi),
        side(DVec2::new(lo.x, hi.y)),
    ];
    !(corners.iter().all(|&s| s > 0.0) || corners.iter().all(|&s| s < 0.0))
}

#[cfg(test)]
mod tests {
    use rand::rngs::StdRng;
    use rand::{Rng, SeedableRng};

    use super::*;

    fn unit() -> Domain {
        Domain {
            u: (0.0, 1.0),
            v: (0.0, 1.0),
        }
    }

    fn square(lo: f64, hi: f64, counter_clockwise: bool) -> Vec<DVec2> {
        let mut p = vec![
            DVec2::new(lo, lo),
            DVec2::new(hi, lo),
            DVec2::new(hi, hi),
            DVec2::new(lo, hi),
            DVec2::new(lo, lo),
        ];
        if !counter_clockwise {
            p.reverse();
        }
        p
    }

    fn circle(centre: DVec2, r: f64, n: usize, counter_clockwise: bool) -> Vec<DVec2> {
        let sign = if counter_clockwise { 1.0 } else { -1.0 };
        (0..=n)
            .map(|k| {
                let a = sign * std::f64::consts::TAU * (k % n) as f64 / n as f64;
                centre + r * DVec2::new(a.cos(), a.sin())
            })
            .collect()
    }

    #[test]
    fn the_signed_distance_is_the_least_over_every_cutting_segment_to_the_bit() {
        // Holes of many sizes and sides, one in each cell of a 6 × 6 grid (a 3 × 3 of small
        // ones crowded into the first), some near the domain's side; points inside, on and
        // beyond the domain, and reaches from a hair to the most cells searched.
        let mut rng = StdRng::seed_from_u64(2024);
        let mut loops = vec![square(0.0, 1.0, true)];
        let mut hole = |rng: &mut StdRng, lo: DVec2, side: f64| {
            let r = rng.random_range(0.05..0.45) * side;
            let room = 0.5 * side - r - 0.01 * side;
            let jitter = DVec2::new(rng.random_range(-room..room), rng.random_range(-room..room));
            let sides = rng.random_range(3..90);
            loops.push(circle(
                lo + DVec2::splat(0.5 * side) + jitter,
                r,
                sides,
                false,
            ));
        };
        for (i, j) in (0..6).flat_map(|i| (0..6).map(move |j| (i, j))) {
            let lo = DVec2::new(i as f64, j as f64) / 6.0;
            if (i, j) == (0, 0) {
                for (a, b) in (0..3).flat_map(|a| (0..3).map(move |b| (a, b))) {
                    hole(
                        &mut rng,
                        lo + DVec2::new(a as f64, b as f64) / 18.0,
                        1.0 / 18.0,
                    );
                }
            } else {
                hole(&mut rng, lo, 1.0 / 6.0);
            }
        }
        let trim = Trim::new(loops, unit()).unwrap();
        let mut tried = 0;
        for _ in 0..20_000 {
            let (u, v) = (rng.random_range(-0.1..1.1), rng.random_range(-0.1..1.1));
            let reach = 10f64.powf(rng.random_range(-5.0..-0.5));
            let Some(d) = trim.try_signed_distance(u, v, reach) else {
                continue;
            };
            tried += 1;
            let p = trim.inset(DVec2::new(u, v));
            let nearest = trim
                .edges()
                .map(|[a, b]| distance_to_segment(p, a, b))
                .fold(reach, f64::min);
            let expected = if trim.contains(u, v) {
                nearest
            } else {
                -nearest
            };
            assert_eq!(d.to_bits(), expected.to_bits(), "({u}, {v}) within {reach}");
        }
        assert!(tried > 5_000, "{tried} points searched");
    }

    #[test]
    fn the_signed_distance_is_that_to_the_hole_rim_and_saturates_at_its_reach() {
        // A hole of radius 0.25 as a 1024-gon, whose chords stray 3 · 10⁻⁶ from the circle.
        let hole = circle(DVec2::splat(0.5), 0.25, 1024, false);
        let trim = Trim::new(vec![square(0.0, 1.0, true), hole], unit()).unwrap();
        let mut rng = StdRng::seed_from_u64(777);
        for _ in 0..2_000 {
            let (u, v) = (rng.random::<f64>(), rng.random::<f64>());
            let r = (DVec2::new(u, v) - DVec2::splat(0.5)).length();
            let reach = 0.05;
            let d = trim.try_signed_distance(u, v, reach).unwrap();
            // Kept outside the hole: the distance is r − 0.25 there, cut inside.
            let exact = (r - 0.25).clamp(-reach, reach);
            assert!((d - exact).abs() < 1e-5, "({u}, {v}): {d} against {exact}");
        }
        // The domain's sides cut nothing: far from the hole, only the reach is seen.
        assert_eq!(trim.try_signed_distance(0.0, 0.02, 0.01), Some(0.01));
        // A reach over the whole grid is refused, as is a point that is not a number.
        assert_eq!(trim.try_signed_distance(0.5, 0.5, 2.0), None);
        assert_eq!(trim.try_signed_distance(f64::NAN, 0.5, 0.1), None);
        assert_eq!(trim.try_signed_distance(0.5, 0.5, f64::INFINITY), None);
    }

    #[test]
    fn a_hole_in_the_domain_is_cut_and_the_rest_kept_up_to_the_domain_edge() {
        let hole = circle(DVec2::splat(0.5), 0.25, 256, false);
        let trim = Trim::new(vec![square(0.0, 1.0, true), hole], unit()).unwrap();
        // Against the exact circle: points away from its polyline (within 2 × 10⁻⁵ of the
        // circle) by more than the chords' sagitta.
        let mut rng = StdRng::seed_from_u64(12345);
        let mut next = || rng.random::<f64>();
        for _ in 0..20_000 {
            let (u, v) = (next(), next());
            let r = (DVec2::new(u, v) - DVec2::splat(0.5)).length();
            if (r - 0.25).abs() < 1e-3 {
                continue;
            }
            assert_eq!(trim.contains(u, v), r > 0.25, "({u}, {v})");
        }
        // On the domain's edges and corners, and past them by rounding, the point is kept.
        for (u, v) in [
            (0.0, 0.5),
            (1.0, 0.5),
            (0.5, 0.0),
            (0.5, 1.0),
            (0.0, 0.0),
            (1.0, 1.0),
        ] {
            assert!(trim.contains(u, v), "({u}, {v})");
            assert!(trim.contains(u + (u - 0.5) * 1e-7, v + (v - 0.5) * 1e-7));
        }
        // The outer loop lies along the domain: it cuts nothing and draws no edge.
        assert_eq!(trim.edges().count(), 256);
        assert_eq!(trim.region(DVec2::ZERO, DVec2::splat(0.1)), Region::Kept);
        assert_eq!(
            trim.region(DVec2::splat(0.45), DVec2::splat(0.55)),
            Region::Cut
        );
        assert_eq!(
            trim.region(DVec2::splat(0.25), DVec2::splat(0.35)),
            Region::Both
        );
        assert_eq!(
            trim.region(DVec2::splat(0.2), DVec2::splat(0.3)),
            Region::Kept
        );
        // A box the circle passes through without a vertex in it.
        assert_eq!(
            trim.region(DVec2::new(0.74, 0.49), DVec2::new(0.76, 0.51)),
            Region::Both
        );
    }

    #[test]
    fn the_cells_answer_as_the_rays_do_through_many_holes() {
        // A grid of 5 × 4 small clockwise circles and a square one, inside the domain loop.
        let mut loops = vec![square(0.0, 1.0, true), square(0.05, 0.15, false)];
        for i in 0..5 {
            for j in 0..4 {
                let centre = DVec2::new(0.25 + 0.15 * f64::from(i), 0.3 + 0.17 * f64::from(j));
                loops.push(circle(centre, 0.05, 64, false));
            }
        }
        let trim = Trim::new(loops, unit()).unwrap();
        let mut rng = StdRng::seed_from_u64(99);
        let mut next = || rng.random::<f64>();
        let mut cut = 0;
        for _ in 0..50_000 {
            let p = DVec2::new(next(), next());
            let by_rays = trim.contains_by_rays(trim.inset(p));
            assert_eq!(trim.contains(p.x, p.y), by_rays, "{p}");
            cut += usize::from(!by_rays);
        }
        assert!(cut > 5000, "{cut}");
        // Level with the square's corners and on its sides' lines, off the square itself
        // (where either answer is right): rays and ways through its vertices.
        let on_square = |p: DVec2| {
            let within = |x: f64| (0.05..=0.15).contains(&x);
            (within(p.x) && (p.y == 0.05 || p.y == 0.15))
                || (within(p.y) && (p.x == 0.05 || p.x == 0.15))
        };
        for k in 0..=100 {
            let t = f64::from(k) / 100.0;
            let points = [DVec2::new(t, 0.05), DVec2::new(0.15, t), DVec2::new(t, t)];
            for p in points.into_iter().filter(|&p| !on_square(p)) {
                assert_eq!(
                    trim.contains(p.x, p.y),
                    trim.contains_by_rays(trim.inset(p)),
                    "{p}"
                );
            }
        }
    }

    #[test]
    fn a_segment_through_a_hole_keeps_the_parts_outside_it() {
        let hole = square(0.4, 0.6, false);
        let trim = Trim::new(vec![square(0.0, 1.0, true), hole], unit()).unwrap();
        let spans = trim.kept_spans(DVec2::new(0.1, 0.5), DVec2::new(0.9, 0.5));
        let expected = [(0.0, 0.375), (0.625, 1.0)];
        assert_eq!(spans.len(), 2);
        for (got, want) in spans.iter().zip(expected) {
            assert!((got.0 - want.0).abs() < 1e-12 && (got.1 - want.1).abs() < 1e-12);
        }
        assert_eq!(
            trim.kept_spans(DVec2::new(0.45, 0.45), DVec2::new(0.55, 0.5)),
            Vec::new()
        );
        assert_eq!(
            trim.kept_spans(DVec2::new(0.1, 0.1), DVec2::new(0.2, 0.3)),
            vec![(0.0, 1.0)]
        );
    }

    #[test]
    fn a_box_meets_a_segment_only_when_they_share_a_point() {
        let (lo, hi) = (DVec2::ZERO, DVec2::ONE);
        // Crossing the box, ending inside it, and touching a corner.
        assert!(segment_meets_box(
            DVec2::new(-1.0, 0.5),
            DVec2::new(2.0, 0.5),
            lo,
            hi
        ));
        assert!(segment_meets_box(
            DVec2::new(0.5, 0.5),
            DVec2::new(3.0, 3.0),
            lo,
            hi
        ));
        assert!(!segment_meets_box(
            DVec2::new(1.0, 2.1),
            DVec2::new(2.1, 1.0),
            lo,
            hi
        ));
        assert!(segment_meets_box(
            DVec2::new(0.0, 2.0),
            DVec2::new(2.0, 0.0),
            lo,
            hi
        ));
        // Past a corner, inside the bounding boxes' overlap.
        assert!(!segment_meets_box(
            DVec2::new(0.5, 2.0),
            DVec2::new(2.0, 0.5),
            lo,
            hi
        ));
    }

    #[test]
    fn loops_must_run_as_their_nesting_says_and_enclose_something() {
        let outer = square(0.0, 1.0, true);
        let hole = square(0.3, 0.6, true);
        let err = Trim::new(vec![outer.clone(), hole], unit()).unwrap_err();
        assert_eq!(
            err,
            TrimError::Orientation {
                index: 1,
                runs: "counter-clockwise",
                depth: 1
            }
        );
        // A lone clockwise loop would keep its inside by one rule and its outside by the other.
        let lone = square(0.3, 0.6, false);
        assert!(matches!(
            Trim::new(vec![lone], unit()),
            Err(TrimError::Orientation {
                index: 0,
                depth: 0,
                ..
            })
        ));
        // An island in a hole runs counter-clockwise again and is kept.
        let trim = Trim::new(
            vec![outer, square(0.2, 0.8, false), square(0.4, 0.6, true)],
            unit(),
        )
        .unwrap();
        assert!(trim.contains(0.1, 0.1) && !trim.contains(0.3, 0.3) && trim.contains(0.5, 0.5));
        let flat = vec![DVec2::ZERO, DVec2::X, DVec2::ZERO];
        assert_eq!(
            Trim::new(vec![flat], unit()),
            Err(TrimError::Empty { index: 0 })
        );
        let nan = vec![DVec2::ZERO, DVec2::X, DVec2::new(f64::NAN, 1.0)];
        assert_eq!(
            Trim::new(vec![nan], unit()),
            Err(TrimError::NotFinite { index: 0 })
        );
    }
}
