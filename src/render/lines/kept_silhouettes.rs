//! The silhouette pieces of each patch from the last frame that found them, kept for a frame
//! that sees the patch as that one did.

use glam::Mat4;

use super::super::camera::Camera;
use super::super::tessellate::Mesh;
use super::contour;
use super::grid_shape::GridShape;
use super::piece::Piece;
use crate::geom::{NamedPatch, PatchLibrary};

/// What a patch's silhouette pieces are a function of besides the patch: the camera, the
/// transform to the image and the image's size.
#[derive(Clone, Copy, Debug, PartialEq)]
struct View {
    camera: Camera,
    view_projection: Mat4,
    size: (u32, u32),
}

/// One patch's silhouette pieces with what they were found from: the patch (its surface and
/// trim) and its grid on the mesh.
#[derive(Debug)]
struct PatchSilhouettes {
    patch: NamedPatch,
    grid: GridShape,
    pieces: Vec<Piece>,
}

impl PatchSilhouettes {
    /// Whether these are patch `patch`'s pieces as `mesh` and `library` have it now: the same
    /// surface and trim, and the same grid bit for bit. The search for them
    /// ([`contour::silhouettes`]) reads nothing else of the patch, and its vertices in their own
    /// order, whatever the patch's place in the mesh, so it would find these pieces again.
    #[must_use]
    fn hold_for(&self, mesh: &Mesh, library: &PatchLibrary, patch: usize) -> bool {
        let now = &library.patches[patch];
        self.patch.same_trim(now)
            && self.patch.surface == now.surface
            && self.grid.is_in(mesh, patch)
    }
}

/// The silhouette pieces of the last frame's patches, per patch (None where a patch draws
/// none), under the view they were found in.
#[derive(Debug, Default)]
pub(crate) struct KeptSilhouettes {
    view: Option<View>,
    patches: Vec<Option<PatchSilhouettes>>,
    /// How many patches' pieces the last frame kept rather than found again.
    kept: usize,
}

impl KeptSilhouettes {
    /// How many patches' silhouette pieces the last call to
    /// [`KeptSilhouettes::silhouettes`] kept from the frame before.
    #[must_use]
    pub fn kept(&self) -> usize {
        self.kept
    }

    /// The silhouette pieces of the patches `drawn` picks, in patch order, as
    /// [`contour::silhouettes`] finds them: a patch's pieces are kept from the last frame when
    /// the view is the same bit for bit and the patch is too ([`PatchSilhouettes::hold_for`]),
    /// and found again otherwise. So a frame where some patches moved under a camera that held
    /// searches only the moved ones, and its pieces are those a fresh search finds.
    pub fn silhouettes(
        &mut self,
        drawn: impl Fn(u32) -> bool + Sync,
        mesh: &Mesh,
        library: &PatchLibrary,
        (camera, view_projection, size): (&Camera, Mat4, (u32, u32)),
    ) -> Vec<Piece> {
        let view = View {
            camera: *camera,
            view_projection,
            size,
        };
        let patches = mesh.grids.len();
        if self.view != Some(view) || self.patches.len() != patches {
            self.patches.clear();
            self.patches.resize_with(patches, || None);
            self.view = Some(view);
        }
        let held: Vec<bool> = (0..patches)
            .map(|p| {
                drawn(p as u32)
                    && self.patches[p]
                        .as_ref()
                        .is_some_and(|s| s.hold_for(mesh, library, p))
            })
            .collect();
        let found = contour::silhouettes(
            |p| drawn(p) && !held[p as usize],
            mesh,
            library,
            camera,
            view_projection,
            size,
        );
        let mut pieces = Vec::new();
        self.kept = 0;
        for (p, found) in found.into_iter().enumerate() {
            match (found, held[p]) {
                (Some(found), _) => {
                    pieces.extend_from_slice(&found);
                    self.patches[p] = Some(PatchSilhouettes {
                        patch: library.patches[p].clone(),
                        grid: GridShape::of(mesh, p),
                        pieces: found,
                    });
                }
                (None, true) => {
                    self.kept += 1;
                    if let Some(kept) = &self.patches[p] {
                        pieces.extend_from_slice(&kept.pieces);
                    }
                }
                (None, false) => self.patches[p] = None,
            }
        }
        pieces
    }
}
