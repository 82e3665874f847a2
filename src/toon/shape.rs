//! Shape detail of X-Toon (Barla et al. 2006, §4): the shading normal blended toward the normal
//! of an abstracted shape, `n' = normalize(lerp(n, n_a, w))`. Positions, and so silhouettes, do
//! not move.

use std::sync::Arc;

use glam::{DMat3, DVec3, Mat3, Vec2, Vec3};
use nalgebra::{Matrix3, SymmetricEigen};
use serde::Deserialize;

use super::abstraction::{Abstraction, MAX_ITERATIONS};
use super::error::XToonError;
use super::point_run::PointRun;
use super::smooth::SmoothedNormals;
use crate::geom::PatchLibrary;
use crate::math::Lanes;
use crate::param::{check, Range};

/// Which frame the highlight operations of a patch with shape detail use: the designed
/// highlight's operations and the X-Toon highlight detail map `|v·r|^s`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
pub enum HighlightFrame {
    /// The blended shading normal n' (with du turned into its tangent plane): highlights sit
    /// where the abstracted tone would put them.
    #[default]
    Abstracted,
    /// The surface's own frame: highlights follow the true shape while the tone is abstracted.
    True,
}

/// Shape detail: the abstraction, the weight w of its normal, and the highlights' frame.
///
/// RON: `(abstraction: Ellipsoid, weight: 0.6, highlight_frame: True)` (`highlight_frame`
/// defaults to `Abstracted`).
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShapeDetail<P = f32> {
    pub abstraction: Abstraction,
    /// w ∈ [0, 1]: 0 shades the true shape, 1 the abstracted one.
    pub weight: P,
    #[serde(default)]
    pub highlight_frame: HighlightFrame,
}

impl<P> ShapeDetail<P> {
    /// The same shape detail with its weight mapped through `f`.
    #[must_use]
    pub fn map<Q>(&self, mut f: impl FnMut(&P) -> Q) -> ShapeDetail<Q> {
        ShapeDetail {
            abstraction: self.abstraction,
            weight: f(&self.weight),
            highlight_frame: self.highlight_frame,
        }
    }
}

impl ShapeDetail<f32> {
    /// Checks w ∈ [0, 1] and the abstraction's own parameters.
    pub fn validate(&self) -> Result<(), XToonError> {
        self.abstraction.validate()?;
        check(
            "shape weight (w)",
            self.weight,
            Range::Unit,
            "; 0 shades the true shape, 1 the abstracted one",
        )?;
        Ok(())
    }

    /// Validates and pairs the weight with `shape`, the model's abstracted shape built once by
    /// [`Abstraction::build`] for this detail's abstraction. With w = 0 there is nothing to
    /// blend: `None`, and the shading is exactly the true shape's.
    pub fn prepare(&self, shape: &Arc<AbstractShape>) -> Result<Option<PreparedShape>, XToonError> {
        self.validate()?;
        if shape.abstraction != self.abstraction {
            return Err(XToonError::ShapeMismatch {
                wanted: self.abstraction,
                built: shape.abstraction,
            });
        }
        Ok((self.weight > 0.0).then(|| PreparedShape {
            shape: Arc::clone(shape),
            weight: self.weight,
            highlight_frame: self.highlight_frame,
        }))
    }
}

impl Abstraction {
    /// Checks the smoothing iterations (1 to 1000).
    pub fn validate(&self) -> Result<(), XToonError> {
        match *self {
            Abstraction::Smoothed { iterations } if !(1..=MAX_ITERATIONS).contains(&iterations) => {
                Err(XToonError::Iterations { iterations })
            }
            _ => Ok(()),
        }
    }

    /// This abstraction of `library`'s model. Done once per model: the principal box is an
    /// eigen-decomposition of the control points' covariance, the smoothed shape an average of the
    /// model's normals on a grid per patch.
    pub fn build(&self, library: &PatchLibrary) -> Result<Arc<AbstractShape>, XToonError> {
        self.validate()?;
        let geometry = match self {
            Abstraction::Smoothed { iterations } => {
                Geometry::Smoothed(SmoothedNormals::new(library, *iterations)?)
            }
            analytic => {
                let points: Vec<DVec3> = library.control_points().collect();
                let b = PrincipalBox::fit(&points)?;
                let centre = b.centre.as_vec3();
                match analytic {
                    Abstraction::Sphere => Geometry::Sphere { centre },
                    Abstraction::Ellipsoid => Geometry::Ellipsoid {
                        centre,
                        gradient: (b.axes
                            * DMat3::from_diagonal((b.semi_axes * b.semi_axes).recip())
                            * b.axes.transpose())
                        .as_mat3(),
                    },
                    _ => Geometry::Cylinder {
                        centre,
                        axis: b.axes.x_axis.as_vec3(),
                    },
                }
            }
        };
        Ok(Arc::new(AbstractShape {
            abstraction: *self,
            geometry,
        }))
    }
}

