//! Contours: the curve where a function of the surface's point and frame changes sign — the
//! silhouette, where the surface turns from facing the eye to facing away, or a light contour
//! ([`light_contour`](super::light_contour)) — found on the mesh and refined onto the surface.

use crate::render::FastMap;

use glam::{DVec2, DVec3, Mat4, Vec3};
use rayon::prelude::*;

use super::super::camera::{Camera, Projection};
use super::super::tessellate::{Mesh, PatchGrid};
use super::piece::Piece;
use super::screen::to_screen;
use crate::geom::{Frame, NurbsSurface, PatchLibrary, Trim};
use crate::render::line_style::LineKind;

/// The most regula falsi steps that move a point of the silhouette from the mesh onto the
/// surface; the search stops sooner once the bracket is narrower than [`BRACKET_PIXELS`] on
/// the image.
const REFINE_STEPS: usize = 12;

/// The search for a point of the silhouette stops when it is bracketed this closely (pixels).
const BRACKET_PIXELS: f32 = 1e-3;

/// A piece whose middle point of the silhouette lies this close (pixels) to its chord is not
/// cut: the chord already follows the curve.
const FLAT_PIXELS: f32 = 0.02;

/// A silhouette piece longer than this on the image (pixels) is cut in two at a point of the
/// true silhouette between its ends, so that its chord stays close to the curve whatever the
/// tessellation: a chord `c` of a curve of radius `ρ` sags by `c²/8ρ`, 0.04 px for 4 px on a
/// 50 px radius.
pub(crate) const LONGEST_PIECE_PIXELS: f32 = 4.0;

/// How many times a piece may be cut in two.
const MOST_HALVINGS: u32 = 8;

/// The fraction of its largest value below which `g` is taken as 0 ([`Level::grazes`]).
pub(crate) const GRAZING: f64 = 1e-6;

/// A signed function of the surface whose zero set is a line: `g` at a point from its frame,
/// and at a mesh vertex from the mesh's own normal and tangent.
pub(crate) trait Level: Sync {
    /// The kind of line where it is zero.
    fn kind(&self) -> LineKind;

    /// `g` at the point of the surface with frame `frame`, at patch parameters `uv`.
    fn at(&self, uv: DVec2, frame: &Frame) -> f64;

    /// `g` at mesh vertex `v`.
    fn at_vertex(&self, mesh: &Mesh, v: u32) -> f64;

    /// Whether `g` at `point` is so small against its largest possible value that its sign is
    /// rounding: it is then taken as 0.
    fn grazes(&self, point: DVec3, g: f64) -> bool;
}

impl Level for EyeSide {
    fn kind(&self) -> LineKind {
        LineKind::Silhouette
    }

    #[inline]
    fn at(&self, _uv: DVec2, frame: &Frame) -> f64 {
        EyeSide::at(self, frame.point, frame.normal)
    }

    #[inline]
    fn at_vertex(&self, mesh: &Mesh, v: u32) -> f64 {
        EyeSide::at_vertex(self, mesh, v)
    }

    #[inline]
    fn grazes(&self, point: DVec3, g: f64) -> bool {
        EyeSide::grazes(self, point, g)
    }
}

/// Which side of the surface the eye is on, as a signed number: `g(P, N) = N·(P − E)` under
/// perspective, `N·F` (F the line of sight) under orthographic projection. The silhouette is
/// where it is zero.
#[derive(Clone, Copy, Debug)]
pub(crate) struct EyeSide {
    eye: Option<DVec3>,
    forward: DVec3,
}

impl EyeSide {
    #[must_use]
    pub fn of(camera: &Camera) -> Self {
        Self {
            eye: match camera.projection {
                Projection::Perspective { .. } => Some(camera.eye.as_dvec3()),
                Projection::Orthographic { .. } => None,
            },
            forward: camera.forward().as_dvec3(),
        }
    }

