//! Frames stay finite and orthonormal on hard surfaces: collapsed edges and corners, coincident
//! control points, extreme weights, models far from the origin.

use glam::DVec3;
use glint::geom::{Frame, NurbsSurface};
use proptest::prelude::*;

/// A rational bicubic patch (4 × 4 net) with the chosen edges collapsed to single points.
fn patch(
    net: Vec<[f64; 3]>,
    weights: Vec<f64>,
    collapse: [bool; 4],
    offset: [f64; 3],
) -> NurbsSurface {
    let offset = DVec3::from(offset);
    let mut points: Vec<Vec<DVec3>> = (0..4)
        .map(|i| {
            (0..4)
                .map(|j| offset + DVec3::new(i as f64, j as f64, 0.0) + DVec3::from(net[i * 4 + j]))
                .collect()
        })
        .collect();
    // Edges: v = 0 (row j = 0), u = 1 (i = 3), v = 1 (j = 3), u = 0 (i = 0). Each collapses to
    // its second control point as it was before any edge moved; collapsed edges that meet at a
    // corner collapse together, to the apex of the first of them, so that the corner is a point
    // where both first derivatives vanish.
    let cells = |edge: usize| -> [(usize, usize); 4] {
        std::array::from_fn(|k| match edge {
            0 => (k, 0),
            1 => (3, k),
            2 => (k, 3),
            _ => (0, k),
        })
    };
    let apexes: [DVec3; 4] = std::array::from_fn(|edge| {
        let (i, j) = cells(edge)[1];
        points[i][j]
    });
    let mut group: [usize; 4] = [0, 1, 2, 3];
    for _ in 0..4 {
        for edge in 0..4 {
            let next = (edge + 1) % 4;
            if collapse[edge] && collapse[next] {
                let first = group[edge].min(group[next]);
                group[edge] = first;
                group[next] = first;
            }
        }
    }
    for edge in (0..4).filter(|&e| collapse[e]) {
        for (i, j) in cells(edge) {
            points[i][j] = apexes[group[edge]];
        }
    }
    let weights: Vec<Vec<f64>> = weights.chunks(4).map(<[f64]>::to_vec).collect();
    let knots = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
    NurbsSurface::new(3, 3, knots.clone(), knots, &points, Some(&weights)).unwrap()
}

/// Parameters with a good share exactly on edges and corners.
fn parameter() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        Just(1.0),
        Just(1e-12),
        Just(1.0 - 1e-12),
        0.0..=1.0
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(20_000))]

    #[test]
    fn frames_are_finite_and_orthonormal_on_degenerate_patches(
        net in prop::collection::vec(prop::array::uniform3(-0.45..0.45f64), 16),
        weights in prop_oneof![
            prop::collection::vec(prop_oneof![Just(1e-6), Just(1e6), 0.05..20.0f64], 16),
            prop::collection::vec(0.1..10.0f64, 16),
        ],
        collapse in prop::array::uniform4(any::<bool>()),
        offset in prop::array::uniform3(prop_oneof![Just(0.0), Just(glint::geom::MAX_COORDINATE - 4.0), -1e3..1e3f64]),
        u in parameter(),
        v in parameter(),
    ) {
        check_frame(net, weights, collapse, offset, u, v)?;
    }
}

/// The frame of [`patch`] at `(u, v)` is finite and orthonormal, and on a collapsed edge the
/// limit of the frames just inside.
fn check_frame(
    net: Vec<[f64; 3]>,
    weights: Vec<f64>,
    collapse: [bool; 4],
    offset: [f64; 3],
    u: f64,
    v: f64,
) -> Result<(), TestCaseError> {
    let spread = weights.iter().copied().fold(0.0, f64::max)
        / weights.iter().copied().fold(f64::INFINITY, f64::min);
    let s = patch(net, weights, collapse, offset);
    let f = s.frame(u, v);
    prop_assert!(f.point.is_finite(), "{:?}", f);
    prop_assert!(
        f.normal.is_finite() && f.du.is_finite() && f.dv.is_finite(),
        "{:?}",
        f
    );
    for axis in [f.normal, f.du, f.dv] {
        prop_assert!((axis.length() - 1.0).abs() < 1e-9, "{:?}", f);
    }
    prop_assert!(f.normal.dot(f.du).abs() < 1e-9, "{:?}", f);
    prop_assert!((f.du.cross(f.dv) - f.normal).length() < 1e-9, "{:?}", f);
    // Inside a collapsed edge, away from its ends (corners are checked below, on a patch
    // whose weights do not make the limit there depend on the way in).
    let interior = |t: f64| t > 0.01 && t < 0.99;
    let on_collapsed_edge = (collapse[0] && v == 0.0 && interior(u))
        || (collapse[1] && u == 1.0 && interior(v))
        || (collapse[2] && v == 1.0 && interior(u))
        || (collapse[3] && u == 0.0 && interior(v));
    if f.degenerate && on_collapsed_edge {
        // The limit from inside: the normal a small step toward the domain centre, where
        // the frame is regular. (Extreme weights make a step in (u, v) a long way on the
        // surface, so the steps start small.)
        let inside: Vec<Frame> = (5..=11)
            .map(|k| 10f64.powi(-k))
            .map(|t| s.frame(u + t * (0.5 - u), v + t * (0.5 - v)))
            .filter(|g| !g.degenerate)
            .collect();
        prop_assert!(
            spread > 1e3
                || inside.is_empty()
                || inside.iter().any(|g| g.normal.dot(f.normal) > 0.999),
            "{:?} vs inside {:?}",
            f,
            inside
        );
    }
    Ok(())
}

