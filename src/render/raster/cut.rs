//! What the rasterizer draws of its triangles: what a cut keeps of them, in the rows asked for.

use crate::geom::Region;

/// Which parts of the triangles are drawn, when not all are: the samples a trimmed patch's trim
/// cuts away are not, so that what is behind them shows.
pub trait Cut: Sync {
    /// Where triangle `triangle` lies: wholly drawn, wholly cut away (never set up), or to be
    /// asked sample by sample ([`Cut::keeps`]).
    fn region(&self, triangle: u32) -> Region;

    /// Whether the sample at the perspective-correct barycentrics `b` of triangle `triangle`
    /// (one whose region is [`Region::Both`]) is drawn.
    fn keeps(&self, triangle: u32, b: [f32; 2]) -> bool;
}

/// What a call draws of its triangles: what the cut keeps of them, in each row `y` over the
/// pixels `rows[y].0 .. rows[y].1` ([`Rasterizer::rasterize_rows_into`]).
pub(super) type Kept<'a> = (Option<&'a dyn Cut>, Option<&'a [(u32, u32)]>);
