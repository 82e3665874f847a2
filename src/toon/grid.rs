//! A grid of vectors read bilinearly between its samples and clamped to its edges: the 2D toon
//! texture and the smoothed shape's normals are each one.

use glam::{Vec3, Vec3A};

use crate::math::LANES;

/// `rows × columns` vectors, read at continuous coordinates `(row, column)` with the samples at
/// whole numbers. Its `Debug` prints its size and a digest of its values, not the values: what
/// a frame's fingerprint reads of a texture or a smoothed shape, in a line, however large.
#[derive(Clone, PartialEq)]
pub(super) struct Grid {
    /// Row by row, each row ending in a copy of its last value, and a copy of the last row so
    /// extended at the bottom: the four values around a point are then always at `k`, `k + 1`,
    /// `k + stride` and `k + stride + 1`, the copies taking weight 0 at the last row or column.
    values: Vec<Vec3A>,
    /// Entries per padded row: `columns + 1`.
    stride: usize,
    rows: usize,
    /// The last row's and the last column's coordinate.
    last_row: f32,
    last_column: f32,
    /// SHA-256 of the values' bits, in order: equal for equal grids, and for two grids that
    /// differ by a bit, different but with negligible chance.
    digest: [u8; 16],
}

impl std::fmt::Debug for Grid {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Grid")
            .field("rows", &self.rows)
            .field("columns", &self.columns())
            .field("digest", &Digest(&self.digest))
            .finish()
    }
}

/// A digest printed as hex digits.
struct Digest<'a>(&'a [u8]);

impl std::fmt::Debug for Digest<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.0.iter().try_for_each(|b| write!(f, "{b:02x}"))
    }
}

/// The first 16 bytes of the SHA-256 of `values`' bits, in order.
#[must_use]
fn digest_of(values: &[Vec3A]) -> [u8; 16] {
    use sha2::Digest as _;
    let mut hash = sha2::Sha256::new();
    for v in values {
        for x in v.to_array() {
            hash.update(x.to_bits().to_le_bytes());
        }
    }
    let full = hash.finalize();
    let mut digest = [0; 16];
    digest.copy_from_slice(&full[..16]);
    digest
}

impl Grid {
    /// The grid of `values` given row by row in rows of `columns`; `values` holds at least one
    /// row, and whole rows, fewer than 2²² of them and of columns, and a `u32` counts the
    /// padded grid's entries.
    ///
    /// # Panics
    /// If it does not.
    pub fn new(values: &[Vec3], columns: usize) -> Self {
        assert!(
            columns > 0 && !values.is_empty() && values.len() % columns == 0,
            "a grid of whole rows"
        );
        let rows = values.len() / columns;
        assert!(
            rows < MAX_SIDE
                && columns < MAX_SIDE
                && (rows + 1) * (columns + 1) <= u32::MAX as usize,
            "a grid of less than 2²² per side, whose entries a u32 counts"
        );
        let padded_rows = values
            .chunks(columns)
            .chain(values.rchunks(columns).take(1));
        let values: Vec<Vec3A> = padded_rows
            .flat_map(|row| row.iter().chain(row.last()).map(|&v| Vec3A::from(v)))
            .collect();
        Self {
            digest: digest_of(&values),
            values,
            stride: columns + 1,
            rows,
            last_row: (rows - 1) as f32,
            last_column: (columns - 1) as f32,
        }
    }

    /// The number of rows.
    #[must_use]
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// The number of columns.
    #[must_use]
    pub fn columns(&self) -> usize {
        self.stride - 1
    }

    /// The sample in `row` and `column`, each clamped to the grid.
    #[must_use]
    pub fn sample(&self, row: usize, column: usize) -> Vec3 {
        let (row, column) = (row.min(self.rows - 1), column.min(self.columns() - 1));
        self.values[row * self.stride + column].into()
    }

