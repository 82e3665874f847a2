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
}
