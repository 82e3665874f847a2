//! The 3 × 3 neighbourhood of a pixel: the pixel and its eight neighbours inside the image.

use super::gbuffer::{GBuffer, Texel, EMPTY};

/// The indices of pixel `pixel`'s 3 × 3 neighbourhood (itself included) in a `width × height`
/// image, row by row; fewer at the image's border.
pub(super) fn around(pixel: usize, (width, height): (usize, usize)) -> impl Iterator<Item = usize> {
    let (x, y) = (pixel % width, pixel / width);
    (y.saturating_sub(1)..=(y + 1).min(height - 1)).flat_map(move |ny| {
        (x.saturating_sub(1)..=(x + 1).min(width - 1)).map(move |nx| ny * width + nx)
    })
}

/// The slots of the texels of texel `t`'s 3 × 3 neighbourhood in `gbuffer` (`[y][x]`, `t` at
/// `[1][1]`), when all nine pixels lie inside the image, are covered and show `t`'s patch
/// (`patches`: per slot, its texel's patch); `None` otherwise.
#[must_use]
pub(super) fn one_patch_around(
    gbuffer: &GBuffer,
    patches: &[u32],
    t: &Texel,
) -> Option<[[usize; 3]; 3]> {
    let (w, h) = (gbuffer.width as usize, gbuffer.height as usize);
    let i = t.pixel as usize;
    let (x, y) = (i % w, i / w);
    if x == 0 || y == 0 || x + 1 >= w || y + 1 >= h {
        return None;
    }
    let mut slots = [[0usize; 3]; 3];
    for (dy, row) in slots.iter_mut().enumerate() {
        for (dx, slot) in row.iter_mut().enumerate() {
            let n = gbuffer.slot[(y + dy - 1) * w + x + dx - 1];
            if n == EMPTY || patches[n as usize] != t.patch {
                return None;
            }
            *slot = n as usize;
        }
    }
    Some(slots)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nine_inside_fewer_at_corners_and_edges() {
        let size = (4, 3);
        assert_eq!(
            around(5, size).collect::<Vec<_>>(),
            [0, 1, 2, 4, 5, 6, 8, 9, 10]
        );
        assert_eq!(around(0, size).collect::<Vec<_>>(), [0, 1, 4, 5]);
        assert_eq!(around(11, size).collect::<Vec<_>>(), [6, 7, 10, 11]);
        assert_eq!(around(1, size).collect::<Vec<_>>(), [0, 1, 2, 4, 5, 6]);
    }
}
