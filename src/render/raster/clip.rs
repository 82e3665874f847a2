//! Clip-space culling and clipping.
//!
//! A vertex's *outcode* has one bit per plane it lies outside of. A triangle whose three
//! outcodes share a bit lies wholly outside that plane and is culled. A triangle with a vertex
//! outside one of the *clip* planes — near `z ≥ 0`, far `z ≤ w`, `w ≥ W_MIN`, or the guard band
//! `|x| ≤ g_x·w`, `|y| ≤ g_y·w` that keeps snapped coordinates inside the fixed-point range — is
//! clipped against exactly those planes (Sutherland–Hodgman). The frustum sides `|x| ≤ w`,
//! `|y| ≤ w` only cull: partly visible triangles are cut by the pixel bounding box instead.
//!
//! Clip-space position is linear in the barycentric coordinates of the original triangle
//! (`clip(P) = Σ b_i·clip(P_i)` since `Σ b_i = 1`), so each clipped vertex carries its original
//! barycentrics, interpolated with the same parameter as its position.

use glam::{DVec2, DVec4};

/// Smallest `w` kept: guards the projection `x/w` where a projection matrix lets `w` reach 0.
pub(super) const W_MIN: f64 = 1e-30;

/// Number of planes clipped against; their outcode bits are the low `CLIP_PLANES` bits.
const CLIP_PLANES: usize = 7;

/// Outcode bits of the planes that clip (the others only cull).
const CLIP_MASK: u16 = (1 << CLIP_PLANES) - 1;

/// Outcode bit of a vertex with a NaN or infinite coordinate.
pub(super) const NOT_FINITE: u16 = 1 << 15;

/// A closed half-space `n·v ≥ c` of homogeneous clip space.
#[derive(Clone, Copy, Debug)]
struct Plane {
    n: DVec4,
    c: f64,
}

impl Plane {
    const fn new(x: f64, y: f64, z: f64, w: f64, c: f64) -> Self {
        Self {
            n: DVec4::new(x, y, z, w),
            c,
        }
    }

    /// Signed distance `n·v − c`, non-negative inside.
    fn distance(&self, v: DVec4) -> f64 {
        self.n.dot(v) - self.c
    }
}

/// The clip planes (first `CLIP_PLANES`, in clipping order) and the culling-only frustum sides.
#[derive(Clone, Debug)]
pub(super) struct Planes([Plane; CLIP_PLANES + 4]);

impl Planes {
    /// The planes for a guard band of `|x/w| ≤ guard_x`, `|y/w| ≤ guard_y` (NDC units).
    pub(super) fn new(guard_x: f64, guard_y: f64) -> Self {
        Self([
            Plane::new(0.0, 0.0, 1.0, 0.0, 0.0),      // near: z ≥ 0
            Plane::new(0.0, 0.0, -1.0, 1.0, 0.0),     // far: z ≤ w
            Plane::new(0.0, 0.0, 0.0, 1.0, W_MIN),    // w ≥ W_MIN
            Plane::new(1.0, 0.0, 0.0, guard_x, 0.0),  // guard band: x ≥ −g_x·w
            Plane::new(-1.0, 0.0, 0.0, guard_x, 0.0), // x ≤ g_x·w
            Plane::new(0.0, 1.0, 0.0, guard_y, 0.0),  // y ≥ −g_y·w
            Plane::new(0.0, -1.0, 0.0, guard_y, 0.0), // y ≤ g_y·w
            Plane::new(1.0, 0.0, 0.0, 1.0, 0.0),      // frustum: x ≥ −w
            Plane::new(-1.0, 0.0, 0.0, 1.0, 0.0),     // x ≤ w
            Plane::new(0.0, 1.0, 0.0, 1.0, 0.0),      // y ≥ −w
            Plane::new(0.0, -1.0, 0.0, 1.0, 0.0),     // y ≤ w
        ])
    }

    /// One bit per plane `v` lies strictly outside of, or `NOT_FINITE`.
    pub(super) fn outcode(&self, v: DVec4) -> u16 {
        if !v.is_finite() {
            return NOT_FINITE;
        }
        self.0
            .iter()
            .enumerate()
            .map(|(bit, plane)| u16::from(plane.distance(v) < 0.0) << bit)
            .fold(0, |code, bit| code | bit)
    }
}