    /// `g(P, N)`: negative where the side `N` points to faces the eye.
    #[inline]
    #[must_use]
    pub fn at(&self, point: DVec3, normal: DVec3) -> f64 {
        match self.eye {
            Some(eye) => normal.dot(point - eye),
            None => normal.dot(self.forward),
        }
    }

    /// Whether `g` at `point` is within [`GRAZING`] of its largest possible value
    /// ([`reach`](Self::reach)): the line of sight lies within 10⁻⁶ radians of the tangent
    /// plane, closer than the mesh's single-precision normals can tell.
    #[inline]
    #[must_use]
    pub fn grazes(&self, point: DVec3, g: f64) -> bool {
        g.abs() <= GRAZING * self.reach(point)
    }

    /// The largest `|g|` at `point`: `|P − E|`, or 1 under orthographic projection.
    #[inline]
    #[must_use]
    pub fn reach(&self, point: DVec3) -> f64 {
        self.eye.map_or(1.0, |eye| point.distance(eye))
    }

    /// `g` at a mesh vertex.
    #[inline]
    #[must_use]
    pub fn at_vertex(&self, mesh: &Mesh, v: u32) -> f64 {
        let v = v as usize;
        self.at(mesh.positions[v].as_dvec3(), mesh.normals[v].as_dvec3())
    }
}

/// How far from edge-on a surface must be seen for a contour on it to be kept, as `|N·V|`:
/// 0.05, the line of sight 3° or more off the tangent plane. A contour of the side seen is cut
/// where it runs into the silhouette this close, a fraction of a pixel short of it (`R ε²/2`
/// for an outline of radius R pixels); a contour of the far side, which runs behind the
/// silhouette within the depth test's reach of it, is not drawn there.
const EDGE_ON: f64 = 0.05;

/// Which side of the silhouette a contour is kept on: where the eye sees the side its normal
/// points to (`g` of [`EyeSide`] below 0), or the other, by at least [`EDGE_ON`].
#[derive(Clone, Copy, Debug)]
pub(crate) struct KeptSide {
    pub eye: EyeSide,
    /// Keep where the eye sees the side the normal points to.
    pub front: bool,
}

impl KeptSide {
    /// How far inside the kept side a point of frame `frame` is: `±N·V − ε`, `N·V = −g / |P − E|`
    /// (`−g` under orthographic projection), the sign `+` for the front; kept where at least 0.
    #[inline]
    fn inside(&self, frame: &Frame) -> f64 {
        let g = self.eye.at(frame.point, frame.normal);
        let n_dot_v = -g / self.eye.reach(frame.point);
        let facing = if self.front { n_dot_v } else { -n_dot_v };
        facing - EDGE_ON
    }
}

/// A point of the silhouette: its (u, v), where it is on the surface and on the mesh.
#[derive(Clone, Copy, Debug)]
struct Crossing {
    uv: DVec2,
    point: DVec3,
    on_mesh: Vec3,
}

/// `g` at most this fraction of the largest at a triangle's corners is rounding: the point is
/// on the silhouette.
const ROUNDING_SIDE: f64 = 1e-9;

/// What finding a contour on one patch needs.
struct OnPatch<'a, L: Level> {
    mesh: &'a Mesh,
    /// The patch's index in the library.
    patch: u32,
    surface: &'a NurbsSurface,
    /// The patch's trim: silhouettes are drawn only on what it keeps.
    trim: Option<&'a Trim>,
    level: &'a L,
    /// Where the contour is drawn, when only on one side of the silhouette.
    kept_side: Option<KeptSide>,
    view_projection: Mat4,
    size: (u32, u32),
}

