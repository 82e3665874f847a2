//! An op stack: the operations of a layer in order, applied to the initial highlight vector.

use glam::Vec3;

use super::layer_frame::PreparedFrame;
use super::ops::PreparedOp;
use super::point_chunk::PointChunk;
use crate::math::{normalize_lanes, Lanes, LANES};

/// Validated operations in order, with a normalization plan.
///
/// Each operation of Anjyo & Hiramitsu 2003 ends by normalizing. Rotation, scaling and tangent squaring are
/// homogeneous (`op(cH) = c op(H)` for c > 0), so the stack normalizes only where the next
/// operation needs a unit H ([`PreparedOp::needs_unit_input`]) and at the end: the same direction
/// as normalizing after every op, with fewer square roots and divisions. An op whose output is
/// (nearly) zero relative to its input keeps its input, as when normalizing after every op.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PreparedStack {
    /// Each op, and whether to normalize the running vector before it.
    steps: Vec<(PreparedOp, bool)>,
    /// Whether to normalize after the last op.
    normalize_output: bool,
}

impl PreparedStack {
    /// The stack of `ops`, applied in order.
    #[must_use]
    pub fn new(ops: impl IntoIterator<Item = PreparedOp>) -> Self {
        // `stale`: an op has run since the running vector was last unit.
        let mut stale = false;
        let steps = ops
            .into_iter()
            .map(|op| {
                let normalize = stale && op.needs_unit_input();
                stale = true;
                (op, normalize)
            })
            .collect();
        Self {
            steps,
            normalize_output: stale,
        }
    }

    /// The stack applied to unit H in frame coordinates `l`; a unit vector in frame coordinates.
    #[inline]
    #[must_use]
    pub fn apply_local(&self, l: Vec3) -> Vec3 {
        let mut h = l;
        for &(op, normalize) in &self.steps {
            if normalize {
                h = unit_or(h, l);
            }
            h = op.step(h);
        }
        if self.normalize_output {
            unit_or(h, l)
        } else {
            h
        }
    }

    /// [`apply_local`](Self::apply_local) on a chunk of vectors, op by op: `c` holds a copy of
    /// `initial` on entry and the results on return.
    pub(crate) fn apply_chunk(&self, initial: &LocalChunk, c: &mut LocalChunk) {
        debug_assert_eq!(initial.len, c.len);
        let (x, y, z) = c.lanes_mut();
        let normalize = |x: &mut [f32], y: &mut [f32], z: &mut [f32]| {
            normalize_lanes(x, y, z, |i, h| unit_or(h, initial.get(i)));
        };
        for &(op, normalize_first) in &self.steps {
            if normalize_first {
                normalize(x, y, z);
            }
            op.step_all(x, y, z);
        }
        if self.normalize_output {
            normalize(x, y, z);
        }
    }
}

/// Frame coordinates of up to [`LANES`] vectors, one array per coordinate, so that loops over
/// them vectorize.
#[derive(Clone, Copy, Debug, Default)]
pub struct LocalChunk {
    vectors: Lanes,
    len: usize,
}

impl LocalChunk {
    /// Replaces the contents by each point's initial highlight vector in the layer frame
    /// `frame` at it ([`PreparedFrame::local`]): the one place where a layer's chunk of world
    /// vectors becomes its frame's coordinates.
    pub fn load_in(&mut self, frame: PreparedFrame, points: &PointChunk) {
        let (frames, hs) = (points.frames(), points.half_vectors());
        self.set(points.len(), |i| frame.local(&frames[i], hs[i]));
    }

    /// Replaces the contents by `local(i)` for i < `len`: vectors already in frame coordinates.
    ///
    /// # Panics
    /// If `len` is more than [`LANES`].
    #[inline]
    pub fn set(&mut self, len: usize, local: impl Fn(usize) -> Vec3) {
        assert!(len <= LANES, "bad chunk");
        self.len = len;
        let (x, y, z) = self.lanes_mut();
        for i in 0..len {
            (x[i], y[i], z[i]) = local(i).into();
        }
    }

    /// Vector `i`.
    #[inline]
    #[must_use]
    pub fn get(&self, i: usize) -> Vec3 {
        self.vectors.get(i)
    }

