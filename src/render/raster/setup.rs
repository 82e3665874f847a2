//! Projection to a fixed-point sub-pixel grid and triangle setup as integer edge functions.
//!
//! Screen positions are in units of 1/256 pixel (`SUBPIXEL_BITS` = 8), y down; the centre of
//! pixel `(x, y)` is `(256·x + 128, 256·y + 128)`. Edge functions are exact in `i64`, so the
//! coverage of a pixel never depends on the order of evaluation, and two triangles sharing an
//! edge see exactly opposite values on it.

use glam::{DVec2, DVec4};

use super::clip::W_MIN;

/// Fractional bits of the sub-pixel grid: vertices are snapped to 1/256 pixel.
pub const SUBPIXEL_BITS: u32 = 8;

/// Sub-pixel units per pixel.
const ONE: i64 = 1 << SUBPIXEL_BITS;

/// Largest viewport side in pixels. With the guard band it bounds snapped coordinates by
/// `2^29` units, so edge-function products stay below `2^61` and fit in `i64`.
pub const MAX_VIEWPORT_SIDE: u32 = 1 << 15;

/// Half-width of the guard band around the viewport centre, in pixels: triangles reaching past
/// it are clipped to it.
const GUARD_BAND_PIXELS: f64 = (1u32 << 20) as f64;

/// Bound on snapped coordinates (`2^29` units); clipped vertices that round past the guard band
/// are clamped to it.
const COORD_LIMIT: f64 = (1u32 << 29) as f64;

/// A rectangle of whole pixels, bounds inclusive; empty when `x0 > x1` or `y0 > y1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct PixelRect {
    pub x0: i32,
    pub y0: i32,
    pub x1: i32,
    pub y1: i32,
}

impl PixelRect {
    pub(super) fn is_empty(&self) -> bool {
        self.x0 > self.x1 || self.y0 > self.y1
    }

    pub(super) fn intersection(&self, other: &Self) -> Self {
        Self {
            x0: self.x0.max(other.x0),
            y0: self.y0.max(other.y0),
            x1: self.x1.min(other.x1),
            y1: self.y1.min(other.y1),
        }
    }
}

/// A vertex projected to the viewport and snapped to the sub-pixel grid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct ScreenVertex {
    /// Snapped position, 1/256 pixel units.
    x: i64,
    y: i64,
    /// NDC depth `z/w`, clamped to [0, 1].
    depth: f32,
    /// `1/w`.
    inv_w: f64,
}

/// The map from clip space to the pixel grid of one viewport.
#[derive(Clone, Copy, Debug)]
pub(super) struct Screen {
    half_width: f64,
    half_height: f64,
    /// All pixels of the viewport.
    pub bounds: PixelRect,
}

impl Screen {
    pub(super) fn new(width: u32, height: u32) -> Self {
        Self {
            half_width: f64::from(width) / 2.0,
            half_height: f64::from(height) / 2.0,
            bounds: PixelRect {
                x0: 0,
                y0: 0,
                x1: width as i32 - 1,
                y1: height as i32 - 1,
            },
        }
    }

    /// The guard band in NDC units, `(g_x, g_y) = GUARD_BAND_PIXELS / (W/2, H/2)`.
    pub(super) fn guard_band(&self) -> (f64, f64) {
        (
            GUARD_BAND_PIXELS / self.half_width,
            GUARD_BAND_PIXELS / self.half_height,
        )
    }

    /// Projects a clip-space vertex inside the clip planes (`w > 0`, within the guard band):
    /// `s_x = (x/w + 1)·W/2`, `s_y = (1 − y/w)·H/2` in pixels, snapped to
    /// `X = round(256·s_x)`, `Y = round(256·s_y)`.
    ///
    /// Clipping can leave a vertex just outside a plane by rounding; `w` is taken as at least
    /// `W_MIN` and the position is clamped to the fixed-point range, so the result is finite.
    pub(super) fn project(&self, v: DVec4) -> ScreenVertex {
        let inv_w = 1.0 / v.w.max(W_MIN);
        let snap = |s: f64| (s * ONE as f64).round().clamp(-COORD_LIMIT, COORD_LIMIT) as i64;
        ScreenVertex {
            x: snap((v.x * inv_w + 1.0) * self.half_width),
            y: snap((1.0 - v.y * inv_w) * self.half_height),
            depth: (v.z * inv_w).clamp(0.0, 1.0) as f32,
            inv_w,
        }
    }
}

