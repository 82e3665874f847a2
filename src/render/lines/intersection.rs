//! Intersection lines: the curves where the mesh's patches pass through one another (the
//! teapot's spout and handle through its body), found once per mesh.

use glam::{DVec2, DVec3, Vec3};
use rayon::prelude::*;

use super::super::tessellate::{Mesh, PatchGrid};
use crate::geom::{PatchLibrary, Region};
use crate::render::{FastMap, FastSet};

/// Grid cells per side of the blocks whose bounds are compared before their triangles are.
const BLOCK: u32 = 8;

/// An axis-aligned box.
#[derive(Clone, Copy, Debug)]
struct Bounds {
    lo: Vec3,
    hi: Vec3,
}

impl Bounds {
    const EMPTY: Bounds = Bounds {
        lo: Vec3::INFINITY,
        hi: Vec3::NEG_INFINITY,
    };

    fn grow(self, p: Vec3) -> Self {
        Self {
            lo: self.lo.min(p),
            hi: self.hi.max(p),
        }
    }

    fn overlaps(&self, other: &Bounds) -> bool {
        self.lo.cmple(other.hi).all() && other.lo.cmple(self.hi).all()
    }
}

/// A straight piece of an intersection curve, in world space, and the two patches that meet
/// along it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Meeting {
    pub ends: [Vec3; 2],
    pub patches: [u32; 2],
}

/// A block of a patch's grid cells: the cells `[i0, i1) × [j0, j1)` and their bounds.
#[derive(Clone, Copy, Debug)]
struct Block {
    patch: u32,
    cells: [u32; 4],
    bounds: Bounds,
}

/// The meetings of one pair of patches, `pair = [p, q]` with `p < q`, in the order
/// [`intersections_keeping`] finds them.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct PairMeetings {
    pub pair: [u32; 2],
    pub meetings: Vec<Meeting>,
}

/// What [`intersections_keeping`] found: the meetings of every pair that meets, in pair order,
/// and how many pairs were kept and how many intersected again.
#[derive(Clone, Debug, Default, PartialEq)]
pub(crate) struct Found {
    /// The pairs that meet somewhere, ordered by `pair`.
    pub pairs: Vec<PairMeetings>,
    /// Pairs of patches both marked the same, whose meetings (or none) were taken from before.
    pub kept: usize,
    /// Pairs intersected triangle by triangle again: the others, whose bounds overlap and which
    /// share no vertex position.
    pub tested: usize,
}

/// The segments along which triangles of two different patches that share no vertex position
/// cross each other, in world space. Patches that meet along an edge (or at a corner) are
/// continuations of one surface and are not intersected with each other; patches that only
/// pass through one another are. Blocks of [`BLOCK`]² cells are compared by their bounds
/// first, so the work grows with the blocks that overlap, not with every pair of triangles.
/// On trimmed patches, triangles cut away whole are skipped and a segment is kept where both
/// patches' trims keep it.
///
/// A pair's meetings depend on its two patches' grids alone: where `same` marks both patches
/// of a pair as on the mesh `before` was found on, the pair's meetings are `before`'s (none
/// when `before` lists no meetings for it) and it is not intersected again. With nothing
/// marked, every pair is found afresh.
#[must_use]
pub(crate) fn intersections_keeping(
    mesh: &Mesh,
    library: &PatchLibrary,
    same: &[bool],
    before: &[PairMeetings],
) -> Found {
    let blocks: Vec<Vec<Block>> = mesh
        .grids
        .iter()
        .enumerate()
        .map(|(patch, grid)| blocks(mesh, patch as u32, grid))
        .collect();
    let patch_bounds: Vec<Bounds> = blocks
        .iter()
        .map(|list| {
            list.iter().fold(Bounds::EMPTY, |b, block| {
                b.grow(block.bounds.lo).grow(block.bounds.hi)
            })
        })
        .collect();
    let patches = blocks.len();
    let kept_patch = |p: usize| same.get(p).copied().unwrap_or(false);
    let touching = touching_patches(mesh, |p| !kept_patch(p as usize));
    let mut found = Found::default();
    let mut pairs: Vec<(&Block, &Block)> = Vec::new();
    for p in 0..patches {
        for q in p + 1..patches {
            if kept_patch(p) && kept_patch(q) {
                found.kept += 1;
                continue;
            }
            if !patch_bounds[p].overlaps(&patch_bounds[q])
                || touching.contains(&(p as u32, q as u32))
            {
                continue;
            }
            found.tested += 1;
            for a in &blocks[p] {
                for b in blocks[q].iter().filter(|b| a.bounds.overlaps(&b.bounds)) {
                    pairs.push((a, b));
                }
            }
        }
    }
    let segments: Vec<Vec<Meeting>> = pairs
        .par_iter()
        .map(|&(a, b)| block_segments(mesh, library, a, b))
        .collect();
    // The new meetings grouped by pair, in pair order.
    let mut fresh: Vec<PairMeetings> = Vec::new();
    for ((a, b), meetings) in pairs.iter().zip(segments) {
        let pair = [a.patch, b.patch];
        match fresh.last_mut() {
            Some(last) if last.pair == pair => last.meetings.extend(meetings),
            _ => fresh.push(PairMeetings { pair, meetings }),
        }
    }
    fresh.retain(|p| !p.meetings.is_empty());
    let kept = before
        .iter()
        .filter(|p| p.pair.iter().all(|&k| kept_patch(k as usize)))
        .cloned();
    found.pairs = merge_by_pair(fresh, kept);
    found
}