    /// The coordinate arrays `(t_u, t_v, h_n)`, each of length [`len`](Self::len).
    #[inline]
    #[must_use]
    pub fn lanes(&self) -> (&[f32], &[f32], &[f32]) {
        let (n, v) = (self.len, &self.vectors);
        (&v.x[..n], &v.y[..n], &v.z[..n])
    }

    #[inline]
    fn lanes_mut(&mut self) -> (&mut [f32], &mut [f32], &mut [f32]) {
        let (n, v) = (self.len, &mut self.vectors);
        (&mut v.x[..n], &mut v.y[..n], &mut v.z[..n])
    }
}

/// `h / ‖h‖`, or `fallback` if `‖h‖²` underflows. Each step keeps the running vector above 10⁻⁶
/// of its input's length, so this needs several near-total scalings in a row.
#[inline(always)]
fn unit_or(h: Vec3, fallback: Vec3) -> Vec3 {
    let len2 = h.length_squared();
    let unit = h * len2.sqrt().recip();
    if len2 >= f32::MIN_POSITIVE {
        unit
    } else {
        fallback
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::highlight::{Axis, Op, SquareStyle, TangentFrame};

    /// `hs` in the frame `(x, y, z)`, as a chunk.
    fn chunk_of(hs: &[Vec3]) -> LocalChunk {
        let mut points = PointChunk::default();
        let frames = vec![TangentFrame::new(Vec3::X, Vec3::Y, Vec3::Z); hs.len()];
        points.load(&frames, hs);
        let mut chunk = LocalChunk::default();
        chunk.load_in(PreparedFrame::Patch, &points);
        chunk
    }

    fn ops() -> Vec<PreparedOp> {
        [
            Op::Translate {
                alpha: 0.3,
                beta: -0.1,
            },
            Op::Rotate { degrees: 25.0 },
            Op::Scale {
                delta: 0.7,
                axis: Axis::Angle(10.0),
            },
            Op::Split {
                gamma_u: 0.1,
                gamma_v: 0.05,
            },
            Op::Square {
                sigma: 0.4,
                n: 2.5,
                style: SquareStyle::Tangent,
            },
            Op::Square {
                sigma: 0.4,
                n: 3.0,
                style: SquareStyle::PerAxis,
            },
        ]
        .iter()
        .map(|op| op.prepare().unwrap())
        .collect()
    }

    #[test]
    fn plan_normalizes_only_before_ops_needing_unit_input() {
        let s = PreparedStack::new(ops());
        let plan: Vec<bool> = s.steps.iter().map(|&(_, n)| n).collect();
        assert_eq!(plan, [false, false, false, true, false, true]);
        assert!(s.normalize_output);
        assert!(!PreparedStack::new([]).normalize_output);
    }

    #[test]
    fn same_as_normalizing_after_every_op() {
        let s = PreparedStack::new(ops());
        for k in 0..50 {
            let a = k as f32 * 0.37;
            let (x, y) = (0.4 * a.cos(), 0.4 * a.sin());
            let l = Vec3::new(x, y, (1.0 - x * x - y * y).sqrt());
            let eager = ops().iter().fold(l, |h, op| op.apply_local(h));
            let lazy = s.apply_local(l);
            assert!((eager - lazy).length() < 1e-6, "{eager} vs {lazy}");
            let initial = chunk_of(&[l; 3]);
            let mut c = initial;
            s.apply_chunk(&initial, &mut c);
            assert_eq!(c.lanes().0.len(), 3);
            assert_eq!([c.get(0), c.get(1), c.get(2)], [lazy; 3]);
        }
    }

    #[test]
    fn zero_output_keeps_input_direction() {
        let s = PreparedStack::new([
            Op::Scale {
                delta: 1.0,
                axis: Axis::U,
            }
            .prepare()
            .unwrap(),
            Op::Rotate { degrees: 90.0 }.prepare().unwrap(),
        ]);
        // H = du: the scaling gives zero and keeps du; the rotation then turns it to −dv.
        assert!((s.apply_local(Vec3::X) + Vec3::Y).length() < 1e-6);
        // The same in a chunk, beside vectors that scale normally.
        let hs = [Vec3::X, Vec3::new(0.3, 0.4, 0.866), Vec3::X, Vec3::Z];
        let initial = chunk_of(&hs);
        let mut c = initial;
        s.apply_chunk(&initial, &mut c);
        for (i, h) in hs.iter().enumerate() {
            assert_eq!(c.get(i), s.apply_local(*h), "{i}");
        }
    }
}