/// The principal box of a point set: its centre, orthonormal axes and semi-axes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PrincipalBox {
    /// The centre of the box.
    pub centre: DVec3,
    /// Columns: the principal axes, by decreasing variance of the points; right-handed.
    pub axes: DMat3,
    /// Half the extent of the points along each axis, at least 10⁻³ of the largest.
    pub semi_axes: DVec3,
}

impl PrincipalBox {
    /// The axes are the eigenvectors of the points' covariance `Σ (p − m)(p − m)ᵀ / n` about
    /// their mean m (a symmetric eigen-decomposition); the box is the points' extent along
    /// them. A semi-axis below 10⁻³ of the largest (a flat model) is raised to it, so the
    /// ellipsoid's `1/a²` stays finite.
    pub fn fit(points: &[DVec3]) -> Result<Self, XToonError> {
        let bad = |reason: &str| Err(XToonError::Shape(reason.into()));
        if points.is_empty() {
            return bad("the model has no control points");
        }
        if points.iter().any(|p| !p.is_finite()) {
            return bad("the model has a control point that is not finite");
        }
        let n = points.len() as f64;
        let mean = points.iter().copied().sum::<DVec3>() / n;
        let mut covariance = Matrix3::<f64>::zeros();
        for p in points {
            let d = *p - mean;
            let d = nalgebra::Vector3::new(d.x, d.y, d.z);
            covariance += d * d.transpose() / n;
        }
        let eigen = SymmetricEigen::new(covariance);
        let mut order = [0, 1, 2];
        order.sort_by(|&a, &b| eigen.eigenvalues[b].total_cmp(&eigen.eigenvalues[a]));
        let column = |k: usize| {
            let c = eigen.eigenvectors.column(order[k]);
            DVec3::new(c[0], c[1], c[2]).normalize()
        };
        let (e0, e1) = (column(0), column(1));
        // The third axis completes a right-handed frame (it is ± the third eigenvector).
        let axes = DMat3::from_cols(e0, e1, e0.cross(e1));
        let (mut low, mut high) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
        for p in points {
            let x = axes.transpose() * (*p - mean);
            low = low.min(x);
            high = high.max(x);
        }
        let half = 0.5 * (high - low);
        let largest = half.max_element();
        if !(largest > 0.0 && largest.is_finite()) {
            return bad("the model's control points all coincide");
        }
        Ok(Self {
            centre: mean + axes * (0.5 * (low + high)),
            axes,
            semi_axes: half.max(DVec3::splat(1e-3 * largest)),
        })
    }
}

/// The abstracted shape of one model, built by [`Abstraction::build`].
#[derive(Clone, Debug, PartialEq)]
pub struct AbstractShape {
    abstraction: Abstraction,
    geometry: Geometry,
}

#[derive(Clone, Debug, PartialEq)]
enum Geometry {
    Sphere {
        centre: Vec3,
    },
    Ellipsoid {
        centre: Vec3,
        /// `A = R diag(1/a_i²) Rᵀ`, with R's columns the principal axes and `a_i` the semi-axes:
        /// the gradient of `(x − c)ᵀ A (x − c)` is `2 A (x − c)`.
        gradient: Mat3,
    },
    Cylinder {
        centre: Vec3,
        axis: Vec3,
    },
    Smoothed(SmoothedNormals),
}

impl AbstractShape {
    /// The abstraction this shape is of.
    #[must_use]
    pub fn abstraction(&self) -> Abstraction {
        self.abstraction
    }

    /// The unit normal of the abstracted shape at the surface point `point` of patch `patch`
    /// at `uv` (see [`Abstraction`] for each formula), or `None` where it has none (the centre
    /// of the sphere or ellipsoid, the axis of the cylinder).
    #[must_use]
    pub fn normal(&self, point: Vec3, patch: usize, uv: Vec2) -> Option<Vec3> {
        let mut direction = Lanes::default();
        self.directions(&PointRun::one(point, Vec3::ZERO, patch, uv), &mut direction);
        direction.get(0).try_normalize()
    }

    /// The abstracted shape's normal direction at each of `points` into `out`, not normalized
    /// (zero where it has none), in a loop over the points for the shape's kind.
    #[inline(always)]
    fn directions(&self, points: &PointRun, out: &mut Lanes) {
        let p = &points.position;
        let offsets = |centre: Vec3, out: &mut Lanes| {
            for k in 0..points.len {
                out.set(k, p.get(k) - centre);
            }
        };
        match &self.geometry {
            Geometry::Sphere { centre } => offsets(*centre, out),
            Geometry::Ellipsoid { centre, gradient } => {
                offsets(*centre, out);
                for k in 0..points.len {
                    out.set(k, *gradient * out.get(k));
                }
            }
            Geometry::Cylinder { centre, axis } => {
                offsets(*centre, out);
                for k in 0..points.len {
                    let d = out.get(k);
                    out.set(k, d - d.dot(*axis) * *axis);
                }
            }
            Geometry::Smoothed(normals) => normals.at_run(points, out),
        }
    }
}

/// Shape detail ready to shade with: the model's abstracted shape and a weight w > 0.
#[derive(Clone, Debug, PartialEq)]
pub struct PreparedShape {
    shape: Arc<AbstractShape>,
    weight: f32,
    highlight_frame: HighlightFrame,
}

