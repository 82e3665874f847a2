//! What the rasterizer reports about the surface under each pixel, checked against ray casting:
//! perspective-correct barycentrics and depth, near-plane clipping (only the part in front of
//! the camera drawn, barycentrics still on the original triangle), and the depth test.

use glam::{DMat4, DVec2, DVec3, DVec4, Mat4, Vec3, Vec4};
use glint::render::raster::{rasterize, RasterOptions, Viewport, VisibilityBuffer};
use rand::{rngs::StdRng, Rng, SeedableRng};

const VIEWPORT: Viewport = Viewport {
    width: 192,
    height: 128,
};
const NEAR: f32 = 0.5;

/// A perspective camera: view-projection matrix in f32 (what a renderer would use) and f64 (the
/// reference), with the eye position.
struct Camera {
    view_projection: Mat4,
    eye: DVec3,
}

impl Camera {
    fn looking_at(eye: Vec3, target: Vec3) -> Self {
        let aspect = VIEWPORT.width as f32 / VIEWPORT.height as f32;
        let projection = Mat4::perspective_rh(1.0, aspect, NEAR, 50.0);
        Self {
            view_projection: projection * Mat4::look_at_rh(eye, target, Vec3::Y),
            eye: eye.as_dvec3(),
        }
    }

    fn clip(&self, p: Vec3) -> Vec4 {
        self.view_projection * p.extend(1.0)
    }

    /// Distance of `p` in front of the eye along the view direction (view-space −z).
    fn view_depth(&self, p: DVec3) -> f64 {
        self.view_projection.as_dmat4().mul_vec4(p.extend(1.0)).w
    }

    /// The ray from the eye through the centre of pixel `(x, y)`.
    fn pixel_ray(&self, x: u32, y: u32) -> DVec3 {
        let ndc = DVec2::new(
            (f64::from(x) + 0.5) / f64::from(VIEWPORT.width) * 2.0 - 1.0,
            1.0 - (f64::from(y) + 0.5) / f64::from(VIEWPORT.height) * 2.0,
        );
        let inverse: DMat4 = self.view_projection.as_dmat4().inverse();
        inverse.project_point3(ndc.extend(1.0)) - self.eye
    }

    /// NDC depth z/w of the point `p`.
    fn ndc_depth(&self, p: DVec3) -> f64 {
        let c: DVec4 = self.view_projection.as_dmat4() * p.extend(1.0);
        c.z / c.w
    }

    fn render(&self, triangles: &[[Vec3; 3]]) -> VisibilityBuffer {
        let positions: Vec<Vec4> = triangles.iter().flatten().map(|&p| self.clip(p)).collect();
        let indices: Vec<[u32; 3]> = (0..triangles.len() as u32)
            .map(|t| [3 * t, 3 * t + 1, 3 * t + 2])
            .collect();
        rasterize(VIEWPORT, &positions, &indices, &RasterOptions::default()).0
    }
}

/// Where the ray `origin + t·dir` meets the plane of triangle `v` (Möller–Trumbore): the ray
/// parameter t and the barycentrics (b1, b2) of the point, also outside the triangle.
fn ray_triangle(origin: DVec3, dir: DVec3, v: [Vec3; 3]) -> (f64, DVec2) {
    let [a, b, c] = v.map(|p| p.as_dvec3());
    let (e1, e2) = (b - a, c - a);
    let p = dir.cross(e2);
    let det = e1.dot(p);
    let s = origin - a;
    let q = s.cross(e1);
    let bary = DVec2::new(s.dot(p), dir.dot(q)) / det;
    (e2.dot(q) / det, bary)
}

fn pixels() -> impl Iterator<Item = (u32, u32)> {
    (0..VIEWPORT.height).flat_map(|y| (0..VIEWPORT.width).map(move |x| (x, y)))
}

fn min_barycentric(b: DVec2) -> f64 {
    b.x.min(b.y).min(1.0 - b.x - b.y)
}

