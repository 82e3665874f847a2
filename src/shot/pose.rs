//! The shot's model at a frame: each instance's patches placed by its transform, and by the
//! transforms of the parts that move inside it, read at that frame.

use std::ops::Range;
use std::sync::Arc;

use super::file::TransformSpec;
use super::validated::Shot;
use crate::geom::{NamedPatch, NurbsSurface, PatchLibrary};

/// How one instance is placed at any frame.
#[derive(Debug)]
pub(super) struct InstancePose {
    /// Its patches in the shot's library.
    pub patches: Range<usize>,
    /// The model as read, in its own coordinates.
    pub model: Arc<PatchLibrary>,
    pub transform: TransformSpec,
    /// The parts that move inside the instance, each with its transform in the model's
    /// coordinates.
    pub parts: Vec<(String, TransformSpec)>,
    /// Per patch of the model, the parts (indices into `parts`) that move it, the outermost
    /// first: each holds every patch of the next.
    pub chains: Vec<Vec<usize>>,
}

impl InstancePose {
    /// Whether the instance's patches move over the shot: some track of its transform or of a
    /// part's is keyed.
    #[must_use]
    pub fn moves(&self) -> bool {
        self.transform.is_keyed() || self.parts.iter().any(|(_, t)| t.is_keyed())
    }

    /// The model's patch `patch` placed at `frame`: `T_instance(T_outer(… T_inner(p)))` for each
    /// control point `p`, the parts' transforms applied innermost first.
    #[must_use]
    pub fn place(&self, patch: usize, frame: f64) -> NurbsSurface {
        let instance = self.transform.at(frame);
        let chain: Vec<_> = self.chains[patch]
            .iter()
            .rev()
            .map(|&part| self.parts[part].1.at(frame))
            .collect();
        self.model.patches[patch].surface.map_points(|p| {
            let inside = chain.iter().fold(p, |q, part| part.apply(q));
            instance.apply(inside)
        })
    }
}

impl Shot {
    /// Whether some instance or part moves over the shot.
    #[must_use]
    pub fn moves(&self) -> bool {
        self.poses.iter().any(InstancePose::moves)
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
