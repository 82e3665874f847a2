//! The kernel average of a surface's normals around a point: area-weighted normal samples
//! binned in space, summed with a compact smooth kernel over a ball.

use std::collections::HashMap;

use glam::DVec3;

/// Sub-cells per ball radius along each axis: samples are merged into cubes of side `R / 4`.
const BINS_PER_RADIUS: f64 = 4.0;

/// A surface's normals averaged over balls of one radius R.
///
/// The average at a point p with normal n is
///
/// `n̄(p, n) = normalize(Σ_k K(|p − p_k|) ½(1 + n·m̂_k) m_k)`, `K(r) = (1 − r²/R²)³` for r < R,
///
/// over binned samples k: each bin merges the samples in one cube of side R/4 whose normals
/// share their dominant axis (±x, ±y, ±z), with `m_k = Σ A n` (its area-weighted normal sum)
/// and `p_k` their area-weighted centroid. K falls to zero with its first two derivatives at R,
/// so the average moves continuously with p. The factor `½(1 + n·m̂_k)` counts a surface at a
/// right angle half and one facing the other way not at all: the far side of a thin part or of
/// a hole, which a smoothing along the surface would never reach, does not cancel the near
/// side. On a sphere every ball is symmetric about the normal: the average is the sphere's
/// normal.
#[derive(Clone, Debug)]
pub(super) struct NormalAverage {
    radius: f64,
    bins: Vec<Bin>,
    /// Bin indices per cube of side R.
    cells: HashMap<[i64; 3], Vec<u32>>,
}

#[derive(Clone, Copy, Debug)]
struct Bin {
    centroid: DVec3,
    normal_sum: DVec3,
}

/// A sample of the surface: its point, unit normal and the area it stands for.
#[derive(Clone, Copy, Debug)]
pub(super) struct AreaSample {
    pub point: DVec3,
    pub normal: DVec3,
    pub area: f64,
}

impl NormalAverage {
    /// Bins `samples` for averages over balls of `radius` (> 0). Samples with no area, or not
    /// finite, are left out.
    pub fn new(samples: impl IntoIterator<Item = AreaSample>, radius: f64) -> Self {
        let side = radius / BINS_PER_RADIUS;
        // (area, Σ A p, Σ A n) per cube and dominant axis.
        let mut merged: HashMap<([i64; 3], u8), (f64, DVec3, DVec3)> = HashMap::new();
        for s in samples {
            let usable =
                s.area > 0.0 && s.area.is_finite() && s.point.is_finite() && s.normal.is_finite();
            if !usable {
                continue;
            }
            let entry = merged
                .entry((cube(s.point, side), dominant_axis(s.normal)))
                .or_insert((0.0, DVec3::ZERO, DVec3::ZERO));
            entry.0 += s.area;
            entry.1 += s.area * s.point;
            entry.2 += s.area * s.normal;
        }
        let mut keys: Vec<_> = merged.keys().copied().collect();
        // A fixed order, so that sums and therefore frames are the same on every run.
        keys.sort_unstable();
        let mut bins = Vec::with_capacity(keys.len());
        let mut cells: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
        for key in keys {
            let (area, weighted_point, normal_sum) = merged[&key];
            let centroid = weighted_point / area;
            cells
                .entry(cube(centroid, radius))
                .or_default()
                .push(bins.len() as u32);
            bins.push(Bin {
                centroid,
                normal_sum,
            });
        }
        Self {
            radius,
            bins,
            cells,
        }
    }

    /// The average normal at `point` for a surface of normal `normal` there (see
    /// [`NormalAverage`]), or `None` when nothing facing its way lies within the radius.
    #[must_use]
    pub fn try_at(&self, point: DVec3, normal: DVec3) -> Option<DVec3> {
        let centre = cube(point, self.radius);
        let r2 = self.radius * self.radius;
        let mut sum = DVec3::ZERO;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let key = [
                        centre[0].saturating_add(dx),
                        centre[1].saturating_add(dy),
                        centre[2].saturating_add(dz),
                    ];
                    for &k in self.cells.get(&key).map_or(&[][..], Vec::as_slice) {
                        let bin = &self.bins[k as usize];
                        let d2 = (bin.centroid - point).length_squared();
                        let length = bin.normal_sum.length();
                        if d2 < r2 && length > 0.0 {
                            let falloff = 1.0 - d2 / r2;
                            let facing = 0.5 * (1.0 + normal.dot(bin.normal_sum) / length);
                            sum += falloff * falloff * falloff * facing * bin.normal_sum;
                        }
                    }
                }
            }
        }
        sum.try_normalize()
    }
}