/// Checks triangle `index` of `buffer` against ray casting on `triangle`: where covered, the
/// barycentrics and depth match the ray's hit, which lies in front of the near plane, and the
/// depth is that of the point at the reported barycentrics; where the
/// ray hits the triangle clearly inside and in front of the near plane, it is covered. Returns
/// the number of pixels covered.
fn assert_matches_ray_casting(
    camera: &Camera,
    buffer: &VisibilityBuffer,
    index: u32,
    triangle: [Vec3; 3],
) -> usize {
    let mut covered = 0;
    for (x, y) in pixels() {
        let dir = camera.pixel_ray(x, y);
        let (t, expected) = ray_triangle(camera.eye, dir, triangle);
        let point = camera.eye + dir * t;
        let in_front = t > 0.0 && camera.view_depth(point) > f64::from(NEAR) + 1e-3;
        match buffer.hit(x, y) {
            Some(hit) if hit.triangle == index => {
                covered += 1;
                assert!(t > 0.0, "pixel ({x}, {y}) draws a point behind the camera");
                assert!(camera.view_depth(point) > f64::from(NEAR) - 1e-3);
                assert!(
                    min_barycentric(expected) > -1e-3,
                    "pixel ({x}, {y}) is outside"
                );
                let got = DVec2::new(hit.barycentric[0].into(), hit.barycentric[1].into());
                assert!(
                    (got - expected).abs().max_element() < 1e-4,
                    "pixel ({x}, {y}): barycentrics {got} vs {expected}"
                );
                // Depth is that of the surface point at the reported barycentrics (both come
                // from the same snapped triangle), and close to the ray's.
                let [a, b, c] = triangle.map(|p| p.as_dvec3());
                let at_bary = camera.ndc_depth(a + (b - a) * got.x + (c - a) * got.y);
                let depth = f64::from(hit.depth);
                assert!(
                    (depth - at_bary).abs() < 1e-5
                        && (depth - camera.ndc_depth(point)).abs() < 1e-4,
                    "pixel ({x}, {y}): depth {depth} vs {at_bary} and {}",
                    camera.ndc_depth(point)
                );
            }
            _ => assert!(
                !(in_front && min_barycentric(expected) > 0.01),
                "pixel ({x}, {y}) is missing"
            ),
        }
    }
    covered
}

#[test]
fn barycentrics_and_depth_are_perspective_correct() {
    let camera = Camera::looking_at(Vec3::new(0.4, 0.3, 3.0), Vec3::ZERO);
    let triangle = [
        Vec3::new(-1.6, -1.0, 1.2),
        Vec3::new(1.3, -0.6, -1.5),
        Vec3::new(-0.2, 1.2, -6.0),
    ];
    for order in [[0, 1, 2], [0, 2, 1]] {
        let triangle = order.map(|i| triangle[i]);
        let buffer = camera.render(&[triangle]);
        let covered = assert_matches_ray_casting(&camera, &buffer, 0, triangle);
        assert!(covered > 3000, "{covered} pixels");
    }
}

#[test]
fn triangles_crossing_the_near_plane_keep_their_barycentrics() {
    // The camera at the origin looks down −z; vertices at z > 0 are behind it.
    let camera = Camera::looking_at(Vec3::ZERO, Vec3::NEG_Z);
    let cases = [
        // One vertex behind the camera: the visible part is a quad.
        [
            Vec3::new(-1.5, -0.6, -3.0),
            Vec3::new(1.2, -0.8, -2.0),
            Vec3::new(0.1, 0.9, 1.5),
        ],
        // Two vertices behind: the visible part is a triangle.
        [
            Vec3::new(0.3, -0.4, -4.0),
            Vec3::new(-1.0, 0.5, 2.0),
            Vec3::new(1.4, 0.7, 0.8),
        ],
        // One vertex between the camera and the near plane.
        [
            Vec3::new(-0.8, -0.5, -2.5),
            Vec3::new(0.9, -0.3, -3.0),
            Vec3::new(0.05, 0.1, -0.2),
        ],
    ];
    for triangle in cases {
        for order in [[0, 1, 2], [2, 1, 0]] {
            let triangle = order.map(|i| triangle[i]);
            let positions = triangle.map(|p| camera.clip(p));
            let (buffer, stats) = rasterize(
                VIEWPORT,
                &positions,
                &[[0, 1, 2]],
                &RasterOptions::default(),
            );
            assert_eq!(stats.triangles_clipped, 1);
            assert!(buffer.depth.iter().all(|d| !d.is_nan()));
            assert!(buffer.barycentric.iter().flatten().all(|b| b.is_finite()));
            let covered = assert_matches_ray_casting(&camera, &buffer, 0, triangle);
            assert!(covered > 500, "{covered} pixels");
        }
    }
}

#[test]
fn triangles_behind_the_camera_or_beyond_the_far_plane_are_culled() {
    let camera = Camera::looking_at(Vec3::ZERO, Vec3::NEG_Z);
    let behind = [
        Vec3::new(-1.0, -1.0, 2.0),
        Vec3::new(1.0, -1.0, 2.0),
        Vec3::new(0.0, 1.0, 0.1),
    ];
    let before_near = behind.map(|p| p * Vec3::new(0.1, 0.1, -0.1));
    let beyond_far = [
        Vec3::new(-30.0, -30.0, -60.0),
        Vec3::new(30.0, -30.0, -60.0),
        Vec3::new(0.0, 30.0, -55.0),
    ];
    for triangle in [behind, before_near, beyond_far] {
        let positions = triangle.map(|p| camera.clip(p));
        let (buffer, stats) = rasterize(
            VIEWPORT,
            &positions,
            &[[0, 1, 2]],
            &RasterOptions::default(),
        );
        assert_eq!((stats.triangles_culled, stats.triangles_clipped), (1, 0));
        assert_eq!(stats.pixels_covered, 0);
        assert!(buffer.triangle.iter().all(|&t| t == u32::MAX));
    }
}

