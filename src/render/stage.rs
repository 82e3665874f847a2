//! The stages of a frame, in the order they run: the one list the plan decides from, the
//! statistics report on and the command line prints.

use std::fmt;

/// A stage of the pipeline ([`Plan`](super::Plan) decides which run).
///
/// ```text
/// Tessellate ▸ Rasterize ▸ GBuffer ▸ Detail ▸ EdgeWidths ▸ Shade ▸ Outline ▸ Aov ▸ Resolve
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Stage {
    /// Patches to a mesh of triangles; the mesh is kept while the segment counts stay the same.
    Tessellate,
    /// The mesh to a visibility buffer: per sample the nearest triangle and its barycentrics.
    Rasterize,
    /// Per covered sample its patch, (u, v), position and shading frame.
    GBuffer,
    /// The X-Toon tone of every texel ahead of shading, when a designed highlight is evaluated
    /// in the abstracted frame; otherwise the shade stage computes the tone as it goes.
    Detail,
    /// Per texel the width of the highlight's edge over the pixel's footprint, for analytic
    /// anti-aliasing.
    EdgeWidths,
    /// Tone and designed highlights, composited: from the G-buffer, or straight from the
    /// visibility buffer when the only effect is the cel tone over interpolated frames.
    Shade,
    /// Ink lines where the G-buffer is discontinuous.
    Outline,
    /// The extra images a shot asked for.
    Aov,
    /// Samples averaged into pixels under supersampling.
    Resolve,
}

impl Stage {
    /// How many stages there are.
    pub const COUNT: usize = 9;

    /// Every stage, in the order a frame runs them.
    pub const ALL: [Stage; Stage::COUNT] = [
        Stage::Tessellate,
        Stage::Rasterize,
        Stage::GBuffer,
        Stage::Detail,
        Stage::EdgeWidths,
        Stage::Shade,
        Stage::Outline,
        Stage::Aov,
        Stage::Resolve,
    ];

    /// The stage's name in statistics: `tessellate`, `rasterize`, `gbuffer`, `detail`,
    /// `edge_widths`, `shade`, `outline`, `aov`, `resolve`.
    #[must_use]
    pub const fn name(self) -> &'static str {
        match self {
            Stage::Tessellate => "tessellate",
            Stage::Rasterize => "rasterize",
            Stage::GBuffer => "gbuffer",
            Stage::Detail => "detail",
            Stage::EdgeWidths => "edge_widths",
            Stage::Shade => "shade",
            Stage::Outline => "outline",
            Stage::Aov => "aov",
            Stage::Resolve => "resolve",
        }
    }

    /// The stage's place in [`Stage::ALL`].
    pub(crate) const fn index(self) -> usize {
        self as usize
    }
}

impl fmt::Display for Stage {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_list_of_stages_is_in_order_and_indexes_itself() {
        for (k, stage) in Stage::ALL.iter().enumerate() {
            assert_eq!(stage.index(), k, "{stage}");
        }
        assert!(Stage::ALL.windows(2).all(|w| w[0] < w[1]));
        let mut names: Vec<&str> = Stage::ALL.iter().map(|s| s.name()).collect();
        names.dedup();
        assert_eq!(names.len(), Stage::COUNT);
    }
}
