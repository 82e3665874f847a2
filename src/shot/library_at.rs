//! The shot's model at a frame: the instances' patches, each moving instance's placed where its
//! transforms and its model's time samples put it at that frame.

use std::path::Path;
use std::sync::Arc;

use glam::DQuat;

use super::pose::InstancePose;
use super::validated::Shot;
use crate::geom::{NamedPatch, PatchLibrary};

impl Shot {
    /// How patch `patch` of the shot's library is turned at `frame` by its instance's and its
    /// parts' transforms, `R_instance · R_outer · … · R_inner`; the identity for a patch the shot
    /// does not have.
    #[must_use]
    pub fn rotation_at(&self, patch: usize, frame: f64) -> DQuat {
        self.poses
            .iter()
            .find(|p| p.patches.contains(&patch))
            .map_or(DQuat::IDENTITY, |p| {
                p.rotation(patch - p.patches.start, frame)
            })
    }

    /// Whether some instance or part moves over the shot.
    #[must_use]
    pub fn moves(&self) -> bool {
        self.poses.iter().any(InstancePose::moves)
    }

    /// The files of the models whose own time samples deform them (animated USD layers): what
    /// a frame uses of such a file is its model at the frame ([`Shot::library_at`]), not all
    /// its bytes.
    pub fn deforming_files(&self) -> impl Iterator<Item = &Path> {
        self.poses
            .iter()
            .filter(|p| p.deform.is_some())
            .map(|p| p.file.as_path())
    }

    /// The model at `frame`: [`Shot::library`] itself when nothing moves; otherwise the same
    /// patches, names, parts and trims, each moving instance's patches placed at `frame`.
    #[must_use]
    pub fn library_at(&self, frame: f64) -> Arc<PatchLibrary> {
        if !self.moves() {
            return Arc::clone(&self.library);
        }
        let mut patches: Vec<NamedPatch> = self.library.patches.clone();
        for pose in self.poses.iter().filter(|p| p.moves()) {
            for (k, index) in pose.patches.clone().enumerate() {
                patches[index].surface = pose.place(k, frame);
            }
        }
        Arc::new(PatchLibrary {
            patches,
            groups: self.library.groups.clone(),
        })
    }
}