#[test]
fn a_triangle_crossing_the_far_plane_is_cut_there() {
    let camera = Camera::looking_at(Vec3::ZERO, Vec3::NEG_Z);
    let triangle = [
        Vec3::new(-2.0, -1.5, -10.0),
        Vec3::new(2.0, -1.5, -10.0),
        Vec3::new(0.0, 30.0, -90.0),
    ];
    let positions = triangle.map(|p| camera.clip(p));
    let (buffer, stats) = rasterize(
        VIEWPORT,
        &positions,
        &[[0, 1, 2]],
        &RasterOptions::default(),
    );
    assert_eq!(stats.triangles_clipped, 1);
    let drawn: Vec<f32> = buffer
        .depth
        .iter()
        .copied()
        .filter(|d| d.is_finite())
        .collect();
    assert!(drawn.len() > 500);
    assert!(drawn.iter().all(|d| (0.0..=1.0).contains(d)));
    // Pixels whose ray meets the plane of the triangle inside it but beyond the far plane
    // (50) stay empty.
    for (x, y) in pixels() {
        let dir = camera.pixel_ray(x, y);
        let (t, b) = ray_triangle(camera.eye, dir, triangle);
        if min_barycentric(b) > 0.01 && camera.view_depth(camera.eye + dir * t) > 50.5 {
            assert!(
                buffer.hit(x, y).is_none(),
                "pixel ({x}, {y}) beyond the far plane"
            );
        }
    }
}

/// Each triangle rendered alone: per pixel the nearest depth with the lowest index there, and the
/// number of pixels two or more triangles cover.
fn nearest_alone(camera: &Camera, triangles: &[[Vec3; 3]]) -> (Vec<Option<(f32, u32)>>, usize) {
    let pixels = VIEWPORT.width as usize * VIEWPORT.height as usize;
    let mut nearest: Vec<Option<(f32, u32)>> = vec![None; pixels];
    let mut count = vec![0; pixels];
    for (index, triangle) in triangles.iter().enumerate() {
        let alone = camera.render(&[*triangle]);
        for ((n, c), &d) in nearest.iter_mut().zip(&mut count).zip(&alone.depth) {
            if d.is_finite() {
                *c += 1;
                if n.is_none_or(|(nearest, _)| d < nearest) {
                    *n = Some((d, index as u32));
                }
            }
        }
    }
    (nearest, count.iter().filter(|&&c| c > 1).count())
}

#[test]
fn the_nearest_triangle_wins_whatever_the_submission_order() {
    let camera = Camera::looking_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO);
    let mut rng = StdRng::seed_from_u64(3);
    let mut point = || {
        Vec3::new(
            rng.random_range(-1.5..1.5),
            rng.random_range(-1.2..1.2),
            rng.random_range(-2.0..2.0),
        )
    };
    // Large overlapping and interpenetrating triangles, then a copy of the first one: equal
    // depth everywhere, where the lower index wins.
    let mut triangles: Vec<[Vec3; 3]> = (0..12).map(|_| [point(), point(), point()]).collect();
    triangles.push(triangles[0]);
    let (expected, overlaps) = nearest_alone(&camera, &triangles);
    assert!(overlaps > 1000, "{overlaps} pixels with overlaps");
    let buffer = camera.render(&triangles);
    let reversed: Vec<[Vec3; 3]> = triangles.iter().rev().copied().collect();
    let buffer_reversed = camera.render(&reversed);
    let last = triangles.len() as u32 - 1;
    for (i, e) in expected.iter().enumerate() {
        let got = buffer.triangle[i];
        let got_reversed = buffer_reversed.triangle[i];
        match e {
            None => assert_eq!((got, got_reversed), (u32::MAX, u32::MAX)),
            Some((depth, index)) => {
                assert_eq!((buffer.depth[i], got), (*depth, *index), "pixel {i}");
                // Reversed, the copy of triangle 0 has index 0 and wins the ties.
                let index_reversed = if *index == 0 { 0 } else { last - index };
                assert_eq!(got_reversed, index_reversed, "pixel {i}, reversed");
                assert_eq!(buffer_reversed.depth[i], *depth);
            }
        }
    }
    assert!(buffer.triangle.iter().filter(|&&t| t == 0).count() > 100);
}