/// The smallest pixel index whose centre `256·i + 128` is at or after `v`:
/// `ceil((v − 128) / 256)`.
fn first_centre_at_or_after(v: i64) -> i64 {
    (v - ONE / 2 + ONE - 1).div_euclid(ONE)
}

/// The largest pixel index whose centre is at or before `v`: `floor((v − 128) / 256)`.
fn last_centre_at_or_before(v: i64) -> i64 {
    (v - ONE / 2).div_euclid(ONE)
}

/// The half-space edge function of the directed edge `a → b`,
/// `E(p) = (b − a) × (p − a) = (b_x − a_x)(p_y − a_y) − (b_y − a_y)(p_x − a_x)`,
/// stepped over pixel centres and biased by the top-left fill rule.
///
/// With the triangle oriented so that `E > 0` inside, a pixel centre on the edge (`E = 0`) is
/// covered only if the edge is a *top* edge (horizontal, interior below: `d_y = 0, d_x > 0`) or a
/// *left* edge (interior to its right: `d_y < 0`), `d = b − a`. Storing `E + bias` with
/// `bias = 0` on top-left edges and `−1` elsewhere turns the test into `E + bias ≥ 0`. Reversing
/// an edge negates `E` exactly and flips whether it is top-left, so a pixel centre on an edge
/// shared by two triangles is covered by exactly one of them.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct EdgeFunction {
    /// `E + bias` at the centre of the triangle's first pixel `(x0, y0)`.
    pub origin: i64,
    /// Change of `E` from one pixel to the next along x: `−256·d_y`.
    pub step_x: i64,
    /// Change of `E` from one row to the next: `256·d_x`.
    pub step_y: i64,
}

impl EdgeFunction {
    /// The edge `a → b` evaluated from the centre of pixel `(x0, y0)`.
    fn new(a: &ScreenVertex, b: &ScreenVertex, x0: i64, y0: i64) -> Self {
        let (dx, dy) = (b.x - a.x, b.y - a.y);
        let (px, py) = (x0 * ONE + ONE / 2, y0 * ONE + ONE / 2);
        let mut edge = Self {
            origin: dx * (py - a.y) - dy * (px - a.x),
            step_x: -dy * ONE,
            step_y: dx * ONE,
        };
        edge.origin += edge.bias();
        edge
    }

    /// The fill-rule bias: 0 on a top or left edge (`d_y < 0`, or `d_y = 0` and `d_x > 0`, read
    /// from the steps), −1 otherwise.
    fn bias(&self) -> i64 {
        let top_left = self.step_x > 0 || (self.step_x == 0 && self.step_y > 0);
        i64::from(top_left) - 1
    }

    /// `E + bias` at the pixel `(dx, dy)` pixels from the triangle's first pixel.
    #[inline]
    pub(super) fn at(&self, dx: i64, dy: i64) -> i64 {
        self.origin + dx * self.step_x + dy * self.step_y
    }
}

/// A triangle ready to rasterize: its pixel bounding box, edge functions, depth plane and what
/// the perspective-correct barycentrics need.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct TriangleSetup {
    /// Pixels whose centres the snapped triangle's bounding box contains, within the viewport.
    pub rect: PixelRect,
    /// `edges[i]` is the edge opposite vertex `i`, so `E_i / (2·area)` is the screen-space
    /// barycentric `λ_i`. The vertices are ordered so that `2·area = (v1 − v0) × (v2 − v0) > 0`
    /// (clockwise as seen on screen, y down); a triangle of the other winding is flipped.
    pub edges: [EdgeFunction; 3],
    /// `(z_i/w_i) / (2·area)`: NDC depth is `Σ_i E_i · depth[i]` (linear in screen space).
    pub depth: [f32; 3],
    /// `−Σ_i bias_i·depth[i]`, undoing the fill-rule bias in the depth sum.
    pub depth_bias: f32,
    /// Per vertex `i`, `[o_i1/w_i, o_i2/w_i, 1/w_i]`, with `o_i` its barycentrics on the
    /// original triangle: the weights of `E_i` in the numerators and the denominator of the
    /// perspective-correct barycentrics.
    perspective: [[f64; 3]; 3],
    /// Index of the original triangle.
    pub triangle: u32,
    /// Whether each covered pixel must be asked of the [`Cut`](super::Cut) before it is drawn
    /// (a triangle a trim loop crosses).
    pub tested: bool,
}