/// A case the search above once found, kept: the far end of a collapsed edge (v = 0,
/// u = 1 − 10⁻¹²) among weights of 10⁻⁶ beside 10⁶, far from the origin.
#[test]
fn a_corner_between_extreme_weights_far_from_the_origin_has_a_unit_frame() {
    let mut net = vec![[0.0; 3]; 16];
    net[1] = [0.3003323721209653, 0.2233538149134751, 0.0619402152471059];
    net[4] = [
        -0.19918550427342063,
        -0.007765387727157351,
        0.4483672482503267,
    ];
    net[7] = [0.0, 0.23263595629390088, -0.18951765060787462];
    net[9] = [
        0.17006708549284485,
        0.33832089018934464,
        0.19681480663234432,
    ];
    net[13] = [0.4103694170593604, 0.4356865235863014, -0.3011307845124488];
    net[14] = [
        -0.1521573715895851,
        -0.43314633585202406,
        -0.29372457700730936,
    ];
    let weights = vec![
        1e-6,
        1e-6,
        1e-6,
        1e-6,
        10.360611418564082,
        1e-6,
        1e-6,
        1e-6,
        1e6,
        11.097906843566598,
        1e-6,
        0.05,
        1e-6,
        19.362586668344978,
        0.05,
        0.05,
    ];
    let collapse = [true, false, false, false];
    // Found at 10⁶ from the origin, which a model may no longer reach: at the farthest it may.
    let far = glint::geom::MAX_COORDINATE - 4.0;
    check_frame(net, weights, collapse, [0.0, far, 0.0], 0.999999999999, 0.0).unwrap();
}

/// A smooth tilted bicubic patch (its normal nowhere near a world axis) with the chosen edges
/// collapsed, as [`patch`] collapses them.
fn tilted(collapse: [bool; 4]) -> NurbsSurface {
    let net = (0..16)
        .map(|k| {
            let (i, j) = ((k / 4) as f64, (k % 4) as f64);
            let bump = 0.3 * (i - 1.5) * (j - 1.5) / 2.25 - 0.2 * (i - 1.5).powi(2) / 2.25;
            [0.0, 0.0, 0.4 * i + 0.7 * j + bump]
        })
        .collect();
    patch(net, vec![1.0; 16], collapse, [0.0; 3])
}

#[test]
fn collapsed_edges_and_corners_take_the_normal_from_just_inside() {
    let mut corners = 0;
    for flags in 0..16u32 {
        let collapse = std::array::from_fn(|e| flags & (1 << e) != 0);
        let s = tilted(collapse);
        for (u, v) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
            .into_iter()
            .chain([(0.5, 0.0), (1.0, 0.5), (0.5, 1.0), (0.0, 0.5), (0.3, 0.0)])
        {
            let f = s.frame(u, v);
            let on = |e: usize| collapse[e] && [v == 0.0, u == 1.0, v == 1.0, u == 0.0][e];
            let collapsed_here = (0..4).filter(|&e| on(e)).count();
            assert_eq!(
                f.degenerate,
                collapsed_here > 0,
                "{collapse:?} at ({u}, {v}): {f:?}"
            );
            corners += usize::from(collapsed_here == 2);
            let step = |t: f64| s.frame(u + t * (0.5 - u), v + t * (0.5 - v));
            let inside = step(1e-6);
            assert!(!inside.degenerate, "{collapse:?} at ({u}, {v})");
            assert!(
                inside.normal.dot(f.normal) > 1.0 - 1e-6,
                "{collapse:?} at ({u}, {v}): {f:?} vs inside {inside:?}"
            );
            // Not the world axes of last resort: the patch faces away from +z.
            assert!(
                f.normal.dot(DVec3::Z) < 0.9,
                "{collapse:?} at ({u}, {v}): {f:?}"
            );
        }
    }
    // Every corner of every patch whose two edges there collapse.
    assert_eq!(corners, 4 * 4);
}
