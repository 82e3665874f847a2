//! The 3 × 3 neighbourhood of a pixel: the pixel and its eight neighbours inside the image.

/// The indices of pixel `pixel`'s 3 × 3 neighbourhood (itself included) in a `width × height`
/// image, row by row; fewer at the image's border.
pub(super) fn around(pixel: usize, (width, height): (usize, usize)) -> impl Iterator<Item = usize> {
    let (x, y) = (pixel % width, pixel / width);
    (y.saturating_sub(1)..=(y + 1).min(height - 1)).flat_map(move |ny| {
        (x.saturating_sub(1)..=(x + 1).min(width - 1)).map(move |nx| ny * width + nx)
    })
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