impl PreparedShape {
    /// Which frame highlights use on this patch.
    #[must_use]
    pub fn highlight_frame(&self) -> HighlightFrame {
        self.highlight_frame
    }

    /// The shading normal `n' = normalize(n + w (n_a − n))` at a point with unit normal `n`.
    ///
    /// `n_a` is the abstracted shape's normal taken on the side of `n` (`n_a·n ≥ 0`), so the two
    /// never cancel and a two-sided surface shades alike from both sides. Where the shape has no
    /// normal, or the blend vanishes, `n` is returned.
    #[must_use]
    pub fn shading_normal(&self, n: Vec3, point: Vec3, patch: usize, uv: Vec2) -> Vec3 {
        let mut out = Lanes::default();
        self.shading_normals(&PointRun::one(point, n, patch, uv), &mut out);
        out.get(0)
    }

    /// [`shading_normal`](Self::shading_normal) at each of `points` into `out`, stage by stage
    /// in loops over the points: every abstracted direction a, every blend, and the blends
    /// normalized ([`Lanes::normalize`]).
    ///
    /// With `n_a = a/‖a‖`, the blend `(1 − w) n + w n_a` points along
    /// `(1 − w) ‖a‖ n + w a`, which needs no division: one normalization per point rather than
    /// two. Where a is zero or not finite the blend is not finite or zero, and the
    /// normalization's fallback returns n.
    #[inline(always)]
    pub(crate) fn shading_normals(&self, points: &PointRun, out: &mut Lanes) {
        let (n, normal) = (points.len, &points.normal);
        self.shape.directions(points, out);
        let w = self.weight;
        for k in 0..n {
            let (normal, a) = (normal.get(k), out.get(k));
            let a = if a.dot(normal) < 0.0 { -a } else { a };
            out.set(k, normal * ((1.0 - w) * a.length()) + a * w);
        }
        out.normalize(n, |k, blend| blend.try_normalize().unwrap_or(normal.get(k)));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn principal_box_of_a_stretched_point_set() {
        // Points on a box 2 × 6 × 1 (semi-axes 1, 3, 0.5), rotated 30° about z and moved.
        let (s, c) = 30f64.to_radians().sin_cos();
        let rotate = |p: DVec3| DVec3::new(c * p.x - s * p.y, s * p.x + c * p.y, p.z);
        let offset = DVec3::new(1.0, -2.0, 0.5);
        let mut points = Vec::new();
        for x in [-1.0, 1.0] {
            for y in [-3.0, -1.0, 1.0, 3.0] {
                for z in [-0.5, 0.5] {
                    points.push(offset + rotate(DVec3::new(x, y, z)));
                }
            }
        }
        let b = PrincipalBox::fit(&points).unwrap();
        assert!((b.centre - offset).length() < 1e-12);
        assert!(b.axes.x_axis.dot(rotate(DVec3::Y)).abs() > 1.0 - 1e-12);
        assert!(b.axes.y_axis.dot(rotate(DVec3::X)).abs() > 1.0 - 1e-12);
        assert!((b.semi_axes - DVec3::new(3.0, 1.0, 0.5)).length() < 1e-12);
        assert!((b.axes.determinant() - 1.0).abs() < 1e-12);
    }

    #[test]
    fn degenerate_point_sets_are_errors() {
        assert!(PrincipalBox::fit(&[]).is_err());
        assert!(PrincipalBox::fit(&[DVec3::ONE; 4]).is_err());
        assert!(PrincipalBox::fit(&[DVec3::ONE, DVec3::new(f64::NAN, 0.0, 0.0)]).is_err());
        // A flat set keeps a finite thickness.
        let flat = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::ONE.with_z(0.0)];
        let b = PrincipalBox::fit(&flat).unwrap();
        assert!(b.semi_axes.min_element() > 0.0);
    }

    #[test]
    fn cylinder_normals_are_radial_and_the_axis_falls_back() {
        let shape = AbstractShape {
            abstraction: Abstraction::Cylinder,
            geometry: Geometry::Cylinder {
                centre: Vec3::ZERO,
                axis: Vec3::Z,
            },
        };
        let n = shape
            .normal(Vec3::new(2.0, 0.0, 5.0), 0, Vec2::ZERO)
            .unwrap();
        assert!((n - Vec3::X).length() < 1e-6);
        assert_eq!(shape.normal(Vec3::new(0.0, 0.0, 3.0), 0, Vec2::ZERO), None);
        let prepared = PreparedShape {
            shape: Arc::new(shape),
            weight: 0.5,
            highlight_frame: HighlightFrame::Abstracted,
        };
        // On the axis the true normal stays; opposite normals do not cancel.
        assert_eq!(
            prepared.shading_normal(Vec3::Y, Vec3::new(0.0, 0.0, 1.0), 0, Vec2::ZERO),
            Vec3::Y
        );
        let n = prepared.shading_normal(Vec3::NEG_X, Vec3::new(1.0, 0.0, 0.0), 0, Vec2::ZERO);
        assert!((n - Vec3::NEG_X).length() < 1e-6);
    }
}
