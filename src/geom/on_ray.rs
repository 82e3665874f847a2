//! The parameters of the surface point a ray passes through, found by Newton steps from a
//! nearby start.

use glam::DVec3;

use super::surface::{NurbsSurface, SurfaceDerivs};
use super::Frame;

/// The most Newton steps [`NurbsSurface::try_refine_on_ray`] takes; from a tessellated start
/// it converges in one to three, more where the ray grazes the surface.
pub const REFINE_STEPS: usize = 8;

/// The residual, relative to the distance along the ray, at which a point counts as on it:
/// 10⁻⁷ rad, far below any pixel.
const ON_RAY: f64 = 1e-7;

/// The most of its residual a probe's Newton step may keep far from the ray
/// ([`RaySearch::stall_beyond`]): near a point where the ray meets the surface at an angle each
/// step squares the residual, so a step that does not halve it most often starts where the ray
/// passes beside the surface.
const STALLED: f64 = 0.5;

/// Halvings of a Newton step that does not bring the point nearer the ray before giving up.
const HALVINGS: usize = 6;

/// Surface evaluations enough for every step [`NurbsSurface::try_refine_on_ray`] may take: the
/// start, and [`REFINE_STEPS`] steps of up to six halvings each.
pub const ALL_EVALUATIONS: u32 = (1 + REFINE_STEPS * (HALVINGS + 1)) as u32;

/// A ray to refine a start onto, and how many surface evaluations the search may spend.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RaySearch {
    /// The (u, v) to start from.
    pub start: (f64, f64),
    /// A point of the ray.
    pub origin: DVec3,
    /// The ray's direction (any length but zero).
    pub direction: DVec3,
    /// The most surface evaluations to spend, the start's included: [`ALL_EVALUATIONS`] for
    /// the full search; fewer to ask only whether the ray meets the surface close to the start,
    /// where a ray that passes beside it would spend the rest approaching its outline. Such a
    /// probe also stops when two steps in a row are held on the same side of the domain, or
    /// one is held where it stands: the ray passes beyond the patch's edge.
    pub evaluations: u32,
    /// A probe (fewer than [`ALL_EVALUATIONS`]) also ends at the first step that does not
    /// halve its distance from the ray and leaves it farther than this (in the ray's units;
    /// infinite: never). Where the ray grazes the surface (at an outline, about a pole) the
    /// steps that land on it may be slow, but they come near the ray, while those of a ray
    /// passing beside the surface stay about as far from it as it passes.
    pub stall_beyond: f64,
}

impl NurbsSurface {
    /// `(u, v)` near `start` whose surface point lies on the ray `origin + t direction`, by
    /// damped Newton steps; `None` where the steps cannot go on (the caller keeps its start).
    ///
    /// With `e1, e2` orthonormal and across the ray, the residual `f = ((S − o)·e1, (S − o)·e2)`
    /// has the Jacobian `J = [[Su·e1, Sv·e1], [Su·e2, Sv·e2]]`; each step solves `J Δ = f` and
    /// moves `(u, v) −= t Δ`, clamped to the domain, with `t = 1, ½, ¼, …` the first that makes
    /// `|f|` smaller (up to 6 halvings), and no step longer than a tenth of the domain: where
    /// the ray grazes the surface, J is nearly singular and the full step overshoots. Stops once
    /// `|f| ≤ 10⁻⁷ |S − o|`, and after [`REFINE_STEPS`] steps, or when no halving helps (the ray
    /// passes beside the surface), returns the nearest point it found. `None` when the
    /// direction is zero or J is singular or not finite. Degrees 1 to 3 take their derivatives
    /// from the fixed-degree evaluation, the same numbers.
    #[must_use]
    pub fn try_refine_on_ray(
        &self,
        start: (f64, f64),
        origin: DVec3,
        direction: DVec3,
    ) -> Option<(f64, f64)> {
        let search = RaySearch {
            start,
            origin,
            direction,
            evaluations: ALL_EVALUATIONS,
            stall_beyond: f64::INFINITY,
        };
        self.with_first_derivs(|derivs| newton_on_ray(self, &search, derivs).1)
    }

