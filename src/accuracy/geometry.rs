//! Geometry alone: how far the tessellated unit sphere is from the analytic one at each density,
//! what the tessellation costs, and what evaluating exact frames per pixel costs.

use std::sync::Arc;

use std::hint::black_box;
use std::time::Instant;

use glam::{Mat4, Vec3};

use crate::render::tessellate::{Density, Tessellator};
use crate::render::{Aovs, FrameMode, Projection, RenderError, Renderer, Settings, Stage};

use super::reference::AnalyticSphere;
use super::sweep::Stack;
use super::timing::median;

/// Barycentric samples per triangle edge: each triangle is checked at the `(n+1)(n+2)/2`
/// points `(i, j, n − i − j) / n`.
const SAMPLES_PER_EDGE: u32 = 4;

/// The mesh of one density against the unit sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshError {
    /// Segments per knot span, in u and in v.
    pub segments: u32,
    pub triangles: usize,
    /// The largest distance `|1 − |P||` from a point of a flat triangle to the sphere.
    pub max_position_error: f64,
    /// The largest angle, in degrees, between the interpolated vertex normal at a point of a
    /// triangle and the exact normal at its interpolated (u, v): what interpolated frames miss
    /// of the frames exact evaluation gives. (Against the nearest sphere point the interpolated
    /// normal of a sphere mesh is exact, since a unit sphere's normal is its position.)
    pub max_normal_degrees: f64,
    /// The median time to tessellate the sphere, in seconds.
    pub tessellate_seconds: f64,
}

/// Tessellates the unit sphere at each number of segments per span and measures the mesh
/// against the sphere; times are medians of `repeats` tessellations from scratch.
pub fn mesh_errors(segments: &[u32], repeats: usize) -> Vec<MeshError> {
    let library = AnalyticSphere::library();
    segments
        .iter()
        .map(|&n| {
            let density = Density::PerSpan { u: n, v: n };
            let mut times: Vec<f64> = (0..repeats.max(1))
                .map(|_| {
                    let mut tessellator = Tessellator::new(Arc::clone(&library));
                    let start = Instant::now();
                    black_box(tessellator.mesh(density, Mat4::IDENTITY, 1, 1));
                    start.elapsed().as_secs_f64()
                })
                .collect();
            let mut tessellator = Tessellator::new(Arc::clone(&library));
            let (mesh, _) = tessellator.mesh(density, Mat4::IDENTITY, 1, 1);
            let (mut position, mut normal) = (0.0f64, 0.0f64);
            let surface = &library.patches[0].surface;
            let s = SAMPLES_PER_EDGE;
            for triangle in &mesh.triangles {
                let [a, b, c] = triangle.map(|i| i as usize);
                for i in 0..=s {
                    for j in 0..=s - i {
                        let w = Vec3::new(i as f32, j as f32, (s - i - j) as f32) / s as f32;
                        let mix = |v: &[Vec3]| v[a] * w.x + v[b] * w.y + v[c] * w.z;
                        let p = mix(&mesh.positions).as_dvec3();
                        position = position.max((1.0 - p.length()).abs());
                        let uv = mesh.uvs[a] * w.x + mesh.uvs[b] * w.y + mesh.uvs[c] * w.z;
                        let truth = surface.frame(f64::from(uv.x), f64::from(uv.y)).normal;
                        if let Some(n) = mix(&mesh.normals).as_dvec3().try_normalize() {
                            let angle = n.dot(truth).clamp(-1.0, 1.0).acos();
                            normal = normal.max(angle.to_degrees());
                        }
                    }
                }
            }
            MeshError {
                segments: n,
                triangles: mesh.triangles.len(),
                max_position_error: position,
                max_normal_degrees: normal,
                tessellate_seconds: median(&mut times),
            }
        })
        .collect()
}

/// What one frame mode costs in the G-buffer stage.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FrameCost {
    pub frames: FrameMode,
    /// NURBS frames evaluated per frame (0 for interpolated frames).
    pub exact_frames: u64,
    /// The median G-buffer time per covered pixel, in nanoseconds.
    pub gbuffer_ns_per_pixel: f64,
    /// The median time of the whole frame, in seconds.
    pub frame_seconds: f64,
}

/// The cost of each frame mode: the identity highlight on the sphere in perspective on a
/// `size × size` image, 16 segments per span, no anti-aliasing; medians of `repeats` frames
/// after one untimed frame. The eye moves by a hundredth of a degree between frames, so that
/// each builds its G-buffer afresh rather than reusing the last one's.
pub fn frame_costs(
    size: u32,
    repeats: usize,
    threads: usize,
) -> Result<Vec<FrameCost>, RenderError> {
    let sphere = AnalyticSphere::new(Projection::Perspective {
        fov_y_degrees: 30.0,
    });
    let library = AnalyticSphere::library();
    let highlight = Stack::Identity.expression();
    let mut scene = sphere.scene(&library, &highlight, Aovs::default());
    let eye = scene.camera.eye;
    let mut renderer = Renderer::new(Arc::clone(&library));
    [
        FrameMode::Interpolated,
        FrameMode::Exact,
        FrameMode::Refined,
    ]
    .into_iter()
    .map(|frames| {
        let settings = Settings {
            density: Density::PerSpan { u: 16, v: 16 },
            frames,
            threads,
            ..Settings::preview(size, size)
        };
        scene.camera.eye = eye;
        let first = renderer.render(&scene, &settings)?;
        let (mut gbuffer, mut total) = (Vec::new(), Vec::new());
        for k in 0..repeats.max(1) {
            let turn = (0.01 * (k % 2 + 1) as f32).to_radians();
            scene.camera.eye = glam::Mat3::from_rotation_z(turn) * eye;
            let stats = renderer.render(&scene, &settings)?.stats;
            gbuffer
                .push(stats[Stage::GBuffer].seconds / stats[Stage::GBuffer].pixels.max(1) as f64);
            total.push(stats.total_seconds);
        }
        Ok(FrameCost {
            frames,
            exact_frames: first.stats.exact_frames,
            gbuffer_ns_per_pixel: 1e9 * median(&mut gbuffer),
            frame_seconds: median(&mut total),
        })
    })
    .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chord_error_of_the_sphere_mesh_follows_the_sagitta() {
        // 4 spans around the equator, so n segments per span cut it into 4n chords of angle
        // θ = 2π / 4n; a chord's midpoint lies 1 − cos(θ/2) inside the unit circle. Triangles
        // reach a little deeper than their edges, so the sagitta bounds the error from below.
        let errors = mesh_errors(&[4, 8], 1);
        for e in &errors {
            let theta = std::f64::consts::TAU / (4.0 * f64::from(e.segments));
            let sagitta = 1.0 - (theta / 2.0).cos();
            assert!(
                e.max_position_error >= sagitta * 0.99 && e.max_position_error < 3.0 * sagitta,
                "{e:?} vs sagitta {sagitta}"
            );
        }
        assert!(
            errors[1].max_normal_degrees < errors[0].max_normal_degrees,
            "{errors:?}"
        );
    }

    #[test]
    fn every_timed_frame_builds_its_g_buffer() {
        // A still camera would reuse the first frame's G-buffer and time nothing.
        for cost in frame_costs(48, 3, 1).unwrap() {
            assert!(cost.gbuffer_ns_per_pixel > 0.0, "{cost:?}");
        }
    }
}