/// The silhouette pieces of every patch. In each triangle of the mesh where `g` takes both
/// signs at its corners, the silhouette runs between the two edges `g` changes sign along; on
/// each, the crossing is found on the surface along the edge's straight line in (u, v)
/// (regula falsi from the mesh's estimate `gₐ / (gₐ − g_b)`), so the ends
/// lie on the true silhouette and the two triangles of an edge find the same point. A piece
/// longer than [`LONGEST_PIECE_PIXELS`] on the `size` image is cut at the point of the
/// silhouette on the line from the triangle's lone corner through its middle (in (u, v)).
/// On a trimmed patch, a piece is cut where a trim loop crosses it and only what the trim keeps
/// is drawn. Patch by patch: None for the patches `searched` does not pick.
#[must_use]
pub(crate) fn silhouettes(
    searched: impl Fn(u32) -> bool + Sync,
    mesh: &Mesh,
    library: &PatchLibrary,
    camera: &Camera,
    view_projection: Mat4,
    size: (u32, u32),
) -> Vec<Option<Vec<Piece>>> {
    let side = EyeSide::of(camera);
    mesh.grids
        .par_iter()
        .enumerate()
        .map(|(k, _)| {
            searched(k as u32).then(|| {
                contour_on_patch(
                    &side,
                    None,
                    k as u32,
                    mesh,
                    library,
                    (view_projection, size),
                )
            })
        })
        .collect()
}

/// The pieces of the zero set of `level` on patch `patch` of `library` (its grid in `mesh`),
/// on what its trim keeps, and on `kept_side` of the silhouette when one is given; found as
/// [`silhouettes`] finds the silhouette.
#[must_use]
pub(crate) fn contour_on_patch<L: Level>(
    level: &L,
    kept_side: Option<KeptSide>,
    patch: u32,
    mesh: &Mesh,
    library: &PatchLibrary,
    (view_projection, size): (Mat4, (u32, u32)),
) -> Vec<Piece> {
    let named = &library.patches[patch as usize];
    let grid = &mesh.grids[patch as usize];
    let on = OnPatch {
        mesh,
        patch,
        surface: &named.surface,
        trim: named.trim.as_deref(),
        level,
        kept_side,
        view_projection,
        size,
    };
    on.contour(grid, &grazing_as_zero(mesh, grid, level))
}

/// `g` at every vertex of `grid` in `mesh`, in the grid's order, 0 where the line of sight
/// grazes the surface ([`EyeSide::grazes`]). There `g` is rounding alone, of either sign: along
/// a seam the silhouette runs on (an orthographic view square to a body of revolution), the two
/// sides' copies of a vertex, each with its own patch's normal, would take opposite signs, and
/// the silhouette would slip between the two sides' triangles, each seeing no sign change;
/// along the seam itself, vertices of random signs would leave it in scraps. At 0, every such
/// vertex is on the front, and the triangles behind find the seam once.
#[must_use]
fn grazing_as_zero<L: Level>(mesh: &Mesh, grid: &PatchGrid, level: &L) -> Vec<f64> {
    let first = grid.first;
    (first..first + grid.nu * grid.nv)
        .map(|v| {
            let g = level.at_vertex(mesh, v);
            if level.grazes(mesh.positions[v as usize].as_dvec3(), g) {
                0.0
            } else {
                g
            }
        })
        .collect()
}

