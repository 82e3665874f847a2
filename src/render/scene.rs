//! What is rendered: the model, how each patch looks, the camera and the light.

use glam::{Vec2, Vec3};

use super::camera::Camera;
use super::line_style::LineStyle;
use crate::geom::PatchLibrary;
use crate::highlight::{DesignedLight, Light, PreparedExpr, TangentFrame};
use crate::toon::{CelRamp, PreparedXToon};

/// How one patch is drawn: its tone, optionally the light its tone reads designed, optionally
/// its designed highlight, and how its lines are drawn when the scene has [`Outlines`].
#[derive(Clone, PartialEq)]
pub struct PatchLook {
    pub tone: Tone,
    /// The light the tone reads, `L'` of the shade stacks on the patch; None: the scene's light.
    /// The highlight reads the scene's light unless the designed light says it reads `L'` too
    /// ([`DesignedLight::highlight_reads`]).
    pub designed_light: Option<DesignedLight>,
    pub highlight: Option<PreparedExpr>,
    /// The patch's own line style; None draws its lines in the outlines' own
    /// ([`Outlines::style`]).
    pub lines: Option<LineStyle>,
}

/// Every field, as `#[derive(Debug)]` prints them, but the designed light only when there is
/// one: a look without it prints as looks did before they had it, so that what a frame's
/// fingerprint hashes of a shot without designed shade stays the same.
impl std::fmt::Debug for PatchLook {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut look = f.debug_struct("PatchLook");
        look.field("tone", &self.tone);
        if let Some(light) = &self.designed_light {
            look.field("designed_light", light);
        }
        look.field("highlight", &self.highlight)
            .field("lines", &self.lines)
            .finish()
    }
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

/// Lines drawn over the shaded image: silhouettes, creases, borders and intersections found
/// on the mesh (docs/rendering.md, "Lines").
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Outlines {
    /// Line width in pixels, in [0, 64], of every patch without a style of its own.
    pub width: f32,
    /// Linear RGB, of every patch without a style of its own.
    pub colour: Vec3,
    /// Where the normals on the two sides of a seam turn by more than this (degrees), a crease
    /// is drawn, fading in over a 10° band around it.
    pub crease_degrees: f32,
    /// Also draw where one patch meets another.
    pub patch_borders: bool,
}

impl Outlines {
    /// The style of a patch without one of its own: this width and colour, every kind of line,
    /// no taper.
    #[must_use]
    pub const fn style(&self) -> LineStyle {
        LineStyle::new(self.width, self.colour)
    }
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
    /// highlight would be (a debug view for animators), H from the light the patch's highlight
    /// reads ([`Scene::highlight_light`]).
    pub n_dot_h: bool,
    /// `N·L'` per pixel: the light its tone reads ([`Scene::tone_n_dot_l`]), on every patch
    /// (a view of where the cel bands' edges lie, and a light pass for compositing).
    pub n_dot_l: bool,
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
    /// Per patch of `library`, its material (an index of the shot's), which material borders
    /// read; empty when no patch draws them, every patch then of one material.
    pub materials: Vec<u32>,
}

impl Scene<'_> {
    /// Whether some patch has a designed highlight.
    #[must_use]
    pub fn has_highlights(&self) -> bool {
        self.looks.iter().any(|look| look.highlight.is_some())
    }

    /// Whether some patch's tone reads a designed light.
    #[must_use]
    pub fn has_designed_light(&self) -> bool {
        self.looks.iter().any(|look| look.designed_light.is_some())
    }

    /// The unit light direction the tone of `patch` reads at a point with surface frame `frame`
    /// (its normal `frame.n`), patch parameters `uv` and world position `position`: `L'` of the
    /// patch's designed light ([`DesignedLight::light`]), or the scene's light L.
    #[inline]
    #[must_use]
    pub fn tone_light(&self, patch: u32, frame: &TangentFrame, uv: Vec2, position: Vec3) -> Vec3 {
        let l = self.light.direction(position, frame.n);
        match &self.looks[patch as usize].designed_light {
            Some(designed) => designed.light(frame, uv, l),
            None => l,
        }
    }

    /// The unit light direction the highlight of `patch` reads at that point: the scene's light
    /// L, or `L'` where the patch's highlight reads its designed light
    /// ([`DesignedLight::highlight_light`]).
    #[inline]
    #[must_use]
    pub fn highlight_light(
        &self,
        patch: u32,
        frame: &TangentFrame,
        uv: Vec2,
        position: Vec3,
    ) -> Vec3 {
        let l = self.light.direction(position, frame.n);
        match &self.looks[patch as usize].designed_light {
            Some(designed) => designed.highlight_light(frame, uv, l),
            None => l,
        }
    }

    /// `N·L'` (or `N·L`) at that point: what the patch's tone reads ([`tone_light`](Self::tone_light)).
    #[inline]
    #[must_use]
    pub fn tone_n_dot_l(&self, patch: u32, frame: &TangentFrame, uv: Vec2, position: Vec3) -> f32 {
        let l = self.light.direction(position, frame.n);
        match &self.looks[patch as usize].designed_light {
            Some(designed) => designed.n_dot_l(frame, uv, l),
            None => frame.n.dot(l),
        }
    }

    /// Whether some patch's tone is a cel ramp with band edges (more than one colour).
    #[must_use]
    pub fn has_band_edges(&self) -> bool {
        self.looks
            .iter()
            .any(|look| matches!(&look.tone, Tone::Cel(ramp) if !ramp.bands.is_empty()))
    }
}
