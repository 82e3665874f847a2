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

fn check_op(f: &TangentFrame, d: &Dir, op: &Op) -> Result<Vec3, TestCaseError> {
    let out = apply(f, op, unit_h(f, d));
    assert_unit(out)?;
    Ok(out)
}

fn apply(f: &TangentFrame, op: &Op, h: Vec3) -> Vec3 {
    op.prepare().unwrap().apply(f, h)
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

fn assert_close(got: Vec3, want: Vec3, tolerance: f32, what: &str) -> Result<(), TestCaseError> {
    prop_assert!(
        (got - want).length() <= tolerance,
        "{}: {:?}, expected {:?}",
        what,
        got,
        want
    );
    Ok(())
}

/// A unit H on a frame axis: `z N + r a` with `a` one of ±du, ±dv and `r = √(1 − z²)`.
fn on_axis(f: &TangentFrame, axis: usize, z: f32) -> Vec3 {
    let a = [f.du, -f.du, f.dv, -f.dv][axis];
    (z * f.n + (1.0 - z * z).max(0.0).sqrt() * a).normalize()
}

proptest! {
    #![proptest_config(config())]

    /// Translation by (α, β) scales `H + α du + β dv` by `1 / c`, so `c = h_n / h'_n`, and the
    /// translation by `(−α / c, −β / c)` brings the result back to H.
    #[test]
    fn translate_is_undone_by_its_solved_inverse(
        f in frame(),
        d in dir(),
        alpha in -2.0f32..2.0,
        beta in -2.0f32..2.0,
    ) {
        let h = unit_h(&f, &d);
        let out = check_op(&f, &d, &Op::Translate { alpha, beta })?;
        // Away from the tangent plane, where c is well conditioned.
        if h.dot(f.n) > 0.2 {
            let c = h.dot(f.n) / out.dot(f.n);
            let inverse = Op::Translate { alpha: -alpha / c, beta: -beta / c };
            assert_close(apply(&f, &inverse, out), h, 1e-5, "translated back")?;
        }
    }

    #[test]
    fn translate_returns_a_unit_vector(f in frame(), d in dir(), op in translate()) {
        check_op(&f, &d, &op)?;
    }

    /// Rotation keeps h_n, and a rotation by −θ undoes one by θ.
    #[test]
    fn rotate_keeps_the_normal_part_and_is_undone_by_its_opposite(
        f in frame(),
        d in dir(),
        degrees in -720.0f32..720.0,
    ) {
        let h = unit_h(&f, &d);
        let out = check_op(&f, &d, &Op::Rotate { degrees })?;
        prop_assert!((out.dot(f.n) - h.dot(f.n)).abs() <= 1e-6, "h_n {} became {}", h.dot(f.n), out.dot(f.n));
        let back = apply(&f, &Op::Rotate { degrees: -degrees }, out);
        assert_close(back, h, 1e-5, "rotated back")?;
    }

    /// δ = 0 is the identity; otherwise the part of H across the axis and its normal part keep
    /// their ratio (only the part along the axis shrinks).
    #[test]
    fn scale_is_the_identity_at_zero_and_shrinks_only_along_its_axis(
        f in frame(),
        d in dir(),
        op in scale(),
    ) {
        let h = unit_h(&f, &d);
        let out = check_op(&f, &d, &op)?;
        let Op::Scale { delta, axis } = &op else { unreachable!() };
        if *delta == 0.0 {
            assert_close(out, h, 1e-6, "δ = 0")?;
        }
        let phi = match axis {
            Axis::U => 0.0,
            Axis::V => 90.0,
            Axis::Angle(phi) => *phi,
        };
        let (s, c) = phi.to_radians().sin_cos();
        let across = -s * f.du + c * f.dv;
        // (H'·across) h_n = (H·across) h'_n: the cross product of the two pairs vanishes.
        let (a, b) = (h.dot(across), h.dot(f.n));
        let (a2, b2) = (out.dot(across), out.dot(f.n));
        if out != h {
            prop_assert!((a2 * b - a * b2).abs() <= 2e-6, "across/normal {} {} became {} {}", a, b, a2, b2);
        }
    }

    #[test]
    fn split_is_the_identity_at_zero(f in frame(), d in dir(), op in split()) {
        let out = check_op(&f, &d, &op)?;
        if op == (Op::Split { gamma_u: 0.0, gamma_v: 0.0 }) {
            assert_close(out, unit_h(&f, &d), 1e-6, "γ = 0")?;
        }
    }

    #[test]
    fn square_returns_a_unit_vector(f in frame(), d in dir(), op in square()) {
        check_op(&f, &d, &op)?;
    }

    /// Tangent squaring leaves H on an axis of the frame where it was: sin 2θ = 0 there (in
    /// frame coordinates, where H is exactly on the axis).
    #[test]
    fn tangent_square_leaves_h_on_an_axis_unchanged(
        axis in 0usize..4,
        z in -1.0f32..1.0,
        sigma in unit_interval(),
        n in exponent(),
    ) {
        let local = TangentFrame::new(Vec3::X, Vec3::Y, Vec3::Z);
        let h = on_axis(&local, axis, z);
        let op = Op::Square { sigma, n, style: SquareStyle::Tangent }.prepare().unwrap();
        assert_close(op.apply_local(h), h, 2e-6, "on an axis")?;
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
