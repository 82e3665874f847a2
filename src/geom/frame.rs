//! The local frame of a surface point: position, unit normal and the two unit tangent
//! directions the highlight operations work in.

use glam::DVec3;

/// The frame `(du, dv, N)` at a surface point (DESIGN §3).
///
/// `N = normalize(Su × Sv)`, `du = normalize(Su)`, `dv = N × du`; the three are orthonormal and
/// right-handed (`du × dv = N`). At a degenerate point (a collapsed row of control points, where
/// `Su × Sv` vanishes) the limit of that frame from inside the patch is used, and `degenerate` is
/// set. Every component is finite.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// The surface point S(u, v).
    pub point: DVec3,
    /// Unit normal N.
    pub normal: DVec3,
    /// Unit tangent along increasing u.
    pub du: DVec3,
    /// Unit tangent `N × du`, along increasing v where the parametrisation is orthogonal.
    pub dv: DVec3,
    /// True when `Su × Sv` vanished here and the frame is the limit from inside the patch.
    pub degenerate: bool,
}
