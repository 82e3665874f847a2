//! A function over a pixel's box taken as the quadratic through its values at the nine pixel
//! centres of the 3 × 3 neighbourhood.

use super::box_coverage;

/// `f(x, y) ≈ c + g_x x + g_y y + ½ c_xx x² + c_xy x y + ½ c_yy y²` over the box `|x|, |y| ≤ ½`
/// (in pixels, about its centre), through `d[y][x]`, the values at the centres around it
/// (`d[1][1]` its own): slope `g = ((d₊ₓ − d₋ₓ)/2, (d₊ᵧ − d₋ᵧ)/2)`, second differences
/// `c_xx = d₊ₓ + d₋ₓ − 2d`, `c_yy` likewise and `c_xy = (d₊₊ − d₊₋ − d₋₊ + d₋₋)/4`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BoxQuadratic {
    pub centre: f32,
    pub gx: f32,
    pub gy: f32,
    pub cxx: f32,
    pub cyy: f32,
    pub cxy: f32,
}

/// How a level set of a [`BoxQuadratic`] that reaches its box crosses it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LevelCrossing {
    /// Nearly straight: drawing it as the straight line of the slope `(g_x, g_y)` through the
    /// centre's value misplaces less than the area asked of the pixel.
    Straight,
    /// Bent over the box, or a jump: the slope changes along itself by more than asked.
    Bent,
}

impl BoxQuadratic {
    /// Sub-boxes per side of the box over which [`coverage_above`](Self::coverage_above) takes
    /// tangent planes.
    pub const SUB: usize = 4;

    /// The quadratic through the nine values `d[y][x]` about `d[1][1]`.
    #[must_use]
    pub fn through(d: &[[f32; 3]; 3]) -> Self {
        let centre = d[1][1];
        Self {
            centre,
            gx: 0.5 * (d[1][2] - d[1][0]),
            gy: 0.5 * (d[2][1] - d[0][1]),
            cxx: d[1][2] + d[1][0] - 2.0 * centre,
            cyy: d[2][1] + d[0][1] - 2.0 * centre,
            cxy: 0.25 * (d[2][2] - d[2][0] - d[0][2] + d[0][0]),
        }
    }

    /// The same quadratic about `(x, y)`: the box of the pixel that far from this one's.
    #[must_use]
    pub fn moved_to(&self, x: f32, y: f32) -> Self {
        Self {
            centre: self.at(x, y),
            gx: self.gx + self.cxx * x + self.cxy * y,
            gy: self.gy + self.cxy * x + self.cyy * y,
            ..*self
        }
    }

    /// Its value at `(x, y)` about the centre.
    #[inline]
    #[must_use]
    pub fn at(&self, x: f32, y: f32) -> f32 {
        self.centre
            + self.gx * x
            + self.gy * y
            + 0.5 * self.cxx * x * x
            + self.cxy * x * y
            + 0.5 * self.cyy * y * y
    }

    /// The fraction of the box where the quadratic exceeds `t`: the mean over [`SUB`](Self::SUB) ×
    /// [`SUB`](Self::SUB) sub-boxes of the [`box_coverage`] of its tangent plane at each one's centre `(x, y)`,
    /// value `f(x, y) − t` and slope `(g_x + c_xx x + c_xy y, g_y + c_xy x + c_yy y)` over the
    /// sub-box's side `1/SUB`. The tangent plane leaves out the bend over a sub-box, a
    /// `SUB²`-th of that over the box.
    #[must_use]
    pub fn coverage_above(&self, t: f32) -> f32 {
        let side = 1.0 / Self::SUB as f32;
        let mut sum = 0.0;
        for j in 0..Self::SUB {
            let y = (j as f32 + 0.5) * side - 0.5;
            for i in 0..Self::SUB {
                let x = (i as f32 + 0.5) * side - 0.5;
                let gx = self.gx + self.cxx * x + self.cxy * y;
                let gy = self.gy + self.cxy * x + self.cyy * y;
                sum += box_coverage(self.at(x, y) - t, gx * side, gy * side);
            }
        }
        sum * side * side
    }

    /// The most the quadratic moves from its centre's value over the box: its linear part by
    /// at most `(|g_x| + |g_y|)/2`, its quadratic part by at most
    /// `(|c_xx| + |c_yy|)/8 + |c_xy|/4`. Not finite where a value is not.
    #[must_use]
    pub fn reach(&self) -> f32 {
        let bend = 0.125 * (self.cxx.abs() + self.cyy.abs()) + 0.25 * self.cxy.abs();
        0.5 * (self.gx.abs() + self.gy.abs()) + bend
    }

