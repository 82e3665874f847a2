//! Light contours: the cel terminator as an ink line — where the `N·L` a patch's tone reads
//! (`N·L'` under designed shade) crosses one of its band thresholds.

use glam::{DVec2, DVec3, Mat4, Vec2, Vec3};
use rayon::prelude::*;

use super::super::camera::Camera;
use super::super::scene::{PatchLook, Tone};
use super::super::tessellate::Mesh;
use super::contour::{contour_on_patch, EyeSide, KeptSide, Level, GRAZING};
use super::piece::Piece;
use crate::geom::{Frame, PatchLibrary};
use crate::highlight::{DesignedLight, Light, TangentFrame};
use crate::render::line_style::LineKind;

/// The thresholds of `N·L` at which a patch of tone `tone` changes band: a cel ramp's band
/// thresholds; for X-Toon, whose tone runs on without bands, 0 (where the light grazes the
/// surface).
#[must_use]
pub(crate) fn thresholds(tone: &Tone) -> Vec<f32> {
    match tone {
        Tone::Cel(ramp) => ramp.bands.iter().map(|&(t, _)| t).collect(),
        Tone::XToon(_) => vec![0.0],
    }
}

/// `g = N_s·L' − t`: the tone's `N·L` (through the patch's designed light, if any) less a
/// band threshold `t`, with the normal turned by `sign` — shading turns it toward the eye
/// where the eye sees the patch's back, so each side of the silhouette has its own contour.
struct LightLevel<'a> {
    light: Light,
    designed: Option<&'a DesignedLight>,
    threshold: f32,
    /// 1 for the normal as the patch has it, −1 turned.
    sign: f32,
}

impl LightLevel<'_> {
    /// `g` at `point` with unit normal `normal` and unit tangent `du` (`dv = N × du`), at
    /// patch parameters `uv`, as shading reads it: in single precision.
    #[inline]
    fn of(&self, point: Vec3, (normal, du): (Vec3, Vec3), uv: Vec2) -> f64 {
        let n = normal * self.sign;
        let l = self.light.direction(point, n);
        let n_dot_l = match self.designed {
            Some(designed) => {
                let frame = TangentFrame::new(du, n.cross(du), n);
                designed.n_dot_l(&frame, uv, l)
            }
            None => n.dot(l),
        };
        f64::from(n_dot_l - self.threshold)
    }
}

impl Level for LightLevel<'_> {
    fn kind(&self) -> LineKind {
        LineKind::LightContour
    }

    #[inline]
    fn at(&self, uv: DVec2, frame: &Frame) -> f64 {
        self.of(
            frame.point.as_vec3(),
            (frame.normal.as_vec3(), frame.du.as_vec3()),
            uv.as_vec2(),
        )
    }

    #[inline]
    fn at_vertex(&self, mesh: &Mesh, v: u32) -> f64 {
        let v = v as usize;
        let normal = mesh.normals[v].normalize_or_zero();
        self.of(mesh.positions[v], (normal, mesh.tangents_u[v]), mesh.uvs[v])
    }

    /// `N·L` is at most 1 in size: within 10⁻⁶ of the threshold is rounding.
    #[inline]
    fn grazes(&self, _point: DVec3, g: f64) -> bool {
        g.abs() <= GRAZING
    }
}

/// The light contours of the patches `drawn` picks, lit by `light`, each patch's tone and
/// designed light in `looks`: per patch, per band threshold, the contour of the normal as the
/// patch has it where the eye sees that side, and of the turned normal where it sees the other.
#[must_use]
pub(crate) fn light_contours(
    drawn: impl Fn(u32) -> bool + Sync,
    (light, looks): (&Light, &[PatchLook]),
    (mesh, library): (&Mesh, &PatchLibrary),
    camera: &Camera,
    (view_projection, size): (Mat4, (u32, u32)),
) -> Vec<Piece> {
    let eye = EyeSide::of(camera);
    (0..library.patches.len() as u32)
        .into_par_iter()
        .filter(|&p| drawn(p))
        .flat_map_iter(|patch| {
            let look = &looks[patch as usize];
            let mut pieces = Vec::new();
            for threshold in thresholds(&look.tone) {
                for front in [true, false] {
                    let level = LightLevel {
                        light: *light,
                        designed: look.designed_light.as_ref(),
                        threshold,
                        sign: if front { 1.0 } else { -1.0 },
                    };
                    let side = KeptSide { eye, front };
                    pieces.extend(contour_on_patch(
                        &level,
                        Some(side),
                        patch,
                        mesh,
                        library,
                        (view_projection, size),
                    ));
                }
            }
            pieces
        })
        .collect()
}
