//! The smoothed shape of a NURBS model: its normals averaged over a neighbourhood whose size
//! the smoothing iterations set, sampled on a grid per patch to look up per point.

use glam::{DVec3, Vec2, Vec3};

use super::error::XToonError;
use super::grid::Grid;
use super::normal_average::{AreaSample, NormalAverage};
use super::point_run::PointRun;
use crate::geom::{GridEvaluator, NurbsSurface, PatchLibrary};
use crate::math::Lanes;

/// Normal grid samples per knot span, in each direction.
const SAMPLES_PER_SPAN: usize = 16;

/// Normal grid intervals per direction at the most: a patch of more than 64 spans in a
/// direction is sampled more coarsely than [`SAMPLES_PER_SPAN`], and its grid stays within
/// 1025 × 1025 normals.
const MAX_INTERVALS: usize = 1024;

/// The intervals of a patch's normal grid along a direction of `spans` knot spans.
fn intervals(spans: usize) -> usize {
    (SAMPLES_PER_SPAN * spans.max(1)).min(MAX_INTERVALS)
}

/// Per patch, the normals of the smoothed model on a uniform grid over its domain.
#[derive(Clone, Debug, PartialEq)]
pub struct SmoothedNormals {
    patches: Vec<NormalGrid>,
}

#[derive(Clone, Debug, PartialEq)]
struct NormalGrid {
    /// Domain start and `(samples − 1) / length` per direction: `(uv − origin) · scale` are
    /// the grid coordinates (row along u, column along v).
    origin: Vec2,
    scale: Vec2,
    normals: Grid,
}

/// A patch's grid of surface samples: `rows × columns` points and unit normals, row-major.
struct PatchSamples {
    domain: ((f64, f64), (f64, f64)),
    columns: usize,
    points: Vec<DVec3>,
    normals: Vec<DVec3>,
}

impl SmoothedNormals {
    /// The model's normals smoothed as `iterations` rounds of averaging each with its
    /// neighbours would, sampled on a grid per patch.
    ///
    /// X-Toon smooths a mesh's normals by repeated averaging over its edges. Repeated averaging
    /// spreads like diffusion, over a distance that grows as the square root of the rounds; here
    /// the spread is taken in one step: the smoothed normal at a point is the kernel average of
    /// the model's normals over a ball (see `NormalAverage`) of radius
    ///
    /// `R = ½ h √iterations`,
    ///
    /// h the mean distance between neighbouring control points of the model's nets. The average
    /// is a function of the point and its normal only, so the smoothed normals are continuous
    /// wherever the model's are: across shared patch edges, seams and collapsed poles alike,
    /// whatever the patches' parametrisations; and a sphere keeps its own normals.
    pub fn new(library: &PatchLibrary, iterations: u32) -> Result<Self, XToonError> {
        let spacing = net_spacing(library.patches.iter().map(|p| &p.surface))
            .ok_or_else(|| XToonError::Shape("the model has no extent".into()))?;
        let radius = 0.5 * spacing * f64::from(iterations).sqrt();
        let samples: Vec<PatchSamples> = library
            .patches
            .iter()
            .map(|p| PatchSamples::new(&p.surface))
            .collect();
        let average = NormalAverage::new(samples.iter().flat_map(PatchSamples::areas), radius);
        let patches = samples
            .iter()
            .map(|s| {
                let normals: Vec<Vec3> = s
                    .points
                    .iter()
                    .zip(&s.normals)
                    .map(|(&p, &n)| average.try_at(p, n).unwrap_or(n).as_vec3())
                    .collect();
                NormalGrid::new(s.domain, &normals, s.columns)
            })
            .collect();
        Ok(Self { patches })
    }

