//! The directions at texels that tone and highlights read: to the eye (V), to the light (L),
//! and Blinn's half vector `H = normalize(L + V)` — one texel at a time, or up to [`LANES`]
//! side by side, with the same values.

use glam::Vec3;

use super::camera::Projection;
use super::gbuffer::Texel;
use super::scene::Scene;
use crate::highlight::{half_vector, Light};
use crate::math::Lanes;

/// Blinn's half vector `normalize(L + V)` at a texel: the highlight vector before any operation,
/// L the light its patch's highlight reads ([`Scene::highlight_light`]).
pub(super) fn initial_half_vector(scene: &Scene, t: &Texel) -> Vec3 {
    half_vector(
        scene.highlight_light(t.patch, &t.frame, t.uv, t.position),
        scene.camera.toward_eye(t.position),
    )
}

/// The unit vectors V from each of up to [`LANES`] `texels` toward the eye
/// ([`Camera::toward_eye`]) into `out`, side by side: under perspective `eye − p` for all, then
/// all normalized at once ([`Lanes::normalize`]), with the same values as texel by texel.
///
/// [`Camera::toward_eye`]: super::Camera::toward_eye
#[inline]
pub(super) fn view_lanes(scene: &Scene, texels: &[Texel], out: &mut Lanes) {
    let n = texels.len();
    match scene.camera.projection {
        Projection::Perspective { .. } => {
            towards(scene.camera.eye, texels, out);
            out.normalize(n, |k, _| scene.camera.toward_eye(texels[k].position));
        }
        Projection::Orthographic { .. } => out.fill(n, scene.camera.toward_eye(Vec3::ZERO)),
    }
}

/// The unit vectors L from each of up to [`LANES`] `texels` toward the light
/// ([`Light::direction`]) into `out`, side by side as [`view_lanes`] does, with the same
/// values as texel by texel.
#[inline]
pub(super) fn light_lanes(scene: &Scene, texels: &[Texel], out: &mut Lanes) {
    let n = texels.len();
    match scene.light {
        Light::Directional { towards: l } => out.fill(n, l),
        Light::Point { position } => {
            towards(position, texels, out);
            out.normalize(n, |k, _| {
                scene.light.direction(texels[k].position, texels[k].frame.n)
            });
        }
    }
}

/// The unit vectors each of up to [`LANES`] `texels` of one patch reads its tone from, into
/// `out`: the light vectors ([`light_lanes`]), each then designed by the patch's designed light
/// where it has one ([`DesignedLight::light`](crate::highlight::DesignedLight::light)).
#[inline]
pub(super) fn tone_light_lanes(scene: &Scene, texels: &[Texel], out: &mut Lanes) {
    light_lanes(scene, texels, out);
    let Some(first) = texels.first() else {
        return;
    };
    if let Some(designed) = &scene.looks[first.patch as usize].designed_light {
        for (k, t) in texels.iter().enumerate() {
            debug_assert_eq!(t.patch, first.patch, "texels of one patch");
            out.set(k, designed.light(&t.frame, t.uv, out.get(k)));
        }
    }
}

/// The vector from each of `texels` to the point `to`, into `out`.
#[inline]
fn towards(to: Vec3, texels: &[Texel], out: &mut Lanes) {
    for (k, t) in texels.iter().enumerate() {
        out.set(k, to - t.position);
    }
}

