//! The smoothed shape of a NURBS model: its control net Laplacian-smoothed as one net across
//! patches, and a grid of the smoothed patches' normals to look up per point.

use glam::{DVec3, Vec2, Vec3};

use super::error::XToonError;
use super::grid::Grid;
use super::xtoon::PointRun;
use crate::geom::{GridEvaluator, NurbsSurface, PatchLibrary};
use crate::math::Lanes;

/// How far each smoothing iteration moves a control point toward its neighbours' mean.
const LAMBDA: f64 = 0.5;

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

/// Per patch, the normals of the smoothed patch on a uniform grid over its domain.
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

impl SmoothedNormals {
    /// Smooths the model's control net `iterations` times and samples the smoothed patches'
    /// normals.
    ///
    /// Control points that coincide (within 10⁻⁹ of the model's size: shared patch edges,
    /// collapsed edges, seams) are welded into one node whose neighbours are the net
    /// neighbours of all its copies; each iteration moves every node by
    /// `λ (mean of its neighbours − itself)` with λ = ½, all at once. Welded copies move
    /// together, so patches that met still meet. Weights and knots are kept.
    pub fn new(library: &PatchLibrary, iterations: u32) -> Result<Self, XToonError> {
        let nets: Vec<&NurbsSurface> = library.patches.iter().map(|p| &p.surface).collect();
        let points: Vec<DVec3> = library.control_points().collect();
        if points.is_empty() {
            return Err(XToonError::Shape("the model has no control points".into()));
        }
        let (node_of, mut nodes) = weld(&points);
        let neighbours = neighbours(&nets, &node_of, nodes.len());
        for _ in 0..iterations {
            nodes = nodes
                .iter()
                .zip(&neighbours)
                .map(|(p, around)| {
                    if around.is_empty() {
                        return *p;
                    }
                    let mean =
                        around.iter().map(|&k| nodes[k]).sum::<DVec3>() / around.len() as f64;
                    *p + LAMBDA * (mean - *p)
                })
                .collect();
        }
        let mut next = 0;
        let mut patches = Vec::with_capacity(nets.len());
        for s in nets {
            let rows: Vec<Vec<DVec3>> = (0..s.count_u())
                .map(|_| {
                    (0..s.count_v())
                        .map(|_| {
                            next += 1;
                            nodes[node_of[next - 1]]
                        })
                        .collect()
                })
                .collect();
            let weights: Vec<Vec<f64>> = (0..s.count_u())
                .map(|i| (0..s.count_v()).map(|j| s.control_point(i, j).1).collect())
                .collect();
            let smoothed = NurbsSurface::new(
                s.knots_u().degree(),
                s.knots_v().degree(),
                s.knots_u().knots().to_vec(),
                s.knots_v().knots().to_vec(),
                &rows,
                Some(&weights),
            )
            .map_err(|e| XToonError::Shape(format!("smoothed patch: {e}")))?;
            patches.push(NormalGrid::new(&smoothed));
        }
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

impl NormalGrid {
    fn new(surface: &NurbsSurface) -> Self {
        let domain = surface.domain();
        let samples = |spans: usize| intervals(spans) + 1;
        let (samples_u, samples_v) = (
            samples(spans(surface.knots_u().knots())),
            samples(spans(surface.knots_v().knots())),
        );
        let grid = GridEvaluator::uniform(surface, samples_u, samples_v);
        let normals: Vec<Vec3> = (0..samples_u)
            .flat_map(|i| {
                grid.row_frames(i)
                    .map(|f| f.normal.as_vec3())
                    .collect::<Vec<_>>()
            })
            .collect();
        let length = |(a, b): (f64, f64)| (b - a) as f32;
        Self {
            origin: Vec2::new(domain.u.0 as f32, domain.v.0 as f32),
            scale: Vec2::new(
                (samples_u - 1) as f32 / length(domain.u),
                (samples_v - 1) as f32 / length(domain.v),
            ),
            normals: Grid::new(&normals, samples_v),
        }
    }
}

/// The number of non-empty knot spans of a knot vector.
fn spans(knots: &[f64]) -> usize {
    knots.windows(2).filter(|w| w[1] > w[0]).count()
}

/// Welds coincident points: for each point its node index, and the nodes' positions. Points
/// within 10⁻⁹ of the set's size of each other (a sweep over the points sorted by x) share a
/// node.
fn weld(points: &[DVec3]) -> (Vec<usize>, Vec<DVec3>) {
    let (low, high) = points
        .iter()
        .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(l, h), p| {
            (l.min(*p), h.max(*p))
        });
    let tolerance = 1e-9 * (high - low).max_element().max(f64::MIN_POSITIVE);
    let mut order: Vec<usize> = (0..points.len()).collect();
    order.sort_by(|&a, &b| points[a].x.total_cmp(&points[b].x));
    let mut node_of = vec![usize::MAX; points.len()];
    let mut nodes = Vec::new();
    for (k, &a) in order.iter().enumerate() {
        if node_of[a] != usize::MAX {
            continue;
        }
        node_of[a] = nodes.len();
        for &b in &order[k + 1..] {
            if points[b].x - points[a].x > tolerance {
                break;
            }
            if node_of[b] == usize::MAX && (points[b] - points[a]).abs().max_element() <= tolerance
            {
                node_of[b] = nodes.len();
            }
        }
        nodes.push(points[a]);
    }
    (node_of, nodes)
}

/// For each node, the distinct other nodes next to one of its copies in a control net (along u
/// or v).
fn neighbours(nets: &[&NurbsSurface], node_of: &[usize], count: usize) -> Vec<Vec<usize>> {
    let mut around: Vec<Vec<usize>> = vec![Vec::new(); count];
    let mut start = 0;
    for s in nets {
        let (nu, nv) = (s.count_u(), s.count_v());
        let node = |i: usize, j: usize| node_of[start + i * nv + j];
        for i in 0..nu {
            for j in 0..nv {
                let (a, b) = (
                    node(i, j),
                    [
                        (i + 1 < nu).then(|| node(i + 1, j)),
                        (j + 1 < nv).then(|| node(i, j + 1)),
                    ],
                );
                for b in b.into_iter().flatten() {
                    if a != b {
                        if !around[a].contains(&b) {
                            around[a].push(b);
                        }
                        if !around[b].contains(&a) {
                            around[b].push(a);
                        }
                    }
                }
            }
        }
        start += nu * nv;
    }
    around
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
        let smoothed = SmoothedNormals {
            patches: vec![NormalGrid::new(&sphere)],
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
    fn welding_joins_shared_points_only() {
        let points = [
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(1e-12, 0.0, 0.0),
            DVec3::new(1.0, 1e-3, 0.0),
        ];
        let (node_of, nodes) = weld(&points);
        assert_eq!(node_of[0], node_of[2]);
        assert_ne!(node_of[1], node_of[3]);
        assert_eq!(nodes.len(), 3);
    }

    #[test]
    fn a_plane_stays_flat_and_its_normals_stay_put() {
        let library = PatchLibrary {
            patches: vec![NamedPatch {
                name: "plane".into(),
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
