//! Dashes: the stretches of a line cut into the lengths its dash pattern draws.

use super::chain::Drawn;
use super::stroke::Capsule;
use crate::render::line_style::Dash;

/// The capsules of `drawn` with each stretch cut by the dash pattern of its capsules
/// (`dash_of(capsule.colour)`): along the stretch from its start, the pattern's drawn
/// [steps](Dash::step) are kept and the others left out, each kept part a capsule of its own
/// (round at both ends, as SVG's round caps draw a dash) with the radius its place along the
/// capsule has. Capsules of a solid pattern stay whole. A stretch's pattern starts afresh at
/// its start, as a path's `stroke-dasharray` does.
#[must_use]
pub(crate) fn dashed(drawn: &Drawn, dash_of: impl Fn(u32) -> Dash) -> Vec<Capsule> {
    let mut out = Vec::with_capacity(drawn.capsules.len());
    for (range, _) in &drawn.stretches {
        // Where the pattern stands: its step, and what is left of it.
        let mut step = 0usize;
        let mut left: Option<f32> = None;
        for c in &drawn.capsules[range.clone()] {
            let dash = dash_of(c.colour);
            if dash.is_solid() {
                out.push(*c);
                continue;
            }
            let length = c.a.distance(c.b);
            let at = |s: f32| if length > 0.0 { s / length } else { 0.0 };
            let part = |s0: f32, s1: f32| {
                let (t0, t1) = (at(s0), at(s1));
                let radius = |t: f32| c.radii[0] + (c.radii[1] - c.radii[0]) * t;
                Capsule {
                    a: c.a.lerp(c.b, t0),
                    b: c.a.lerp(c.b, t1),
                    radii: [radius(t0), radius(t1)],
                    ..*c
                }
            };
            let mut s = 0.0f32;
            loop {
                let (whole, draws) = dash.step(step);
                let remaining = left.unwrap_or(whole);
                let end = s + remaining;
                if draws && (end > s || left.is_none()) {
                    out.push(part(s, end.min(length)));
                }
                if end > length {
                    left = Some(end - length);
                    break;
                }
                s = end;
                step = (step + 1) % dash.cycle();
                left = None;
                if s == length {
                    // The next step starts at the next capsule.
                    break;
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use glam::Vec2;

    use super::*;

    #[test]
    fn a_dashed_stretch_keeps_the_pattern_s_drawn_lengths_across_its_capsules() {
        // A straight stretch 30 px long in capsules of 7, 11 and 12 px, then a second stretch.
        let capsule = |x0: f32, x1: f32| Capsule {
            a: Vec2::new(x0, 5.0),
            b: Vec2::new(x1, 5.0),
            radii: [1.0, 1.0],
            opacity: 1.0,
            colour: 0,
        };
        let drawn = Drawn {
            capsules: vec![
                capsule(0.0, 7.0),
                capsule(7.0, 18.0),
                capsule(18.0, 30.0),
                capsule(40.0, 45.0),
            ],
            pieces: vec![0; 4],
            stretches: vec![(0..3, false), (3..4, false)],
        };
        let dash = Dash::try_new(&[4.0, 2.0, 1.0]).unwrap();
        let capsules = dashed(&drawn, |_| dash);
        // What the pattern draws of each stretch, from its start.
        let mut expected: Vec<(f32, f32)> = dash.drawn(30.0);
        expected.extend(
            dash.drawn(5.0)
                .into_iter()
                .map(|(a, b)| (a + 40.0, b + 40.0)),
        );
        // Kept parts that meet at a capsule's end are one dash.
        let mut got: Vec<(f32, f32)> = Vec::new();
        for c in &capsules {
            match got.last_mut() {
                Some(last) if (last.1 - c.a.x).abs() < 1e-4 && c.a.x != 40.0 => last.1 = c.b.x,
                _ => got.push((c.a.x, c.b.x)),
            }
        }
        assert_eq!(got.len(), expected.len(), "{got:?} against {expected:?}");
        for (g, e) in got.iter().zip(&expected) {
            assert!(
                (g.0 - e.0).abs() < 1e-4 && (g.1 - e.1).abs() < 1e-4,
                "{got:?} {expected:?}"
            );
        }
        // A solid pattern leaves the capsules as they are.
        assert_eq!(dashed(&drawn, |_| Dash::SOLID), drawn.capsules);
    }

    #[test]
    fn a_dash_of_a_tapering_capsule_takes_the_radius_where_it_lies() {
        // From radius 0 at x = 0 to 2 at x = 10 (a line's end narrowing), dashed 2 on, 2 off.
        let drawn = Drawn {
            capsules: vec![Capsule {
                a: Vec2::ZERO,
                b: Vec2::new(10.0, 0.0),
                radii: [0.0, 2.0],
                opacity: 1.0,
                colour: 0,
            }],
            pieces: vec![0],
            stretches: vec![(0..1, false)],
        };
        let capsules = dashed(&drawn, |_| Dash::try_new(&[2.0, 2.0]).unwrap());
        assert_eq!(capsules.len(), 3);
        for c in &capsules {
            for (end, radius) in [(c.a, c.radii[0]), (c.b, c.radii[1])] {
                assert!((radius - 0.2 * end.x).abs() < 1e-6, "at {end}: {radius}");
            }
        }
    }
}
