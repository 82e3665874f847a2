//! Error measures between a rendered highlight matte and the reference coverage, both per pixel
//! in [0, 1] on the same image, rows from the top.

/// The soft intersection over union `Σ min(a, b) / Σ max(a, b)`: for hard mattes (0 or 1) the
/// plain IoU of the two regions. `None` when both are empty.
pub fn iou(rendered: &[f32], reference: &[f32]) -> Option<f64> {
    let (both, either) = rendered
        .iter()
        .zip(reference)
        .fold((0.0f64, 0.0f64), |(both, either), (&a, &b)| {
            (both + f64::from(a.min(b)), either + f64::from(a.max(b)))
        });
    (either > 0.0).then(|| both / either)
}

/// The length in pixels of the reference region's boundary: the ½ level line of its coverage
/// image, traced by marching squares over the cells between pixel centres (values outside the
/// image are 0; each cell edge whose ends straddle ½ is cut where the linear interpolation
/// crosses it, and the cuts of a cell are joined in edge order).
pub fn boundary_length(coverage: &[f32], width: usize) -> f64 {
    let height = coverage.len() / width.max(1);
    let at = |x: isize, y: isize| -> f64 {
        if (0..width as isize).contains(&x) && (0..height as isize).contains(&y) {
            f64::from(coverage[y as usize * width + x as usize])
        } else {
            0.0
        }
    };
    let mut length = 0.0;
    for y in -1..height as isize {
        for x in -1..width as isize {
            // The cell's corners in order around it, as (x, y, value).
            let corners = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
                .map(|(dx, dy): (f64, f64)| (dx, dy, at(x + dx as isize, y + dy as isize)));
            let mut cuts = [(0.0, 0.0); 4];
            let mut count = 0;
            for edge in 0..4 {
                let (ax, ay, a) = corners[edge];
                let (bx, by, b) = corners[(edge + 1) % 4];
                if (a >= 0.5) != (b >= 0.5) {
                    let t = (0.5 - a) / (b - a);
                    cuts[count] = (ax + t * (bx - ax), ay + t * (by - ay));
                    count += 1;
                }
            }
            for pair in cuts[..count].chunks_exact(2) {
                length += (pair[1].0 - pair[0].0).hypot(pair[1].1 - pair[0].1);
            }
        }
    }
    length
}

/// The mean displacement, in pixels, of the rendered highlight's boundary from the reference's:
/// the area between them `Σ |a − c|` divided by the reference boundary's length
/// ([`boundary_length`]). A boundary moved by `d` pixels along its normal everywhere gives `d`;
/// hard edges on an exact boundary give the mean sampling error of the edge pixels. `None` when
/// the reference has no boundary.
pub fn boundary_displacement(rendered: &[f32], reference: &[f32], width: usize) -> Option<f64> {
    let length = boundary_length(reference, width);
    let area: f64 = rendered
        .iter()
        .zip(reference)
        .map(|(&a, &c)| f64::from((a - c).abs()))
        .sum();
    (length > 0.0).then(|| area / length)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A `size × size` coverage image of the disc of `radius` about `centre`, `k × k` samples
    /// per pixel.
    fn disc(size: usize, centre: (f64, f64), radius: f64, k: usize) -> Vec<f32> {
        (0..size * size)
            .map(|i| {
                let (px, py) = ((i % size) as f64, (i / size) as f64);
                let hits = (0..k * k)
                    .filter(|s| {
                        let x = px + ((s % k) as f64 + 0.5) / k as f64 - centre.0;
                        let y = py + ((s / k) as f64 + 0.5) / k as f64 - centre.1;
                        x * x + y * y < radius * radius
                    })
                    .count();
                hits as f32 / (k * k) as f32
            })
            .collect()
    }

    #[test]
    fn iou_of_two_overlapping_squares_is_their_shared_fraction() {
        let square = |x0: usize| -> Vec<f32> {
            (0..100)
                .map(|i| f32::from(u8::from((x0..x0 + 4).contains(&(i % 10)) && i / 10 < 4)))
                .collect()
        };
        // 4 × 4 squares shifted by 2 columns: shared 8, union 24.
        let score = iou(&square(0), &square(2)).unwrap();
        assert!((score - 8.0 / 24.0).abs() < 1e-12, "{score}");
        assert_eq!(iou(&[0.0; 4], &[0.0; 4]), None);
    }

    #[test]
    fn boundary_length_of_a_disc_is_its_circumference() {
        let radius = 30.0;
        let length = boundary_length(&disc(100, (50.0, 50.0), radius, 8), 100);
        let circumference = std::f64::consts::TAU * radius;
        assert!(
            (length / circumference - 1.0).abs() < 0.01,
            "{length} vs {circumference}"
        );
    }

    #[test]
    fn displacement_of_a_grown_disc_is_the_growth() {
        let truth = disc(120, (60.0, 60.0), 30.0, 8);
        let grown = disc(120, (60.0, 60.0), 32.0, 8);
        let d = boundary_displacement(&grown, &truth, 120).unwrap();
        // The area between the circles over the inner circumference: (32² − 30²) / 60 = 2.07.
        assert!((d - 2.07).abs() < 0.08, "{d}");
        let hard = disc(120, (60.0, 60.0), 30.0, 1);
        let sampled = boundary_displacement(&hard, &truth, 120).unwrap();
        let smooth = boundary_displacement(&disc(120, (60.0, 60.0), 30.0, 4), &truth, 120);
        assert!(sampled > 0.1 && sampled < 0.4, "{sampled}");
        assert!(smooth.unwrap() < 0.5 * sampled);
    }
}