    /// Whether the level set `f = t` crosses the box straight enough to be drawn as the
    /// straight line of the slope through the centre's value. With `c_gg` and `c_pp` the second
    /// derivatives along `g` and across it, the straight line lies at `r = (t − c)/‖g‖` along
    /// `g`; the curvature along `g` moves it by `c_gg r²/(2‖g‖)`, and the bend across `g`
    /// (`c_pp x²/(2‖g‖)` at `x` along the line) by the mean of that over the box's width,
    /// `c_pp/(24‖g‖)`. [`LevelCrossing::Straight`] where their sum is at most `area` of the
    /// pixel and the slope changes along itself by at most `jump` of itself from one pixel to
    /// the next (`|c_gg| ≤ jump ‖g‖`: more is a jump, one part of a surface in front of another,
    /// or a surface turning away toward its silhouette); `None` without a slope.
    #[must_use]
    pub fn crossing(&self, t: f32, area: f32, jump: f32) -> Option<LevelCrossing> {
        let Self {
            centre,
            gx,
            gy,
            cxx,
            cyy,
            cxy,
        } = *self;
        let slope2 = gx * gx + gy * gy;
        if slope2.is_nan() || slope2 <= 0.0 {
            return None;
        }
        let slope = slope2.sqrt();
        let along = (gx * gx * cxx + 2.0 * gx * gy * cxy + gy * gy * cyy) / slope2;
        let across = (gy * gy * cxx - 2.0 * gx * gy * cxy + gx * gx * cyy) / slope2;
        let r = (t - centre) / slope;
        let misplaced = (0.5 * along.abs() * r * r + across.abs() / 24.0) / slope;
        Some(if misplaced <= area && along.abs() <= jump * slope {
            LevelCrossing::Straight
        } else {
            LevelCrossing::Bent
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `f` at the nine centres around the pixel.
    fn around(f: impl Fn(f32, f32) -> f32) -> [[f32; 3]; 3] {
        std::array::from_fn(|y| std::array::from_fn(|x| f(x as f32 - 1.0, y as f32 - 1.0)))
    }

    #[test]
    fn a_moved_quadratic_takes_the_same_values() {
        let q = BoxQuadratic::through(&around(|x, y| {
            0.3 + 0.2 * x - 0.1 * y + 0.5 * 0.04 * x * x + 0.07 * x * y - 0.5 * 0.06 * y * y
        }));
        let moved = q.moved_to(1.0, -1.0);
        for (x, y) in [(0.0, 0.0), (0.4, -0.3), (-0.5, 0.5), (1.0, 1.0)] {
            let (a, b) = (moved.at(x, y), q.at(x + 1.0, y - 1.0));
            assert!((a - b).abs() < 1e-6, "({x}, {y}): {a} against {b}");
        }
    }

    #[test]
    fn a_quadratic_is_recovered_from_its_nine_values() {
        let q = BoxQuadratic::through(&around(|x, y| {
            0.3 + 0.2 * x - 0.1 * y + 0.5 * 0.04 * x * x + 0.07 * x * y - 0.5 * 0.06 * y * y
        }));
        let expected = [0.3, 0.2, -0.1, 0.04, -0.06, 0.07];
        let got = [q.centre, q.gx, q.gy, q.cxx, q.cyy, q.cxy];
        for (g, e) in got.iter().zip(expected) {
            assert!((g - e).abs() < 1e-6, "{got:?}");
        }
    }

    #[test]
    fn the_reach_bounds_the_quadratic_over_the_box() {
        let f = |x: f32, y: f32| 0.1 * x - 0.3 * y + 0.2 * x * x - 0.15 * x * y + 0.05 * y * y;
        let q = BoxQuadratic::through(&around(f));
        let mut most = 0.0f32;
        for i in 0..=20 {
            for j in 0..=20 {
                let (x, y) = (i as f32 / 20.0 - 0.5, j as f32 / 20.0 - 0.5);
                most = most.max((f(x, y) - f(0.0, 0.0)).abs());
            }
        }
        assert!(most <= q.reach() + 1e-6 && most > 0.5 * q.reach());
    }

    #[test]
    fn the_coverage_above_a_level_is_the_area_the_quadratic_exceeds_it_on() {
        // Against counting a 600 × 600 grid of points of the box, in f64: a gentle curve, the
        // rim of a disc of radius 2 px centred 1.8 px to the left, a saddle, and a straight
        // edge.
        let cases: [(f64, f64, f64, f64, f64, f64); 4] = [
            (0.02, 0.1, 0.03, -0.04, 0.01, 0.02),
            (0.038, -0.18, 0.0, -0.1, -0.1, 0.0),
            (0.0, 0.05, 0.0, 0.0, 0.0, 0.3),
            (-0.03, -0.2, 0.1, 0.0, 0.0, 0.0),
        ];
        for (c, gx, gy, cxx, cyy, cxy) in cases {
            let f = |x: f64, y: f64| {
                c + gx * x + gy * y + 0.5 * cxx * x * x + cxy * x * y + 0.5 * cyy * y * y
            };
            let n = 600;
            let inside = (0..n * n)
                .filter(|i| {
                    let x = (f64::from(i % n) + 0.5) / f64::from(n) - 0.5;
                    let y = (f64::from(i / n) + 0.5) / f64::from(n) - 0.5;
                    f(x, y) > 0.0
                })
                .count() as f64
                / f64::from(n * n);
            let q = BoxQuadratic::through(&around(|x, y| f(f64::from(x), f64::from(y)) as f32));
            let got = f64::from(q.coverage_above(0.0));
            assert!(
                (got - inside).abs() < 4e-3,
                "{c} {gx} {gy}: {got} against {inside}"
            );
        }
    }

    #[test]
    fn a_flat_quadratic_has_no_crossing() {
        let q = BoxQuadratic::through(&around(|_, _| 0.4));
        assert_eq!(q.crossing(0.4, 0.02, 0.5), None);
    }
}
