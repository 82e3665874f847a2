//! Stability of the highlight operations and the inside test over any finite orthonormal frame,
//! unit H and in-range parameters (proptest, 100 000 cases per property).

use glam::{Quat, Vec3};
use glint::highlight::{inside, Axis, Layer, Op, SquareStyle, TangentFrame};
use proptest::prelude::*;

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: 100_000,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// A random orthonormal right-handed frame: the columns of a random rotation.
fn frame() -> impl Strategy<Value = TangentFrame> {
    prop::array::uniform4(-1.0f32..1.0)
        .prop_filter("rotation", |q| {
            let l = q.iter().map(|c| c * c).sum::<f32>();
            l > 1e-3
        })
        .prop_map(|[x, y, z, w]| {
            let q = Quat::from_xyzw(x, y, z, w).normalize();
            TangentFrame::new(q * Vec3::X, q * Vec3::Y, q * Vec3::Z)
        })
}

/// Which unit H to take in a frame: the special directions, the tangent plane, or anywhere.
#[derive(Clone, Debug)]
enum Dir {
    Normal,
    MinusNormal,
    PlusDu,
    MinusDu,
    PlusDv,
    Tangent(f32),
    Any(f32, f32),
}

fn dir() -> impl Strategy<Value = Dir> {
    prop_oneof![
        Just(Dir::Normal),
        Just(Dir::MinusNormal),
        Just(Dir::PlusDu),
        Just(Dir::MinusDu),
        Just(Dir::PlusDv),
        (0.0f32..std::f32::consts::TAU).prop_map(Dir::Tangent),
        (-1.0f32..1.0, 0.0f32..std::f32::consts::TAU).prop_map(|(z, a)| Dir::Any(z, a)),
        // Close to N, where highlights live.
        (0.99f32..1.0, 0.0f32..std::f32::consts::TAU).prop_map(|(z, a)| Dir::Any(z, a)),
    ]
}

fn unit_h(f: &TangentFrame, d: &Dir) -> Vec3 {
    match *d {
        Dir::Normal => f.n,
        Dir::MinusNormal => -f.n,
        Dir::PlusDu => f.du,
        Dir::MinusDu => -f.du,
        Dir::PlusDv => f.dv,
        Dir::Tangent(a) => (a.cos() * f.du + a.sin() * f.dv).normalize(),
        Dir::Any(z, a) => {
            let r = (1.0 - z * z).max(0.0).sqrt();
            f.to_world(Vec3::new(r * a.cos(), r * a.sin(), z))
                .normalize()
        }
    }
}

fn unit_interval() -> impl Strategy<Value = f32> {
    prop_oneof![Just(0.0f32), Just(1.0f32), 0.0f32..=1.0]
}

fn translation() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(1e6f32),
        Just(-1e6f32),
        Just(0.0f32),
        -2.0f32..2.0,
        -1e6f32..1e6
    ]
}

/// n from 0.01 to 1000, log-uniform, with both ends.
fn exponent() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(0.01f32),
        Just(1000.0f32),
        Just(1.0f32),
        (0.01f32.log2()..1000.0f32.log2()).prop_map(f32::exp2),
    ]
}

fn style() -> impl Strategy<Value = SquareStyle> {
    prop_oneof![Just(SquareStyle::Tangent), Just(SquareStyle::PerAxis)]
}

fn axis() -> impl Strategy<Value = Axis> {
    prop_oneof![
        Just(Axis::U),
        Just(Axis::V),
        (-360.0f32..360.0).prop_map(Axis::Angle)
    ]
}

fn translate() -> impl Strategy<Value = Op> {
    (translation(), translation()).prop_map(|(alpha, beta)| Op::Translate { alpha, beta })
}

fn rotate() -> impl Strategy<Value = Op> {
    (-720.0f32..720.0).prop_map(|degrees| Op::Rotate { degrees })
}

fn scale() -> impl Strategy<Value = Op> {
    (unit_interval(), axis()).prop_map(|(delta, axis)| Op::Scale { delta, axis })
}