/// What a triangle's three outcodes call for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Verdict {
    /// A vertex is NaN or infinite.
    Invalid,
    /// All three vertices lie outside one plane.
    Outside,
    /// Inside every clip plane: rasterize as is.
    Inside,
    /// Crosses the clip planes whose bits are set.
    Clip(u16),
}

/// Classifies a triangle by its vertices' outcodes.
pub(super) fn classify(codes: [u16; 3]) -> Verdict {
    let any = codes[0] | codes[1] | codes[2];
    if any & NOT_FINITE != 0 {
        Verdict::Invalid
    } else if codes[0] & codes[1] & codes[2] != 0 {
        Verdict::Outside
    } else if any & CLIP_MASK == 0 {
        Verdict::Inside
    } else {
        Verdict::Clip(any & CLIP_MASK)
    }
}

/// A polygon vertex: clip-space position and its barycentrics `(b1, b2)` on the original
/// triangle.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct PolygonVertex {
    pub pos: DVec4,
    pub bary: DVec2,
}

impl PolygonVertex {
    /// The point where the segment from `inside` (distance `d_in ≥ 0`) to `outside`
    /// (`d_out < 0`) meets the plane: `t = d_in / (d_in − d_out)`, `v = inside + t·(outside −
    /// inside)`. Always computed from the inside end, so the two triangles sharing an edge
    /// produce the same point.
    fn crossing(inside: Self, d_in: f64, outside: Self, d_out: f64) -> Self {
        let t = d_in / (d_in - d_out);
        Self {
            pos: inside.pos + (outside.pos - inside.pos) * t,
            bary: inside.bary + (outside.bary - inside.bary) * t,
        }
    }
}

/// The most vertices a clipped triangle can have: one more per clip plane.
const MAX_VERTICES: usize = 3 + CLIP_PLANES;

/// A convex polygon of at most `MAX_VERTICES` vertices, in order.
#[derive(Clone, Copy, Debug)]
pub(super) struct Polygon {
    vertices: [PolygonVertex; MAX_VERTICES],
    len: usize,
}

impl Polygon {
    fn empty() -> Self {
        Self {
            vertices: [PolygonVertex::default(); MAX_VERTICES],
            len: 0,
        }
    }

    fn push(&mut self, v: PolygonVertex) {
        self.vertices[self.len] = v;
        self.len += 1;
    }

    /// The vertices in order.
    pub(super) fn vertices(&self) -> &[PolygonVertex] {
        &self.vertices[..self.len]
    }

    /// The triangle fan `(v0, v_i, v_{i+1})` covering the polygon.
    pub(super) fn fan(&self) -> impl Iterator<Item = [PolygonVertex; 3]> + '_ {
        let v = self.vertices();
        (2..v.len()).map(move |i| [v[0], v[i - 1], v[i]])
    }

    /// The part of the polygon inside `plane` (one Sutherland–Hodgman step).
    fn clipped(&self, plane: &Plane) -> Self {
        let mut out = Self::empty();
        let v = self.vertices();
        for (i, &a) in v.iter().enumerate() {
            let b = v[(i + 1) % v.len()];
            let (da, db) = (plane.distance(a.pos), plane.distance(b.pos));
            if da >= 0.0 {
                out.push(a);
            }
            match (da >= 0.0, db >= 0.0) {
                (true, false) => out.push(PolygonVertex::crossing(a, da, b, db)),
                (false, true) => out.push(PolygonVertex::crossing(b, db, a, da)),
                _ => {}
            }
        }
        out
    }
}

/// The triangle `v` clipped against the clip planes whose bits are set in `planes_to_clip`;
/// fewer than three vertices when nothing remains.
pub(super) fn clip_triangle(v: [DVec4; 3], planes: &Planes, planes_to_clip: u16) -> Polygon {
    let mut polygon = Polygon::empty();
    for (pos, bary) in v.into_iter().zip([DVec2::ZERO, DVec2::X, DVec2::Y]) {
        polygon.push(PolygonVertex { pos, bary });
    }
    for (bit, plane) in planes.0[..CLIP_PLANES].iter().enumerate() {
        if planes_to_clip & 1 << bit != 0 && polygon.len >= 3 {
            polygon = polygon.clipped(plane);
        }
    }
    polygon
}