/// The cube of side `side` holding `p`.
fn cube(p: DVec3, side: f64) -> [i64; 3] {
    let c = (p / side).floor();
    // Casts saturate: a point beyond ±2⁶³ sides lands in the outermost cube.
    [c.x as i64, c.y as i64, c.z as i64]
}

/// 0 to 5 for a normal's dominant axis and sign: +x, −x, +y, −y, +z, −z.
fn dominant_axis(n: DVec3) -> u8 {
    let a = n.abs();
    let (axis, value) = if a.x >= a.y && a.x >= a.z {
        (0, n.x)
    } else if a.y >= a.z {
        (1, n.y)
    } else {
        (2, n.z)
    };
    2 * axis + u8::from(value < 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Samples of the unit sphere at `n × 2n` longitude–latitude points, each with its
    /// quadrature area `cos φ Δθ Δφ`.
    fn sphere_samples(n: usize) -> Vec<AreaSample> {
        let mut out = Vec::new();
        let (dphi, dtheta) = (
            std::f64::consts::PI / n as f64,
            std::f64::consts::PI / n as f64,
        );
        for i in 0..n {
            let phi = -std::f64::consts::FRAC_PI_2 + (i as f64 + 0.5) * dphi;
            for j in 0..2 * n {
                let theta = (j as f64 + 0.5) * dtheta;
                let p = DVec3::new(phi.cos() * theta.cos(), phi.cos() * theta.sin(), phi.sin());
                out.push(AreaSample {
                    point: p,
                    normal: p,
                    area: phi.cos() * dphi * dtheta,
                });
            }
        }
        out
    }

    #[test]
    fn a_sphere_averages_to_its_own_normals() {
        let average = NormalAverage::new(sphere_samples(90), 0.6);
        for p in [
            DVec3::X,
            DVec3::new(0.3, -0.5, 0.81).normalize(),
            DVec3::Z,
            -DVec3::Z,
        ] {
            let n = average.try_at(p, p).unwrap();
            assert!(n.dot(p) > 1.0 - 1e-5, "{p}: {n}");
        }
    }

    #[test]
    fn a_step_is_softened_within_the_radius_only() {
        // A floor (+z, x < 0) falling away down a wall (+x, z < 0) at the y axis.
        // Sample rows off the cube boundaries (multiples of 0.125), so that both faces bin alike.
        let mut samples = Vec::new();
        for i in 0..200 {
            let t = 0.0025 + 0.01 * i as f64;
            for j in 0..200 {
                let b = j as f64 * 0.01 - 0.995;
                samples.push(AreaSample {
                    point: DVec3::new(-t, b, 0.0),
                    normal: DVec3::Z,
                    area: 1e-4,
                });
                samples.push(AreaSample {
                    point: DVec3::new(0.0, b, -t),
                    normal: DVec3::X,
                    area: 1e-4,
                });
            }
        }
        let average = NormalAverage::new(samples, 0.5);
        let far = average
            .try_at(DVec3::new(-1.5, 0.0, 0.0), DVec3::Z)
            .unwrap();
        assert!((far - DVec3::Z).length() < 1e-12, "{far}");
        let near = average
            .try_at(DVec3::new(-0.1, 0.0, 0.0), DVec3::Z)
            .unwrap();
        assert!(
            near.z > 0.5 && near.x > 0.05 && near.y.abs() < 1e-9,
            "{near}"
        );
        // Halfway round the edge the average leans as far toward either face.
        let edge = average
            .try_at(DVec3::ZERO, DVec3::new(1.0, 0.0, 1.0).normalize())
            .unwrap();
        assert!((edge.x - edge.z).abs() < 1e-12, "{edge}");
        // Facing away from everything: no average.
        assert_eq!(average.try_at(DVec3::new(-1.5, 0.0, 0.0), -DVec3::Z), None);
    }

    #[test]
    fn dominant_axes_are_told_apart_by_sign() {
        let axes = [
            DVec3::X,
            -DVec3::X,
            DVec3::Y,
            -DVec3::Y,
            DVec3::Z,
            -DVec3::Z,
        ];
        for (k, a) in axes.iter().enumerate() {
            assert_eq!(dominant_axis(*a + 0.1 * DVec3::ONE), k as u8, "{a}");
        }
    }
}
