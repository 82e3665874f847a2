//! A layer's frame: the tangent axes its operations act along at each surface point.

use glam::Vec3;
use serde::{Deserialize, Serialize};

use super::error::HighlightError;
use super::frame::TangentFrame;
use crate::param::{check, Range};

/// The tangent axes `(du', dv')` a layer's operations (translation, rotation, directional
/// scaling, split, squaring) act along at a point whose shading frame is `(du, dv, N)`.
///
/// - `Patch` (the default): the patch's own frame, `du' = du` along increasing u. Neighbouring
///   patches parameterized in different directions give the layer different axes, and a
///   highlight that spans them steps at the seam.
/// - `Along(axis: a)`: one direction field over every patch the layer is drawn on,
///   `du' = normalize(a − (a·N) N)`, `dv' = N × du'`, with the point's own N. It is as
///   continuous as N, so a layer keeps its shape across G1 seams whatever the patches'
///   parameterizations. Where `a` is (nearly) along N, `|a − (a·N) N| < ALONG_TOLERANCE` for the
///   unit `a`, the field has no direction and the point keeps the patch's own frame.
///
/// `a` is a direction in world coordinates as the layer is evaluated; it need not be unit.
///
/// RON: `frame: Patch` or `frame: Along(axis: (1.0, 0.0, 0.0))`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, bound(deserialize = "P: Deserialize<'de>"))]
pub enum LayerFrame<P = f32> {
    /// The patch's own frame: du along increasing u, dv = N × du.
    #[default]
    Patch,
    /// The field `du' = normalize(a − (a·N) N)`, `dv' = N × du'` of one direction `a`.
    Along {
        /// The direction `a` (x, y, z), in world coordinates; not zero.
        axis: [P; 3],
    },
}

/// Below this length of the unit axis's tangential part `|a − (a·N) N|` (the sine of the angle
/// between `a` and N, about 0.06°), [`LayerFrame::Along`] keeps the patch's own frame: the
/// field's direction is lost in rounding there (f32 puts an error of about 10⁻⁷ on it).
pub const ALONG_TOLERANCE: f32 = 1e-3;

impl<P> LayerFrame<P> {
    /// Whether this is the patch's own frame.
    #[must_use]
    pub fn is_patch(&self) -> bool {
        matches!(self, Self::Patch)
    }

    /// The same frame with every numeric parameter mapped through `f`: the axis's x, y, z.
    #[must_use]
    pub fn map<Q>(&self, mut f: impl FnMut(&P) -> Q) -> LayerFrame<Q> {
        match self {
            Self::Patch => LayerFrame::Patch,
            Self::Along { axis } => LayerFrame::Along {
                axis: [f(&axis[0]), f(&axis[1]), f(&axis[2])],
            },
        }
    }
}

impl LayerFrame<f32> {
    /// Checks that an axis is finite and has a direction (`a / |a|` exists in f32).
    pub fn validate(&self) -> Result<(), HighlightError> {
        self.prepare().map(|_| ())
    }

    /// Validates and precomputes the per-point form: the unit axis `a / |a|`.
    pub fn prepare(&self) -> Result<PreparedFrame, HighlightError> {
        match self {
            Self::Patch => Ok(PreparedFrame::Patch),
            Self::Along { axis } => {
                for c in axis {
                    check("frame axis component", *c, Range::Finite, "")?;
                }
                let [x, y, z] = *axis;
                Vec3::from_array(*axis)
                    .try_normalize()
                    .map(PreparedFrame::Along)
                    .ok_or(HighlightError::AxisWithoutDirection { x, y, z })
            }
        }
    }
}

/// A validated [`LayerFrame`], ready to give the layer's frame at many points.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum PreparedFrame {
    /// The patch's own frame.
    #[default]
    Patch,
    /// The field of this unit axis.
    Along(Vec3),
}

impl PreparedFrame {
    /// The layer's frame at a point whose shading frame is `patch`: `patch` itself, or for the
    /// unit axis `a`, `(du', N × du', N)` with `du' = (a − (a·N) N) / |a − (a·N) N|` — the
    /// patch's own frame where `|a − (a·N) N| < ALONG_TOLERANCE` ([`ALONG_TOLERANCE`]).
    #[inline]
    #[must_use]
    pub fn at(&self, patch: &TangentFrame) -> TangentFrame {
        match *self {
            Self::Patch => *patch,
            Self::Along(a) => {
                let n = patch.n;
                let tangential = a - a.dot(n) * n;
                let length_squared = tangential.length_squared();
                if length_squared < ALONG_TOLERANCE * ALONG_TOLERANCE {
                    return *patch;
                }
                let du = tangential * length_squared.sqrt().recip();
                TangentFrame::new(du, n.cross(du), n)
            }
        }
    }

