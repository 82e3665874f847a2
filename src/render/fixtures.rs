//! Test fixtures of the render module: the unit ball, the camera that sees it and a scene of
//! it, and a mesh in the clip space of a view.

use glam::{DVec3, Mat4, Vec3, Vec4};

use super::camera::{Camera, Projection};
use super::scene::{Aovs, Scene};
use super::tessellate::{Density, Mesh, Tessellator};
use crate::geom::{shapes, NamedPatch, PatchLibrary};
use crate::highlight::Light;

/// A camera 6 units out along −y, looking at the origin.
pub(super) fn camera() -> Camera {
    Camera {
        eye: Vec3::new(0.0, -6.0, 1.0),
        target: Vec3::ZERO,
        up: Vec3::Z,
        projection: Projection::Perspective {
            fov_y_degrees: 30.0,
        },
        near: 0.1,
        far: 100.0,
    }
}

/// The unit ball at the origin, one patch named `ball`, which [`camera`] sees whole.
pub(super) fn ball_library() -> PatchLibrary {
    PatchLibrary::new(vec![NamedPatch {
        name: "ball".into(),
        trim: None,
        surface: shapes::sphere(DVec3::ZERO, 1.0).unwrap(),
    }])
}

/// A scene of `library` with no looks, seen by [`camera`], asking for `aovs`.
pub(super) fn empty_scene(library: &PatchLibrary, aovs: Aovs) -> Scene<'_> {
    Scene {
        library,
        looks: Vec::new(),
        camera: camera(),
        light: Light::Directional { towards: Vec3::Z },
        outlines: None,
        aovs,
        materials: Vec::new(),
    }
}

/// The vertices of `mesh` in the clip space of `view_projection`.
pub(super) fn clip_space(mesh: &Mesh, view_projection: Mat4) -> Vec<Vec4> {
    mesh.positions
        .iter()
        .map(|p| view_projection * p.extend(1.0))
        .collect()
}

/// The mesh of `library` seen by `camera` on a `width × height` image, within `pixels` of the
/// surface on screen, with the view-projection and the mesh's vertices in its clip space.
pub(super) fn mesh_in_view(
    library: &PatchLibrary,
    camera: &Camera,
    (width, height): (u32, u32),
    pixels: f32,
) -> (Mesh, Mat4, Vec<Vec4>) {
    let view_projection = camera.view_projection(width as f32 / height as f32);
    let mut tessellator = Tessellator::new(library.clone());
    let (mesh, _) = tessellator.mesh(
        Density::ScreenTolerance { pixels },
        view_projection,
        width,
        height,
    );
    let clip = clip_space(mesh, view_projection);
    (mesh.clone(), view_projection, clip)
}

/// `f` at the nine centres around a pixel, row by row, its own at `(0, 0)`.
pub(super) fn nine(f: impl Fn(f32, f32) -> f32) -> [[f32; 3]; 3] {
    std::array::from_fn(|y| std::array::from_fn(|x| f(x as f32 - 1.0, y as f32 - 1.0)))
}