/// `a` and `b`, each ordered by pair and with no pair in both, merged in pair order.
fn merge_by_pair(a: Vec<PairMeetings>, b: impl Iterator<Item = PairMeetings>) -> Vec<PairMeetings> {
    let mut out = Vec::with_capacity(a.len());
    let mut b = b.peekable();
    for next in a {
        while let Some(earlier) = b.next_if(|k| k.pair < next.pair) {
            out.push(earlier);
        }
        out.push(next);
    }
    out.extend(b);
    out
}

/// The blocks of one patch's grid.
fn blocks(mesh: &Mesh, patch: u32, grid: &PatchGrid) -> Vec<Block> {
    let (cu, cv) = (grid.nu.saturating_sub(1), grid.nv.saturating_sub(1));
    let mut out = Vec::new();
    for i0 in (0..cu).step_by(BLOCK as usize) {
        for j0 in (0..cv).step_by(BLOCK as usize) {
            let (i1, j1) = ((i0 + BLOCK).min(cu), (j0 + BLOCK).min(cv));
            let mut bounds = Bounds::EMPTY;
            for i in i0..=i1 {
                for j in j0..=j1 {
                    bounds = bounds.grow(mesh.positions[grid.vertex(i, j) as usize]);
                }
            }
            out.push(Block {
                patch,
                cells: [i0, i1, j0, j1],
                bounds,
            });
        }
    }
    out
}

/// The pairs of patches `(lower, higher)` that share a vertex position (a piece of boundary
/// across from the other, or a corner), of those pairs of which `asked` picks at least one
/// patch: the positions of the picked patches' boundaries are filed, and every patch's
/// boundary looked up among them.
fn touching_patches(mesh: &Mesh, asked: impl Fn(u32) -> bool) -> FastSet<(u32, u32)> {
    let mut by_position: FastMap<[u32; 3], Vec<u32>> = FastMap::default();
    for (patch, g) in (0..).zip(&mesh.grids).filter(|(p, _)| asked(*p)) {
        for key in boundary_positions(mesh, *g) {
            let list = by_position.entry(key).or_default();
            if list.last() != Some(&patch) && !list.contains(&patch) {
                list.push(patch);
            }
        }
    }
    let mut pairs = FastSet::default();
    for (patch, g) in (0..).zip(&mesh.grids) {
        for key in boundary_positions(mesh, *g) {
            let others = by_position.get(&key).map_or(&[][..], Vec::as_slice);
            for &other in others.iter().filter(|&&o| o != patch) {
                pairs.insert((patch.min(other), patch.max(other)));
            }
        }
    }
    pairs
}