impl TriangleSetup {
    /// Sets up the triangle with corners `v` (any winding), or `None` if its snapped area is
    /// zero or its bounding box holds no pixel centre of the viewport.
    pub(super) fn new(
        v: [(ScreenVertex, DVec2); 3],
        triangle: u32,
        screen: &Screen,
    ) -> Option<Self> {
        let [a, b, c] = v;
        let area2 = (b.0.x - a.0.x) * (c.0.y - a.0.y) - (b.0.y - a.0.y) * (c.0.x - a.0.x);
        let [(v0, o0), (v1, o1), (v2, o2)] = match area2 {
            0 => return None,
            a2 if a2 < 0 => [a, c, b],
            _ => [a, b, c],
        };
        let rect = bounding_rect(&[v0, v1, v2]).intersection(&screen.bounds);
        if rect.is_empty() {
            return None;
        }
        let (x0, y0) = (i64::from(rect.x0), i64::from(rect.y0));
        let edges = [
            EdgeFunction::new(&v1, &v2, x0, y0),
            EdgeFunction::new(&v2, &v0, x0, y0),
            EdgeFunction::new(&v0, &v1, x0, y0),
        ];
        let inv_area2 = 1.0 / area2.unsigned_abs() as f64;
        let depth = [v0, v1, v2].map(|v| (f64::from(v.depth) * inv_area2) as f32);
        let depth_bias = -edges
            .iter()
            .zip(depth)
            .map(|(e, d)| e.bias() as f32 * d)
            .sum::<f32>();
        Some(Self {
            rect,
            edges,
            depth,
            depth_bias,
            perspective: [(v0, o0), (v1, o1), (v2, o2)]
                .map(|(v, o)| [o.x * v.inv_w, o.y * v.inv_w, v.inv_w]),
            triangle,
            tested: false,
        })
    }

    /// NDC depth at a pixel from its biased edge values `e_i = E_i + bias_i`:
    /// `z/w = Σ_i λ_i·z_i/w_i = Σ_i E_i·(z_i/w_i)/(2·area)`.
    #[inline]
    pub(super) fn depth_at(&self, e: [i64; 3]) -> f32 {
        e[0] as f32 * self.depth[0]
            + e[1] as f32 * self.depth[1]
            + e[2] as f32 * self.depth[2]
            + self.depth_bias
    }

    /// The perspective-correct barycentrics `(b1, b2)` on the original triangle of the centre of
    /// pixel `(x, y)`, a pixel the triangle covers: with the exact edge values `E_i ≥ 0`,
    /// `λ_i = (E_i / w_i) / Σ_j (E_j / w_j)` are the barycentrics on this (sub-)triangle, and
    /// `(b1, b2) = Σ_i λ_i·o_i` from the original barycentrics `o_i` of its vertices. Every term
    /// is non-negative and `Σ_i E_i = 2·area > 0`, so the denominator is positive.
    pub(super) fn barycentric(&self, x: i32, y: i32) -> [f32; 2] {
        let (dx, dy) = (i64::from(x - self.rect.x0), i64::from(y - self.rect.y0));
        let mut sums = [0.0; 3];
        for (edge, weights) in self.edges.iter().zip(&self.perspective) {
            let e = (edge.at(dx, dy) - edge.bias()) as f64;
            for (sum, weight) in sums.iter_mut().zip(weights) {
                *sum += e * weight;
            }
        }
        let inv_denominator = 1.0 / sums[2];
        [
            (sums[0] * inv_denominator) as f32,
            (sums[1] * inv_denominator) as f32,
        ]
    }
}

