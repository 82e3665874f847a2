//! A piece of a line: a straight segment of a curve found on the mesh, with its ends on the
//! surface and on the mesh, and the runs of it the depth buffer shows.

use glam::{DVec3, Mat4, Vec2, Vec3};

use super::stroke::Capsule;
use super::to_screen;
use super::visible::DepthTest;

/// The kinds of line: what decided that a curve is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum LineKind {
    /// Where the surface turns from facing the eye to facing away (`N·(P − E) = 0`).
    Silhouette,
    /// Where two patches meet at an angle above the crease angle.
    Crease,
    /// A patch's boundary that no other patch continues, or (with patch borders on) one where
    /// two patches meet.
    Border,
}

/// A straight piece of a line between two points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Piece {
    /// The ends, on the surface: where the piece is drawn.
    pub ends: [DVec3; 2],
    /// The ends on the mesh at the same parameters: what the depth test compares, since the
    /// depth buffer holds the mesh.
    pub on_mesh: [Vec3; 2],
    /// How strongly the piece is inked, in [0, 1] (a crease fading with its angle).
    pub opacity: f32,
    pub kind: LineKind,
}

/// A piece seen on the image: its ends in pixels and their NDC depths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct OnScreen {
    ends: [Vec2; 2],
    depths: [f32; 2],
    opacity: f32,
}

/// Samples along a piece are at most this many pixels apart.
const STEP: f32 = 0.5;

/// The most samples a piece is cut into: a piece longer than this many steps is drawn from
/// fewer, farther-apart samples (only a piece reaching far outside the image is that long).
const MOST_SAMPLES: f32 = 16384.0;

impl Piece {
    /// The piece on an image of `size` pixels through `view_projection`; None when an end is
    /// at or behind the eye, or the piece, widened by `radius`, misses the image.
    #[must_use]
    pub fn on_screen(
        &self,
        view_projection: Mat4,
        size: (u32, u32),
        radius: f32,
    ) -> Option<OnScreen> {
        let project = |p: Vec3| to_screen(view_projection * p.extend(1.0), size);
        let (a, _) = project(self.ends[0].as_vec3())?;
        let (b, _) = project(self.ends[1].as_vec3())?;
        let (_, za) = project(self.on_mesh[0])?;
        let (_, zb) = project(self.on_mesh[1])?;
        let reach = radius + 1.0;
        let (lo, hi) = (a.min(b) - reach, a.max(b) + reach);
        let inside = hi.x >= 0.0 && hi.y >= 0.0 && lo.x <= size.0 as f32 && lo.y <= size.1 as f32;
        inside.then_some(OnScreen {
            ends: [a, b],
            depths: [za, zb],
            opacity: self.opacity,
        })
    }
}

impl OnScreen {
    /// The runs of the piece that `depth` shows, as capsules of `radius`: the piece is cut into
    /// samples at most [`STEP`] apart (both ends included), and each run of consecutive visible
    /// samples becomes one capsule from its first to its last.
    #[must_use]
    pub fn visible_runs(&self, depth: &DepthTest, radius: f32) -> Vec<Capsule> {
        let [a, b] = self.ends;
        let n = ((b - a).length() / STEP).ceil().clamp(1.0, MOST_SAMPLES) as u32;
        let at = |i: u32| i as f32 / n as f32;
        let mut runs = Vec::new();
        let mut start: Option<u32> = None;
        for i in 0..=n {
            let t = at(i);
            let seen = depth.shows(
                a.lerp(b, t),
                self.depths[0] + (self.depths[1] - self.depths[0]) * t,
            );
            match (seen, start) {
                (true, None) => start = Some(i),
                (false, Some(s)) => {
                    runs.push(self.capsule(at(s), at(i - 1), radius));
                    start = None;
                }
                _ => {}
            }
        }
        if let Some(s) = start {
            runs.push(self.capsule(at(s), 1.0, radius));
        }
        runs
    }

    fn capsule(&self, t0: f32, t1: f32, radius: f32) -> Capsule {
        let [a, b] = self.ends;
        Capsule {
            a: a.lerp(b, t0),
            b: a.lerp(b, t1),
            radius,
            opacity: self.opacity,
        }
    }
}
