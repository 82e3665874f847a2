//! The RON syntax of highlight descriptions, and their genericity over the parameter type.

use glint::anim::Track;
use glint::highlight::{Axis, Expr, Layer, Mask, Op, SquareStyle};

fn op(s: &str) -> Op {
    ron::from_str(s).unwrap_or_else(|e| panic!("{s}: {e}"))
}

#[test]
fn ops_parse_from_ron() {
    assert_eq!(
        op("Translate(alpha: 0.2, beta: -0.1)"),
        Op::Translate {
            alpha: 0.2,
            beta: -0.1
        }
    );
    assert_eq!(op("Rotate(degrees: 30.0)"), Op::Rotate { degrees: 30.0 });
    assert_eq!(
        op("Scale(delta: 0.5, axis: V)"),
        Op::Scale {
            delta: 0.5,
            axis: Axis::V
        }
    );
    assert_eq!(
        op("Scale(delta: 0.5, axis: Angle(45.0))"),
        Op::Scale {
            delta: 0.5,
            axis: Axis::Angle(45.0)
        }
    );
    assert_eq!(
        op("Scale(delta: 0.5)"),
        Op::Scale {
            delta: 0.5,
            axis: Axis::U
        }
    );
    assert_eq!(
        op("Split(gamma_u: 0.3, gamma_v: 0.0)"),
        Op::Split {
            gamma_u: 0.3,
            gamma_v: 0.0
        }
    );
    assert_eq!(
        op("Square(sigma: 0.2, n: 2.0)"),
        Op::Square {
            sigma: 0.2,
            n: 2.0,
            style: SquareStyle::Tangent
        }
    );
    assert_eq!(
        op("Square(sigma: 0.2, n: 2.5, style: PerAxis)"),
        Op::Square {
            sigma: 0.2,
            n: 2.5,
            style: SquareStyle::PerAxis
        }
    );
}

#[test]
fn unknown_fields_and_ops_are_rejected() {
    for bad in [
        "Translate(alpha: 0.2, beta: 0.0, gamma: 1.0)",
        "Rotate(degree: 30.0)",
        "Shear(amount: 1.0)",
        "Square(sigma: 0.2)",
    ] {
        assert!(ron::from_str::<Op>(bad).is_err(), "{bad} accepted");
    }
    let layer = "(stack: [], epsilon: 0.1, colour: (1.0, 1.0, 1.0), opacity: 1.0, colour_space: 1)";
    assert!(ron::from_str::<Layer>(layer).is_err());
}

const CRESCENT: &str = r#"
Subtract(
    Layer((
        stack: [Square(sigma: 0.2, n: 2.0)],
        epsilon: 0.05,
        colour: (1.0, 0.95, 0.9),
        opacity: 0.9,
        feather: Some(0.002),
        mask: Some((u: (0.0, 0.5), v: (0.1, 0.9), feather: 0.05)),
    )),
    Layer((
        stack: [Translate(alpha: 0.15, beta: 0.0)],
        epsilon: 0.05,
        colour: (0.0, 0.0, 0.0),
        opacity: 1.0,
    )),
)
"#;

#[test]
fn expression_parses_prepares_and_round_trips() {
    let e: Expr = ron::from_str(CRESCENT).unwrap();
    let Expr::Subtract(a, b) = &e else {
        panic!("not a subtraction: {e:?}")
    };
    let Expr::Layer(a) = a.as_ref() else { panic!() };
    assert_eq!(a.feather, Some(0.002));
    assert_eq!(
        a.mask,
        Some(Mask {
            u: (0.0, 0.5),
            v: (0.1, 0.9),
            feather: 0.05
        })
    );
    assert!(matches!(b.as_ref(), Expr::Layer(l) if l.mask.is_none() && l.feather.is_none()));
    assert!(e.prepare().is_ok());
    let text = ron::to_string(&e).unwrap();
    assert_eq!(ron::from_str::<Expr>(&text).unwrap(), e);
}

#[test]
fn descriptions_are_generic_over_the_parameter_type() {
    let animated: Expr<Track<f32>> = ron::from_str(
        r#"Layer((
            stack: [Translate(alpha: [(0.0, 0.0), (10.0, 0.5)], beta: 0.0), Rotate(degrees: 15.0)],
            epsilon: 0.05,
            colour: (1.0, 1.0, 1.0),
            opacity: [(0.0, 1.0), (10.0, 0.0)],
        ))"#,
    )
    .unwrap();
    let at4: Expr = animated.map(|t| t.at(4.0));
    let Expr::Layer(l) = &at4 else { panic!() };
    assert_eq!(
        l.stack[0],
        Op::Translate {
            alpha: 0.2,
            beta: 0.0
        }
    );
    assert_eq!(l.stack[1], Op::Rotate { degrees: 15.0 });
    assert!((l.opacity - 0.6).abs() < 1e-6);
    assert!(at4.prepare().is_ok());
    // Resolved past the last key, the opacity holds its last value; left out, it is 1.
    let Expr::Layer(l) = animated.map(|t| t.at(20.0)) else {
        panic!()
    };
    assert_eq!(l.opacity, 0.0);
    let plain: Layer<Track<f32>> =
        ron::from_str("(stack: [], epsilon: 0.1, colour: (1, 1, 1))").unwrap();
    assert_eq!(plain.map(|t| t.at(0.0)), Layer::new(vec![], 0.1, [1.0; 3]));
}

#[test]
fn the_layer_documented_in_docs_highlights_parses_and_prepares() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/highlights.md");
    let doc = std::fs::read_to_string(path).unwrap();
    let start = doc.find("```ron\n").unwrap() + "```ron\n".len();
    let end = start + doc[start..].find("```").unwrap();
    let layer: glint::highlight::Layer = ron::from_str(&doc[start..end]).unwrap();
    assert_eq!(layer.stack.len(), 2);
    assert!(layer.mask.is_some());
    layer.prepare().unwrap();
}