impl<L: Level> OnPatch<'_, L> {
    /// The contour's pieces on the patch whose vertices are `grid`, `g` given at each of them
    /// in the grid's order.
    fn contour(&self, grid: &PatchGrid, g: &[f64]) -> Vec<Piece> {
        let (nu, nv) = (grid.nu, grid.nv);
        let value = |v: u32| g[(v - grid.first) as usize];
        let front = |v: u32| value(v) >= 0.0;
        let mut pieces = Vec::new();
        // Each crossed edge is met by the two triangles beside it: found once.
        let mut crossings: FastMap<(u32, u32), Crossing> = FastMap::default();
        let mut on_edge = |x: u32, y: u32| {
            *crossings
                .entry((x.min(y), x.max(y)))
                .or_insert_with(|| self.on_edge((x, value(x)), (y, value(y))))
        };
        for i in 0..nu.saturating_sub(1) {
            for j in 0..nv.saturating_sub(1) {
                let (a, b, c, d) = (
                    grid.vertex(i, j),
                    grid.vertex(i + 1, j),
                    grid.vertex(i + 1, j + 1),
                    grid.vertex(i, j + 1),
                );
                if [b, c, d].iter().all(|&v| front(v) == front(a)) {
                    continue;
                }
                for triangle in [[a, b, c], [a, c, d]] {
                    // The corner on its own side, and the other two.
                    let Some(k) = (0..3).find(|&k| {
                        front(triangle[k]) != front(triangle[(k + 1) % 3])
                            && front(triangle[k]) != front(triangle[(k + 2) % 3])
                    }) else {
                        continue;
                    };
                    let (lone, p, q) = (triangle[k], triangle[(k + 1) % 3], triangle[(k + 2) % 3]);
                    let (start, end) = (on_edge(lone, p), on_edge(lone, q));
                    let corners = [lone, p, q].map(|v| (v, value(v)));
                    self.cut(&corners, start, end, 0, &mut pieces);
                }
            }
        }
        pieces
    }

    /// The silhouette's crossing of the mesh edge from `x` to `y` (`g` of opposite signs),
    /// computed from the lower-numbered vertex so that both triangles of the edge agree.
    fn on_edge(&self, x: (u32, f64), y: (u32, f64)) -> Crossing {
        let ((x, gx), (y, gy)) = if x.0 < y.0 { (x, y) } else { (y, x) };
        let uv = |v: u32| self.mesh.uvs[v as usize].as_dvec2();
        let (px, py) = (
            self.mesh.positions[x as usize],
            self.mesh.positions[y as usize],
        );
        let bracket = self.bracket(px.as_dvec3(), py.as_dvec3());
        let found = root_on_line(
            self.surface,
            &|uv, f| self.level.at(uv, f),
            (uv(x), gx),
            (uv(y), gy),
            bracket,
        );
        let on_mesh = px.lerp(py, found.0 as f32);
        Crossing {
            uv: found.1,
            point: found.2.unwrap_or(on_mesh.as_dvec3()),
            on_mesh,
        }
    }

    /// Draws the silhouette from `start` to `end` inside the triangle `corners` (the lone
    /// corner first, each with its `g`): one piece, or two halves cut at a point of the true
    /// silhouette when it is long on the image.
    fn cut(
        &self,
        corners: &[(u32, f64); 3],
        start: Crossing,
        end: Crossing,
        halvings: u32,
        pieces: &mut Vec<Piece>,
    ) {
        if start.point == end.point {
            return;
        }
        let long = halvings < MOST_HALVINGS
            && self.screen_length(start.point, end.point) > LONGEST_PIECE_PIXELS;
        if let Some(middle) = long.then(|| self.middle(corners, start, end)).flatten() {
            if self.off_chord(start.point, end.point, middle.point) > FLAT_PIXELS {
                self.cut(corners, start, middle, halvings + 1, pieces);
                self.cut(corners, middle, end, halvings + 1, pieces);
                return;
            }
        }
        let Some((start, end)) = self.on_kept_side(corners, start, end) else {
            return;
        };
        let Some(trim) = self.trim else {
            pieces.push(self.piece(start, end));
            return;
        };
        // Only the parts the trim keeps, cut where a trim loop crosses the piece in (u, v).
        let at = |t: f64| {
            if t <= 0.0 {
                start
            } else if t >= 1.0 {
                end
            } else {
                let uv = start.uv.lerp(end.uv, t);
                let on_mesh = self.on_mesh(corners, uv);
                let point = self.surface.point(uv.x, uv.y);
                Crossing {
                    uv,
                    point: if point.is_finite() {
                        point
                    } else {
                        on_mesh.as_dvec3()
                    },
                    on_mesh,
                }
            }
        };
        for (t0, t1) in trim.kept_spans(start.uv, end.uv) {
            pieces.push(self.piece(at(t0), at(t1)));
        }
    }

    /// What lies on the kept side of the silhouette of the piece from `start` to `end` inside
    /// the triangle `corners` ([`KeptSide::inside`]): all of it without a kept side, none of
    /// it when neither end is on it, and otherwise the part from the end on it to where the
    /// side's edge crosses it, found on the surface along the piece's line in (u, v).
    fn on_kept_side(
        &self,
        corners: &[(u32, f64); 3],
        start: Crossing,
        end: Crossing,
    ) -> Option<(Crossing, Crossing)> {
        let Some(kept) = self.kept_side else {
            return Some((start, end));
        };
        let inside = |at: DVec2| kept.inside(&self.surface.frame(at.x, at.y));
        let (g_start, g_end) = (inside(start.uv), inside(end.uv));
        match (g_start >= 0.0, g_end >= 0.0) {
            (true, true) => Some((start, end)),
            (false, false) => None,
            (keeps_start, _) => {
                let bracket = self.bracket(start.point, end.point);
                let (_, at, point) = root_on_line(
                    self.surface,
                    &|_, f| kept.inside(f),
                    (start.uv, g_start),
                    (end.uv, g_end),
                    bracket,
                );
                let on_mesh = self.on_mesh(corners, at);
                let cut = Crossing {
                    uv: at,
                    point: point.unwrap_or(on_mesh.as_dvec3()),
                    on_mesh,
                };
                Some(if keeps_start {
                    (start, cut)
                } else {
                    (cut, end)
                })
            }
        }
    }

    /// The contour's piece from `start` to `end`.
    fn piece(&self, start: Crossing, end: Crossing) -> Piece {
        Piece {
            ends: [start.point, end.point],
            on_mesh: [start.on_mesh, end.on_mesh],
            opacity: 1.0,
            kind: self.level.kind(),
            open: false,
            patches: [self.patch; 2],
        }
    }

    /// The point of the silhouette on the line in (u, v) from the lone corner through the
    /// middle `m` of `start` and `end`, up to the opposite edge, or as far again past it where
    /// `g` there still has the lone corner's sign; else on the line [`across`](Self::across)
    /// the chord; None when neither meets it.
    ///
    /// Where `g` is rounding alone — at most [`ROUNDING_SIDE`] of the largest at the corners —
    /// the point is on the silhouette: at `m` itself (a silhouette running along a seam or an
    /// edge of the mesh, where any point of the line from the lone corner is a root of noise),
    /// or at the opposite edge.
    fn middle(
        &self,
        corners: &[(u32, f64); 3],
        start: Crossing,
        end: Crossing,
    ) -> Option<Crossing> {
        let uv = |v: u32| self.mesh.uvs[v as usize].as_dvec2();
        let [(lone, g_lone), (p, g_p), (q, g_q)] = *corners;
        let rounding = ROUNDING_SIDE * g_lone.abs().max(g_p.abs()).max(g_q.abs());
        let on_silhouette = |at: DVec2| {
            let frame = self.surface.frame(at.x, at.y);
            let g = self.level.at(at, &frame);
            (frame.point.is_finite() && g.abs() <= rounding).then(|| Crossing {
                uv: at,
                point: frame.point,
                on_mesh: self.on_mesh(corners, at),
            })
        };
        let (o, a, b) = (uv(lone), uv(p), uv(q));
        let m = 0.5 * (start.uv + end.uv);
        if let Some(middle) = on_silhouette(m) {
            return Some(middle);
        }
        // Where the line o + s (m − o) meets the edge a + t (b − a).
        let (d, e) = (m - o, b - a);
        let det = d.perp_dot(e);
        if det.abs() <= f64::EPSILON * d.length() * e.length() {
            return self.across(corners, start, end);
        }
        let s = (a - o).perp_dot(e) / det;
        if !(s.is_finite() && s >= 1.0) {
            return self.across(corners, start, end);
        }
        let far = o + d * s;
        if let Some(middle) = on_silhouette(far) {
            return Some(middle);
        }
        let frame = self.surface.frame(far.x, far.y);
        let g_far = self.level.at(far, &frame);
        if (g_far >= 0.0) == (g_lone >= 0.0) {
            // The contour on the surface may bulge past the opposite side, which the mesh's
            // linear `g` does not: look as far again beyond it.
            let beyond = far + (far - m);
            if self.surface.domain().contains(beyond.x, beyond.y) {
                let frame = self.surface.frame(beyond.x, beyond.y);
                let g_beyond = self.level.at(beyond, &frame);
                if g_beyond.is_finite() && (g_beyond >= 0.0) != (g_lone >= 0.0) {
                    return self.root_between(corners, (far, g_far), (beyond, g_beyond));
                }
            }
            return self.across(corners, start, end);
        }
        self.root_between(corners, (o, g_lone), (far, g_far))
    }

    /// The point of the contour on the line in (u, v) through the middle of `start` and `end`
    /// square to the chord between them, across the triangle `corners`; None when `g` takes
    /// one sign at both its ends. Where `g` on the surface departs from the mesh's (about a
    /// pole, whose cells the (u, v) rectangle stretches), the line from the lone corner may
    /// miss the contour while this one, the shortest across it, meets it.
    fn across(
        &self,
        corners: &[(u32, f64); 3],
        start: Crossing,
        end: Crossing,
    ) -> Option<Crossing> {
        let uv = |v: u32| self.mesh.uvs[v as usize].as_dvec2();
        let [o, a, b] = corners.map(|(v, _)| uv(v));
        let m = 0.5 * (start.uv + end.uv);
        let dir = (end.uv - start.uv).perp();
        // The line m + s dir meets the triangle's sides between its least and greatest s.
        let (mut least, mut most) = (f64::INFINITY, f64::NEG_INFINITY);
        for (p, q) in [(o, a), (a, b), (b, o)] {
            let e = q - p;
            let det = dir.perp_dot(e);
            if det.abs() <= f64::EPSILON * dir.length() * e.length() {
                continue;
            }
            let t = (m - p).perp_dot(dir) / -det;
            let s = (p - m).perp_dot(e) / det;
            if s.is_finite() && (0.0..=1.0).contains(&t) {
                least = least.min(s);
                most = most.max(s);
            }
        }
        if !(least < 0.0 && most > 0.0) {
            return None;
        }
        let (lo, hi) = (m + dir * least, m + dir * most);
        let g = |at: DVec2| self.level.at(at, &self.surface.frame(at.x, at.y));
        let (g_lo, g_hi) = (g(lo), g(hi));
        if !(g_lo.is_finite() && g_hi.is_finite()) || (g_lo >= 0.0) == (g_hi >= 0.0) {
            return None;
        }
        self.root_between(corners, (lo, g_lo), (hi, g_hi))
    }

    /// The contour's point on the line in (u, v) from `from` to `to` inside the triangle
    /// `corners`, `g` of opposite signs at the two.
    fn root_between(
        &self,
        corners: &[(u32, f64); 3],
        (from, g_from): (DVec2, f64),
        (to, g_to): (DVec2, f64),
    ) -> Option<Crossing> {
        let bracket = self.bracket(
            self.on_mesh(corners, from).as_dvec3(),
            self.on_mesh(corners, to).as_dvec3(),
        );
        let (_, at, point) = root_on_line(
            self.surface,
            &|uv, f| self.level.at(uv, f),
            (from, g_from),
            (to, g_to),
            bracket,
        );
        let on_mesh = self.on_mesh(corners, at);
        Some(Crossing {
            uv: at,
            point: point.unwrap_or(on_mesh.as_dvec3()),
            on_mesh,
        })
    }

    /// The mesh's point at (u, v) inside the triangle `corners`, by barycentric coordinates in
    /// (u, v).
    fn on_mesh(&self, corners: &[(u32, f64); 3], at: DVec2) -> Vec3 {
        let [x, y, z] = corners.map(|(v, _)| v);
        let uv = |v: u32| self.mesh.uvs[v as usize].as_dvec2();
        let position = |v: u32| self.mesh.positions[v as usize];
        let (a, b, c) = (uv(x), uv(y), uv(z));
        let area = (b - a).perp_dot(c - a);
        if area == 0.0 {
            return position(x);
        }
        let wb = ((at - a).perp_dot(c - a) / area) as f32;
        let wc = ((b - a).perp_dot(at - a) / area) as f32;
        position(x) * (1.0 - wb - wc) + position(y) * wb + position(z) * wc
    }

    fn screen_length(&self, a: DVec3, b: DVec3) -> f32 {
        screen_length(self.view_projection, self.size, a, b)
    }

    /// The fraction of the line from `a` to `b` that is [`BRACKET_PIXELS`] long on the image.
    fn bracket(&self, a: DVec3, b: DVec3) -> f64 {
        f64::from(BRACKET_PIXELS / self.screen_length(a, b).max(BRACKET_PIXELS))
    }

    /// How far `point` lies from the chord from `a` to `b` on the image, in pixels (0 when
    /// one is behind the eye).
    fn off_chord(&self, a: DVec3, b: DVec3, point: DVec3) -> f32 {
        let project = |p: DVec3| {
            to_screen(self.view_projection * p.as_vec3().extend(1.0), self.size).map(|(s, _)| s)
        };
        match (project(a), project(b), project(point)) {
            (Some(a), Some(b), Some(p)) => {
                let ab = b - a;
                let t =
                    ((p - a).dot(ab) / ab.length_squared().max(f32::MIN_POSITIVE)).clamp(0.0, 1.0);
                p.distance(a + ab * t)
            }
            _ => 0.0,
        }
    }
}

