//! The highlight operations at increasing parameter values on a sphere seen head-on (Figure 4
//! of Anjyo & Hiramitsu 2003), one PNG grid per operation plus one for the Boolean
//! post-operations.
//!
//! Usage: `cargo run --release --example ops_gallery [OUT_DIR]` (default `out/gallery/`).
//! Each tile ray-casts the analytic unit sphere orthographically along −z with a two-tone cel
//! base, a directional light from the upper left and the frame (east, north, outward), so du
//! points right and dv up at the centre. Edges are 4×4 supersampled.

use std::path::{Path, PathBuf};

use glam::{DVec3, Vec2, Vec3};
use glint::highlight::{
    half_vector, Axis, Expr, Footprint, Layer, Op, PreparedExpr, SquareStyle, TangentFrame,
};
use image::{Rgb, RgbImage};

const TILE: u32 = 160;
const SUPERSAMPLE: u32 = 4;
const EPSILON: f32 = 0.03;

/// Toward the light, upper left and in front.
fn light() -> Vec3 {
    Vec3::new(-0.35, 0.45, 0.82).normalize()
}

fn layer(stack: Vec<Op>) -> Layer {
    Layer::new(stack, EPSILON, [1.0, 1.0, 0.95])
}

fn single(stack: Vec<Op>) -> Expr {
    Expr::Layer(layer(stack))
}

/// Linear RGB of one sample at tile coordinates `(x, y)` in [−1, 1]², or None off the sphere.
fn shade(expr: &PreparedExpr, x: f64, y: f64) -> Option<Vec3> {
    let r2 = x * x + y * y;
    if r2 >= 1.0 {
        return None;
    }
    let n = DVec3::new(x, y, (1.0 - r2).sqrt());
    let east = DVec3::new(n.z, 0.0, -n.x).normalize();
    let frame = TangentFrame::new(east.as_vec3(), n.cross(east).as_vec3(), n.as_vec3());
    let uv = Vec2::new(n.x.atan2(n.z) as f32, n.y.asin() as f32);
    let (l, v) = (light(), Vec3::Z);
    let base = if frame.n.dot(l) > 0.25 {
        Vec3::new(0.75, 0.22, 0.16)
    } else {
        Vec3::new(0.30, 0.07, 0.10)
    };
    let hl = expr.eval(&frame, uv, half_vector(l, v), Footprint::HARD);
    Some(base.lerp(hl.colour, hl.coverage))
}

fn srgb(c: f32) -> u8 {
    let c = c.clamp(0.0, 1.0);
    let s = if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    };
    (s * 255.0).round() as u8
}

/// Draws the tile of `expr` with its top-left corner at pixel `(ox, oy)`.
fn draw_tile(img: &mut RgbImage, ox: u32, oy: u32, expr: &PreparedExpr) {
    let background = Vec3::splat(0.02);
    let scale = 1.08; // sphere radius is 1/1.08 of the half tile
    for py in 0..TILE {
        for px in 0..TILE {
            let mut sum = Vec3::ZERO;
            for sy in 0..SUPERSAMPLE {
                for sx in 0..SUPERSAMPLE {
                    let fx = (f64::from(px) + (f64::from(sx) + 0.5) / f64::from(SUPERSAMPLE))
                        / f64::from(TILE);
                    let fy = (f64::from(py) + (f64::from(sy) + 0.5) / f64::from(SUPERSAMPLE))
                        / f64::from(TILE);
                    let (x, y) = ((2.0 * fx - 1.0) * scale, (1.0 - 2.0 * fy) * scale);
                    sum += shade(expr, x, y).unwrap_or(background);
                }
            }
            let c = sum / (SUPERSAMPLE * SUPERSAMPLE) as f32;
            img.put_pixel(ox + px, oy + py, Rgb([srgb(c.x), srgb(c.y), srgb(c.z)]));
        }
    }
}