fn split() -> impl Strategy<Value = Op> {
    let gamma = || prop_oneof![Just(0.0f32), 0.0f32..10.0];
    (gamma(), gamma()).prop_map(|(gamma_u, gamma_v)| Op::Split { gamma_u, gamma_v })
}

fn square() -> impl Strategy<Value = Op> {
    (unit_interval(), exponent(), style()).prop_map(|(sigma, n, style)| Op::Square {
        sigma,
        n,
        style,
    })
}

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![translate(), rotate(), scale(), split(), square()]
}

fn check_op(f: &TangentFrame, d: &Dir, op: &Op) -> Result<(), TestCaseError> {
    assert_unit(op.prepare().unwrap().apply(f, unit_h(f, d)))
}

fn assert_unit(v: Vec3) -> Result<(), TestCaseError> {
    prop_assert!(v.is_finite(), "not finite: {v:?}");
    prop_assert!(
        (v.length() - 1.0).abs() <= 1e-6,
        "not unit: {v:?}, |v| = {}",
        v.length()
    );
    Ok(())
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn translate_returns_a_unit_vector(f in frame(), d in dir(), op in translate()) {
        check_op(&f, &d, &op)?;
    }

    #[test]
    fn rotate_returns_a_unit_vector(f in frame(), d in dir(), op in rotate()) {
        check_op(&f, &d, &op)?;
    }

    #[test]
    fn scale_returns_a_unit_vector(f in frame(), d in dir(), op in scale()) {
        check_op(&f, &d, &op)?;
    }

    #[test]
    fn split_returns_a_unit_vector(f in frame(), d in dir(), op in split()) {
        check_op(&f, &d, &op)?;
    }

    #[test]
    fn square_returns_a_unit_vector(f in frame(), d in dir(), op in square()) {
        check_op(&f, &d, &op)?;
    }

    #[test]
    fn a_five_op_stack_returns_a_unit_vector(
        f in frame(),
        d in dir(),
        ops in prop::collection::vec(op(), 5),
        eps in prop_oneof![Just(1e-7f32), Just(2.0f32), (1e-7f32.log2()..1.0).prop_map(f32::exp2)],
    ) {
        let h = unit_h(&f, &d);
        let layer = Layer::new(ops, eps, [1.0; 3])
            .prepare()
            .unwrap();
        assert_unit(layer.highlight_vector(&f, h))?;
        let s = layer.signed(&f, h);
        prop_assert!(s.is_finite());
        // The batch path computes the same value.
        let mut batch = [f32::NAN];
        layer.signed_many(&[f], &[h], &mut batch);
        prop_assert_eq!(batch[0].to_bits(), s.to_bits());
    }

    /// The f32 inside test `‖N − H‖²/2 < ε` against the same formula in f64 on the same
    /// inputs, for ε from 1e-7 to 2 and H placed near the edge `1 − (N, H) = ε`.
    #[test]
    fn inside_test_agrees_with_f64_away_from_the_edge(
        f in frame(),
        log_eps in 1e-7f32.log2()..1.0,
        k in 0.5f64..1.5,
        a in 0.0f64..std::f64::consts::TAU,
    ) {
        let eps = log_eps.exp2();
        let (du, dv, n) = (f.du.as_dvec3(), f.dv.as_dvec3(), f.n.as_dvec3());
        // 1 − cos ρ = k ε.
        let rho = 2.0 * (k * f64::from(eps) / 2.0).min(1.0).sqrt().asin();
        let t = a.cos() * du + a.sin() * dv;
        let h = (rho.cos() * n + rho.sin() * t).as_vec3();
        let reference = f64::from(eps) - 0.5 * (f.n.as_dvec3() - h.as_dvec3()).length_squared();
        if reference.abs() > 1e-3 * f64::from(eps) {
            prop_assert_eq!(inside(f.n, h, eps), reference > 0.0, "ε = {}, k = {}", eps, k);
            let layer = Layer::new(vec![], eps, [1.0; 3])
                .prepare()
                .unwrap();
            prop_assert_eq!(layer.signed(&f, h) > 0.0, reference > 0.0, "layer path, ε = {}", eps);
        }
    }
}
