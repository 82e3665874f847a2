//! The abstracted shapes that the shading normal of X-Toon's shape detail blends toward.

use serde::Deserialize;

/// The abstracted shape whose normals the shading blends toward.
///
/// RON: `Sphere`, `Ellipsoid`, `Cylinder`, `Smoothed(iterations: 10)`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Abstraction {
    /// A sphere about the centre of the model's principal box: `n_a = normalize(p − c)`.
    Sphere,
    /// The ellipsoid of the model's principal box (axes from the eigenvectors of the covariance
    /// of its control points, semi-axes `a_i` from their extent along each axis). `n_a` is the
    /// true gradient of `Σ x_i² / a_i²`, `normalize(R (x / a²))` with `x = Rᵀ (p − c)` the
    /// point in the principal frame — the normal of the ellipsoid through p, exact on it.
    Ellipsoid,
    /// A cylinder through the box centre along the principal axis `e` (largest variance):
    /// `n_a = normalize((p − c) − ((p − c)·e) e)`.
    Cylinder,
    /// The model's normals smoothed: `n_a` is the kernel average of the model's normals over a
    /// ball of radius `½ h √iterations` around the point, h the mean control-net spacing, as
    /// that many rounds of averaging with the neighbours would spread them (see
    /// [`SmoothedNormals::new`](super::SmoothedNormals::new)).
    Smoothed {
        /// Smoothing iterations, 1 to 1000.
        iterations: u32,
    },
}

/// The most smoothing iterations of [`Abstraction::Smoothed`].
pub const MAX_ITERATIONS: u32 = 1000;
