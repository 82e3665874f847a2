//! A drawn outline made ready to evaluate: its closed polyline and the signed distance to it.

use glam::{DVec2, Vec2, Vec3};

/// Edges held side by side, so that a point's distance to [`EDGE_LANES`] of them is taken at
/// once.
const EDGE_LANES: usize = 8;

/// [`EDGE_LANES`] edges of the polyline, one array per coordinate: each edge's start `a`, its
/// direction `e = b − a` and `1 / |e|²` (0 for an edge of no length). Lanes past the last edge
/// hold a point edge far outside (`a` at 10⁶, `e` = 0), nearer no point than a real edge and
/// crossing no ray.
#[derive(Clone, Copy, Debug, PartialEq)]
struct EdgeChunk {
    ax: [f32; EDGE_LANES],
    ay: [f32; EDGE_LANES],
    ex: [f32; EDGE_LANES],
    ey: [f32; EDGE_LANES],
    inv_len2: [f32; EDGE_LANES],
}

impl EdgeChunk {
    /// A chunk of edges standing for none.
    const FAR: Self = Self {
        ax: [1e6; EDGE_LANES],
        ay: [1e6; EDGE_LANES],
        ex: [0.0; EDGE_LANES],
        ey: [0.0; EDGE_LANES],
        inv_len2: [0.0; EDGE_LANES],
    };
}

/// A closed, simple polyline in the tangent coordinates `t' = ((H', du), (H', dv))`, with the
/// scale that puts its signed distance in the units of a disc's signed value.
#[derive(Clone, Debug, PartialEq)]
pub struct PreparedOutline {
    edges: Vec<EdgeChunk>,
    /// `c = r / √(1 − r²)`, r the radius of the disc of the polygon's area (see [`Self::signed`]).
    scale: f32,
}

impl PreparedOutline {
    /// The polygon through `points` in order, closed from the last back to the first, with
    /// `|t'| < 1`. It need not be simple (a frame between two keys of a morph may cross itself):
    /// inside is where its winding number is not zero. An edge of no length is the distance to
    /// its point; a polygon of no area (a morph collapsing to a point or a line) covers nothing.
    #[must_use]
    pub fn new(points: &[DVec2]) -> Self {
        let n = points.len();
        let mut edges = vec![EdgeChunk::FAR; n.div_ceil(EDGE_LANES)];
        for k in 0..n {
            let a = points[k].as_vec2();
            let e = points[(k + 1) % n].as_vec2() - a;
            let inverse = 1.0 / e.length_squared();
            let (chunk, lane) = (&mut edges[k / EDGE_LANES], k % EDGE_LANES);
            chunk.ax[lane] = a.x;
            chunk.ay[lane] = a.y;
            chunk.ex[lane] = e.x;
            chunk.ey[lane] = e.y;
            chunk.inv_len2[lane] = if inverse.is_finite() { inverse } else { 0.0 };
        }
        let area = polygon_area(points).abs();
        let r2 = (area / std::f64::consts::PI).clamp(1e-12, 0.999);
        Self {
            edges,
            scale: (r2 / (1.0 - r2)).sqrt() as f32,
        }
    }

    /// The signed distance from `p` to the polygon, positive inside: `±min_k |p − (a_k + t e_k)|`
    /// with `t = clamp((p − a_k)·e_k / |e_k|², 0, 1)`, inside where the winding number of the
    /// polygon about p is not zero (for a simple polygon, where an odd number of edges cross
    /// the ray from p toward +x).
    /// With no edges (no points) every p is outside, at distance 1.
    #[must_use]
    pub fn distance(&self, p: Vec2) -> f32 {
        if self.edges.is_empty() {
            return -1.0;
        }
        // Per lane, over the edges it holds; lanes are independent, so they run side by side.
        let mut nearest = [f32::INFINITY; EDGE_LANES];
        let mut winding = [0_i32; EDGE_LANES];
        for c in &self.edges {
            for k in 0..EDGE_LANES {
                let (wx, wy) = (p.x - c.ax[k], p.y - c.ay[k]);
                let t = ((wx * c.ex[k] + wy * c.ey[k]) * c.inv_len2[k]).clamp(0.0, 1.0);
                let (dx, dy) = (wx - c.ex[k] * t, wy - c.ey[k] * t);
                nearest[k] = nearest[k].min(dx * dx + dy * dy);
                // Upward edges that p is left of count +1, downward ones it is right of −1.
                let b_y = c.ay[k] + c.ey[k];
                let side = c.ex[k] * wy - c.ey[k] * wx;
                let up = (c.ay[k] <= p.y) & (b_y > p.y) & (side > 0.0);
                let down = (c.ay[k] > p.y) & (b_y <= p.y) & (side < 0.0);
                winding[k] += i32::from(up) - i32::from(down);
            }
        }
        let nearest = nearest.into_iter().fold(f32::INFINITY, f32::min);
        let winding: i32 = winding.iter().sum();
        let d = nearest.sqrt();
        if winding != 0 {
            d
        } else {
            -d
        }
    }

