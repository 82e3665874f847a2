//! Frames stay finite and orthonormal on hard surfaces: collapsed edges and corners, coincident
//! control points, extreme weights, models far from the origin.

use glam::DVec3;
use glint::geom::NurbsSurface;
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
    // Edges: v = 0 (row j = 0), u = 1 (i = 3), v = 1 (j = 3), u = 0 (i = 0).
    for (edge, &on) in collapse.iter().enumerate() {
        if !on {
            continue;
        }
        let cells: Vec<(usize, usize)> = match edge {
            0 => (0..4).map(|i| (i, 0)).collect(),
            1 => (0..4).map(|j| (3, j)).collect(),
            2 => (0..4).map(|i| (i, 3)).collect(),
            _ => (0..4).map(|j| (0, j)).collect(),
        };
        let apex = points[cells[1].0][cells[1].1];
        for (i, j) in cells {
            points[i][j] = apex;
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
        weights in prop::collection::vec(prop_oneof![Just(1e-6), Just(1e6), 0.05..20.0f64], 16),
        collapse in prop::array::uniform4(any::<bool>()),
        offset in prop::array::uniform3(prop_oneof![Just(0.0), Just(glint::geom::MAX_COORDINATE - 4.0), -1e3..1e3f64]),
        u in parameter(),
        v in parameter(),
    ) {
        let s = patch(net, weights, collapse, offset);
        let f = s.frame(u, v);
        prop_assert!(f.point.is_finite(), "{:?}", f);
        prop_assert!(f.normal.is_finite() && f.du.is_finite() && f.dv.is_finite(), "{:?}", f);
        for axis in [f.normal, f.du, f.dv] {
            prop_assert!((axis.length() - 1.0).abs() < 1e-9, "{:?}", f);
        }
        prop_assert!(f.normal.dot(f.du).abs() < 1e-9, "{:?}", f);
        prop_assert!((f.du.cross(f.dv) - f.normal).length() < 1e-9, "{:?}", f);
    }
}