/// The positions, bit for bit, of the vertices on the boundary of `grid`'s domain.
fn boundary_positions(mesh: &Mesh, grid: PatchGrid) -> impl Iterator<Item = [u32; 3]> + '_ {
    let (nu, nv) = (grid.nu, grid.nv);
    let key = |v: u32| mesh.positions[v as usize].to_array().map(f32::to_bits);
    (0..nu)
        .flat_map(move |i| [grid.vertex(i, 0), grid.vertex(i, nv - 1)])
        .chain((0..nv).flat_map(move |j| [grid.vertex(0, j), grid.vertex(nu - 1, j)]))
        .map(key)
}

/// The triangles of a block, as vertex triples with their corners' (u, v); none that the
/// patch's trim cuts away whole ([`Mesh::triangle_region`]).
fn triangles(mesh: &Mesh, block: &Block) -> Vec<([Vec3; 3], [DVec2; 3])> {
    let grid = &mesh.grids[block.patch as usize];
    let [i0, i1, j0, j1] = block.cells;
    let cut = |i: u32, j: u32| {
        mesh.triangle_region.get(grid.triangle(i, j) as usize) == Some(&Region::Cut)
    };
    let at = |i: u32, j: u32| {
        let v = grid.vertex(i, j) as usize;
        (mesh.positions[v], mesh.uvs[v].as_dvec2())
    };
    let mut out = Vec::with_capacity(((i1 - i0) * (j1 - j0) * 2) as usize);
    for i in i0..i1 {
        for j in j0..j1 {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            if cut(i, j) {
                continue;
            }
            out.push(([a.0, b.0, c.0], [a.1, b.1, c.1]));
            out.push(([a.0, c.0, d.0], [a.1, c.1, d.1]));
        }
    }
    out
}

/// The (u, v) at `p`, a point of triangle `t` whose corners are at `uv`, by its barycentric
/// coordinates on the triangle.
fn uv_at(t: &[Vec3; 3], uv: &[DVec2; 3], p: Vec3) -> DVec2 {
    let [a, b, c] = t.map(|q| q.as_dvec3());
    let (e1, e2, d) = (b - a, c - a, p.as_dvec3() - a);
    let (d11, d12, d22) = (e1.dot(e1), e1.dot(e2), e2.dot(e2));
    let (d1, d2) = (d.dot(e1), d.dot(e2));
    let det = d11 * d22 - d12 * d12;
    if det == 0.0 {
        return uv[0];
    }
    let (wb, wc) = ((d22 * d1 - d12 * d2) / det, (d11 * d2 - d12 * d1) / det);
    uv[0] + (uv[1] - uv[0]) * wb + (uv[2] - uv[0]) * wc
}

/// The parts of the segment `ends`, where triangles `t` (of patch `p`) and `u` (of patch `q`)
/// cross, that both patches' trims keep, as intervals of its parameter.
fn kept_by_both(
    library: &PatchLibrary,
    ends: [Vec3; 2],
    (p, t): (u32, &([Vec3; 3], [DVec2; 3])),
    (q, u): (u32, &([Vec3; 3], [DVec2; 3])),
) -> Vec<(f64, f64)> {
    let spans = |patch: u32, (corners, uv): &([Vec3; 3], [DVec2; 3])| {
        library.patches[patch as usize].trim.as_ref().map_or_else(
            || vec![(0.0, 1.0)],
            |trim| trim.kept_spans(uv_at(corners, uv, ends[0]), uv_at(corners, uv, ends[1])),
        )
    };
    let (a, b) = (spans(p, t), spans(q, u));
    let mut both = Vec::new();
    for &(a0, a1) in &a {
        for &(b0, b1) in &b {
            let (lo, hi) = (a0.max(b0), a1.min(b1));
            if lo < hi {
                both.push((lo, hi));
            }
        }
    }
    both
}

fn triangle_bounds(t: &[Vec3; 3]) -> Bounds {
    t.iter().fold(Bounds::EMPTY, |b, &p| b.grow(p))
}

