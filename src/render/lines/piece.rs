//! A piece of a line: a straight segment of a curve found on the mesh, with its ends on the
//! surface and on the mesh, and its place on the image.

use glam::{DVec3, Mat4, Vec2, Vec3};

use super::screen::to_screen;
use super::stroke::Capsule;
use crate::render::line_style::{LineKind, LineStyle};

/// A straight piece of a line between two points.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Piece {
    /// The ends, on the surface: where the piece is drawn.
    pub ends: [DVec3; 2],
    /// The ends on the mesh at the same parameters: where the depth test looks and what it
    /// compares, since the depth buffer holds the mesh (whose outline may lie a tessellation
    /// tolerance inside the surface's).
    pub on_mesh: [Vec3; 2],
    /// How strongly the piece is inked, in [0, 1] (a crease fading with its angle).
    pub opacity: f32,
    pub kind: LineKind,
    /// Whether its surface ends at it with nothing beyond: a border no other patch continues
    /// (a patch's open side, what a trim leaves of a boundary on one side, a trim's rim). Seen
    /// edge-on, such a border outlines its surface as a silhouette does
    /// ([`DepthTest::shows_open`](super::visible::DepthTest::shows_open)).
    pub open: bool,
    /// The patches it lies on: the same twice for a curve of one patch, the two patches for a
    /// seam or an intersection.
    pub patches: [u32; 2],
}

/// A piece seen on the image: its ends in pixels and their NDC depths.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct OnScreen {
    ends: [Vec2; 2],
    /// The ends on the mesh, in pixels, and their NDC depths.
    on_mesh: [Vec2; 2],
    depths: [f32; 2],
    opacity: f32,
    /// Half the width of its line, in pixels.
    pub radius: f32,
    /// Over how many pixels from a stretch's ends its line narrows ([`LineStyle::taper`]).
    pub taper: f32,
    /// The patch whose style draws it, which names its colour (for a hidden line, that
    /// patch's index after every patch's: [`hidden`](Self::hidden)).
    pub style: u32,
    /// How far around its points the depth test looks ([`DepthTest::shows`]).
    ///
    /// [`DepthTest::shows`]: super::visible::DepthTest::shows
    pub reach: f32,
    /// The patch of an open border ([`Piece::open`]), whose depth test is
    /// [`DepthTest::shows_open`](super::visible::DepthTest::shows_open).
    pub open_on: Option<u32>,
    /// Whether it lies inside a surface's outline (a light contour), where the background does
    /// not show it ([`DepthTest::shows_on_surface`](super::visible::DepthTest::shows_on_surface)).
    pub inside: bool,
}

impl Piece {
    /// The piece on an image of `size` pixels through `view_projection`, drawn in the style of
    /// patch `style` (`styles[style]`); None when an end is at or behind the eye, or the piece,
    /// widened by half its width, misses the image.
    #[must_use]
    pub fn on_screen(
        &self,
        view_projection: Mat4,
        size: (u32, u32),
        styles: &[LineStyle],
        style: u32,
    ) -> Option<OnScreen> {
        let radius = 0.5 * styles[style as usize].width;
        let project = |p: Vec3| to_screen(view_projection * p.extend(1.0), size);
        let (a, _) = project(self.ends[0].as_vec3())?;
        let (b, _) = project(self.ends[1].as_vec3())?;
        let (ma, za) = project(self.on_mesh[0])?;
        let (mb, zb) = project(self.on_mesh[1])?;
        let reach = radius + 1.0;
        let (lo, hi) = (a.min(b) - reach, a.max(b) + reach);
        let inside = hi.x >= 0.0 && hi.y >= 0.0 && lo.x <= size.0 as f32 && lo.y <= size.1 as f32;
        inside.then_some(OnScreen {
            ends: [a, b],
            on_mesh: [ma, mb],
            depths: [za, zb],
            opacity: self.opacity,
            radius,
            taper: styles[style as usize].taper,
            style,
            // A light contour may run along a silhouette, where the surface about it is seen
            // at a grazing angle, as a silhouette is.
            reach: match self.kind {
                LineKind::Silhouette | LineKind::Intersection | LineKind::LightContour => 1.0,
                LineKind::Crease | LineKind::Border | LineKind::MaterialBorder => 0.5,
            },
            open_on: (self.kind == LineKind::Border && self.open).then_some(self.patches[0]),
            inside: self.kind == LineKind::LightContour,
        })
    }
}

impl OnScreen {
    /// Its length on the image, in pixels.
    #[must_use]
    pub fn length(&self) -> f32 {
        self.ends[0].distance(self.ends[1])
    }

    /// The point a fraction `t` of the way from its first end, in pixels.
    #[must_use]
    pub fn point(&self, t: f32) -> Vec2 {
        self.ends[0].lerp(self.ends[1], t)
    }

    /// The NDC depth of the mesh's point a fraction `t` of the way (affine along a straight
    /// piece on the image).
    #[must_use]
    pub fn depth(&self, t: f32) -> f32 {
        self.depths[0] + (self.depths[1] - self.depths[0]) * t
    }

    /// How far the depth test looks around the point a fraction `t` of the way: the kind's
    /// [`reach`](Self::reach), and as far again as the surface's point lies from the mesh's
    /// on the image (the tessellation's error there), so that the window holds what the mesh
    /// shows where the surface is.
    #[must_use]
    pub fn reach_at(&self, t: f32) -> f32 {
        let apart = |k: usize| self.ends[k].distance(self.on_mesh[k]);
        self.reach + apart(0) + (apart(1) - apart(0)) * t
    }

    /// The piece drawn as a hidden line: of radius `radius`, without taper, in the colour
    /// of palette entry `colour`.
    #[must_use]
    pub fn hidden(&self, radius: f32, colour: u32) -> OnScreen {
        OnScreen {
            radius,
            taper: 0.0,
            style: colour,
            ..*self
        }
    }

    /// The stretch from fraction `t0` to `t1` as a capsule whose radius runs from `radii[0]`
    /// to `radii[1]`.
    #[must_use]
    pub fn capsule(&self, t0: f32, t1: f32, radii: [f32; 2]) -> Capsule {
        Capsule {
            a: self.point(t0),
            b: self.point(t1),
            radii,
            opacity: self.opacity,
            colour: self.style,
        }
    }
}