/// One PNG: a row per entry of `rows`, a tile per expression.
fn grid(
    dir: &Path,
    name: &str,
    rows: Vec<Vec<Expr>>,
) -> Result<PathBuf, Box<dyn std::error::Error>> {
    let cols = rows.iter().map(Vec::len).max().unwrap_or(0) as u32;
    let mut img = RgbImage::from_pixel(cols * TILE, rows.len() as u32 * TILE, Rgb([5, 5, 5]));
    for (r, row) in rows.iter().enumerate() {
        for (c, expr) in row.iter().enumerate() {
            draw_tile(&mut img, c as u32 * TILE, r as u32 * TILE, &expr.prepare()?);
        }
    }
    let path = dir.join(format!("{name}.png"));
    img.save(&path)?;
    Ok(path)
}

fn row(values: &[f32], op: impl Fn(f32) -> Vec<Op>) -> Vec<Expr> {
    values.iter().map(|&v| single(op(v))).collect()
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let dir = PathBuf::from(
        std::env::args()
            .nth(1)
            .unwrap_or_else(|| "out/gallery".into()),
    );
    std::fs::create_dir_all(&dir)?;
    let steps = [0.0, 0.1, 0.2, 0.3, 0.4];
    let unit_steps = [0.0, 0.2, 0.4, 0.6, 0.8];
    let square = |sigma, n, style| Op::Square { sigma, n, style };

    let sheets = vec![
        (
            "translate",
            vec![
                row(&steps, |a| {
                    vec![Op::Translate {
                        alpha: a,
                        beta: 0.0,
                    }]
                }),
                row(&steps, |b| {
                    vec![Op::Translate {
                        alpha: 0.0,
                        beta: b,
                    }]
                }),
            ],
        ),
        (
            "rotate",
            vec![row(&[0.0, 22.5, 45.0, 67.5, 90.0], |d| {
                vec![
                    Op::Rotate { degrees: d },
                    Op::Scale {
                        delta: 0.7,
                        axis: Axis::U,
                    },
                ]
            })],
        ),
        (
            "scale",
            [Axis::U, Axis::V, Axis::Angle(45.0)]
                .into_iter()
                .map(|axis| {
                    row(&unit_steps, |delta| {
                        vec![Op::Scale {
                            delta,
                            axis: axis.clone(),
                        }]
                    })
                })
                .collect(),
        ),
        (
            "split",
            vec![
                row(&steps, |g| {
                    vec![Op::Split {
                        gamma_u: g,
                        gamma_v: 0.0,
                    }]
                }),
                row(&steps, |g| {
                    vec![Op::Split {
                        gamma_u: g,
                        gamma_v: g,
                    }]
                }),
            ],
        ),
        (
            "square",
            vec![
                row(&[0.0, 0.05, 0.1, 0.15, 0.2, 0.3], |s| {
                    vec![square(s, 2.0, SquareStyle::Tangent)]
                }),
                row(&[0.0, 0.05, 0.1, 0.15, 0.2, 0.3], |s| {
                    vec![square(s, 5.0, SquareStyle::Tangent)]
                }),
                row(&[0.0, 0.2, 0.4, 0.6, 0.8, 1.0], |s| {
                    vec![square(s, 2.0, SquareStyle::PerAxis)]
                }),
            ],
        ),
        ("boolean", booleans()),
    ];
    for (name, rows) in sheets {
        println!("{}", grid(&dir, name, rows)?.display());
    }
    Ok(())
}

/// Row 1: A, B, A ∪ B, A \ B (a crescent), A ∩ B. Row 2: the crescent as B moves further.
fn booleans() -> Vec<Vec<Expr>> {
    let a = || Box::new(single(vec![]));
    let b = |alpha: f32| {
        Box::new(Expr::Layer(Layer {
            colour: [0.3, 0.6, 1.0],
            ..layer(vec![Op::Translate { alpha, beta: 0.05 }])
        }))
    };
    vec![
        vec![
            *a(),
            *b(0.15),
            Expr::Union(a(), b(0.15)),
            Expr::Subtract(a(), b(0.15)),
            Expr::Intersect(a(), b(0.15)),
        ],
        [0.05, 0.1, 0.15, 0.2, 0.3]
            .iter()
            .map(|&alpha| Expr::Subtract(a(), b(alpha)))
            .collect(),
    ]
}
