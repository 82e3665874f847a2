//! Time per evaluated point of the highlight, f32: a bare Blinn threshold test, a 5-op stack and
//! a 2-layer Boolean expression, over the same 64k (frame, (u, v), H) points of a sphere; each
//! through the batch methods, and the stack and expression also one call per point.

mod support;

use std::hint::black_box;

use criterion::{Criterion, Throughput};
use glam::{Vec2, Vec3};
use glint::highlight::{
    inside, Axis, Expr, Footprint, Layer, Op, Shade, SquareStyle, TangentFrame,
};
use rand::{Rng, SeedableRng};

const POINTS: usize = 1 << 16;

/// Points of the unit sphere with the frame (east, north, outward), (u, v) = (λ, φ), and the
/// half vector of a fixed light and orthographic view.
struct Points {
    frames: Vec<TangentFrame>,
    uvs: Vec<Vec2>,
    hs: Vec<Vec3>,
}

fn points() -> Points {
    let mut rng = rand::rngs::StdRng::seed_from_u64(1);
    let h = (Vec3::new(-0.4, 0.5, 0.77).normalize() + Vec3::Z).normalize();
    let mut p = Points {
        frames: Vec::with_capacity(POINTS),
        uvs: Vec::with_capacity(POINTS),
        hs: vec![h; POINTS],
    };
    for _ in 0..POINTS {
        let lat = rng.random_range(-1.5f32..1.5);
        let lon = rng.random_range(-3.1f32..3.1);
        let (sp, cp) = lat.sin_cos();
        let (sl, cl) = lon.sin_cos();
        let n = Vec3::new(cp * sl, sp, cp * cl);
        let east = Vec3::new(cl, 0.0, -sl);
        p.frames.push(TangentFrame::new(east, n.cross(east), n));
        p.uvs.push(Vec2::new(lon, lat));
    }
    p
}

fn layer(stack: Vec<Op>, epsilon: f32) -> Layer {
    Layer::new(stack, epsilon, [1.0, 1.0, 1.0])
}

fn square() -> Op {
    Op::Square {
        sigma: 0.2,
        n: 2.0,
        style: SquareStyle::Tangent,
    }
}

fn bench(c: &mut Criterion) {
    let p = points();
    let eps = 0.05;
    let five_ops = vec![
        Op::Translate {
            alpha: 0.1,
            beta: -0.05,
        },
        Op::Rotate { degrees: 30.0 },
        Op::Scale {
            delta: 0.4,
            axis: Axis::U,
        },
        Op::Split {
            gamma_u: 0.05,
            gamma_v: 0.0,
        },
        square(),
    ];
    let stack = layer(five_ops, eps).prepare().unwrap();
    let boolean = Expr::Subtract(
        Box::new(Expr::Layer(layer(vec![square()], eps))),
        Box::new(Expr::Layer(layer(
            vec![Op::Translate {
                alpha: 0.15,
                beta: 0.0,
            }],
            eps,
        ))),
    )
    .prepare()
    .unwrap();
    let mut signed = vec![0.0; POINTS];
    let mut shades = vec![
        Shade {
            coverage: 0.0,
            colour: Vec3::ZERO
        };
        POINTS
    ];

    let mut g = c.benchmark_group("highlight_per_point");
    g.throughput(Throughput::Elements(POINTS as u64));
    g.bench_function("blinn_threshold", |b| {
        b.iter(|| {
            let (frames, hs) = black_box((&p.frames, &p.hs));
            frames
                .iter()
                .zip(hs)
                .filter(|(f, h)| inside(f.n, **h, eps))
                .count()
        })
    });
    g.bench_function("stack_5_ops", |b| {
        b.iter(|| {
            stack.signed_many(black_box(&p.frames), black_box(&p.hs), &mut signed);
            signed.iter().filter(|&&s| s > 0.0).count()
        })
    });
    g.bench_function("boolean_2_layers", |b| {
        b.iter(|| {
            let (frames, uvs, hs) = black_box((&p.frames, &p.uvs, &p.hs));
            boolean.eval_many(frames, uvs, hs, Footprint::HARD, &mut shades);
            shades.iter().map(|s| s.coverage).sum::<f32>()
        })
    });
    g.bench_function("stack_5_ops_one_call_per_point", |b| {
        b.iter(|| {
            let (frames, hs) = black_box((&p.frames, &p.hs));
            frames
                .iter()
                .zip(hs)
                .filter(|(f, h)| stack.signed(f, **h) > 0.0)
                .count()
        })
    });
    g.bench_function("boolean_2_layers_one_call_per_point", |b| {
        b.iter(|| {
            let (frames, uvs, hs) = black_box((&p.frames, &p.uvs, &p.hs));
            frames
                .iter()
                .zip(uvs)
                .zip(hs)
                .map(|((f, uv), h)| boolean.eval(f, *uv, *h, Footprint::HARD).coverage)
                .sum::<f32>()
        })
    });
    g.finish();
}

fn main() {
    let mut c = Criterion::default().configure_from_args();
    bench(&mut c);
    c.final_summary();
    let group = "highlight_per_point";
    support::print_ratios(
        "time over the bare Blinn test for the same 64k points (÷ 65536 for per point)",
        &[
            (group, "stack_5_ops", "blinn_threshold"),
            (group, "boolean_2_layers", "blinn_threshold"),
            (group, "stack_5_ops_one_call_per_point", "stack_5_ops"),
        ],
    );
}