/// The segments where the triangles of two blocks cross, on what both patches' trims keep.
fn block_segments(mesh: &Mesh, library: &PatchLibrary, a: &Block, b: &Block) -> Vec<Meeting> {
    let (ta, tb) = (triangles(mesh, a), triangles(mesh, b));
    let trimmed = [a.patch, b.patch]
        .iter()
        .any(|&p| library.patches[p as usize].trim.is_some());
    let bb: Vec<Bounds> = tb.iter().map(|(t, _)| triangle_bounds(t)).collect();
    let mut out = Vec::new();
    for t in &ta {
        let bt = triangle_bounds(&t.0);
        if !bt.overlaps(&b.bounds) {
            continue;
        }
        for (u, bu) in tb.iter().zip(&bb) {
            if !bt.overlaps(bu) {
                continue;
            }
            let Some(ends) = triangle_crossing(&t.0, &u.0) else {
                continue;
            };
            let patches = [a.patch, b.patch];
            if !trimmed {
                out.push(Meeting { ends, patches });
                continue;
            }
            for (t0, t1) in kept_by_both(library, ends, (a.patch, t), (b.patch, u)) {
                let at = |s: f64| ends[0].lerp(ends[1], s as f32);
                out.push(Meeting {
                    ends: [at(t0), at(t1)],
                    patches,
                });
            }
        }
    }
    out
}

/// Where triangle `t` crosses the plane of `u`: the segment between the two points at which
/// its edges pass through the plane, or None when its corners lie on one side (or on the
/// plane). Distances are signed `n·(p − u₀)`.
fn through_plane(t: &[DVec3; 3], u: &[DVec3; 3]) -> Option<[DVec3; 2]> {
    let n = (u[1] - u[0]).cross(u[2] - u[0]);
    if n == DVec3::ZERO {
        return None;
    }
    let d = t.map(|p| n.dot(p - u[0]));
    let mut points = Vec::with_capacity(2);
    for k in 0..3 {
        let (p, q) = (k, (k + 1) % 3);
        if (d[p] < 0.0) != (d[q] < 0.0) && d[p] != d[q] {
            let s = d[p] / (d[p] - d[q]);
            points.push(t[p].lerp(t[q], s));
        }
    }
    match points[..] {
        [x, y] => Some([x, y]),
        _ => None,
    }
}

/// The segment where triangles `t` and `u` cross, if they do: each triangle's crossing of the
/// other's plane lies on the line the planes share, and the two overlap along it.
fn triangle_crossing(t: &[Vec3; 3], u: &[Vec3; 3]) -> Option<[Vec3; 2]> {
    let (t, u) = (t.map(|p| p.as_dvec3()), u.map(|p| p.as_dvec3()));
    let s = through_plane(&t, &u)?;
    let r = through_plane(&u, &t)?;
    let along = s[1] - s[0];
    let length = along.length_squared();
    if length == 0.0 {
        return None;
    }
    let param = |p: DVec3| (p - s[0]).dot(along) / length;
    let (r0, r1) = (param(r[0]), param(r[1]));
    let (lo, hi) = (r0.min(r1).max(0.0), r0.max(r1).min(1.0));
    (lo < hi).then(|| [s[0] + along * lo, s[0] + along * hi].map(|p| p.as_vec3()))
}

#[cfg(test)]
mod tests {
    use super::super::super::tessellate::Tessellator;
    use super::*;
    use crate::geom::{shapes, NamedPatch};

    /// A torus about z, a ball through its tube and a second ball centred at `(1, y, 0)`
    /// through both.
    fn torus_and_balls(y: f64) -> PatchLibrary {
        let patch = |name: &str, surface| NamedPatch {
            name: name.into(),
            trim: None,
            surface,
        };
        PatchLibrary::new(vec![
            patch("torus", shapes::torus(2.0, 0.5).unwrap()),
            patch("a", shapes::sphere(DVec3::new(2.0, 0.0, 0.0), 0.8).unwrap()),
            patch("b", shapes::sphere(DVec3::new(1.0, y, 0.0), 0.6).unwrap()),
        ])
    }

    fn mesh_of(library: PatchLibrary) -> (Mesh, PatchLibrary) {
        let mut tessellator = Tessellator::new(library.clone());
        let mesh = tessellator.mesh_of(vec![(6, 6); 3]).0.clone();
        (mesh, library)
    }