    /// The signed value of the stack's unit output `l` in the layer's frame (N is +z), in the
    /// units of a disc's `s = ε − ‖N − H'‖²/2`: `s = c·d(t')`, d the signed distance
    /// ([`distance`](Self::distance)) at `t' = (l_x, l_y)` and `c = r/√(1 − r²)`, r the radius of
    /// the disc with the polygon's area.
    ///
    /// For the disc of radius r, `s = ε − (1 − √(1 − |t'|²))`, whose slope across its edge is
    /// `r/√(1 − r²)` per unit of t': so an outline that draws that circle has the disc's `s` to
    /// first order at the edge, and a feather or an edge width written in units of ε reads the
    /// same on a drawn shape as on the disc of its area. Below the tangent plane (`l_z ≤ 0`,
    /// no t') it goes on falling ([`distance_at`](Self::distance_at)).
    #[inline]
    #[must_use]
    pub fn signed(&self, l: Vec3) -> f32 {
        self.scale * self.distance_at(l)
    }

    /// The signed distance of the stack's unit output `l` (N is +z), unscaled: `d(t')` with
    /// `t' = (l_x, l_y)` above the tangent plane; below it (`l_z ≤ 0`, no t'), `d(t̂) + l_z`
    /// with t̂ the unit direction of t', which meets the value above at `l_z = 0` (there
    /// `|t'| = 1`, outside every valid outline), and −1 + l_z where t' = 0.
    #[inline]
    #[must_use]
    pub fn distance_at(&self, l: Vec3) -> f32 {
        let t = Vec2::new(l.x, l.y);
        if l.z > 0.0 {
            return self.distance(t);
        }
        let away = match t.try_normalize() {
            Some(direction) => self.distance(direction),
            None => -1.0,
        };
        away + l.z
    }

    /// `c = r/√(1 − r²)`, the factor from t' distance to the units of a disc's `s`
    /// ([`signed`](Self::signed)).
    #[must_use]
    pub fn scale(&self) -> f32 {
        self.scale
    }
}

