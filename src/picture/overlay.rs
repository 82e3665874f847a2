//! Marks drawn over a rendered frame for the person tuning it: patch seams, the highlight
//! matte, and pin points — each on an sRGB RGBA8 image, rows from the top.

/// Darkens the pixels where the patch changes to the right or below (a seam between patches,
/// or the silhouette against the background): `ids` holds a patch index per pixel, `u32::MAX`
/// on the background.
pub fn draw_seams(rgba: &mut [u8], ids: &[u32], width: u32, height: u32) {
    let (w, h) = (width as usize, height as usize);
    for y in 0..h {
        for x in 0..w {
            let id = ids[y * w + x];
            let right = (x + 1 < w).then(|| ids[y * w + x + 1]);
            let below = (y + 1 < h).then(|| ids[(y + 1) * w + x]);
            let seam = [right, below]
                .into_iter()
                .flatten()
                .any(|other| other != id && (other != u32::MAX || id != u32::MAX));
            if seam {
                let at = (y * w + x) * 4;
                blend(&mut rgba[at..at + 4], [20, 20, 28], 0.8);
            }
        }
    }
}

/// Tints the highlight matte magenta in proportion to its coverage, and draws its edge (where
/// coverage crosses ½ between neighbours) solid.
pub fn draw_matte(rgba: &mut [u8], matte: &[f32], width: u32, height: u32) {
    const MAGENTA: [u8; 3] = [255, 0, 200];
    let (w, h) = (width as usize, height as usize);
    for y in 0..h {
        for x in 0..w {
            let m = matte[y * w + x].clamp(0.0, 1.0);
            let inside = m >= 0.5;
            let edge = [
                (x + 1 < w).then(|| matte[y * w + x + 1]),
                (y + 1 < h).then(|| matte[(y + 1) * w + x]),
            ]
            .into_iter()
            .flatten()
            .any(|other| (other >= 0.5) != inside);
            let at = (y * w + x) * 4;
            if edge {
                blend(&mut rgba[at..at + 4], MAGENTA, 1.0);
            } else if m > 0.0 {
                blend(&mut rgba[at..at + 4], MAGENTA, 0.45 * m);
            }
        }
    }
}

/// Draws a pin marker centred on image position `(x, y)` (a pixel's centre at integer values):
/// a ring of radius 6 px in yellow with a dark outline, and a dot at its centre. Parts outside
/// the image are clipped.
pub fn draw_pin(rgba: &mut [u8], width: u32, height: u32, (x, y): (f64, f64)) {
    if !(x.is_finite() && y.is_finite()) {
        return;
    }
    let (cx, cy) = (x.round() as i64, y.round() as i64);
    for dy in -9i64..=9 {
        for dx in -9i64..=9 {
            let (px, py) = (cx + dx, cy + dy);
            if px < 0 || py < 0 || px >= i64::from(width) || py >= i64::from(height) {
                continue;
            }
            let r = ((dx * dx + dy * dy) as f64).sqrt();
            let colour = if (5.0..=7.0).contains(&r) || r <= 1.5 {
                [255, 220, 0]
            } else if (4.0..5.0).contains(&r) || (7.0..8.0).contains(&r) {
                [0, 0, 0]
            } else {
                continue;
            };
            let at = (py as usize * width as usize + px as usize) * 4;
            blend(&mut rgba[at..at + 4], colour, 1.0);
        }
    }
}

/// `pixel` mixed toward opaque `colour` by `amount` ∈ [0, 1].
fn blend(pixel: &mut [u8], colour: [u8; 3], amount: f32) {
    for c in 0..3 {
        let mixed = f32::from(pixel[c]) * (1.0 - amount) + f32::from(colour[c]) * amount;
        pixel[c] = mixed.round() as u8;
    }
    let alpha = f32::from(pixel[3]) * (1.0 - amount) + 255.0 * amount;
    pixel[3] = alpha.round() as u8;
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seams_fall_where_the_patch_changes() {
        // Two patches side by side over a background row.
        let (w, h) = (4, 2);
        let ids = [0, 0, 1, 1, u32::MAX, u32::MAX, u32::MAX, u32::MAX];
        let mut rgba = vec![255u8; w * h * 4];
        draw_seams(&mut rgba, &ids, w as u32, h as u32);
        let dark: Vec<bool> = rgba.chunks(4).map(|p| p[0] < 128).collect();
        // Pixel 1 meets patch 1 to its right; every top pixel meets the background below.
        assert_eq!(dark, [true, true, true, true, false, false, false, false]);
    }

    #[test]
    fn the_matte_edge_is_drawn_solid_and_its_inside_tinted() {
        let (w, h) = (3, 1);
        let matte = [1.0, 1.0, 0.0];
        let mut rgba = [0u8, 0, 0, 255].repeat(3);
        draw_matte(&mut rgba, &matte, w, h);
        assert_eq!(&rgba[4..8], &[255, 0, 200, 255], "the edge, solid");
        assert!(rgba[0] > 0 && rgba[0] < 255, "inside, tinted");
        assert_eq!(&rgba[8..12], &[0, 0, 0, 255], "outside, untouched");
    }

    #[test]
    fn a_pin_is_drawn_around_its_point_and_clipped_at_the_border() {
        let (w, h) = (20u32, 20u32);
        let mut rgba = vec![0u8; (w * h * 4) as usize];
        draw_pin(&mut rgba, w, h, (1.0, 10.0));
        let at = |x: usize, y: usize| &rgba[(y * w as usize + x) * 4..][..4];
        assert_eq!(at(1, 10), &[255, 220, 0, 255], "the centre dot");
        assert_eq!(at(7, 10), &[255, 220, 0, 255], "the ring, 6 px right");
        assert_eq!(at(4, 10)[3], 0, "inside the ring, untouched");
        draw_pin(&mut rgba, w, h, (f64::NAN, 0.0));
    }
}