/// The pixels whose centres lie in the bounding box of the snapped vertices `v`.
fn bounding_rect(v: &[ScreenVertex; 3]) -> PixelRect {
    let min = |f: fn(&ScreenVertex) -> i64| f(&v[0]).min(f(&v[1])).min(f(&v[2]));
    let max = |f: fn(&ScreenVertex) -> i64| f(&v[0]).max(f(&v[1])).max(f(&v[2]));
    // Snapped coordinates are below 2^29 units, so pixel indices fit in i32.
    PixelRect {
        x0: first_centre_at_or_after(min(|p| p.x)) as i32,
        y0: first_centre_at_or_after(min(|p| p.y)) as i32,
        x1: last_centre_at_or_before(max(|p| p.x)) as i32,
        y1: last_centre_at_or_before(max(|p| p.y)) as i32,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn vertex(x: i64, y: i64) -> ScreenVertex {
        ScreenVertex {
            x,
            y,
            depth: 0.5,
            inv_w: 1.0,
        }
    }

    #[test]
    fn pixel_centres_bounding_a_span() {
        // Pixel 0's centre is at 128 units, pixel 1's at 384.
        assert_eq!(first_centre_at_or_after(128), 0);
        assert_eq!(first_centre_at_or_after(129), 1);
        assert_eq!(first_centre_at_or_after(-200), -1);
        assert_eq!(last_centre_at_or_before(383), 0);
        assert_eq!(last_centre_at_or_before(384), 1);
        assert_eq!(last_centre_at_or_before(127), -1);
    }

    #[test]
    fn a_reversed_edge_negates_and_exactly_one_direction_is_top_left() {
        let directions = [
            (5, 0),
            (-5, 0),
            (0, 7),
            (0, -7),
            (3, 4),
            (-3, 4),
            (3, -4),
            (-3, -4),
        ];
        for (dx, dy) in directions {
            let (a, b) = (vertex(1000, 2000), vertex(1000 + dx * 100, 2000 + dy * 100));
            let forward = EdgeFunction::new(&a, &b, 3, 9);
            let backward = EdgeFunction::new(&b, &a, 3, 9);
            assert_eq!(
                forward.bias() + backward.bias(),
                -1,
                "direction ({dx}, {dy})"
            );
            // Top (rightward along x, y down) and left (upward) edges are the ones kept.
            let kept = dy < 0 || (dy == 0 && dx > 0);
            assert_eq!(
                forward.bias(),
                i64::from(kept) - 1,
                "direction ({dx}, {dy})"
            );
            for (px, py) in [(0, 0), (4, -2), (17, 5)] {
                let e = forward.at(px, py) - forward.bias();
                assert_eq!(e, -(backward.at(px, py) - backward.bias()));
            }
        }
    }

    #[test]
    fn both_windings_set_up_the_same_triangle() {
        let screen = Screen::new(32, 32);
        let corners = [vertex(300, 400), vertex(5000, 900), vertex(1200, 6000)];
        let bary = [DVec2::ZERO, DVec2::X, DVec2::Y];
        let setup = |order: [usize; 3]| {
            TriangleSetup::new(order.map(|i| (corners[i], bary[i])), 0, &screen).unwrap()
        };
        let (a, b) = (setup([0, 1, 2]), setup([0, 2, 1]));
        assert_eq!(a, b);
        let degenerate = [vertex(0, 0), vertex(256, 256), vertex(512, 512)];
        assert!(TriangleSetup::new(degenerate.map(|v| (v, DVec2::ZERO)), 0, &screen).is_none());
    }

    #[test]
    fn projection_maps_clip_space_to_snapped_pixels() {
        let screen = Screen::new(640, 360);
        // x/w = 0.5, y/w = −0.25, z/w = 0.3: s = (1.5 · 320, 1.25 · 180) = (480, 225) pixels.
        let w = 2.0;
        let v = screen.project(DVec4::new(0.5 * w, -0.25 * w, 0.3 * w, w));
        assert_eq!((v.x, v.y), (480 * 256, 225 * 256));
        assert_eq!((v.depth, v.inv_w), (0.3, 0.5));
        // Rounded to the nearest 1/256 pixel: 100.3/256 px → 100, 100.7/256 px → 101.
        let at = |sx: f64| {
            let x = sx / 320.0 - 1.0;
            screen.project(DVec4::new(x, 0.0, 0.5, 1.0)).x
        };
        assert_eq!(at(100.3 / 256.0), 100);
        assert_eq!(at(100.7 / 256.0), 101);
        // Depth clamped to [0, 1]; w no smaller than W_MIN; positions clamped to the range.
        assert_eq!(screen.project(DVec4::new(0.0, 0.0, 3.0, 2.0)).depth, 1.0);
        assert_eq!(screen.project(DVec4::new(0.0, 0.0, -1.0, 2.0)).depth, 0.0);
        let tiny = screen.project(DVec4::new(1.0, -1.0, 0.0, 0.0));
        assert_eq!(tiny.inv_w, 1.0 / W_MIN);
        assert_eq!((tiny.x, tiny.y), (1 << 29, 1 << 29));
        let far_left = screen.project(DVec4::new(-1e30, 1e30, 0.0, 1.0));
        assert_eq!((far_left.x, far_left.y), (-(1 << 29), -(1 << 29)));
        assert_eq!(
            screen.guard_band(),
            (f64::from(1 << 20) / 320.0, f64::from(1 << 20) / 180.0)
        );
        assert_eq!(
            screen.bounds,
            PixelRect {
                x0: 0,
                y0: 0,
                x1: 639,
                y1: 359
            }
        );
    }

    #[test]
    fn rectangles_are_empty_only_when_reversed_and_intersect_per_side() {
        let r = |x0, y0, x1, y1| PixelRect { x0, y0, x1, y1 };
        assert!(!r(3, 3, 3, 3).is_empty());
        assert!(r(4, 3, 3, 3).is_empty() && r(3, 4, 3, 3).is_empty());
        assert_eq!(
            r(0, 5, 10, 20).intersection(&r(4, 0, 30, 8)),
            r(4, 5, 10, 8)
        );
    }

    /// The right triangle with its legs along the axes from pixel corner (0, 0), `legs` pixels
    /// long, corner depths 0.2, 0.5 and 0.8, and `1/w` per corner.
    fn right_triangle(legs: i64, inv_w: [f64; 3], screen: &Screen) -> Option<TriangleSetup> {
        let corners = [(0, 0), (legs * ONE, 0), (0, legs * ONE)];
        let depths = [0.2, 0.5, 0.8];
        let bary = [DVec2::ZERO, DVec2::X, DVec2::Y];
        let v = std::array::from_fn(|i| {
            (
                ScreenVertex {
                    x: corners[i].0,
                    y: corners[i].1,
                    depth: depths[i],
                    inv_w: inv_w[i],
                },
                bary[i],
            )
        });
        TriangleSetup::new(v, 7, screen)
    }

    #[test]
    fn a_right_triangle_covers_the_centres_below_its_hypotenuse_with_linear_depth() {
        let screen = Screen::new(32, 32);
        let t = right_triangle(10, [1.0; 3], &screen).unwrap();
        assert_eq!(t.triangle, 7);
        // Centres (x + ½, y + ½) from 0.5 to 9.5 lie in the bounding box.
        assert_eq!(
            t.rect,
            PixelRect {
                x0: 0,
                y0: 0,
                x1: 9,
                y1: 9
            }
        );
        let mut covered = 0;
        for y in 0..10 {
            for x in 0..10 {
                let e = t.edges.map(|edge| edge.at(i64::from(x), i64::from(y)));
                let inside = e.iter().all(|&e| e >= 0);
                // The hypotenuse runs from (10, 0) to (0, 10), down and left: not a top or a
                // left edge, so centres on it (x + y = 9) are left to the neighbour.
                assert_eq!(inside, x + y <= 8, "({x}, {y})");
                if !inside {
                    continue;
                }
                covered += 1;
                let (s, r) = ((f64::from(x) + 0.5) / 10.0, (f64::from(y) + 0.5) / 10.0);
                let want = 0.2 + 0.3 * s + 0.6 * r;
                let depth = t.depth_at(e);
                assert!(
                    (f64::from(depth) - want).abs() < 1e-6,
                    "({x}, {y}): {depth}"
                );
                let [b1, b2] = t.barycentric(x, y);
                assert!((f64::from(b1) - s).abs() < 1e-6 && (f64::from(b2) - r).abs() < 1e-6);
            }
        }
        assert_eq!(covered, 45);
    }

    #[test]
    fn the_fill_rule_bias_is_undone_in_depth_and_barycentrics() {
        // Two pixels on a side, the smallest triangle covering a centre: its hypotenuse is not
        // a top or left edge, so its edge value carries a bias of −1 in 2·area = 2¹⁸ units,
        // 4e-6 of λ₀, which the depth and the barycentrics must take off again.
        let screen = Screen::new(4, 4);
        let t = right_triangle(2, [1.0; 3], &screen).unwrap();
        let e = t.edges.map(|edge| edge.at(0, 0));
        assert!(e.iter().all(|&e| e >= 0));
        // The centre (½, ½) is at s = r = ¼.
        let depth = f64::from(t.depth_at(e));
        assert!(
            (depth - (0.2 + 0.3 * 0.25 + 0.6 * 0.25)).abs() < 2e-7,
            "{depth}"
        );
        let [b1, b2] = t.barycentric(0, 0);
        assert!(
            (f64::from(b1) - 0.25).abs() < 2e-7 && (f64::from(b2) - 0.25).abs() < 2e-7,
            "{b1} {b2}"
        );
    }

    #[test]
    fn barycentrics_are_perspective_correct() {
        // With 1/w = (1, 1/2, 1/4), λ_i ∝ (screen λ_i) · (1/w_i).
        let screen = Screen::new(32, 32);
        let inv_w = [1.0, 0.5, 0.25];
        let t = right_triangle(10, inv_w, &screen).unwrap();
        for (x, y) in [(0, 0), (3, 4), (7, 0), (0, 7), (2, 2)] {
            let (s, r) = ((f64::from(x) + 0.5) / 10.0, (f64::from(y) + 0.5) / 10.0);
            let screen_weights = [1.0 - s - r, s, r];
            let weighted: Vec<f64> = (0..3).map(|i| screen_weights[i] * inv_w[i]).collect();
            let total: f64 = weighted.iter().sum();
            let [b1, b2] = t.barycentric(x, y);
            assert!(
                (f64::from(b1) - weighted[1] / total).abs() < 1e-6,
                "({x}, {y})"
            );
            assert!(
                (f64::from(b2) - weighted[2] / total).abs() < 1e-6,
                "({x}, {y})"
            );
        }
    }

    #[test]
    fn the_box_is_cut_to_the_viewport_and_a_triangle_outside_it_is_dropped() {
        let small = Screen::new(6, 4);
        let t = right_triangle(10, [1.0; 3], &small).unwrap();
        assert_eq!(
            t.rect,
            PixelRect {
                x0: 0,
                y0: 0,
                x1: 5,
                y1: 3
            }
        );
        // The box of a triangle up and to the left of the viewport holds no pixel of it.
        let v = [(-3000, -3000), (-256, -3000), (-3000, -256)]
            .map(|(x, y)| (vertex(x, y), DVec2::ZERO));
        assert!(TriangleSetup::new(v, 0, &small).is_none());
        // A sliver between two pixel centres holds none either.
        let v = [(300, 0), (350, 0), (300, 2000)].map(|(x, y)| (vertex(x, y), DVec2::ZERO));
        assert!(TriangleSetup::new(v, 0, &small).is_none());
    }

    #[test]
    fn the_box_spans_the_extremes_of_every_corner() {
        // Each corner holds one extreme, so a box from any one or two corners is too small. The
        // first centre at or after 900 units is pixel 4's (1152), after 200 pixel 1's (384); the
        // last at or before 5000 is pixel 19's (4992), before 6000 pixel 22's (5760).
        let v = [vertex(900, 3000), vertex(5000, 200), vertex(2500, 6000)];
        assert_eq!(
            bounding_rect(&v),
            PixelRect {
                x0: first_centre_at_or_after(900) as i32,
                y0: first_centre_at_or_after(200) as i32,
                x1: last_centre_at_or_before(5000) as i32,
                y1: last_centre_at_or_before(6000) as i32,
            }
        );
        assert_eq!(
            bounding_rect(&v),
            PixelRect {
                x0: 4,
                y0: 1,
                x1: 19,
                y1: 22
            }
        );
    }
}
