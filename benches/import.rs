//! Reading a model of 1000 patches: a USD text layer against the same patches as a RON patch
//! library, in turns, round after round. Each patch is a rational bicubic NURBS patch on a 6 × 6
//! net, under a transformed `Xform` parent in the layer. Run with `cargo bench --bench import`;
//! it prints the median time of each and their ratio per round, with quartiles.

use std::fmt::Write as _;
use std::hint::black_box;
use std::time::Instant;

use glint::formats::{parse_patch_ron, parse_usda};

const PATCHES: usize = 1000;
const NET: usize = 6;
const ROUNDS: usize = 30;

/// The control point (i, j) of patch `k`, and its weight: values exact in single precision.
fn point(k: usize, i: usize, j: usize) -> ([f64; 3], f64) {
    let x = (k % 40) as f64 * 8.0 + i as f64;
    let y = (k / 40) as f64 * 8.0 + j as f64;
    let z = ((i * 7 + j * 3 + k) % 5) as f64 * 0.25;
    let w = 1.0 + ((i + j + k) % 3) as f64 * 0.25;
    ([x, y, z], w)
}

const KNOTS: &str = "0, 0, 0, 0, 0.5, 0.75, 1, 1, 1, 1";

fn usda() -> String {
    let mut s = String::from("#usda 1.0\n(\n    upAxis = \"Z\"\n)\n\ndef Xform \"model\"\n{\n    double3 xformOp:translate = (1, 2, 3)\n    uniform token[] xformOpOrder = [\"xformOp:translate\"]\n");
    for k in 0..PATCHES {
        let (mut points, mut weights) = (Vec::new(), Vec::new());
        for j in 0..NET {
            for i in 0..NET {
                let ([x, y, z], w) = point(k, i, j);
                points.push(format!("({x}, {y}, {z})"));
                weights.push(format!("{w}"));
            }
        }
        let _ = write!(
            s,
            "    def NurbsPatch \"p{k}\"\n    {{\n        int uVertexCount = {NET}\n        int vVertexCount = {NET}\n        int uOrder = 4\n        int vOrder = 4\n        double[] uKnots = [{KNOTS}]\n        double[] vKnots = [{KNOTS}]\n        double2 uRange = (0, 1)\n        double2 vRange = (0, 1)\n        point3f[] points = [{}]\n        double[] pointWeights = [{}]\n    }}\n",
            points.join(", "),
            weights.join(", ")
        );
    }
    s.push_str("}\n");
    s
}

fn ron() -> String {
    let mut s = String::from("(\n    patches: [\n");
    for k in 0..PATCHES {
        let rows: Vec<String> = (0..NET)
            .map(|i| {
                let row: Vec<String> = (0..NET)
                    .map(|j| {
                        let ([x, y, z], _) = point(k, i, j);
                        format!("({x:?}, {y:?}, {z:?})")
                    })
                    .collect();
                format!("[{}]", row.join(", "))
            })
            .collect();
        let weights: Vec<String> = (0..NET)
            .map(|i| {
                let row: Vec<String> = (0..NET)
                    .map(|j| format!("{:?}", point(k, i, j).1))
                    .collect();
                format!("[{}]", row.join(", "))
            })
            .collect();
        let _ = writeln!(
            s,
            "        (name: \"p{k}\", surface: Nurbs(degree: (3, 3), knots_u: [{KNOTS}], knots_v: [{KNOTS}], points: [{}], weights: Some([{}]))),",
            rows.join(", "),
            weights.join(", ")
        );
    }
    s.push_str("    ],\n)\n");
    s
}

fn quartiles(mut v: Vec<f64>) -> [f64; 3] {
    v.sort_by(f64::total_cmp);
    let at = |q: f64| v[((v.len() - 1) as f64 * q).round() as usize];
    [at(0.25), at(0.5), at(0.75)]
}

fn main() {
    let (usda, ron) = (usda(), ron());
    let (mut usd_ms, mut ron_ms, mut ratios) = (Vec::new(), Vec::new(), Vec::new());
    for round in 0..ROUNDS + 2 {
        let time = |f: &dyn Fn()| {
            let start = Instant::now();
            f();
            start.elapsed().as_secs_f64() * 1e3
        };
        let read_usd = || {
            black_box(parse_usda(&usda, "model.usda").unwrap());
        };
        let read_ron = || {
            black_box(parse_patch_ron(&ron, "model.ron").unwrap());
        };
        // Alternate which goes first.
        let (a, b) = if round % 2 == 0 {
            let a = time(&read_usd);
            (a, time(&read_ron))
        } else {
            let b = time(&read_ron);
            (time(&read_usd), b)
        };
        if round >= 2 {
            usd_ms.push(a);
            ron_ms.push(b);
            ratios.push(a / b);
        }
    }
    println!(
        "reading {PATCHES} rational bicubic patches (6 × 6 nets): {} KB of USDA, {} KB of RON",
        usda.len() / 1024,
        ron.len() / 1024
    );
    let show = |name: &str, v: Vec<f64>| {
        let [q1, m, q3] = quartiles(v);
        println!("{name:<20} {m:>8.2} ms  [{q1:.2}, {q3:.2}]");
    };
    show("usda", usd_ms);
    show("ron", ron_ms);
    let [q1, m, q3] = quartiles(ratios);
    println!("usda / ron           {m:>8.3}     [{q1:.3}, {q3:.3}]  (per round)");
}
