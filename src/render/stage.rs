//! The stages of a frame, in the order they run: the one list the plan decides from, the
//! statistics report on and the command line prints.

use std::fmt;

/// Defines [`Stage`] with [`Stage::ALL`], [`Stage::COUNT`] and [`Stage::name`] from one list,
/// so that a new stage is one line here and cannot be left out of any of them.
macro_rules! stages {
    ($( $(#[doc = $doc:literal])* $stage:ident => $name:literal, )*) => {
        /// A stage of the pipeline ([`Plan`](super::Plan) decides which run).
        ///
        /// ```text
        /// Tessellate ▸ Rasterize ▸ GBuffer ▸ Detail ▸ EdgeWidths ▸ TrimEdges ▸ Shade ▸ Outline
        ///   ▸ Supersample ▸ Aov ▸ Resolve
        /// ```
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
        pub enum Stage {
            $( $(#[doc = $doc])* $stage, )*
        }

        impl Stage {
            /// How many stages there are.
            pub const COUNT: usize = [$($name),*].len();

            /// Every stage, in the order a frame runs them.
            pub const ALL: [Stage; Stage::COUNT] = [$(Stage::$stage),*];

            /// The stage's name in statistics: `tessellate`, `rasterize`, `gbuffer`, `detail`,
            /// `edge_widths`, `trim_edges`, `shade`, `outline`, `supersample`, `aov`, `resolve`.
            #[must_use]
            pub const fn name(self) -> &'static str {
                match self {
                    $( Stage::$stage => $name, )*
                }
            }
        }
    };
}

stages! {
    /// Patches to a mesh of triangles; the mesh is kept while the segment counts stay the same.
    Tessellate => "tessellate",
    /// The mesh to a visibility buffer: per sample the nearest triangle and its barycentrics.
    Rasterize => "rasterize",
    /// Per covered sample its patch, (u, v), position and shading frame.
    GBuffer => "gbuffer",
    /// The X-Toon tone of every texel ahead of shading, when a designed highlight is evaluated
    /// in the abstracted frame; otherwise the shade stage computes the tone as it goes.
    Detail => "detail",
    /// Per texel the width of the highlight's edge over the pixel's footprint, for analytic
    /// anti-aliasing.
    EdgeWidths => "edge_widths",
    /// Under adaptive anti-aliasing on a frame with trimmed cel patches, the pixels about the
    /// trims' rims whose colour one sample on each side of the rim gives, weighted by the rim's
    /// cover of the box; the supersampling leaves them out.
    TrimEdges => "trim_edges",
    /// Tone and designed highlights, composited: from the G-buffer, or straight from the
    /// visibility buffer when the only effect is the cel tone over interpolated frames.
    Shade => "shade",
    /// Ink lines where the G-buffer is discontinuous.
    Outline => "outline",
    /// Under adaptive anti-aliasing, the pixels whose colour differs from a neighbour's drawn
    /// again at K × K samples, tile by tile, and averaged.
    Supersample => "supersample",
    /// The extra images a shot asked for.
    Aov => "aov",
    /// Samples averaged into pixels under supersampling.
    Resolve => "resolve",
}

impl Stage {
    /// The stage's place in [`Stage::ALL`].
    #[must_use]
    pub const fn index(self) -> usize {
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