#[test]
fn two_overlapping_triangles_the_nearer_wins() {
    let camera = Camera::looking_at(Vec3::new(0.0, 0.0, 4.0), Vec3::ZERO);
    let near = [
        Vec3::new(-1.0, -1.0, 0.5),
        Vec3::new(1.0, -1.0, 0.5),
        Vec3::new(0.0, 1.0, 0.5),
    ];
    let far = near.map(|p| Vec3::new(-p.x + 0.3, -p.y, -1.0));
    for (triangles, near_index) in [([near, far], 0), ([far, near], 1)] {
        let buffer = camera.render(&triangles);
        let alone_near = camera.render(&[near]);
        let alone_far = camera.render(&[far]);
        let mut overlap = 0;
        for i in 0..buffer.triangle.len() {
            let (in_near, in_far) = (alone_near.triangle[i] == 0, alone_far.triangle[i] == 0);
            if in_near {
                assert_eq!(buffer.triangle[i], near_index);
                overlap += usize::from(in_far);
            } else if in_far {
                assert_eq!(buffer.triangle[i], 1 - near_index);
            }
        }
        assert!(overlap > 500, "{overlap} overlapping pixels");
    }
}

#[test]
fn a_mesh_clipped_by_the_near_plane_stays_watertight() {
    // A floor under the camera reaching behind it, as a jittered grid of quads in both
    // windings: where its interior is in front of the near plane every pixel is covered exactly
    // once, and no pixel twice anywhere, however the clipped edges fall.
    let camera = Camera::looking_at(Vec3::ZERO, Vec3::new(0.0, -0.8, -1.0));
    let (columns, rows) = (24, 20);
    let (x_range, z_range, floor) = ((-1.5, 1.5), (-4.0, 1.0), -0.25);
    let mut rng = StdRng::seed_from_u64(17);
    let mut points = Vec::new();
    for j in 0..=rows {
        for i in 0..=columns {
            let (u, v) = (i as f32 / columns as f32, j as f32 / rows as f32);
            let interior = i > 0 && i < columns && j > 0 && j < rows;
            let jitter = if interior { 0.2 } else { 0.0 };
            let u = u + rng.random_range(-jitter..=jitter) / columns as f32;
            let v = v + rng.random_range(-jitter..=jitter) / rows as f32;
            let x = x_range.0 + (x_range.1 - x_range.0) * u;
            let z = z_range.0 + (z_range.1 - z_range.0) * v;
            points.push(Vec3::new(x, floor, z));
        }
    }
    let index = |i: usize, j: usize| j * (columns + 1) + i;
    let mut triangles = Vec::new();
    for j in 0..rows {
        for i in 0..columns {
            let (a, b) = (points[index(i, j)], points[index(i + 1, j)]);
            let (c, d) = (points[index(i + 1, j + 1)], points[index(i, j + 1)]);
            for [p, q, r] in [[a, b, c], [a, c, d]] {
                triangles.push(if rng.random_bool(0.5) {
                    [p, q, r]
                } else {
                    [p, r, q]
                });
            }
        }
    }
    let mut count = vec![0u32; VIEWPORT.width as usize * VIEWPORT.height as usize];
    let mut clipped = 0;
    for triangle in &triangles {
        let positions = triangle.map(|p| camera.clip(p));
        let (buffer, stats) = rasterize(
            VIEWPORT,
            &positions,
            &[[0, 1, 2]],
            &RasterOptions::default(),
        );
        clipped += stats.triangles_clipped;
        for (c, &t) in count.iter_mut().zip(&buffer.triangle) {
            *c += u32::from(t != u32::MAX);
        }
    }
    assert!(clipped >= 12, "{clipped} triangles clipped");
    let mut inside = 0;
    for (x, y) in pixels() {
        let c = count[(y * VIEWPORT.width + x) as usize];
        assert!(c <= 1, "pixel ({x}, {y}) covered {c} times");
        let dir = camera.pixel_ray(x, y);
        let t = (f64::from(floor) - camera.eye.y) / dir.y;
        let p = camera.eye + dir * t;
        let margin = 0.05;
        let well_inside = t > 0.0
            && p.x > f64::from(x_range.0) + margin
            && p.x < f64::from(x_range.1) - margin
            && p.z > f64::from(z_range.0) + margin
            && camera.view_depth(p) > f64::from(NEAR) + margin;
        if well_inside {
            assert_eq!(c, 1, "pixel ({x}, {y}) on the floor");
            inside += 1;
        }
    }
    assert!(inside > 5000, "{inside} pixels on the floor");
}