    /// The smoothed normal of patch `points.patch` at each of the points' `(u, v)` into `out`:
    /// bilinear between the grid normals around it (not normalized; zero for a patch index out
    /// of range).
    #[inline(always)]
    pub(super) fn at_run(&self, points: &PointRun, out: &mut Lanes) {
        let n = points.len;
        match self.patches.get(points.patch) {
            Some(grid) => grid.normals.bilinear(
                n,
                |k| (points.u[k] - grid.origin.x) * grid.scale.x,
                |k| (points.v[k] - grid.origin.y) * grid.scale.y,
                |k, normal| out.set(k, normal),
            ),
            None => out.fill(n, Vec3::ZERO),
        }
    }
}

impl PatchSamples {
    /// The surface's points and normals on its normal grid.
    fn new(surface: &NurbsSurface) -> Self {
        let domain = surface.domain();
        let samples = |knots: &[f64]| intervals(spans(knots)) + 1;
        let (rows, columns) = (
            samples(surface.knots_u().knots()),
            samples(surface.knots_v().knots()),
        );
        let grid = GridEvaluator::uniform(surface, rows, columns);
        let (points, normals) = (0..rows)
            .flat_map(|i| grid.row_frames(i).collect::<Vec<_>>())
            .map(|f| (f.point, f.normal))
            .unzip();
        Self {
            domain: (domain.u, domain.v),
            columns,
            points,
            normals,
        }
    }

    /// Each sample with the area of the grid cells around it: `¼ |(p₊ᵤ − p₋ᵤ) × (p₊ᵥ − p₋ᵥ)|`
    /// with the neighbours one sample away (the sample itself on an edge, which halves its
    /// share as the trapezoid rule does).
    fn areas(&self) -> impl Iterator<Item = AreaSample> + '_ {
        let columns = self.columns;
        let rows = self.points.len() / columns;
        (0..rows).flat_map(move |i| {
            (0..columns).map(move |j| {
                let at = |i: usize, j: usize| self.points[i * columns + j];
                let along_u = at((i + 1).min(rows - 1), j) - at(i.saturating_sub(1), j);
                let along_v = at(i, (j + 1).min(columns - 1)) - at(i, j.saturating_sub(1));
                AreaSample {
                    point: at(i, j),
                    normal: self.normals[i * columns + j],
                    area: 0.25 * along_u.cross(along_v).length(),
                }
            })
        })
    }
}

impl NormalGrid {
    /// The grid of `normals` (row-major, `columns` per row) spanning `domain` (u, v).
    fn new(domain: ((f64, f64), (f64, f64)), normals: &[Vec3], columns: usize) -> Self {
        let rows = normals.len() / columns;
        let length = |(a, b): (f64, f64)| (b - a) as f32;
        Self {
            origin: Vec2::new(domain.0 .0 as f32, domain.1 .0 as f32),
            scale: Vec2::new(
                (rows - 1) as f32 / length(domain.0),
                (columns - 1) as f32 / length(domain.1),
            ),
            normals: Grid::new(normals, columns),
        }
    }
}

/// The number of non-empty knot spans of a knot vector.
fn spans(knots: &[f64]) -> usize {
    knots.windows(2).filter(|w| w[1] > w[0]).count()
}