    /// For k < `n` ≤ [`LANES`], the value at `(row(k), column(k))` into `put(k, value)`: with each
    /// coordinate clamped to the grid (NaN reads 0), `r = ⌊row⌋`, `c = ⌊column⌋` and
    /// `(a, b) = (row − r, column − c)`,
    /// `lerp(lerp(g[r][c], g[r][c+1], b), lerp(g[r+1][c], g[r+1][c+1], b), a)`.
    ///
    /// The cells (as the index of their first value) and weights of all n points come first,
    /// in a loop of their own that vectorizes; then the reads.
    ///
    /// # Panics
    /// If `n` is more than [`LANES`].
    #[inline(always)]
    pub fn bilinear(
        &self,
        n: usize,
        row: impl Fn(usize) -> f32,
        column: impl Fn(usize) -> f32,
        mut put: impl FnMut(usize, Vec3),
    ) {
        assert!(n <= LANES, "bad run");
        let mut at = [0u32; LANES];
        let (mut a, mut b) = ([0.0f32; LANES], [0.0f32; LANES]);
        let stride = self.stride as u32;
        for k in 0..n {
            // `max` then `min` clamps, and takes NaN to 0.
            let r = row(k).max(0.0).min(self.last_row);
            let c = column(k).max(0.0).min(self.last_column);
            let (cell_row, cell_column) = (floor(r), floor(c));
            (a[k], b[k]) = (r - cell_row as f32, c - cell_column as f32);
            at[k] = cell_row as u32 * stride + cell_column as u32;
        }
        for k in 0..n {
            let at = at[k] as usize;
            // One bounds check for the four values.
            let around = &self.values[at..at + self.stride + 2];
            let (this, next) = (&around[..2], &around[self.stride..]);
            let value = lerp(
                lerp(this[0], this[1], b[k]),
                lerp(next[0], next[1], b[k]),
                a[k],
            );
            put(k, value.into());
        }
    }
}

/// `p + (q − p) s`: `p` itself at `s = 0`, with fewer operations than glam's `lerp`.
#[inline(always)]
fn lerp(p: Vec3A, q: Vec3A, s: f32) -> Vec3A {
    p + (q - p) * s
}

/// The most rows or columns a grid may have: its coordinates stay where [`floor`] holds.
const MAX_SIDE: usize = 1 << 22;

/// `⌊x⌋` for `0 ≤ x < 2²²`: `x + 2²³` is rounded to a whole number, which then sits in the low
/// bits of its representation (`0x4B00_0000` is that of 2²³), and one less is taken where
/// that rounded up. Unlike `x as i32`, which must saturate, the steps vectorize.
#[inline(always)]
fn floor(x: f32) -> i32 {
    const TWO_TO_23: f32 = 8_388_608.0;
    let rounded = (x + TWO_TO_23).to_bits() as i32 - TWO_TO_23.to_bits() as i32;
    rounded - i32::from(rounded as f32 > x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bilinear_weights_and_clamping() {
        // 2 rows × 3 columns, value (row, column, 0).
        let values: Vec<Vec3> = (0..2)
            .flat_map(|r| (0..3).map(move |c| Vec3::new(r as f32, c as f32, 0.0)))
            .collect();
        let grid = Grid::new(&values, 3);
        let points = [
            (0.25, 1.5, Vec3::new(0.25, 1.5, 0.0)),
            (1.0, 2.0, Vec3::new(1.0, 2.0, 0.0)),
            (-3.0, 7.0, Vec3::new(0.0, 2.0, 0.0)),
            (f32::NAN, f32::INFINITY, Vec3::new(0.0, 2.0, 0.0)),
        ];
        let mut got = [Vec3::NAN; 4];
        grid.bilinear(4, |k| points[k].0, |k| points[k].1, |k, v| got[k] = v);
        for (g, (.., want)) in got.iter().zip(points) {
            assert!((*g - want).length() < 1e-6, "{g} against {want}");
        }
        assert_eq!(grid.sample(5, 1), Vec3::new(1.0, 1.0, 0.0));
    }

    #[test]
    fn floor_of_the_coordinates() {
        let below = |x: f32| f32::from_bits(x.to_bits() - 1);
        for x in [
            0.0, 0.25, 0.5, 1.0, 1.5, 2.5, 7.999, 4095.0, 4095.5, 65_536.75,
        ] {
            assert_eq!(floor(x), x.floor() as i32, "{x}");
            if x >= 1.0 {
                assert_eq!(floor(below(x)), below(x).floor() as i32, "below {x}");
            }
        }
        let largest = below(MAX_SIDE as f32);
        assert_eq!(floor(largest), largest.floor() as i32);
    }
}
