//! One patch's grid of mesh vertices as a line finder saw it, to tell whether the patch is
//! bit for bit where it was.

use glam::{Vec2, Vec3};

use super::super::tessellate::{Mesh, PatchGrid};

/// One patch's grid: its counts and its vertices' positions, normals and (u, v), row by row.
/// A patch whose grid is bit for bit the same, of the same surface, has the same lines of its
/// own (silhouettes) and meets every other unchanged patch where it did (intersections).
#[derive(Debug, Default, PartialEq)]
pub(super) struct GridShape {
    nu: u32,
    nv: u32,
    positions: Vec<Vec3>,
    normals: Vec<Vec3>,
    uvs: Vec<Vec2>,
}

impl GridShape {
    /// Whether patch `patch`'s grid in `mesh` is this one, bit for bit.
    #[must_use]
    pub fn is_in(&self, mesh: &Mesh, patch: usize) -> bool {
        let grid = &mesh.grids[patch];
        let range = grid_range(grid);
        (self.nu, self.nv) == (grid.nu, grid.nv)
            && same_bits(
                &self.positions,
                &mesh.positions[range.clone()],
                Vec3::to_array,
            )
            && same_bits(&self.normals, &mesh.normals[range.clone()], Vec3::to_array)
            && same_bits(&self.uvs, &mesh.uvs[range], Vec2::to_array)
    }

    /// Patch `patch`'s grid in `mesh`.
    #[must_use]
    pub fn of(mesh: &Mesh, patch: usize) -> Self {
        let grid = &mesh.grids[patch];
        let range = grid_range(grid);
        Self {
            nu: grid.nu,
            nv: grid.nv,
            positions: mesh.positions[range.clone()].to_vec(),
            normals: mesh.normals[range.clone()].to_vec(),
            uvs: mesh.uvs[range].to_vec(),
        }
    }
}

/// Whether `a` and `b` hold the same vectors bit for bit (`-0.0` is not `0.0`, as it is not to
/// the line finders' arithmetic downstream of a sign).
#[must_use]
fn same_bits<T: Copy, const N: usize>(a: &[T], b: &[T], array: impl Fn(&T) -> [f32; N]) -> bool {
    a.len() == b.len()
        && a.iter()
            .zip(b)
            .all(|(p, q)| array(p).map(f32::to_bits) == array(q).map(f32::to_bits))
}

/// The vertices of `grid` in its mesh: `first .. first + nu nv`.
#[must_use]
fn grid_range(grid: &PatchGrid) -> std::ops::Range<usize> {
    let first = grid.first as usize;
    first..first + grid.nu as usize * grid.nv as usize
}