/// [`initial_half_vector`] at each of up to [`LANES`] `texels` into `out`, given their view
/// vectors `view`, side by side: the light vectors ([`light_lanes`], designed where a patch's
/// highlight reads its designed light) and the normalized sums
/// each in loops over one coordinate array at a time, with the same values as texel by texel.
pub(super) fn initial_half_vectors(
    scene: &Scene,
    texels: &[Texel],
    view: &Lanes,
    out: &mut [Vec3],
) {
    let n = texels.len();
    let mut sum = Lanes::default();
    light_lanes(scene, texels, &mut sum);
    // L' where a patch's highlight reads its designed light.
    for (k, t) in texels.iter().enumerate() {
        if let Some(designed) = &scene.looks[t.patch as usize].designed_light {
            sum.set(k, designed.highlight_light(&t.frame, t.uv, sum.get(k)));
        }
    }
    // H = normalize(L + V).
    for k in 0..n {
        sum.set(k, sum.get(k) + view.get(k));
    }
    sum.normalize(n, |k, _| initial_half_vector(scene, &texels[k]));
    for (k, h) in out.iter_mut().enumerate() {
        *h = sum.get(k);
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec2;

    use super::*;
    use crate::geom::PatchLibrary;
    use crate::highlight::{DesignedLight, HighlightLight, Op, ShadeStack, TangentFrame};
    use crate::math::LANES;
    use crate::render::scene::Aovs;
    use crate::render::{Camera, PatchLook, Tone};
    use crate::toon::CelRamp;

    /// Texels at scattered points, one of them on the eye and one on the point light.
    fn texels(eye: Vec3, light: Vec3) -> Vec<Texel> {
        (0..LANES)
            .map(|k| {
                let a = k as f32 * 0.7;
                let position = match k {
                    3 => eye,
                    5 => light,
                    _ => Vec3::new(a.cos(), a.sin(), 0.1 * a) * (1.0 + 0.3 * a),
                };
                let n = Vec3::new(a.sin(), 0.3, a.cos()).normalize();
                let du = n.any_orthonormal_vector();
                Texel {
                    pixel: k as u32,
                    depth: 0.5,
                    patch: 0,
                    uv: Vec2::ZERO,
                    position,
                    frame: TangentFrame::new(du, n.cross(du), n),
                    back: false,
                }
            })
            .collect()
    }

    #[test]
    fn half_vectors_side_by_side_equal_those_texel_by_texel() {
        let library = PatchLibrary::default();
        let eye = Vec3::new(0.5, -6.0, 2.0);
        let light_at = Vec3::new(-3.0, 2.0, 5.0);
        let lights = [
            Light::Directional {
                towards: Vec3::new(0.3, -0.6, 0.75).normalize(),
            },
            Light::Point { position: light_at },
            // Straight behind every point seen by the orthographic camera: L + V vanishes.
            Light::Directional { towards: Vec3::Y },
        ];
        let projections = [
            Projection::Perspective {
                fov_y_degrees: 40.0,
            },
            Projection::Orthographic { height: 4.0 },
        ];
        let texels = texels(eye, light_at);
        // The patch's highlight reading the scene's light, and its designed light.
        let designed = |reads| {
            let stack = ShadeStack {
                stack: vec![Op::Translate {
                    alpha: 0.4,
                    beta: -0.2,
                }],
                mask: None,
            };
            Some(DesignedLight::new(vec![stack.prepare().unwrap()]).read_by_highlight(reads))
        };
        let lights_read = [
            None,
            designed(HighlightLight::Plain),
            designed(HighlightLight::Designed),
        ];
        for (light, designed_light) in lights
            .into_iter()
            .flat_map(|l| lights_read.iter().map(move |d| (l, d.clone())))
        {
            for projection in projections {
                let look = PatchLook {
                    tone: Tone::Cel(CelRamp::two_tone(Vec3::ZERO, Vec3::ONE, 0.3)),
                    designed_light: designed_light.clone(),
                    highlight: None,
                    lines: None,
                };
                let scene = Scene {
                    library: &library,
                    looks: vec![look],
                    camera: Camera {
                        eye,
                        target: eye + Vec3::Y,
                        up: Vec3::Z,
                        projection,
                        near: 0.1,
                        far: 100.0,
                    },
                    light,
                    outlines: None,
                    aovs: Aovs::default(),
                    materials: Vec::new(),
                };
                let mut side_by_side = [Vec3::ZERO; LANES];
                let mut view = Lanes::default();
                view_lanes(&scene, &texels, &mut view);
                initial_half_vectors(&scene, &texels, &view, &mut side_by_side);
                for (t, h) in texels.iter().zip(side_by_side) {
                    let one = initial_half_vector(&scene, t);
                    let l = match &designed_light {
                        Some(d) if d.highlight_reads() == HighlightLight::Designed => {
                            d.light(&t.frame, t.uv, light.direction(t.position, t.frame.n))
                        }
                        _ => light.direction(t.position, t.frame.n),
                    };
                    let v = scene.camera.toward_eye(t.position);
                    assert!(
                        (l + v).length() < 1e-3 || (one - (l + v).normalize()).length() < 1e-5,
                        "{light:?} {projection:?}: {one} is not normalize(L + V)"
                    );
                    assert!(h.is_finite(), "{light:?} {projection:?}: {h}");
                    assert_eq!(
                        h.to_array().map(f32::to_bits),
                        one.to_array().map(f32::to_bits)
                    );
                }
            }
        }
    }
}