    /// Frames at the points where rays meet the surface: for each `k`, [`try_refine_on_ray`]
    /// from `searches[k].start` along its ray, within its evaluations, with `params[k]` set to
    /// the (u, v) found (or the start where there is none) and `frames[k]` to the frame there,
    /// as [`frames`](Self::frames) gives it.
    ///
    /// The frame comes from the derivatives of the last Newton step, so a refined frame costs
    /// the steps alone; degrees 1 to 3 take their derivatives from the fixed-degree evaluation.
    ///
    /// [`try_refine_on_ray`]: Self::try_refine_on_ray
    ///
    /// # Panics
    /// If the slices differ in length.
    pub fn frames_on_rays(
        &self,
        searches: &[RaySearch],
        params: &mut [(f64, f64)],
        frames: &mut [Frame],
    ) {
        assert!(
            searches.len() == params.len() && params.len() == frames.len(),
            "one parameter and frame per search"
        );
        let domain = self.domain();
        let each = |derivs: &mut dyn FnMut(f64, f64) -> SurfaceDerivs| {
            for ((search, param), frame) in searches
                .iter()
                .zip(params.iter_mut())
                .zip(frames.iter_mut())
            {
                let (d, refined) = newton_on_ray(self, search, &mut *derivs);
                let (u, v) = refined.unwrap_or(search.start);
                let d = if refined.is_some() { d } else { derivs(u, v) };
                *param = (u, v);
                *frame = Frame::from_derivs(&d, u, v, &domain)
                    .filter(|f| !f.degenerate)
                    .unwrap_or_else(|| self.frame_general(u, v));
            }
        };
        self.with_first_derivs(each);
    }

    /// `run` given the point and first derivatives at any (u, v): from the fixed-degree
    /// evaluation for degrees 1 to 3, else from [`derivs`](Self::derivs).
    fn with_first_derivs<R>(
        &self,
        run: impl FnOnce(&mut dyn FnMut(f64, f64) -> SurfaceDerivs) -> R,
    ) -> R {
        match self.fixed_derivs() {
            Some(mut fixed) => run(&mut |u, v| fixed.at(self, u, v)),
            None => run(&mut |u, v| self.derivs(u, v, 1)),
        }
    }
}

