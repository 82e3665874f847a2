//! The four boundary edges of a patch's domain, and which of them collapse to a point (a
//! sphere's poles, the teapot's lid apex).

use std::fmt;

use glam::DVec3;

use super::NurbsSurface;

/// A boundary edge of a patch's parameter domain.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Edge {
    /// `u = u_min`, running along v.
    UMin,
    /// `u = u_max`.
    UMax,
    /// `v = v_min`, running along u.
    VMin,
    /// `v = v_max`.
    VMax,
}

impl Edge {
    /// The four edges.
    pub const ALL: [Edge; 4] = [Edge::UMin, Edge::UMax, Edge::VMin, Edge::VMax];
}

impl fmt::Display for Edge {
    /// `u=min`, `u=max`, `v=min` or `v=max`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Edge::UMin => "u=min",
            Edge::UMax => "u=max",
            Edge::VMin => "v=min",
            Edge::VMax => "v=max",
        })
    }
}

/// Points compared along an edge.
const SAMPLES: usize = 17;

/// An edge counts as collapsed when its points stay this close, relative to the size of the
/// control net.
const RELATIVE_TOLERANCE: f64 = 1e-9;

impl NurbsSurface {
    /// The edges along which the surface is one point: `‖S(edge(t)) − S(edge(0))‖ ≤ 10⁻⁹ · d`
    /// at 17 evenly spaced `t`, with `d` the diagonal of the control net's bounding box. Where
    /// an edge collapses the frame there is the limit from inside the patch.
    #[must_use]
    pub fn collapsed_edges(&self) -> Vec<Edge> {
        let (min, max) = self
            .control_points()
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p), hi.max(p))
            });
        let tolerance = RELATIVE_TOLERANCE * (max - min).length();
        let domain = self.domain();
        let at = |edge: Edge, t: f64| {
            let u = domain.u.0 + t * (domain.u.1 - domain.u.0);
            let v = domain.v.0 + t * (domain.v.1 - domain.v.0);
            match edge {
                Edge::UMin => self.point(domain.u.0, v),
                Edge::UMax => self.point(domain.u.1, v),
                Edge::VMin => self.point(u, domain.v.0),
                Edge::VMax => self.point(u, domain.v.1),
            }
        };
        Edge::ALL
            .into_iter()
            .filter(|&edge| {
                let first = at(edge, 0.0);
                (1..SAMPLES).all(|k| {
                    let t = k as f64 / (SAMPLES - 1) as f64;
                    at(edge, t).distance(first) <= tolerance
                })
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::shapes;

    #[test]
    fn a_sphere_collapses_at_its_poles_and_a_plane_nowhere() {
        let sphere = shapes::sphere(DVec3::new(1.0, 2.0, 3.0), 2.0).unwrap();
        assert_eq!(sphere.collapsed_edges(), vec![Edge::VMin, Edge::VMax]);
        assert!(shapes::plane(2.0, 1.0)
            .unwrap()
            .collapsed_edges()
            .is_empty());
        assert!(shapes::torus(1.0, 0.3)
            .unwrap()
            .collapsed_edges()
            .is_empty());
    }
}
