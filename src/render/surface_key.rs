//! The key of a frame's surfaces: everything its mesh, visibility buffer and G-buffer depend on
//! besides the model, so that a renderer reuses them when the next frame's key is the same.

use super::camera::{Camera, Projection};
use super::plan::{Plan, Surfaces};
use super::settings::{FrameMode, Settings};
use super::tessellate::Density;

/// What the stages that [depend on surfaces only](Plan::depends_on_surfaces_only) read of a
/// frame besides the model: the camera, the image in samples, the tessellation density and the
/// frame mode of the G-buffer ([`Plan::frames`]), where the shade stage reads surfaces, and whether the G-buffer also holds the
/// outline pass's edge surfaces. Not the thread count: output does not depend on it.
///
/// Numbers are compared bit for bit (−0 is not 0), so that equal keys give equal bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct SurfaceKey {
    camera: [u32; 13],
    /// Width and height in samples.
    samples: (u32, u32),
    density: [u32; 3],
    frames: FrameMode,
    surfaces: Surfaces,
}

impl SurfaceKey {
    /// The key of a frame of `camera` under `settings`, run as `plan` (before any reuse).
    #[must_use]
    pub fn new(camera: &Camera, settings: &Settings, plan: &Plan) -> Self {
        let k = settings.samples_per_side();
        Self {
            camera: camera_bits(camera),
            samples: (settings.width * k, settings.height * k),
            density: match settings.density {
                Density::PerSpan { u, v } => [0, u, v],
                Density::ScreenTolerance { pixels } => [1, pixels.to_bits(), 0],
            },
            frames: plan.frames,
            surfaces: plan.surfaces,
        }
    }
}

/// The camera's numbers as bits: eye, target, up, the projection and its value, near, far.
fn camera_bits(camera: &Camera) -> [u32; 13] {
    let (projection, value) = match camera.projection {
        Projection::Perspective { fov_y_degrees } => (0, fov_y_degrees),
        Projection::Orthographic { height } => (1, height),
    };
    let [ex, ey, ez] = camera.eye.to_array().map(f32::to_bits);
    let [tx, ty, tz] = camera.target.to_array().map(f32::to_bits);
    let [ux, uy, uz] = camera.up.to_array().map(f32::to_bits);
    [
        ex,
        ey,
        ez,
        tx,
        ty,
        tz,
        ux,
        uy,
        uz,
        projection,
        value.to_bits(),
        camera.near.to_bits(),
        camera.far.to_bits(),
    ]
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::geom::PatchLibrary;
    use crate::render::fixtures::{camera, empty_scene};
    use crate::render::{Aovs, Outlines, Scene};

    /// The plan of a scene with no patches under `settings`: the shade stage reads the
    /// visibility buffer unless the scene asks for an AOV.
    fn plan_under(settings: &Settings, outlines: bool, depth_aov: bool) -> Plan {
        let library = PatchLibrary::default();
        let aovs = Aovs {
            depth: depth_aov,
            ..Aovs::default()
        };
        let scene = Scene {
            outlines: outlines.then_some(Outlines {
                width: 1.0,
                colour: Vec3::ZERO,
                crease_degrees: 60.0,
                patch_borders: false,
            }),
            ..empty_scene(&library, aovs)
        };
        Plan::new(&scene, settings)
    }

    /// [`plan_under`] the preview settings.
    fn plan(outlines: bool, depth_aov: bool) -> Plan {
        plan_under(&Settings::preview(64, 48), outlines, depth_aov)
    }

    #[test]
    fn any_change_to_what_the_surfaces_read_changes_the_key() {
        let settings = Settings::preview(64, 48);
        let texels = plan(false, true);
        assert_eq!(texels.surfaces, Surfaces::Texels);
        let key = SurfaceKey::new(&camera(), &settings, &texels);
        assert_eq!(key, SurfaceKey::new(&camera(), &settings, &texels));
        let threads = Settings {
            threads: 3,
            ..settings
        };
        assert_eq!(
            key,
            SurfaceKey::new(&camera(), &threads, &texels),
            "threads do not change output"
        );
        let moved = Camera {
            eye: Vec3::new(0.0, -6.0, 1.000_001),
            ..camera()
        };
        let signed_zero = Camera {
            target: Vec3::new(-0.0, 0.0, 0.0),
            ..camera()
        };
        let ortho = Camera {
            projection: Projection::Orthographic { height: 30.0 },
            ..camera()
        };
        for other in [moved, signed_zero, ortho] {
            assert_ne!(
                key,
                SurfaceKey::new(&other, &settings, &texels),
                "{other:?}"
            );
        }
        for other in [
            Settings::preview(64, 49),
            Settings {
                frames: FrameMode::Exact,
                ..settings
            },
            Settings {
                density: Density::ScreenTolerance { pixels: 0.5 },
                ..settings
            },
            Settings {
                antialias: crate::render::Antialias::Supersample(2),
                ..settings
            },
        ] {
            let planned = plan_under(&other, false, true);
            assert_ne!(
                key,
                SurfaceKey::new(&camera(), &other, &planned),
                "{other:?}"
            );
        }
        // Under adaptive anti-aliasing the G-buffer's frames follow the AOVs: refined when the
        // depth AOV reads them, interpolated otherwise.
        let adaptive = Settings::final_quality(64, 48);
        let (read, flat) = (
            plan_under(&adaptive, false, true),
            plan_under(&adaptive, false, false),
        );
        assert_eq!(
            (read.frames, flat.frames),
            (FrameMode::Refined, FrameMode::Interpolated)
        );
        assert_ne!(
            SurfaceKey::new(&camera(), &adaptive, &read),
            SurfaceKey::new(&camera(), &adaptive, &flat)
        );
        let visibility = plan(false, false);
        assert_eq!(visibility.surfaces, Surfaces::Visibility);
        assert_ne!(key, SurfaceKey::new(&camera(), &settings, &visibility));
        // Lines are found on the mesh: they read nothing of the G-buffer, and need none.
        assert_eq!(
            key,
            SurfaceKey::new(&camera(), &settings, &plan(true, true))
        );
        assert_eq!(plan(true, false).surfaces, Surfaces::Visibility);
    }
}
