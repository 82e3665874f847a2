//! The visibility of the patches that stayed where they were, kept so that a frame where
//! others moved rasterizes only the moved ones over it.

use std::ops::Range;

use glam::{Vec2, Vec3};

use super::raster::Layer;
use super::surface_key::SurfaceKey;
use super::tessellate::{Mesh, PatchGrid};
use crate::geom::Region;

/// A [`Layer`] of the triangles of the patches it holds, with what it was made from: the
/// frame's surface key and, for the patches held, their grids, vertex positions, (u, v) and
/// trim regions in the mesh. While a frame's key and all of those are the same bit for bit, the
/// held patches' triangles rasterize to the same pixels (their clip-space vertices, set-up and
/// cut are functions of them alone), and drawing the other patches over the layer gives the
/// buffer a full raster gives ([`Rasterizer::rasterize_over_into`]).
///
/// [`Rasterizer::rasterize_over_into`]: super::raster::Rasterizer::rasterize_over_into
pub(super) struct StaticLayer {
    /// Which layer this is, counting those a renderer made.
    pub id: u64,
    key: SurfaceKey,
    /// Per patch, whether its triangles are in the layer.
    held: Vec<bool>,
    grids: Vec<PatchGrid>,
    positions: Vec<Vec3>,
    uvs: Vec<Vec2>,
    regions: Vec<Region>,
    pub layer: Layer,
}

impl StaticLayer {
    /// The record of layer `id` of the patches `held` marks, in `mesh` under `key`; its pixels
    /// are to be drawn into [`StaticLayer::layer`], which starts as `layer`.
    #[must_use]
    pub fn of(id: u64, key: SurfaceKey, mesh: &Mesh, held: Vec<bool>, layer: Layer) -> Self {
        Self {
            id,
            key,
            held,
            grids: mesh.grids.clone(),
            positions: mesh.positions.clone(),
            uvs: mesh.uvs.clone(),
            regions: mesh.triangle_region.clone(),
            layer,
        }
    }

    /// Whether the layer shows the held patches of `mesh` under `key`: none of them is among
    /// those `moved` marks (moved or deformed since the last frame rasterized), and the key,
    /// and for every held patch its grid, vertex positions (bit for bit), (u, v) and trim
    /// regions, are the ones it was made from.
    #[must_use]
    pub fn holds(&self, key: &SurfaceKey, mesh: &Mesh, moved: &[bool]) -> bool {
        self.key == *key
            && self.held.len() == mesh.grids.len()
            && !self
                .held
                .iter()
                .zip(moved)
                .any(|(&held, &moved)| held && moved)
            && self.regions.is_empty() == mesh.triangle_region.is_empty()
            && self
                .held
                .iter()
                .zip(&self.grids)
                .zip(&mesh.grids)
                .filter(|((&held, _), _)| held)
                .all(|((_, was), now)| was == now && self.same_grid(now, mesh))
    }

    /// Whether the vertices and triangles of `grid` (one of the layer's grids) are those of
    /// `mesh`.
    fn same_grid(&self, grid: &PatchGrid, mesh: &Mesh) -> bool {
        let vertices = grid.first as usize..(grid.first + grid.nu * grid.nv) as usize;
        let cells = 2 * (grid.nu - 1) as usize * (grid.nv - 1) as usize;
        let triangles = grid.first_triangle as usize..grid.first_triangle as usize + cells;
        let bits = |v: &Vec3| v.to_array().map(f32::to_bits);
        let uv_bits = |v: &Vec2| v.to_array().map(f32::to_bits);
        let same_positions = self.positions[vertices.clone()]
            .iter()
            .map(bits)
            .eq(mesh.positions[vertices.clone()].iter().map(bits));
        let same_uvs = self.uvs[vertices.clone()]
            .iter()
            .map(uv_bits)
            .eq(mesh.uvs[vertices].iter().map(uv_bits));
        let same_regions = self.regions.is_empty()
            || self.regions[triangles.clone()] == mesh.triangle_region[triangles];
        same_positions && same_uvs && same_regions
    }

    /// Per patch, whether the layer holds it.
    #[must_use]
    pub fn held(&self) -> &[bool] {
        &self.held
    }

    /// The triangles of the patches the layer does not hold: those to draw over it.
    #[must_use]
    pub fn unheld(&self, mesh: &Mesh) -> Vec<Range<u32>> {
        triangle_ranges(mesh, |p| !self.held[p])
    }
}

/// The triangles of the patches of `mesh` that `chosen` picks, as ascending ranges of indices,
/// neighbours merged.
#[must_use]
pub(super) fn triangle_ranges(mesh: &Mesh, chosen: impl Fn(usize) -> bool) -> Vec<Range<u32>> {
    let mut ranges: Vec<Range<u32>> = Vec::new();
    for (_, g) in mesh.grids.iter().enumerate().filter(|(p, _)| chosen(*p)) {
        let end = g.first_triangle + 2 * (g.nu - 1) * (g.nv - 1);
        match ranges.last_mut() {
            Some(last) if last.end == g.first_triangle => last.end = end,
            _ => ranges.push(g.first_triangle..end),
        }
    }
    ranges
}
