//! Detail maps of X-Toon (Barla et al. 2006, §3.1–3.2): the detail D ∈ [0, 1] of a surface
//! point from its depth or its orientation to the viewer and the light.

use glam::{Vec2, Vec3};
use serde::Deserialize;

use super::error::XToonError;
use super::point_run::PointRun;
use crate::math::{Exponent, Lanes};
use crate::param::{check, Range};

/// Where the detail D of a point comes from. Every number is a parameter of type `P` (a number,
/// or an animation track resolved to one per frame).
///
/// RON: `Depth(z_min: 4.0, r: 3.0)`, `DepthOfField(focus: (0.0, 0.0, 1.0), z_min: 0.5, r: 4.0)`,
/// `NearSilhouette(r: 2.0)`, `Highlight(s: 20.0)`.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum DetailMap<P = f32> {
    /// Level of abstraction and aerial perspective. Paper:
    /// `D = 1 − log(z / z_min) / log(z_max / z_min) = 1 − log_r(z / z_min)` with `z_max = r z_min`,
    /// z the distance from the eye along the focal axis.
    ///
    /// D = 1 up to `z_min`, 0 from `r z_min` on; a point at or behind the eye (`z ≤ 0`, which
    /// the formula cannot take) gets the near value 1.
    Depth {
        /// z_min > 0: where detail starts to fall.
        z_min: P,
        /// r > 1: detail reaches 0 at `r z_min`.
        r: P,
    },
    /// Depth of field around a focus point c, on the Euclidean distance z from the eye. Paper,
    /// with `z_c = ‖c − eye‖`, `z±_min = z_c ± z_min`, `z±_max = z_c ± r z_min`:
    /// `D = 1 − log(z / z−_min) / log(z−_max / z−_min)` for `z < z_c`,
    /// `D = log(z / z+_max) / log(z+_min / z+_max)` for `z > z_c`.
    ///
    /// D = 1 in the focus band `[z−_min, z+_min]` and falls to 0 at `z±_max`, continuously on
    /// both sides. Barla, Thollot & Markosian 2006 assume `z−_max > 0`; where the eye comes nearer to the focus than
    /// `r z_min`, the near ramp ends at `max(z_c − r z_min, z−_min / r)` instead (the two agree
    /// where they meet), and where the eye is inside the band (`z−_min ≤ 0`) everything in
    /// front of the focus is in focus.
    DepthOfField {
        /// The focus point c (world coordinates).
        focus: [P; 3],
        /// z_min > 0: half the depth of the focus band.
        z_min: P,
        /// r > 1: detail reaches 0 at `z_c ± r z_min`.
        r: P,
    },
    /// Near-silhouette. Paper: `D = |n·v|^r`: 1 facing the camera, 0 at the silhouette.
    NearSilhouette {
        /// r ≥ 0: how fast detail falls toward the silhouette (0 keeps D = 1).
        r: P,
    },
    /// Highlight. Paper (Phong): `D = |v·r|^s` with `r = 2 (n·l) n − l` the reflected light.
    ///
    /// As in Barla, Thollot & Markosian 2006 the absolute value also lights the mirror spot where `r = −v`; it lies
    /// where `n·l = −n·v < 0`, in the dark tones, so a texture whose dark tones do not change
    /// down the detail axis does not show it.
    Highlight {
        /// s ≥ 1, the shininess: larger is a tighter spot.
        s: P,
    },
}

impl<P> DetailMap<P> {
    /// The same map with every numeric parameter mapped through `f`, in declaration order.
    #[must_use]
    pub fn map<Q>(&self, mut f: impl FnMut(&P) -> Q) -> DetailMap<Q> {
        match self {
            DetailMap::Depth { z_min, r } => DetailMap::Depth {
                z_min: f(z_min),
                r: f(r),
            },
            DetailMap::DepthOfField { focus, z_min, r } => DetailMap::DepthOfField {
                focus: [f(&focus[0]), f(&focus[1]), f(&focus[2])],
                z_min: f(z_min),
                r: f(r),
            },
            DetailMap::NearSilhouette { r } => DetailMap::NearSilhouette { r: f(r) },
            DetailMap::Highlight { s } => DetailMap::Highlight { s: f(s) },
        }
    }
}