    #[test]
    fn pairs_of_unmoved_patches_keep_their_meetings_and_the_rest_equal_a_fresh_search() {
        let (before_mesh, before_library) = mesh_of(torus_and_balls(0.0));
        let before = intersections_keeping(&before_mesh, &before_library, &[], &[]);
        // Every pair meets: torus–a, torus–b and a–b.
        let pairs: Vec<[u32; 2]> = before.pairs.iter().map(|p| p.pair).collect();
        assert_eq!(pairs, [[0, 1], [0, 2], [1, 2]]);
        assert_eq!((before.kept, before.tested), (0, 3));
        // Ball b moves: torus–a is kept, the pairs with b are found again.
        let (mesh, library) = mesh_of(torus_and_balls(0.1));
        let kept = intersections_keeping(&mesh, &library, &[true, true, false], &before.pairs);
        let fresh = intersections_keeping(&mesh, &library, &[], &[]);
        assert_eq!((kept.kept, kept.tested), (1, 2));
        assert_eq!(kept.pairs, fresh.pairs);
        assert_eq!(kept.pairs[0], before.pairs[0]);
        assert_ne!(kept.pairs[1], before.pairs[1]);
    }

    #[test]
    fn two_crossing_triangles_meet_along_the_segment_their_planes_share_within_both() {
        // A triangle in z = 0 and one in x = 0.25 reaching across it: they meet on the line
        // x = 0.25, z = 0, for y where both triangles are.
        let flat = [
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 1.0, 0.0),
        ];
        let upright = [
            Vec3::new(0.25, -1.0, -1.0),
            Vec3::new(0.25, 2.0, -1.0),
            Vec3::new(0.25, 0.5, 1.0),
        ];
        let [a, b] = triangle_crossing(&flat, &upright).unwrap();
        let (lo, hi) = (a.y.min(b.y), a.y.max(b.y));
        // In the flat triangle, x = 0.25 runs for y in [0, 0.75]; in the upright one, z = 0 is
        // halfway up, where it spans y in [-0.25, 1.25].
        for p in [a, b] {
            assert!((p.x - 0.25).abs() < 1e-6 && p.z.abs() < 1e-6, "{p}");
        }
        assert!(lo.abs() < 1e-6 && (hi - 0.75).abs() < 1e-6, "{lo} {hi}");
        // Moved aside, they miss.
        let aside = upright.map(|p| p + Vec3::new(2.0, 0.0, 0.0));
        assert_eq!(triangle_crossing(&flat, &aside), None);
        // Narrowed to z = 0 for y in [0.3, 0.5], the upright one bounds the segment at both
        // ends, inside the flat one's.
        let narrow = [
            Vec3::new(0.25, 0.2, -1.0),
            Vec3::new(0.25, 0.6, -1.0),
            Vec3::new(0.25, 0.4, 1.0),
        ];
        let [a, b] = triangle_crossing(&flat, &narrow).unwrap();
        let (lo, hi) = (a.y.min(b.y), a.y.max(b.y));
        assert!(
            (lo - 0.3).abs() < 1e-6 && (hi - 0.5).abs() < 1e-6,
            "{lo} {hi}"
        );
    }

    /// The total length of `meetings`.
    fn length(meetings: &[&Meeting]) -> f64 {
        meetings
            .iter()
            .map(|m| f64::from(m.ends[0].distance(m.ends[1])))
            .sum()
    }

    /// The meetings of patches `pair` in `found`.
    fn of_pair(found: &Found, pair: [u32; 2]) -> Vec<&Meeting> {
        found
            .pairs
            .iter()
            .filter(|p| p.pair == pair)
            .flat_map(|p| &p.meetings)
            .collect()
    }

    #[test]
    fn on_a_trimmed_patch_meetings_are_kept_where_its_trim_keeps_it_and_cut_where_the_trim_crosses_them(
    ) {
        let (mesh, library) = mesh_of(torus_and_balls(0.0));
        let whole = intersections_keeping(&mesh, &library, &[], &[]);
        // Ball a keeps u ≤ 0.45: east from +x about its centre, past +y to short of −x. The
        // torus meets it in two loops, one each side of y = 0; ball b in a ring about its west
        // pole, which the trim's edge cuts.
        let mut trimmed = library.clone();
        let domain = trimmed.patches[1].surface.domain();
        let corner = |s, t| {
            let (u, v) = domain.lerp(s, t);
            DVec2::new(u, v)
        };
        let kept = vec![
            corner(-0.1, -0.1),
            corner(0.45, -0.1),
            corner(0.45, 1.1),
            corner(-0.1, 1.1),
        ];
        trimmed.patches[1].trim = Some(std::sync::Arc::new(
            crate::geom::Trim::new(vec![kept], domain).unwrap(),
        ));
        let (mesh, trimmed) = mesh_of(trimmed);
        let cut = intersections_keeping(&mesh, &trimmed, &[], &[]);
        // The torus's loop at y > 0 whole, the other gone.
        let torus_a = of_pair(&whole, [0, 1]);
        let north: Vec<&Meeting> = torus_a
            .iter()
            .copied()
            .filter(|m| m.ends[0].y + m.ends[1].y > 0.0)
            .collect();
        assert!(length(&north) > 1.0 && length(&north) < length(&torus_a) - 1.0);
        let kept_torus_a = of_pair(&cut, [0, 1]);
        assert!(kept_torus_a
            .iter()
            .all(|m| m.ends.iter().all(|e| e.y > 0.0)));
        assert!(
            (length(&kept_torus_a) - length(&north)).abs() < 1e-5,
            "{} of {}",
            length(&kept_torus_a),
            length(&north)
        );
        // Of the ring with ball b, the part east of the trim's edge, cut short at it.
        let centre = glam::DVec2::new(2.0, 0.0);
        let east_of = |p: Vec3| (p.as_dvec3().truncate() - centre).to_angle().to_degrees();
        let (u_edge, v_mid) = domain.lerp(0.45, 0.5);
        let edge = east_of(trimmed.patches[1].surface.point(u_edge, v_mid).as_vec3());
        let ring = of_pair(&whole, [1, 2]);
        let kept_ring = of_pair(&cut, [1, 2]);
        assert!(kept_ring.iter().all(|m| m
            .ends
            .iter()
            .all(|&e| (0.0..edge + 2.0).contains(&east_of(e)))));
        let ahead: Vec<&Meeting> = ring
            .iter()
            .copied()
            .filter(|m| {
                m.ends
                    .iter()
                    .all(|&e| (0.0..edge - 2.0).contains(&east_of(e)))
            })
            .collect();
        assert!(length(&ahead) > 0.1, "{}", length(&ahead));
        assert!(
            length(&kept_ring) > length(&ahead) && length(&kept_ring) < length(&ring) - 0.1,
            "{} of {}, {} wholly kept",
            length(&kept_ring),
            length(&ring),
            length(&ahead)
        );
    }

    #[test]
    fn patches_that_share_a_vertex_position_are_not_intersected() {
        // Two squares hinged along x = 0, the second folded back over the first to 30° from
        // it, on grids of different density: their bounds overlap, their seam is shared.
        let (s, c) = 150f64.to_radians().sin_cos();
        // The bilinear square through `corner(r, y)` for r from `r0` to `r1` and y from 0 to 1.
        let square = |corner: &dyn Fn(f64, f64) -> DVec3, (r0, r1): (f64, f64)| {
            let net = [r0, r1].map(|r| vec![corner(r, 0.0), corner(r, 1.0)]);
            crate::geom::shapes::bezier(1, 1, &net).unwrap()
        };
        // What is found with the folded square slid by `slide` along the seam.
        let found = |slide: f64| {
            let library = PatchLibrary::new(vec![
                NamedPatch::new("flat", square(&|x, y| DVec3::new(x, y, 0.0), (-1.0, 0.0))),
                NamedPatch::new(
                    "folded",
                    square(&|r, y| DVec3::new(r * c, y + slide, r * s), (0.0, 1.0)),
                ),
            ]);
            let mut tessellator = Tessellator::new(library.clone());
            let mesh = tessellator.mesh_of(vec![(6, 6), (5, 9)]).0.clone();
            intersections_keeping(&mesh, &library, &[], &[])
        };
        let shared = found(0.0);
        assert_eq!((shared.tested, shared.pairs.len()), (0, 0));
        // Slid along the seam, so that no vertex of one lies on one of the other, the same
        // pair is intersected.
        assert_eq!(found(0.05).tested, 1);
    }
}