#[cfg(test)]
mod tests {
    use super::*;

    fn planes() -> Planes {
        Planes::new(100.0, 100.0)
    }

    fn clip(v: [DVec4; 3]) -> Polygon {
        let planes = planes();
        match classify(v.map(|p| planes.outcode(p))) {
            Verdict::Clip(bits) => clip_triangle(v, &planes, bits),
            other => panic!("expected a clip, got {other:?}"),
        }
    }

    #[test]
    fn one_vertex_behind_the_near_plane_gives_a_quad() {
        let p = clip([
            DVec4::new(0.0, 0.0, -1.0, 1.0),
            DVec4::new(0.5, 0.0, 1.0, 3.0),
            DVec4::new(0.0, 0.5, 1.0, 3.0),
        ]);
        assert_eq!(p.vertices().len(), 4);
        assert_eq!(p.fan().count(), 2);
        for v in p.vertices() {
            assert!(v.pos.z >= 0.0);
            // Position stays the barycentric combination of the original vertices.
            let b0 = 1.0 - v.bary.x - v.bary.y;
            let expected = DVec4::new(0.0, 0.0, -1.0, 1.0) * b0
                + DVec4::new(0.5, 0.0, 1.0, 3.0) * v.bary.x
                + DVec4::new(0.0, 0.5, 1.0, 3.0) * v.bary.y;
            assert!((v.pos - expected).length() < 1e-12);
        }
    }

    #[test]
    fn two_vertices_behind_the_near_plane_give_a_triangle() {
        let p = clip([
            DVec4::new(0.0, 0.0, 1.0, 2.0),
            DVec4::new(0.5, 0.0, -1.0, 1.0),
            DVec4::new(0.0, 0.5, -1.0, 1.0),
        ]);
        assert_eq!(p.vertices().len(), 3);
        assert!(p.vertices().iter().all(|v| v.pos.z >= 0.0));
    }

    #[test]
    fn shared_edges_clip_to_the_same_points() {
        let (a, b) = (
            DVec4::new(0.3, 0.1, -0.7, 0.9),
            DVec4::new(-0.2, 0.4, 0.9, 2.1),
        );
        let first = clip([a, b, DVec4::new(1.0, 1.0, 1.0, 2.0)]);
        let second = clip([b, a, DVec4::new(-1.0, -1.0, 1.0, 2.0)]);
        let on_plane = |p: &Polygon| -> Vec<DVec4> {
            p.vertices()
                .iter()
                .filter(|v| v.pos.z.abs() < 1e-9)
                .map(|v| v.pos)
                .collect()
        };
        let shared: Vec<DVec4> = on_plane(&first)
            .into_iter()
            .filter(|p| on_plane(&second).contains(p))
            .collect();
        assert_eq!(shared.len(), 1, "the crossing of edge ab is bit-identical");
    }

    #[test]
    fn classification() {
        let planes = planes();
        let code = |x, y, z, w| planes.outcode(DVec4::new(x, y, z, w));
        let inside = code(0.0, 0.0, 0.5, 1.0);
        assert_eq!(inside, 0);
        assert_eq!(classify([inside; 3]), Verdict::Inside);
        let behind = code(0.0, 0.0, -1.0, 1.0);
        assert_eq!(classify([behind; 3]), Verdict::Outside);
        assert_eq!(classify([inside, inside, behind]), Verdict::Clip(1));
        let right = code(2.0, 0.0, 0.5, 1.0);
        assert_eq!(classify([right; 3]), Verdict::Outside);
        assert_eq!(classify([inside, right, right]), Verdict::Inside);
        let nan = planes.outcode(DVec4::new(f64::NAN, 0.0, 0.5, 1.0));
        assert_eq!(classify([inside, nan, inside]), Verdict::Invalid);
    }
}