/// The shoelace area of the closed polygon `points`: positive counter-clockwise.
#[must_use]
pub fn polygon_area(points: &[DVec2]) -> f64 {
    let n = points.len();
    0.5 * (0..n)
        .map(|k| points[k].perp_dot(points[(k + 1) % n]))
        .sum::<f64>()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn poly(points: &[(f64, f64)]) -> PreparedOutline {
        let p: Vec<DVec2> = points.iter().map(|&(x, y)| DVec2::new(x, y)).collect();
        PreparedOutline::new(&p)
    }

    fn close(a: f32, b: f32) -> bool {
        (a - b).abs() < 1e-6
    }

    #[test]
    fn a_square_distances_inside_outside_and_at_a_corner() {
        // The square [−0.2, 0.2]², written clockwise: the sign does not depend on the direction.
        let sq = poly(&[(-0.2, -0.2), (-0.2, 0.2), (0.2, 0.2), (0.2, -0.2)]);
        assert!(close(sq.distance(Vec2::ZERO), 0.2));
        assert!(close(sq.distance(Vec2::new(0.15, 0.0)), 0.05));
        assert!(close(sq.distance(Vec2::new(0.3, 0.0)), -0.1));
        // Off the corner (0.2, 0.2) diagonally: the distance to the vertex, 0.1·√2.
        assert!(close(sq.distance(Vec2::new(0.3, 0.3)), -0.1 * 2f32.sqrt()));
        // Inside near the corner: the nearer side.
        assert!(close(sq.distance(Vec2::new(0.19, 0.15)), 0.01));
    }

    #[test]
    fn a_concave_notch_is_outside_in_its_mouth() {
        // A square 0.4 wide with a notch cut down from its top to (0, 0).
        let notch = poly(&[
            (-0.2, -0.2),
            (0.2, -0.2),
            (0.2, 0.2),
            (0.1, 0.2),
            (0.0, 0.0),
            (-0.1, 0.2),
            (-0.2, 0.2),
        ]);
        // In the mouth of the notch, straight above its tip by 0.1: outside, nearest the two
        // slanted sides, at distance 0.1·sin(atan(0.1/0.2)) = 0.1/√5.
        let d = notch.distance(Vec2::new(0.0, 0.1));
        assert!(close(d, -0.1 / 5f32.sqrt()), "{d}");
        // Below the tip, inside by 0.05 to the tip itself (sides further) and 0.15 to the bottom.
        assert!(close(notch.distance(Vec2::new(0.0, -0.05)), 0.05));
    }

    #[test]
    fn a_star_is_outside_between_its_tips_and_inside_at_its_centre() {
        let points: Vec<(f64, f64)> = (0..10)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 10.0;
                let r = if k % 2 == 0 { 0.3 } else { 0.12 };
                (r * a.cos(), r * a.sin())
            })
            .collect();
        let star = poly(&points);
        // The centre: the foot of the perpendicular onto an edge's line falls past the inner
        // corner (at t = 0.3·0.2029/0.0461 ≈ 1.32 along the edge from the tip), so the nearest
        // points are the five inner corners, 0.12 away.
        let (outer, inner) = (DVec2::new(0.3, 0.0), {
            let a = std::f64::consts::TAU / 10.0;
            DVec2::new(0.12 * a.cos(), 0.12 * a.sin())
        });
        let e = inner - outer;
        assert!((-outer).dot(e) / e.length_squared() > 1.0);
        assert!(close(star.distance(Vec2::ZERO), 0.12));
        // Beyond an inner corner, toward where a tip would be on a pentagon: outside.
        let a = std::f32::consts::TAU / 10.0;
        let beyond = Vec2::new(a.cos(), a.sin()) * 0.2;
        assert!(star.distance(beyond) < 0.0);
        // The tip itself is on the edge.
        assert!(star.distance(Vec2::new(0.3, 0.0)).abs() < 1e-6);
    }

    #[test]
    fn the_scale_matches_the_disc_slope_at_its_edge() {
        // A fine polygon of the circle of radius r: s falls at r/√(1 − r²) per unit of t'.
        let r = 0.3_f64;
        let circle: Vec<DVec2> = (0..512)
            .map(|k| {
                let a = std::f64::consts::TAU * k as f64 / 512.0;
                DVec2::new(r * a.cos(), r * a.sin())
            })
            .collect();
        let o = PreparedOutline::new(&circle);
        let want = r / (1.0 - r * r).sqrt();
        assert!((f64::from(o.scale) - want).abs() < 1e-4 * want);
        // Below the tangent plane the value is negative and continuous at l_z = 0.
        let at = |z: f32| o.signed(Vec3::new((1.0 - z * z).sqrt(), 0.0, z));
        assert!(at(-0.5) < at(0.0) && at(0.0) < 0.0);
        assert!((at(1e-4) - at(-1e-4)).abs() < 1e-3);
        assert!(o.signed(Vec3::NEG_Z) < 0.0);
    }

    #[test]
    fn a_crossing_or_collapsed_polygon_evaluates_without_nan() {
        // A bow tie: inside each lobe (winding ±1), outside beyond.
        let bow = poly(&[(0.0, 0.0), (0.2, 0.2), (0.2, 0.0), (0.0, 0.2)]);
        assert!(bow.distance(Vec2::new(0.03, 0.1)) > 0.0);
        assert!(bow.distance(Vec2::new(0.17, 0.1)) > 0.0);
        assert!(bow.distance(Vec2::new(0.1, 0.19)) < 0.0);
        // Collapsed to a point, to a line, and to nothing: finite and outside everywhere.
        for points in [
            &[(0.1, 0.1)][..],
            &[(0.0, 0.0), (0.2, 0.0)][..],
            &[(0.0, 0.0), (0.1, 0.0), (0.2, 0.0)][..],
            &[][..],
        ] {
            let o = poly(points);
            for p in [Vec3::Z, Vec3::new(0.1, 0.0, 0.99).normalize(), Vec3::NEG_Z] {
                let s = o.signed(p);
                assert!(s.is_finite() && s <= 0.0, "{points:?} {p}: {s}");
            }
        }
    }
}
