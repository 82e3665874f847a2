//! Dilation of a grid of flags by a square: every flag within a radius of a set one.

/// Sets every flag of the `width × height` grid `flags` within `radius` (in x and in y: a
/// square) of one that is set, in time linear in the grid: a sliding count along each row, then
/// one down the columns, a row at a time. `rows` is scratch.
pub(in crate::render) fn dilate(
    flags: &mut [bool],
    (width, height): (usize, usize),
    radius: usize,
    (rows, counts): (&mut Vec<bool>, &mut Vec<u32>),
) {
    if radius == 0 {
        return;
    }
    // Along the rows, into `rows`.
    rows.clear();
    rows.resize(width * height, false);
    for (row, out) in flags.chunks(width).zip(rows.chunks_mut(width)) {
        let mut set = row[..radius.min(width)].iter().filter(|&&f| f).count();
        for (x, o) in out.iter_mut().enumerate() {
            if let Some(&f) = row.get(x + radius) {
                set += usize::from(f);
            }
            *o = set > 0;
            if x >= radius {
                set -= usize::from(row[x - radius]);
            }
        }
    }
    // Down the columns: `counts[x]` is the set flags of column x among rows y − radius ..= y + radius.
    counts.clear();
    counts.resize(width, 0);
    for row in rows.chunks(width).take(radius) {
        for (c, &f) in counts.iter_mut().zip(row) {
            *c += u32::from(f);
        }
    }
    for y in 0..height {
        if let Some(entering) = rows.get((y + radius) * width..(y + radius + 1) * width) {
            for (c, &f) in counts.iter_mut().zip(entering) {
                *c += u32::from(f);
            }
        }
        for (o, &c) in flags[y * width..(y + 1) * width]
            .iter_mut()
            .zip(counts.iter())
        {
            *o = c > 0;
        }
        if y >= radius {
            let leaving = &rows[(y - radius) * width..(y - radius + 1) * width];
            for (c, &f) in counts.iter_mut().zip(leaving) {
                *c -= u32::from(f);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dilation_sets_exactly_the_square_around_each_set_flag() {
        // Against the definition, on grids with flags at corners, edges and inside.
        let (w, h) = (9usize, 7usize);
        let set = [(0usize, 0usize), (8, 3), (4, 6), (5, 2)];
        for radius in 0..=4 {
            let mut flags = vec![false; w * h];
            for &(x, y) in &set {
                flags[y * w + x] = true;
            }
            let mut scratch = (Vec::new(), Vec::new());
            dilate(&mut flags, (w, h), radius, (&mut scratch.0, &mut scratch.1));
            for y in 0..h {
                for x in 0..w {
                    let near = set
                        .iter()
                        .any(|&(sx, sy)| sx.abs_diff(x) <= radius && sy.abs_diff(y) <= radius);
                    assert_eq!(flags[y * w + x], near, "({x}, {y}) at radius {radius}");
                }
            }
        }
    }
}