    /// The world vector `h` in the layer's frame at a point whose shading frame is `patch`:
    /// `((h, du'), (h, dv'), (h, N))` of [`at`](Self::at). This is where every evaluation of a
    /// layer turns the initial highlight vector into the coordinates its operations act in.
    #[inline]
    #[must_use]
    pub fn local(&self, patch: &TangentFrame, h: Vec3) -> Vec3 {
        self.at(patch).to_local(h)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const FRAME: TangentFrame = TangentFrame::new(Vec3::X, Vec3::Y, Vec3::Z);

    /// A unit frame with normal `n` and du the unit tangent nearest `toward`.
    fn frame_with_normal(n: Vec3, toward: Vec3) -> TangentFrame {
        let n = n.normalize();
        let du = (toward - toward.dot(n) * n).normalize();
        TangentFrame::new(du, n.cross(du), n)
    }

    #[test]
    fn patch_is_the_shading_frame_bit_for_bit() {
        let f = frame_with_normal(Vec3::new(0.3, -0.5, 0.8), Vec3::new(0.2, 1.0, 0.1));
        let h = Vec3::new(0.1, 0.7, 0.7).normalize();
        let p = LayerFrame::<f32>::Patch.prepare().unwrap();
        assert_eq!(p.at(&f), f);
        let local = p.local(&f, h);
        assert_eq!(local.x.to_bits(), h.dot(f.du).to_bits());
        assert_eq!(local.y.to_bits(), h.dot(f.dv).to_bits());
        assert_eq!(local.z.to_bits(), h.dot(f.n).to_bits());
        assert_eq!(local, f.to_local(h));
    }

    #[test]
    fn along_takes_the_projected_axis_whatever_the_patch_frame() {
        let axis = Vec3::new(2.0, 0.5, -1.0);
        let p = LayerFrame::Along {
            axis: axis.to_array(),
        }
        .prepare()
        .unwrap();
        let n = Vec3::new(0.3, -0.5, 0.8).normalize();
        // Independently: the tangent plane's component of the axis, in f64.
        let (a, nn) = (axis.as_dvec3().normalize(), n.as_dvec3());
        let want_du = (a - a.dot(nn) * nn).normalize();
        let want_dv = nn.cross(want_du);
        // The same field for patch frames turned every way about N (u reversed, u and v
        // swapped, …).
        for toward in [Vec3::X, -Vec3::X, Vec3::Y, Vec3::new(-0.4, 0.9, 0.2)] {
            let f = frame_with_normal(n, toward);
            let l = p.at(&f);
            assert!(
                (l.du.as_dvec3() - want_du).length() < 1e-6,
                "{toward}: {}",
                l.du
            );
            assert!(
                (l.dv.as_dvec3() - want_dv).length() < 1e-6,
                "{toward}: {}",
                l.dv
            );
            assert_eq!(l.n, f.n);
            assert!((l.du.cross(l.dv) - l.n).length() < 1e-6);
            let h = Vec3::new(0.2, 0.3, 0.9).normalize();
            let local = p.local(&f, h).as_dvec3();
            let hd = h.as_dvec3();
            let want = glam::DVec3::new(hd.dot(want_du), hd.dot(want_dv), hd.dot(nn));
            assert!((local - want).length() < 1e-6, "{local} vs {want}");
        }
    }

    #[test]
    fn along_the_normal_keeps_the_patch_frame_and_stays_finite() {
        let p = LayerFrame::Along {
            axis: [0.0, 0.0, 3.0],
        }
        .prepare()
        .unwrap();
        // At the pole N = a exactly, and just inside the tolerance: the patch's frame.
        for n in [
            Vec3::Z,
            -Vec3::Z,
            Vec3::new(0.0, 0.5 * ALONG_TOLERANCE, 1.0),
        ] {
            let f = frame_with_normal(n, Vec3::X);
            let l = p.at(&f);
            assert_eq!(l, f);
            assert!(p.local(&f, Vec3::new(0.6, 0.0, 0.8)).is_finite());
        }
        // Just past it: the field, unit and finite.
        let f = frame_with_normal(Vec3::new(0.0, 2.0 * ALONG_TOLERANCE, 1.0), Vec3::X);
        let l = p.at(&f);
        assert!(l.du.is_finite() && (l.du.length() - 1.0).abs() < 1e-5);
        assert!(
            l.du.dot(Vec3::Y) < -0.99 || l.du.dot(Vec3::Y) > 0.99,
            "{}",
            l.du
        );
    }

    #[test]
    fn a_zero_or_unbounded_axis_is_refused_with_its_value() {
        let msg = LayerFrame::Along {
            axis: [0.0, 0.0, 0.0],
        }
        .validate()
        .unwrap_err()
        .to_string();
        assert!(msg.contains("frame axis is (0, 0, 0)"), "{msg}");
        assert!(LayerFrame::Along {
            axis: [f32::NAN, 1.0, 0.0]
        }
        .validate()
        .is_err());
        assert!(LayerFrame::Along {
            axis: [f32::MAX, f32::MAX, 0.0]
        }
        .validate()
        .is_err());
        assert!(LayerFrame::Along {
            axis: [1e-10, 0.0, 0.0]
        }
        .validate()
        .is_ok());
        assert!(LayerFrame::<f32>::Patch.validate().is_ok());
    }

    #[test]
    fn ron_reads_patch_by_default_and_refuses_unknown_fields() {
        let along: LayerFrame = ron::from_str("Along(axis: (1, 0, 0))").unwrap();
        assert_eq!(
            along,
            LayerFrame::Along {
                axis: [1.0, 0.0, 0.0]
            }
        );
        let patch: LayerFrame = ron::from_str("Patch").unwrap();
        assert!(patch.is_patch());
        assert!(ron::from_str::<LayerFrame>("Along(axis: (1, 0, 0), up: (0, 0, 1))").is_err());
        assert!(ron::from_str::<LayerFrame>("Along()").is_err());
        assert!(ron::from_str::<LayerFrame>("Along(axis: (1, 0))").is_err());
        assert_eq!(
            FRAME,
            LayerFrame::<f32>::Patch.prepare().unwrap().at(&FRAME)
        );
    }
}
