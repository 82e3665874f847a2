//! What is rendered: the model, how each patch looks, the camera and the light.

use glam::Vec3;

use super::camera::Camera;
use crate::geom::PatchLibrary;
use crate::highlight::{Light, PreparedExpr};
use crate::toon::{CelRamp, PreparedXToon};

/// How one patch is drawn: its tone and, optionally, its designed highlight.
#[derive(Clone, Debug, PartialEq)]
pub struct PatchLook {
    pub tone: Tone,
    pub highlight: Option<PreparedExpr>,
}

/// The tone of a patch.
#[derive(Clone, Debug, PartialEq)]
pub enum Tone {
    /// Flat cel bands over `N·L`.
    Cel(CelRamp),
    /// X-Toon: a 2D toon texture over `(n'·l, D)`, with a detail map and optional shape detail
    /// (see docs/xtoon.md). A patch with shape detail and [`HighlightFrame::Abstracted`] has its
    /// designed highlight evaluated in the abstracted frame.
    ///
    /// [`HighlightFrame::Abstracted`]: crate::toon::HighlightFrame::Abstracted
    XToon(PreparedXToon),
}

/// Lines drawn over the shaded image where the G-buffer is discontinuous.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Outlines {
    /// Line width in pixels (≥ 1).
    pub width: f32,
    /// Linear RGB.
    pub colour: Vec3,
    /// Normals turning by more than this between neighbouring pixels of a patch draw a crease.
    pub crease_degrees: f32,
    /// Also draw where one patch meets another.
    pub patch_borders: bool,
}

/// Optional extra images (arbitrary output variables) filled beside the colour.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Aovs {
    /// Final highlight coverage per pixel.
    pub matte: bool,
    /// Patch index per pixel.
    pub patch_id: bool,
    /// NDC depth per pixel.
    pub depth: bool,
    /// Shading normal per pixel.
    pub normal: bool,
    /// Patch parameters (u, v) per pixel.
    pub uv: bool,
    /// `N·H` of the initial half vector per pixel, on every patch: where the undesigned Blinn
    /// highlight would be (a debug view for animators).
    pub n_dot_h: bool,
    /// The lines alone, with their coverage as alpha (transparent where none are drawn).
    pub outline: bool,
}

/// Everything one frame shows.
#[derive(Clone, Debug)]
pub struct Scene<'a> {
    pub library: &'a PatchLibrary,
    /// One look per patch of `library`, in its order.
    pub looks: Vec<PatchLook>,
    pub camera: Camera,
    /// The light for tone and highlights.
    pub light: Light,
    pub outlines: Option<Outlines>,
    pub aovs: Aovs,
}
