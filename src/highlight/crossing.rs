//! Where a closed polyline crosses or touches itself.

use glam::DVec2;

/// The first pair of edges `(i, j)`, `i < j`, of the closed polyline `points` that meet other
/// than at the vertex two neighbours share, and a point where they meet; None for a simple
/// polygon. Edge k runs from `points[k]` to `points[(k + 1) % n]`.
///
/// A sweep along x: the edges sorted by their least x, each tested against the edges after it
/// whose x-interval overlaps its own (then their y-intervals, then exactly). Two edges meet
/// where each one's ends are not strictly on the same side of the other's line (the signs of
/// the orientation determinants `(b − a) × (c − a)`, in f64); collinear edges meet where they
/// overlap. Neighbours share a vertex and meet elsewhere only when they fold back along one
/// line. The work is `O(n log n + k)` for k overlapping pairs, and at most `O(n²)`.
#[must_use]
pub fn first_crossing(points: &[DVec2]) -> Option<(usize, usize, DVec2)> {
    let n = points.len();
    if n < 3 {
        return None;
    }
    let edge = |k: usize| (points[k], points[(k + 1) % n]);
    let mut order: Vec<usize> = (0..n).collect();
    let min_x = |k: usize| {
        let (a, b) = edge(k);
        a.x.min(b.x)
    };
    order.sort_by(|&i, &j| min_x(i).total_cmp(&min_x(j)));
    let mut found: Option<(usize, usize, DVec2)> = None;
    for (rank, &i) in order.iter().enumerate() {
        let (a, b) = edge(i);
        let max_x = a.x.max(b.x);
        for &j in &order[rank + 1..] {
            if min_x(j) > max_x {
                break;
            }
            let (c, d) = edge(j);
            if a.y.max(b.y) < c.y.min(d.y) || c.y.max(d.y) < a.y.min(b.y) {
                continue;
            }
            let (lo, hi) = (i.min(j), i.max(j));
            let meet = if hi == lo + 1 || (lo == 0 && hi == n - 1) {
                // Neighbours: the shared vertex is no crossing; folding back along it is.
                let (first, second) = if hi == lo + 1 { (lo, hi) } else { (hi, lo) };
                folds_back(edge(first), edge(second))
            } else {
                segments_meet((a, b), (c, d))
            };
            if let Some(p) = meet {
                // Keep the pair that comes first in the outline's order, whatever the sweep's.
                if found.is_none_or(|(fi, fj, _)| (lo, hi) < (fi, fj)) {
                    found = Some((lo, hi, p));
                }
            }
        }
    }
    found
}

/// `(b − a) × (c − a)`: positive where c is left of the line from a to b.
fn orient(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    (b - a).perp_dot(c - a)
}

/// Whether `c`, known collinear with `a b`, lies within the segment's box.
fn within(a: DVec2, b: DVec2, c: DVec2) -> bool {
    c.x >= a.x.min(b.x) && c.x <= a.x.max(b.x) && c.y >= a.y.min(b.y) && c.y <= a.y.max(b.y)
}

/// A point where the segments `a b` and `c d` meet, if they do.
fn segments_meet((a, b): (DVec2, DVec2), (c, d): (DVec2, DVec2)) -> Option<DVec2> {
    let (o1, o2) = (orient(a, b, c), orient(a, b, d));
    let (o3, o4) = (orient(c, d, a), orient(c, d, b));
    if o1 == 0.0 && within(a, b, c) {
        return Some(c);
    }
    if o2 == 0.0 && within(a, b, d) {
        return Some(d);
    }
    if o3 == 0.0 && within(c, d, a) {
        return Some(a);
    }
    if o4 == 0.0 && within(c, d, b) {
        return Some(b);
    }
    if (o1 > 0.0) != (o2 > 0.0)
        && o1 != 0.0
        && o2 != 0.0
        && (o3 > 0.0) != (o4 > 0.0)
        && o3 != 0.0
        && o4 != 0.0
    {
        let t = o3 / (o3 - o4);
        return Some(a + (b - a) * t);
    }
    None
}

/// Where the edge after a vertex runs back along the edge before it: the two are collinear at
/// their shared vertex and point opposite ways.
fn folds_back((a, b): (DVec2, DVec2), (_, d): (DVec2, DVec2)) -> Option<DVec2> {
    let (before, after) = (b - a, d - b);
    (before.perp_dot(after) == 0.0 && before.dot(after) < 0.0).then_some(b)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn poly(points: &[(f64, f64)]) -> Vec<DVec2> {
        points.iter().map(|&(x, y)| DVec2::new(x, y)).collect()
    }

    #[test]
    fn a_square_and_a_concave_notch_are_simple() {
        assert_eq!(
            first_crossing(&poly(&[(0., 0.), (1., 0.), (1., 1.), (0., 1.)])),
            None
        );
        let notch = poly(&[(0., 0.), (1., 0.), (1., 1.), (0.5, 0.2), (0., 1.)]);
        assert_eq!(first_crossing(&notch), None);
    }

    #[test]
    fn a_bow_tie_crosses_at_its_middle() {
        let bow = poly(&[(0., 0.), (1., 1.), (1., 0.), (0., 1.)]);
        let (i, j, p) = first_crossing(&bow).unwrap();
        assert_eq!((i, j), (0, 2));
        assert!((p - DVec2::new(0.5, 0.5)).length() < 1e-12, "{p}");
    }

    #[test]
    fn a_vertex_on_another_edge_and_a_spike_are_refused() {
        // The vertex (0.5, 0) lies on edge 0.
        let touch = poly(&[(0., 0.), (1., 0.), (1., 1.), (0.5, 0.0), (0., 1.)]);
        assert!(first_crossing(&touch).is_some());
        // Edge 1 runs back along edge 0.
        let spike = poly(&[(0., 0.), (1., 0.), (0.5, 0.0), (0.5, 1.0)]);
        assert!(first_crossing(&spike).is_some());
    }

    #[test]
    fn a_star_drawn_in_one_stroke_crosses_and_drawn_round_does_not() {
        let tip = |k: usize, r: f64| {
            let a = std::f64::consts::TAU * k as f64 / 5.0;
            DVec2::new(r * a.cos(), r * a.sin())
        };
        let pentagram: Vec<DVec2> = (0..5).map(|k| tip(2 * k % 5, 1.0)).collect();
        assert!(first_crossing(&pentagram).is_some());
        let star: Vec<DVec2> = (0..10)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 10.0;
                let r = if k % 2 == 0 { 1.0 } else { 0.4 };
                DVec2::new(r * a.cos(), r * a.sin())
            })
            .collect();
        assert_eq!(first_crossing(&star), None);
    }
}