/// The mean distance between control points next to each other along u or v in the nets,
/// leaving out coincident ones (collapsed edges); `None` when there are none apart.
fn net_spacing<'a>(nets: impl Iterator<Item = &'a NurbsSurface>) -> Option<f64> {
    let (mut total, mut count) = (0.0, 0u64);
    for s in nets {
        let (nu, nv) = (s.count_u(), s.count_v());
        for i in 0..nu {
            for j in 0..nv {
                let p = s.control_point(i, j).0;
                let next = [
                    (i + 1 < nu).then(|| s.control_point(i + 1, j).0),
                    (j + 1 < nv).then(|| s.control_point(i, j + 1).0),
                ];
                for q in next.into_iter().flatten() {
                    let d = p.distance(q);
                    if d > 0.0 {
                        total += d;
                        count += 1;
                    }
                }
            }
        }
    }
    let mean = total / count as f64;
    (count > 0 && mean.is_finite() && mean > 0.0).then_some(mean)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{shapes, NamedPatch};

    /// The smoothed normal of `patch` at `uv`.
    fn at(smoothed: &SmoothedNormals, patch: usize, uv: Vec2) -> Vec3 {
        let mut normal = Lanes::default();
        smoothed.at_run(&PointRun::one(Vec3::ZERO, Vec3::Z, patch, uv), &mut normal);
        normal.get(0)
    }

    #[test]
    fn grid_lookups_at_the_samples_give_the_surface_normals_there() {
        // A curved patch whose normal differs everywhere: any misread sample shows.
        let sphere = shapes::sphere(DVec3::ZERO, 1.0).unwrap();
        let samples = PatchSamples::new(&sphere);
        let normals: Vec<Vec3> = samples.normals.iter().map(|n| n.as_vec3()).collect();
        let smoothed = SmoothedNormals {
            patches: vec![NormalGrid::new(samples.domain, &normals, samples.columns)],
        };
        let domain = sphere.domain();
        let last = |knots: &[f64]| intervals(spans(knots)) as u32;
        let (last_u, last_v) = (
            last(sphere.knots_u().knots()),
            last(sphere.knots_v().knots()),
        );
        let at_sample =
            |k: u32, n: u32, (a, b): (f64, f64)| a + (b - a) * f64::from(k) / f64::from(n);
        for i in 0..=last_u {
            for j in 0..=last_v {
                let (u, v) = (
                    at_sample(i, last_u, domain.u),
                    at_sample(j, last_v, domain.v),
                );
                let want = sphere.frame(u, v).normal.as_vec3();
                let got = at(&smoothed, 0, Vec2::new(u as f32, v as f32));
                assert!((got - want).length() < 1e-4, "({i}, {j}): {got} vs {want}");
            }
        }
    }

    #[test]
    fn net_spacing_is_the_mean_gap_between_distinct_neighbours() {
        // A 3 × 2 net, spaced 1 along u and 2 along v, its last row collapsed to one point.
        let points = vec![
            vec![DVec3::ZERO, DVec3::new(0.0, 2.0, 0.0)],
            vec![DVec3::X, DVec3::new(1.0, 2.0, 0.0)],
            vec![DVec3::new(2.0, 1.0, 0.0); 2],
        ];
        let surface = NurbsSurface::new(
            2,
            1,
            vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            vec![0.0, 0.0, 1.0, 1.0],
            &points,
            None,
        )
        .unwrap();
        // Along u: 1, 1, √2, √2; along v: 2, 2 (and 0, left out).
        let want = (2.0 + 2.0 * 2f64.sqrt() + 4.0) / 6.0;
        let got = net_spacing([&surface].into_iter()).unwrap();
        assert!((got - want).abs() < 1e-15, "{got} vs {want}");
        let point = vec![vec![DVec3::ONE; 2]; 2];
        let knots = vec![0.0, 0.0, 1.0, 1.0];
        let collapsed = NurbsSurface::new(1, 1, knots.clone(), knots, &point, None).unwrap();
        assert_eq!(net_spacing([&collapsed].into_iter()), None);
    }

    #[test]
    fn a_plane_stays_flat_and_its_normals_stay_put() {
        let library = PatchLibrary {
            patches: vec![NamedPatch {
                name: "plane".into(),
                trim: None,
                surface: shapes::plane(2.0, 1.0).unwrap(),
            }],
            groups: Vec::new(),
        };
        let smoothed = SmoothedNormals::new(&library, 5).unwrap();
        for uv in [
            Vec2::ZERO,
            Vec2::new(0.3, 0.9),
            Vec2::ONE,
            Vec2::splat(-4.0),
        ] {
            assert!((at(&smoothed, 0, uv).normalize() - Vec3::Z).length() < 1e-6);
        }
        assert_eq!(at(&smoothed, 1, Vec2::ZERO), Vec3::ZERO);
    }
}