/// [`NurbsSurface::try_refine_on_ray`] with first derivatives from `derivs`, within the
/// search's evaluations (at least the start's): the (u, v) found, or `None`, and the
/// derivatives at the (u, v) returned (at the start when `None`, or when the direction is zero,
/// nothing evaluated: default derivatives).
fn newton_on_ray(
    surface: &NurbsSurface,
    search: &RaySearch,
    mut derivs: impl FnMut(f64, f64) -> SurfaceDerivs,
) -> (SurfaceDerivs, Option<(f64, f64)>) {
    let RaySearch {
        start,
        origin,
        direction,
        ..
    } = *search;
    let mut left = search.evaluations.saturating_sub(1);
    let domain = surface.domain();
    let Some(d) = direction.try_normalize() else {
        return (SurfaceDerivs::default(), None);
    };
    let (e1, e2) = d.any_orthonormal_pair();
    let reach = 0.1 * (domain.u.1 - domain.u.0).max(domain.v.1 - domain.v.0);
    let residual = |point: DVec3| {
        let r = point - origin;
        let (f1, f2) = (r.dot(e1), r.dot(e2));
        (f1, f2, (f1 * f1 + f2 * f2).sqrt(), r.length())
    };
    let (mut u, mut v) = start;
    let mut s = derivs(u, v);
    let (mut f1, mut f2, mut error, mut distance) = residual(s.point);
    // A probe asks only whether the ray meets the surface near the start: two steps in a row
    // held on the same side of the domain they would have left, or a step the domain holds
    // where it is, say that the ray passes beyond it; a step that does not halve the residual
    // and leaves it beyond the search's `stall_beyond` ([`STALLED`]), that it passes beside
    // it or meets it far from the start.
    let probe = search.evaluations < ALL_EVALUATIONS;
    let stall_beyond = if probe {
        search.stall_beyond
    } else {
        f64::INFINITY
    };
    let mut pressed = 0u8;
    'steps: for _ in 0..REFINE_STEPS {
        if error <= ON_RAY * distance {
            break;
        }
        let (a, b, c, e) = (s.su.dot(e1), s.sv.dot(e1), s.su.dot(e2), s.sv.dot(e2));
        let det = a * e - b * c;
        if det.abs() <= 1e-300 || !det.is_finite() {
            return (s, None);
        }
        let (step_u, step_v) = ((e * f1 - b * f2) / det, (a * f2 - c * f1) / det);
        let length = step_u.abs() + step_v.abs();
        if !length.is_finite() {
            return (s, None);
        }
        let mut t = (reach / length).min(1.0);
        let mut better = None;
        for _ in 0..=HALVINGS {
            if left == 0 {
                break;
            }
            left -= 1;
            let (ru, rv) = (u - t * step_u, v - t * step_v);
            let nu = ru.clamp(domain.u.0, domain.u.1);
            let nv = rv.clamp(domain.v.0, domain.v.1);
            if probe && (nu, nv) == (u, v) {
                break 'steps;
            }
            let ns = derivs(nu, nv);
            let (g1, g2, g_error, g_distance) = residual(ns.point);
            // A probe's step that does not halve the residual starts outside the reach of
            // any point where the ray meets the surface: it ends at the nearer of the two.
            if g_error > STALLED * error && g_error > stall_beyond {
                if g_error < error {
                    (u, v, s) = (nu, nv, ns);
                }
                break 'steps;
            }
            if g_error < error {
                let against = u8::from(ru < nu)
                    | u8::from(ru > nu) << 1
                    | u8::from(rv < nv) << 2
                    | u8::from(rv > nv) << 3;
                better = Some((nu, nv, ns, (g1, g2, g_error, g_distance), against));
                break;
            }
            t *= 0.5;
        }
        let Some((nu, nv, ns, g, against)) = better else {
            break;
        };
        (u, v, s) = (nu, nv, ns);
        (f1, f2, error, distance) = g;
        if probe && against != 0 && against == pressed {
            break;
        }
        pressed = against;
    }
    (s, Some((u, v)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refinement_puts_the_surface_point_on_the_ray() {
        let sphere = crate::geom::shapes::sphere(DVec3::ZERO, 1.0).unwrap();
        let target = sphere.point(0.3, 0.6);
        let origin = DVec3::new(0.2, -4.0, 0.7);
        let (u, v) = sphere
            .try_refine_on_ray((0.31, 0.59), origin, target - origin)
            .unwrap();
        // Stopped once the point is within 10⁻⁷ of the distance from the ray.
        let p = sphere.point(u, v);
        let off = (p - origin).reject_from(target - origin).length();
        assert!(off <= 1e-7 * (p - origin).length(), "{off}");
        assert!(
            (u - 0.3).abs() < 1e-6 && (v - 0.6).abs() < 1e-6,
            "({u}, {v})"
        );
        // A ray that misses the surface nearby: the nearest point found is off it. No ray at all.
        let start = (0.31, 0.59);
        let (u, v) = sphere.try_refine_on_ray(start, origin, DVec3::Z).unwrap();
        let off = (sphere.point(u, v) - origin).reject_from(DVec3::Z).length();
        assert!(off > 0.1, "{off}");
        assert_eq!(sphere.try_refine_on_ray(start, origin, DVec3::ZERO), None);
    }

    #[test]
    fn frames_on_rays_are_the_frames_at_the_refined_parameters() {
        let sphere = crate::geom::shapes::sphere(DVec3::new(0.1, 0.2, -0.3), 1.3).unwrap();
        let origin = DVec3::new(0.4, -6.0, 0.9);
        let targets = [(0.3, 0.6), (0.05, 0.5), (0.7, 0.92), (0.5, 0.2)];
        let starts: Vec<(f64, f64)> = targets
            .iter()
            .map(|&(u, v)| (u + 0.01, v - 0.008))
            .collect();
        let searches: Vec<RaySearch> = targets
            .iter()
            .zip(&starts)
            .map(|(&(u, v), &start)| RaySearch {
                start,
                origin,
                direction: sphere.point(u, v) - origin,
                evaluations: ALL_EVALUATIONS,
                stall_beyond: f64::INFINITY,
            })
            .collect();
        let mut params = vec![(0.0, 0.0); 4];
        let mut frames = vec![sphere.frame(0.0, 0.0); 4];
        sphere.frames_on_rays(&searches, &mut params, &mut frames);
        for k in 0..4 {
            let s = searches[k];
            let alone = sphere.try_refine_on_ray(s.start, s.origin, s.direction);
            assert_eq!(Some(params[k]), alone, "ray {k}");
            let direct = sphere.frame(params[k].0, params[k].1);
            assert!((frames[k].point - direct.point).length() < 1e-12, "ray {k}");
            assert!(
                (frames[k].normal - direct.normal).length() < 1e-12,
                "ray {k}"
            );
            assert!((frames[k].du - direct.du).length() < 1e-12, "ray {k}");
        }
    }

    #[test]
    fn a_search_spends_no_more_evaluations_than_it_is_given() {
        let sphere = crate::geom::shapes::sphere(DVec3::ZERO, 1.0).unwrap();
        let origin = DVec3::new(0.2, -4.0, 0.7);
        // A ray that passes beside the sphere: the full search spends many evaluations on it.
        let search = |evaluations| RaySearch {
            start: (0.31, 0.59),
            origin,
            direction: DVec3::Z,
            evaluations,
            stall_beyond: f64::INFINITY,
        };
        let count = |evaluations| {
            let mut spent = 0;
            let (_, found) = newton_on_ray(&sphere, &search(evaluations), |u, v| {
                spent += 1;
                sphere.derivs(u, v, 1)
            });
            (spent, found.is_some())
        };
        let (all, _) = count(ALL_EVALUATIONS);
        assert!(all > 8, "the full search took only {all} evaluations");
        for budget in [1, 2, 5, 8] {
            assert_eq!(count(budget), (budget, true), "budget {budget}");
        }
        // A hit close to the start is found within a few.
        let target = sphere.point(0.3, 0.6);
        let hit = RaySearch {
            direction: target - origin,
            evaluations: 4,
            ..search(0)
        };
        let (_, found) = newton_on_ray(&sphere, &hit, |u, v| sphere.derivs(u, v, 1));
        let (u, v) = found.unwrap();
        assert!(
            (u - 0.3).abs() < 1e-6 && (v - 0.6).abs() < 1e-6,
            "({u}, {v})"
        );
    }

    #[test]
    fn a_probe_beside_the_surface_stops_at_its_first_stalled_step_far_from_the_ray() {
        // A ray passing 0.1 beside the unit sphere, probed from where a ray through the
        // outline would start: no step halves the distance, which stays about 0.1.
        let sphere = crate::geom::shapes::sphere(DVec3::ZERO, 1.0).unwrap();
        let origin = DVec3::new(-1.1, -50.0, 0.05);
        let start = (0.5, 0.52);
        let probe = |direction: DVec3, stall_beyond| RaySearch {
            start,
            origin,
            direction,
            evaluations: 5,
            stall_beyond,
        };
        let count = |search: RaySearch| {
            let mut spent = 0;
            let (d, _) = newton_on_ray(&sphere, &search, |u, v| {
                spent += 1;
                sphere.derivs(u, v, 1)
            });
            (spent, d.point)
        };
        let (patient, _) = count(probe(DVec3::Y, f64::INFINITY));
        assert_eq!(
            patient, 5,
            "without a stall distance the probe spends its budget"
        );
        let (quick, point) = count(probe(DVec3::Y, 0.01));
        assert_eq!(quick, 2, "the start and one stalled step");
        let off = (point - origin).reject_from(DVec3::Y).length();
        assert!(off > 0.05, "{off}");
        // Stalled within the distance allowed, the probe goes on.
        let (near, _) = count(probe(DVec3::Y, 0.5));
        assert_eq!(near, 5);
        // A ray that meets the sphere head-on near the start is found as before.
        let target = sphere.point(0.52, 0.5);
        let hit = RaySearch {
            origin: target * 5.0,
            direction: -target,
            ..probe(DVec3::Y, 0.01)
        };
        let (_, point) = count(hit);
        assert!((point - target).length() < 1e-6, "{point}");
    }

    #[test]
    fn a_probe_past_the_domain_stops_once_two_steps_end_on_its_edge() {
        // A ray that meets the plane's extension beyond u's upper end: each step heads past it
        // and is held on the edge. A probe gives up after two such steps; the full search goes
        // on to its end (and finds no nearer point either way); a ray inside is unaffected.
        let plane = crate::geom::shapes::plane(2.0, 2.0).unwrap();
        let domain = plane.domain();
        let at = |u: f64, v: f64| {
            let (u0, u1) = domain.u;
            let (v0, v1) = domain.v;
            plane.point(u0 + u * (u1 - u0), v0 + v * (v1 - v0))
        };
        let inside = at(0.9, 0.5);
        let beyond = inside + (at(1.0, 0.5) - at(0.9, 0.5)) * 3.0;
        let origin = DVec3::new(0.1, 0.2, 4.0);
        let search = |target: DVec3, evaluations| RaySearch {
            start: (
                domain.u.0 + 0.8 * (domain.u.1 - domain.u.0),
                domain.v.0 + 0.5 * (domain.v.1 - domain.v.0),
            ),
            origin,
            direction: target - origin,
            evaluations,
            stall_beyond: f64::INFINITY,
        };
        let count = |search: RaySearch| {
            let mut spent = 0;
            let (d, found) = newton_on_ray(&plane, &search, |u, v| {
                spent += 1;
                plane.derivs(u, v, 1)
            });
            (spent, found, d.point)
        };
        let (probe, _, point) = count(search(beyond, 5));
        assert_eq!(probe, 3, "start and two steps held on the edge");
        let off = (point - origin).reject_from(beyond - origin).length();
        assert!(off > 0.1, "{off}");
        let (full, _, _) = count(search(beyond, ALL_EVALUATIONS));
        assert!(full > 3, "{full}");
        let (_, found, point) = count(search(inside, 5));
        assert!(found.is_some() && (point - inside).length() < 1e-9);
    }

    #[test]
    fn a_grazing_ray_is_met_from_a_chord_of_the_silhouette() {
        // A unit sphere seen from far along −y; the ray passes 0.995 from the centre, crossing
        // the surface where the normal is 84° from the line of sight (away from the seam at +x).
        let sphere = crate::geom::shapes::sphere(DVec3::ZERO, 1.0).unwrap();
        let origin = DVec3::new(-0.995, -50.0, 0.0);
        let direction = DVec3::Y;
        // Start from the middle of a chord between two points of the silhouette circle's
        // neighbourhood: the (u, v) halfway between the front crossing and the limb.
        let front = DVec3::new(-0.995, -(1.0f64 - 0.995 * 0.995).sqrt(), 0.0);
        let limb = DVec3::new(-1.0, 0.0, 0.0);
        let near = |p: DVec3| {
            let mut best = (f64::INFINITY, (0.0, 0.0));
            for i in 0..=400 {
                for j in 0..=400 {
                    let uv = (f64::from(i) / 400.0, f64::from(j) / 400.0);
                    let d = (sphere.point(uv.0, uv.1) - p).length();
                    if d < best.0 {
                        best = (d, uv);
                    }
                }
            }
            best.1
        };
        let (a, b) = (near(front), near(limb));
        let start = ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
        let (u, v) = sphere.try_refine_on_ray(start, origin, direction).unwrap();
        let p = sphere.point(u, v);
        let off = (p - origin).reject_from(direction).length();
        assert!(off <= 1e-7 * (p - origin).length(), "{off} at {p}");
        assert!((p - front).length() < 1e-4, "{p}: not the near crossing");
    }
}
