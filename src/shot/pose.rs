//! How an instance is placed at any frame: its transform, the transforms of the parts that move
//! inside it, and its model's own time samples.

use std::ops::Range;
use std::path::PathBuf;
use std::sync::Arc;

use glam::DQuat;

use super::file::TransformSpec;
use crate::formats::UsdMotion;
use crate::geom::{NurbsSurface, PatchLibrary};

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
    /// The model's own motion, when it is an animated USD layer.
    pub deform: Option<Deform>,
    /// The model's file.
    pub file: PathBuf,
}

/// An animated USD layer's motion, and which of its time codes each frame shows.
#[derive(Debug)]
pub(super) struct Deform {
    pub motion: UsdMotion,
    pub timing: Timing,
}

/// `time code = start + (frame − first) · per_frame`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Timing {
    pub first: f64,
    pub start: f64,
    pub per_frame: f64,
}

impl Timing {
    /// The time code frame `frame` shows.
    #[must_use]
    pub fn time_code(&self, frame: f64) -> f64 {
        self.start + (frame - self.first) * self.per_frame
    }
}

impl InstancePose {
    /// Whether the instance's patches move over the shot: some track of its transform or of a
    /// part's is keyed.
    #[must_use]
    pub fn moves(&self) -> bool {
        self.transform.is_keyed()
            || self.parts.iter().any(|(_, t)| t.is_keyed())
            || self.deform.is_some()
    }

    /// The model's patch `patch` placed at `frame`: `T_instance(T_outer(… T_inner(p)))` for each
    /// control point `p`, the parts' transforms applied innermost first; of an animated USD
    /// layer, `p` is the control point at the frame's time code
    /// ([`UsdMotion::points_at`]).
    #[must_use]
    pub fn place(&self, patch: usize, frame: f64) -> NurbsSurface {
        let model = &self.model.patches[patch].surface;
        let deformed = self
            .deform
            .as_ref()
            .filter(|d| d.motion.moving().contains(&patch))
            .and_then(|d| {
                model.try_with_points(&d.motion.points_at(patch, d.timing.time_code(frame)))
            });
        let instance = self.transform.at(frame);
        let chain: Vec<_> = self.chains[patch]
            .iter()
            .rev()
            .map(|&part| self.parts[part].1.at(frame))
            .collect();
        deformed.as_ref().unwrap_or(model).map_points(|p| {
            let inside = chain.iter().fold(p, |q, part| part.apply(q));
            instance.apply(inside)
        })
    }
}

impl InstancePose {
    /// How the model's patch `patch` is turned at `frame`: `R_instance · R_outer · … · R_inner`,
    /// the rotation its directions take (the scales are uniform and the translations move no
    /// direction).
    #[must_use]
    pub fn rotation(&self, patch: usize, frame: f64) -> DQuat {
        self.chains[patch]
            .iter()
            .fold(self.transform.at(frame).rotation, |r, &part| {
                r * self.parts[part].1.at(frame).rotation
            })
    }
}
