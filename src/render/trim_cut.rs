//! A mesh's trimmed patches as the rasterizer's [`Cut`]: a sample is drawn where its patch's trim
//! keeps the (u, v) the sample lands on.

use super::raster::{interpolate, Cut};
use super::tessellate::Mesh;
use crate::geom::{PatchLibrary, Region};

/// The trims of `library`'s patches over the triangles of `mesh`.
pub(crate) struct MeshCut<'a> {
    mesh: &'a Mesh,
    library: &'a PatchLibrary,
}

impl<'a> MeshCut<'a> {
    /// The cut of `mesh`, or None when no patch of it is trimmed.
    #[must_use]
    pub fn of(mesh: &'a Mesh, library: &'a PatchLibrary) -> Option<Self> {
        (!mesh.triangle_region.is_empty()).then_some(Self { mesh, library })
    }
}

impl Cut for MeshCut<'_> {
    fn region(&self, triangle: u32) -> Region {
        self.mesh.triangle_region[triangle as usize]
    }

    /// Whether the patch's trim keeps `(u, v) = Σ bᵢ (u, v)ᵢ`, the sample's place on the flat
    /// triangle (perspective-correct).
    fn keeps(&self, triangle: u32, b: [f32; 2]) -> bool {
        let t = triangle as usize;
        let [a, c, d] = self.mesh.triangles[t].map(|v| self.mesh.uvs[v as usize]);
        let uv = interpolate(b, a, c, d);
        let patch = &self.library.patches[self.mesh.triangle_patch[t] as usize];
        patch.keeps(f64::from(uv.x), f64::from(uv.y))
    }
}

/// A cut over some of a mesh's triangles, renumbered: triangle `i` of the list rasterized is
/// triangle `triangles[i]` of the mesh.
pub(crate) struct Renumbered<'a> {
    pub cut: &'a dyn Cut,
    pub triangles: &'a [u32],
}

impl Cut for Renumbered<'_> {
    fn region(&self, triangle: u32) -> Region {
        self.cut.region(self.triangles[triangle as usize])
    }

    fn keeps(&self, triangle: u32, b: [f32; 2]) -> bool {
        self.cut.keeps(self.triangles[triangle as usize], b)
    }
}
