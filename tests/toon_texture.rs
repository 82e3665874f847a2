//! 2D toon textures: lookup orientation and clamping on a hand-built 2×2 texture, bilinear
//! lookups over a wider and taller one, reading from PNG, and the shipped textures against the
//! generator that makes them.

use glam::Vec3;
use glint::formats::png::{write_png, PngLayout};
use glint::formats::{read_toon_texture, srgb_to_linear};
use glint::toon::texture_families::Family;
use glint::toon::ToonTexture;

const TOP_DARK: Vec3 = Vec3::new(1.0, 0.0, 0.0);
const TOP_LIT: Vec3 = Vec3::new(0.0, 1.0, 0.0);
const BOTTOM_DARK: Vec3 = Vec3::new(0.0, 0.0, 1.0);
const BOTTOM_LIT: Vec3 = Vec3::new(1.0, 1.0, 1.0);

/// Rows from the top: (n·l = −1 side, n·l = 1 side).
fn two_by_two() -> ToonTexture {
    ToonTexture::new(2, 2, vec![TOP_DARK, TOP_LIT, BOTTOM_DARK, BOTTOM_LIT]).unwrap()
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).abs().max_element() < 1e-6
}

#[test]
fn the_top_row_is_full_detail_and_the_left_column_dark() {
    let t = two_by_two();
    assert_eq!(t.sample(-1.0, 1.0), TOP_DARK);
    assert_eq!(t.sample(1.0, 1.0), TOP_LIT);
    assert_eq!(t.sample(-1.0, 0.0), BOTTOM_DARK);
    assert_eq!(t.sample(1.0, 0.0), BOTTOM_LIT);
    // Halfway on both axes: the mean of the four.
    let mean = (TOP_DARK + TOP_LIT + BOTTOM_DARK + BOTTOM_LIT) / 4.0;
    assert!(close(t.sample(0.0, 0.5), mean));
    // Bilinear between the texel centres, off the centres.
    assert!(close(t.sample(0.0, 1.0), (TOP_DARK + TOP_LIT) / 2.0));
    let quarter = TOP_DARK
        .lerp(TOP_LIT, 0.25)
        .lerp(BOTTOM_DARK.lerp(BOTTOM_LIT, 0.25), 0.25);
    // n·l = −0.25 is x = 0.375 and D = 0.625 is 0.375 down: a quarter of the way from the
    // first texel centres (0.25) on both axes.
    assert!(
        close(t.sample(-0.25, 0.625), quarter),
        "{}",
        t.sample(-0.25, 0.625)
    );
}

#[test]
fn texel_centres_read_their_texel_and_midpoints_the_mean_in_a_5_by_3_texture() {
    let (width, height) = (5, 3);
    let colour = |x: usize, y: usize| Vec3::new(x as f32, y as f32, (10 * x + y) as f32);
    let texels = (0..height)
        .flat_map(|y| (0..width).map(move |x| colour(x, y)))
        .collect();
    let t = ToonTexture::new(width, height, texels).unwrap();
    // Where the lookup puts the centre of column x and of row y.
    let n_dot_l = |x: f32| (x + 0.5) / width as f32 * 2.0 - 1.0;
    let detail = |y: f32| 1.0 - (y + 0.5) / height as f32;
    for y in 0..height {
        for x in 0..width {
            assert_eq!(t.texel(x, y), colour(x, y));
            let (fx, fy) = (x as f32, y as f32);
            assert!(
                close(t.sample(n_dot_l(fx), detail(fy)), colour(x, y)),
                "({x}, {y})"
            );
            if x + 1 < width && y + 1 < height {
                let mean =
                    (colour(x, y) + colour(x + 1, y) + colour(x, y + 1) + colour(x + 1, y + 1))
                        / 4.0;
                let got = t.sample(n_dot_l(fx + 0.5), detail(fy + 0.5));
                assert!(close(got, mean), "({x}, {y}): {got} vs {mean}");
            }
        }
    }
}

#[test]
fn lookups_clamp_to_the_edge_texels() {
    let t = two_by_two();
    // Inside the outer half texel and beyond the axes: the edge texel itself.
    for (nl, d, want) in [
        (-0.6, 0.9, TOP_DARK),
        (-5.0, 7.0, TOP_DARK),
        (0.6, 0.8, TOP_LIT),
        (3.0, 1.5, TOP_LIT),
        (-1.0, -2.0, BOTTOM_DARK),
        (f32::INFINITY, f32::NEG_INFINITY, BOTTOM_LIT),
    ] {
        assert_eq!(t.sample(nl, d), want, "n·l = {nl}, D = {d}");
    }
    // Clamped on one axis, interpolated on the other.
    assert!(close(t.sample(-9.0, 0.5), (TOP_DARK + BOTTOM_DARK) / 2.0));
    // NaN is read at the edge, never NaN.
    assert!(t.sample(f32::NAN, f32::NAN).is_finite());
}

#[test]
fn a_png_texture_reads_top_row_as_full_detail_in_linear_rgb() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.png");
    // Top row: black then sRGB 128 grey; bottom row: red then white.
    #[rustfmt::skip]
    let rgba = [
        0, 0, 0, 255,      128, 128, 128, 255,
        255, 0, 0, 255,    255, 255, 255, 255,
    ];
    write_png(&path, 2, 2, PngLayout::Rgba8, &rgba).unwrap();
    let t = read_toon_texture(&path).unwrap();
    assert_eq!((t.width(), t.height()), (2, 2));
    assert_eq!(t.sample(-1.0, 1.0), Vec3::ZERO);
    assert_eq!(
        t.sample(1.0, 1.0),
        Vec3::splat(srgb_to_linear(128.0 / 255.0))
    );
    assert!((t.sample(1.0, 1.0).x - 0.2159).abs() < 1e-4);
    assert_eq!(t.sample(-1.0, 0.0), Vec3::X);
    assert_eq!(t.sample(1.0, 0.0), Vec3::ONE);
}

#[test]
fn the_shipped_textures_are_what_the_generator_makes() {
    let dir = crate::common::root().join("textures");
    for family in Family::ALL {
        let path = dir.join(format!("{}.png", family.name()));
        let shipped = image::open(&path)
            .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
            .to_rgba8();
        let made = family.image();
        assert_eq!(
            (shipped.width() as usize, shipped.height() as usize),
            (made.width, made.height),
            "{}",
            path.display()
        );
        assert!(
            shipped.as_raw() == &made.rgba,
            "{} differs from the generator; remake it with `cargo run --example toon_textures`",
            path.display()
        );
        // And it loads as a texture.
        read_toon_texture(&path).unwrap();
    }
}