/// Where `g` is zero on the surface along the straight line in (u, v) from `from` to `to`
/// (with `g` of opposite signs there), to within `bracket` of the way: the fraction of the
/// way, the (u, v), and the point on the surface (None if no evaluation gave a finite one).
/// Regula falsi (Illinois) keeps the root bracketed, so the fraction stays in [0, 1]
/// whatever the surface does between.
fn root_on_line(
    surface: &NurbsSurface,
    level: &dyn Fn(DVec2, &Frame) -> f64,
    (from, g_from): (DVec2, f64),
    (to, g_to): (DVec2, f64),
    bracket: f64,
) -> (f64, DVec2, Option<DVec3>) {
    let (mut lo, mut hi) = ((0.0, g_from), (1.0, g_to));
    let mut t = linear_root(lo, hi);
    let mut found = None;
    let mut last_side = 0i8;
    for _ in 0..REFINE_STEPS {
        let uv = from.lerp(to, t);
        let frame = surface.frame(uv.x, uv.y);
        let value = level(uv, &frame);
        if frame.point.is_finite() {
            found = Some((t, frame.point));
        }
        if value == 0.0 || !value.is_finite() {
            break;
        }
        if (value < 0.0) == (lo.1 < 0.0) {
            lo = (t, value);
            if last_side == -1 {
                hi.1 *= 0.5;
            }
            last_side = -1;
        } else {
            hi = (t, value);
            if last_side == 1 {
                lo.1 *= 0.5;
            }
            last_side = 1;
        }
        t = linear_root(lo, hi);
        if (hi.0 - lo.0).abs() < bracket {
            break;
        }
    }
    match found {
        Some((t, point)) => (t, from.lerp(to, t), Some(point)),
        None => (t, from.lerp(to, t), None),
    }
}

/// The length in pixels, on a `size` image through `view_projection`, of the segment between
/// two points; 0 when one is at or behind the eye.
#[must_use]
pub(crate) fn screen_length(view_projection: Mat4, size: (u32, u32), a: DVec3, b: DVec3) -> f32 {
    let project = |p: DVec3| to_screen(view_projection * p.as_vec3().extend(1.0), size);
    match (project(a), project(b)) {
        (Some((a, _)), Some((b, _))) => a.distance(b),
        _ => 0.0,
    }
}

/// The zero of the line through `(t₀, g₀)` and `(t₁, g₁)`, clamped between them.
#[inline]
fn linear_root((t0, g0): (f64, f64), (t1, g1): (f64, f64)) -> f64 {
    let t = t0 + (t1 - t0) * g0 / (g0 - g1);
    if t.is_finite() {
        t.clamp(t0.min(t1), t0.max(t1))
    } else {
        0.5 * (t0 + t1)
    }
}
