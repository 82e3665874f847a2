//! The distance from a point to a line segment in the plane, in f64 and in f32.

use glam::{DVec2, Vec2};

/// Writes `distance_to_segment` for one precision, so that both share one formula.
macro_rules! distance_to_segment {
    ($(#[$doc:meta])* $name:ident, $vec:ty, $scalar:ty) => {
        $(#[$doc])*
        ///
        /// The distance from `p` to the segment from `a` to `b`: to its nearest point
        /// `a + t (b − a)`, `t = clamp((p − a)·(b − a) / |b − a|², 0, 1)`; from `a` where the
        /// segment has no length.
        #[must_use]
        pub fn $name(p: $vec, a: $vec, b: $vec) -> $scalar {
            let along = b - a;
            let length_squared = along.length_squared();
            let t = if length_squared > 0.0 {
                ((p - a).dot(along) / length_squared).clamp(0.0, 1.0)
            } else {
                0.0
            };
            p.distance(a + along * t)
        }
    };
}

distance_to_segment!(
    /// In f64, for (u, v) points of trim loops and curves.
    distance_to_segment,
    DVec2,
    f64
);
distance_to_segment!(
    /// In f32, for pixel positions.
    distance_to_segment_f32,
    Vec2,
    f32
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_nearest_point_is_an_end_or_the_foot_of_the_perpendicular() {
        let (a, b) = (DVec2::new(0.0, 0.0), DVec2::new(4.0, 0.0));
        assert_eq!(distance_to_segment(DVec2::new(2.0, 3.0), a, b), 3.0);
        assert_eq!(distance_to_segment(DVec2::new(7.0, 4.0), a, b), 5.0);
        assert_eq!(distance_to_segment(DVec2::new(-3.0, 4.0), a, a), 5.0);
        let (a, b) = (Vec2::new(0.0, 0.0), Vec2::new(4.0, 0.0));
        assert_eq!(distance_to_segment_f32(Vec2::new(2.0, 3.0), a, b), 3.0);
        assert_eq!(distance_to_segment_f32(Vec2::new(7.0, 4.0), a, b), 5.0);
        assert_eq!(distance_to_segment_f32(Vec2::new(-3.0, 4.0), a, a), 5.0);
    }
}
