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

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::super::super::tessellate::Tessellator;
    use super::*;
    use crate::geom::{shapes, NamedPatch, PatchLibrary};

    /// Two balls side by side, each on a grid of 6 × 6 segments a span.
    fn mesh() -> Mesh {
        let patch = |name: &str, surface| NamedPatch {
            name: name.into(),
            trim: None,
            surface,
        };
        let library = PatchLibrary::new(vec![
            patch("ball", shapes::sphere(DVec3::ZERO, 1.0).unwrap()),
            patch("other", shapes::sphere(DVec3::X * 3.0, 1.0).unwrap()),
        ]);
        let mut tessellator = Tessellator::new(library);
        tessellator.mesh_of(vec![(6, 6); 2]).0.clone()
    }

    #[test]
    fn a_grid_is_in_a_mesh_only_where_its_counts_positions_normals_and_uvs_all_match() {
        let mesh = mesh();
        let ball = GridShape::of(&mesh, 0);
        assert!(ball.is_in(&mesh, 0));
        // The other ball's grid has the same counts and other vertices.
        assert_eq!((ball.nu, ball.nv), (mesh.grids[1].nu, mesh.grids[1].nv));
        assert!(!ball.is_in(&mesh, 1));
        // One vertex of the ball mirrored in x (or u) in one field alone.
        fn mirrored(v: Vec3) -> Vec3 {
            Vec3::new(-v.x, v.y, v.z)
        }
        let middle = (mesh.grids[0].first + mesh.grids[0].nu * mesh.grids[0].nv / 2 + 3) as usize;
        type Edit = fn(&mut Mesh, usize);
        let edits: [(&str, Edit); 3] = [
            ("position", |m, k| m.positions[k] = mirrored(m.positions[k])),
            ("normal", |m, k| m.normals[k] = mirrored(m.normals[k])),
            ("uv", |m, k| m.uvs[k].x = -m.uvs[k].x),
        ];
        for (field, edit) in edits {
            let mut moved = mesh.clone();
            edit(&mut moved, middle);
            assert!(!ball.is_in(&moved, 0), "{field}");
            assert!(GridShape::of(&mesh, 1).is_in(&moved, 1), "{field}");
        }
        // The same vertices under other counts of as many.
        let mut regridded = mesh.clone();
        (regridded.grids[0].nu, regridded.grids[0].nv) = (1, ball.nu * ball.nv);
        assert!(!ball.is_in(&regridded, 0));
    }
}