const Z_MIN_HINT: &str =
    "; detail starts to fall at z_min, so it must be a distance in front of the eye";
const R_HINT: &str = "; detail reaches 0 at r·z_min, beyond z_min";

impl DetailMap<f32> {
    /// Checks `z_min > 0`, `r > 1` (depth, depth of field), a finite focus, `r ≥ 0`
    /// (near-silhouette) and `s ≥ 1` (highlight).
    pub fn validate(&self) -> Result<(), XToonError> {
        let checked = match *self {
            DetailMap::Depth { z_min, r } => {
                check("depth z_min", z_min, Range::Positive, Z_MIN_HINT)?;
                check("depth r", r, Range::AboveOne, R_HINT)
            }
            DetailMap::DepthOfField { focus, z_min, r } => {
                for c in focus {
                    check("depth of field focus coordinate", c, Range::Finite, "")?;
                }
                check("depth of field z_min", z_min, Range::Positive, Z_MIN_HINT)?;
                check("depth of field r", r, Range::AboveOne, R_HINT)
            }
            DetailMap::NearSilhouette { r } => check(
                "near-silhouette r",
                r,
                Range::NonNegative,
                "; 0 keeps full detail, larger values abstract more toward the silhouette",
            ),
            DetailMap::Highlight { s } => check(
                "highlight s",
                s,
                Range::AtLeastOne,
                "; the shininess: 1 is a broad spot, larger values tighter",
            ),
        };
        Ok(checked?)
    }

    /// Validates and precomputes the per-point form; `invert` maps D to `1 − D`.
    pub fn prepare(&self, invert: bool) -> Result<PreparedDetail, XToonError> {
        self.validate()?;
        let map = match *self {
            DetailMap::Depth { z_min, r } => Prepared::Depth {
                z_min,
                z_max: r * z_min,
                ln_z_min: z_min.ln(),
                inverse_ln_r: r.ln().recip(),
            },
            DetailMap::DepthOfField { focus, z_min, r } => Prepared::DepthOfField {
                focus: Vec3::from_array(focus),
                z_min,
                r,
            },
            DetailMap::NearSilhouette { r } => Prepared::NearSilhouette {
                r: Exponent::new(r),
            },
            DetailMap::Highlight { s } => Prepared::Highlight {
                s: Exponent::new(s),
            },
        };
        Ok(PreparedDetail { map, invert })
    }
}

/// A validated detail map, to be placed in a view ([`PreparedDetail::in_view`]) once per frame.
#[derive(Clone, Debug, PartialEq)]
pub struct PreparedDetail {
    map: Prepared,
    invert: bool,
}

#[derive(Clone, Debug, PartialEq)]
enum Prepared {
    Depth {
        z_min: f32,
        z_max: f32,
        ln_z_min: f32,
        inverse_ln_r: f32,
    },
    DepthOfField {
        focus: Vec3,
        z_min: f32,
        r: f32,
    },
    NearSilhouette {
        r: Exponent,
    },
    Highlight {
        s: Exponent,
    },
}

/// A detail map seen from one eye: what [`ViewDetail::value`] needs per point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ViewDetail {
    map: InView,
    invert: bool,
}

/// `D = (ln z − ln_end) · inverse` on one side of a logarithmic ramp.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Ramp {
    ln_end: f32,
    inverse: f32,
}

impl Ramp {
    /// The ramp with D = 1 at `full` and D = 0 at `end` (both > 0, distinct):
    /// `D = log(z / end) / log(full / end)`.
    fn new(full: f32, end: f32) -> Self {
        Self {
            ln_end: end.ln(),
            inverse: (full.ln() - end.ln()).recip(),
        }
    }

