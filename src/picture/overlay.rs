//! Marks drawn over a rendered frame for the person tuning it: patch seams, the highlight
//! matte, the cel bands' edges, pin points and their tracks, and a layer's centres — each on an
//! sRGB RGBA8 image, rows from the top.

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

/// Draws the edges of the cel bands — the terminator and every other band's edge — in cyan:
/// where the band of `N·L'` (`n_dot_l`, per pixel) changes to the right or below between two
/// pixels of patches toned alike. `tone` gives, per patch index (`ids`, `u32::MAX` on the
/// background), its tone's number and its band thresholds in increasing order (`None`: no cel
/// bands), so that an edge is drawn only between pixels whose bands are counted the same way.
pub fn draw_band_edges(
    rgba: &mut [u8],
    n_dot_l: &[f32],
    ids: &[u32],
    (width, height): (u32, u32),
    tone: impl Fn(u32) -> Option<(usize, Vec<f32>)>,
) {
    const CYAN: [u8; 3] = [0, 230, 255];
    let (w, h) = (width as usize, height as usize);
    // Each patch's tone, asked once.
    let patches = ids
        .iter()
        .filter(|&&id| id != u32::MAX)
        .max()
        .map_or(0, |&m| m as usize + 1);
    let tones: Vec<Option<(usize, Vec<f32>)>> = (0..patches as u32).map(&tone).collect();
    // Per pixel: its tone's number and its band (how many thresholds N·L' reaches).
    let bands: Vec<Option<(usize, usize)>> = (0..w * h)
        .map(|p| {
            let (k, thresholds) = tones.get(ids[p] as usize)?.as_ref()?;
            Some((
                *k,
                thresholds.iter().take_while(|&&t| n_dot_l[p] >= t).count(),
            ))
        })
        .collect();
    for y in 0..h {
        for x in 0..w {
            let Some((tone, band)) = bands[y * w + x] else {
                continue;
            };
            let edge = [
                (x + 1 < w).then(|| y * w + x + 1),
                (y + 1 < h).then(|| (y + 1) * w + x),
            ]
            .into_iter()
            .flatten()
            .any(|n| matches!(bands[n], Some((t, b)) if t == tone && b != band));
            if edge {
                let at = (y * w + x) * 4;
                blend(&mut rgba[at..at + 4], CYAN, 1.0);
            }
        }
    }
}

/// Paints opaque `colour_at(dx, dy)` on every pixel within `reach` pixels (a square) of image
/// position `(x, y)` where it gives one; parts outside the image are clipped, and a position
/// that is not finite paints nothing.
fn stamp(
    rgba: &mut [u8],
    (width, height): (u32, u32),
    (x, y): (f64, f64),
    reach: i64,
    colour_at: impl Fn(i64, i64) -> Option<[u8; 3]>,
) {
    if !(x.is_finite() && y.is_finite()) {
        return;
    }
    let (cx, cy) = (x.round() as i64, y.round() as i64);
    for dy in -reach..=reach {
        for dx in -reach..=reach {
            let (px, py) = (cx + dx, cy + dy);
            if px < 0 || py < 0 || px >= i64::from(width) || py >= i64::from(height) {
                continue;
            }
            if let Some(colour) = colour_at(dx, dy) {
                let at = (py as usize * width as usize + px as usize) * 4;
                blend(&mut rgba[at..at + 4], colour, 1.0);
            }
        }
    }
}

/// The distance of `(dx, dy)` from the origin.
fn radius(dx: i64, dy: i64) -> f64 {
    ((dx * dx + dy * dy) as f64).sqrt()
}

/// Draws a pin marker centred on image position `(x, y)` (a pixel's centre at integer values):
/// a ring of radius 6 px in yellow with a dark outline, and a dot at its centre. Parts outside
/// the image are clipped.
pub fn draw_pin(rgba: &mut [u8], width: u32, height: u32, at: (f64, f64)) {
    stamp(rgba, (width, height), at, 9, |dx, dy| {
        let r = radius(dx, dy);
        if (5.0..=7.0).contains(&r) || r <= 1.5 {
            Some([255, 220, 0])
        } else if (4.0..5.0).contains(&r) || (7.0..8.0).contains(&r) {
            Some([0, 0, 0])
        } else {
            None
        }
    });
}

/// Draws a pin's track: a yellow dot of radius 1.5 px on each image position of `points`, each
/// with a dark rim, the rims first so that no dot hides another's centre and a shot's worth of
/// them reads as a path. Parts outside the image are clipped.
pub fn draw_track(rgba: &mut [u8], width: u32, height: u32, points: &[(f64, f64)]) {
    for (reach, colour) in [(2.5, [0, 0, 0]), (1.5, [255, 220, 0])] {
        for &at in points {
            stamp(rgba, (width, height), at, 3, |dx, dy| {
                (radius(dx, dy) <= reach).then_some(colour)
            });
        }
    }
}

/// Draws a highlight centre's marker on image position `(x, y)` (a pixel's centre at integer
/// values): a magenta cross whose four arms, 3 px wide, run from 3 to 8 px off the point, each
/// with a dark outline, so that the point itself stays in view. Parts outside the image are
/// clipped.
pub fn draw_centre(rgba: &mut [u8], width: u32, height: u32, at: (f64, f64)) {
    // Whether (dx, dy) lies on an arm of half width `w` running from `from` to `to` px out.
    let on_arm = |dx: i64, dy: i64, w: i64, from: i64, to: i64| {
        let along = |a: i64, b: i64| b.abs() <= w && (from..=to).contains(&a.abs());
        along(dx, dy) || along(dy, dx)
    };
    stamp(rgba, (width, height), at, 9, |dx, dy| {
        if on_arm(dx, dy, 1, 3, 8) {
            Some([255, 60, 200])
        } else if on_arm(dx, dy, 2, 2, 9) {
            Some([0, 0, 0])
        } else {
            None
        }
    });
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
    fn band_edges_are_drawn_where_the_band_changes_between_pixels_toned_alike() {
        // One row: patches 0 and 1 share a tone with its threshold at 0.3, patch 2 has another
        // at 0.5; the background after.
        let n_dot_l = [0.1, 0.2, 0.4, 0.45, 0.35, 0.6, 0.0];
        let ids = [0, 0, 0, 1, 2, 2, u32::MAX];
        let mut rgba = [0u8, 0, 0, 255].repeat(7);
        draw_band_edges(&mut rgba, &n_dot_l, &ids, (7, 1), |id| match id {
            0 | 1 => Some((0, vec![0.3])),
            _ => Some((1, vec![0.5])),
        });
        let cyan: Vec<bool> = rgba.chunks(4).map(|p| p[..3] == [0, 230, 255]).collect();
        // 0.2 → 0.4 crosses 0.3 (drawn); 0.45 → 0.35 on another tone (not); 0.35 → 0.6 crosses
        // 0.5 (drawn); nothing against the background.
        assert_eq!(cyan, [false, true, false, false, true, false, false]);
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