    #[inline]
    fn at(self, z: f32) -> f32 {
        (z.ln() - self.ln_end) * self.inverse
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum InView {
    /// D = 1 up to `z_min` and 0 from `z_max = r·z_min` on.
    Depth {
        eye: Vec3,
        forward: Vec3,
        z_min: f32,
        z_max: f32,
        ln_z_min: f32,
        inverse_ln_r: f32,
    },
    DepthOfField {
        eye: Vec3,
        z_c: f32,
        /// None: the eye is inside the focus band, everything nearer than the focus is in focus.
        near: Option<Ramp>,
        far: Ramp,
    },
    NearSilhouette {
        r: Exponent,
    },
    Highlight {
        s: Exponent,
    },
}

impl PreparedDetail {
    /// The map seen from `eye` looking along the unit `forward` (the focal axis).
    #[must_use]
    pub fn in_view(&self, eye: Vec3, forward: Vec3) -> ViewDetail {
        let map = match self.map {
            Prepared::Depth {
                z_min,
                z_max,
                ln_z_min,
                inverse_ln_r,
            } => InView::Depth {
                eye,
                forward,
                z_min,
                z_max,
                ln_z_min,
                inverse_ln_r,
            },
            Prepared::DepthOfField { focus, z_min, r } => {
                let z_c = focus.distance(eye);
                let near_full = z_c - z_min;
                let near = (near_full > 0.0)
                    .then(|| Ramp::new(near_full, (z_c - r * z_min).max(near_full / r)));
                InView::DepthOfField {
                    eye,
                    z_c,
                    near,
                    far: Ramp::new(z_c + z_min, z_c + r * z_min),
                }
            }
            Prepared::NearSilhouette { r } => InView::NearSilhouette { r },
            Prepared::Highlight { s } => InView::Highlight { s },
        };
        ViewDetail {
            map,
            invert: self.invert,
        }
    }
}

impl ViewDetail {
    /// Whether [`value`](Self::value) reads its `view` vector (the orientation maps do, the
    /// depth maps do not).
    #[inline]
    #[must_use]
    pub fn uses_view(&self) -> bool {
        matches!(
            self.map,
            InView::NearSilhouette { .. } | InView::Highlight { .. }
        )
    }

    /// The detail D ∈ [0, 1] at `point` (see [`DetailMap`] for each formula), with `view` and
    /// `light` the unit vectors from the point toward the eye and the light, `normal` the
    /// surface's unit normal (near-silhouette) and `highlight_normal` the unit normal the
    /// highlight map reflects the light about. Clamped to [0, 1] (NaN gives 0), then `1 − D`
    /// when inverted.
    #[must_use]
    pub fn value(
        &self,
        point: Vec3,
        view: Vec3,
        light: Vec3,
        normal: Vec3,
        highlight_normal: Vec3,
    ) -> f32 {
        let mut d = [0.0];
        self.values(
            &PointRun::one(point, normal, 0, Vec2::ZERO),
            &Lanes::first(view),
            &Lanes::first(light),
            &Lanes::first(highlight_normal),
            &mut d,
        );
        d[0]
    }

    /// [`value`](Self::value) at each of `points` into `out[k]`, seen along `view[k]`, lit from
    /// `light[k]` and reflecting about `highlight_normal[k]` (`view` read only when the map
    /// [uses it](Self::uses_view)): the map's formula in a loop over the points, then the
    /// clamp and inversion in another.
    ///
    /// # Panics
    /// If `out` is not `points.len` long.
    #[inline(always)]
    pub fn values(
        &self,
        points: &PointRun,
        view: &Lanes,
        light: &Lanes,
        highlight_normal: &Lanes,
        out: &mut [f32],
    ) {
        let n = points.len;
        assert_eq!(out.len(), n, "one value per point");
        let p = &points.position;
        match self.map {
            InView::Depth {
                eye,
                forward,
                z_min,
                z_max,
                ln_z_min,
                inverse_ln_r,
            } => {
                for (k, d) in out.iter_mut().enumerate() {
                    *d = (p.get(k) - eye).dot(forward);
                }
                // The logarithm only inside the band where D falls from 1 to 0 (NaN gives 1).
                for d in out.iter_mut() {
                    let z = *d;
                    *d = if z >= z_max {
                        0.0
                    } else if z > z_min {
                        1.0 - (z.ln() - ln_z_min) * inverse_ln_r
                    } else {
                        1.0
                    };
                }
            }
            InView::DepthOfField {
                eye,
                z_c,
                near,
                far,
            } => {
                for (k, d) in out.iter_mut().enumerate() {
                    *d = p.get(k).distance(eye);
                }
                for d in out.iter_mut() {
                    let z = *d;
                    *d = if z > z_c {
                        far.at(z)
                    } else {
                        near.map_or(1.0, |ramp| ramp.at(z))
                    };
                }
            }
            InView::NearSilhouette { r } => {
                for (k, d) in out.iter_mut().enumerate() {
                    *d = points.normal.get(k).dot(view.get(k)).abs();
                }
                r.pow_each(out);
            }
            InView::Highlight { s } => {
                for (k, d) in out.iter_mut().enumerate() {
                    let (h, l) = (highlight_normal.get(k), light.get(k));
                    let reflected = 2.0 * h.dot(l) * h - l;
                    *d = view.get(k).dot(reflected).abs();
                }
                s.pow_each(out);
            }
        }
        for d in out.iter_mut() {
            let clamped = clamp_unit(*d);
            *d = if self.invert { 1.0 - clamped } else { clamped };
        }
    }
}

/// `x` clamped to [0, 1]; NaN gives 0.
#[inline]
fn clamp_unit(x: f32) -> f32 {
    if x >= 1.0 {
        1.0
    } else if x > 0.0 {
        x
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn view(map: DetailMap) -> ViewDetail {
        map.prepare(false)
            .unwrap()
            .in_view(Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0))
    }

    /// D at distance z straight ahead.
    fn at(v: &ViewDetail, z: f32) -> f32 {
        v.value(Vec3::new(0.0, z, 0.0), Vec3::Z, Vec3::Z, Vec3::Z, Vec3::Z)
    }

    #[test]
    fn clamp_unit_takes_nan_to_zero() {
        assert_eq!(clamp_unit(f32::NAN), 0.0);
        assert_eq!(clamp_unit(-1.0), 0.0);
        assert_eq!(clamp_unit(0.25), 0.25);
        assert_eq!(clamp_unit(f32::INFINITY), 1.0);
    }

    #[test]
    fn near_ramp_of_depth_of_field_is_guarded_when_the_eye_comes_close() {
        // z_c = 3, z_min = 1, r = 4: z−_min = 2, and z_c − r z_min = −1 < 0, so the ramp ends
        // at z−_min / r = 0.5.
        let v = view(DetailMap::DepthOfField {
            focus: [0.0, 3.0, 0.0],
            z_min: 1.0,
            r: 4.0,
        });
        assert_eq!(at(&v, 2.0), 1.0);
        assert!(at(&v, 0.5).abs() < 1e-6);
        assert!((at(&v, 1.0) - 0.5).abs() < 1e-6);
        assert_eq!(at(&v, 0.0), 0.0);
        // The eye inside the band: all in focus up to the focus point.
        let inside = view(DetailMap::DepthOfField {
            focus: [0.0, 0.5, 0.0],
            z_min: 1.0,
            r: 4.0,
        });
        assert_eq!(at(&inside, 0.0), 1.0);
        assert_eq!(at(&inside, 0.4), 1.0);
    }
}
