//! Placing a designed band edge where the animator points: the translation of a shade entry's
//! light that puts a cel band's edge (`N·L'` at its threshold) through the surface point under a
//! pixel (docs/highlights.md, "Placing the shadow").

use glam::Vec2;

use super::place_error::PlaceError;
use super::RenderJob;
use crate::highlight::{DesignedLight, Op, ShadeStack};
use crate::param::MAX_STEP;
use crate::render::SurfacePoint;
use crate::shot::MaterialState;

/// Which shade entry and band to place; `None` picks as [`RenderJob::place_shade`] says.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ShadeChoice {
    /// The shade entry (includes first, from 0); it must pick the patch under the pixel.
    pub entry: Option<usize>,
    /// The band of the patch's cel ramp, from 0 in increasing threshold order.
    pub band: Option<usize>,
}

/// A band edge placed through the surface point under a pixel by a shade entry's translation.
#[derive(Clone, Debug, PartialEq)]
pub struct ShadePlacement {
    /// The frame the camera, light and parameters were read at.
    pub frame: f64,
    /// The image position asked for, in pixels (a pixel's centre at integer values).
    pub pixel: (f64, f64),
    /// The patch under the pixel (index into the shot's library).
    pub patch: usize,
    /// Its parameters where the pixel's ray meets it.
    pub uv: (f64, f64),
    /// The shade entry whose translation is solved for (includes first).
    pub entry: usize,
    /// The index in the entry's stack of that translation: its last `Translate`.
    pub op: usize,
    /// The band whose edge is placed, from 0.
    pub band: usize,
    /// Its threshold at the frame: `N·L'` on its edge.
    pub threshold: f32,
    /// `N·L'` at the point before placing.
    pub n_dot_l_before: f32,
    /// The translation's `(α, β)` at the frame before placing.
    pub before: Vec2,
    /// The translation `(α, β)` that puts the edge through the point.
    pub translation: Vec2,
    /// `N·L'` at the point with that translation: the threshold, to within the solve's
    /// tolerance.
    pub n_dot_l: f32,
}

/// How near `N·L'` must come to the threshold for a root of the solve to count: a sign change
/// of `N·L' − t` larger than this is a jump (a split's seam), not the edge.
const ROOT_TOLERANCE: f32 = 1e-4;

/// The outward march along the direction: steps of a quarter of the distance out, from
/// `FIRST_STEP` up to `FINE_STEP`, until `FINE_REACH`; past it steps growing by `STEP_RATIO`.
/// The fine steps keep a narrow hump of `N·L'` (where the line passes near `L' = N`) from
/// being stepped over.
const FIRST_STEP: f64 = 1e-4;
const FINE_STEP: f64 = 0.01;
const FINE_REACH: f64 = 20.0;
const STEP_RATIO: f64 = 1.5;

/// Halvings of a bracket.
const BISECTIONS: usize = 80;

impl RenderJob {
    /// Places a band edge of the patch under image position `pixel` (in pixels, pixel
    /// `(i, j)`'s centre at `(i, j)`) at `frame` by solving the placing translation of a shade
    /// entry: its last `Translate(α, β)`.
    ///
    /// The patch and its `(u, v)` are found as for [`RenderJob::place`]. The entry is
    /// `choice.entry` or the last entry picking the patch; the band is `choice.band` or, of the
    /// bands whose edge a translation can move to the point (a threshold of the sign of `N·L`
    /// there, not 0), the one whose threshold is nearest `N·L'` there now. With `d` the unit
    /// tangential direction of the light at the point, `(l_u, l_v) / ‖(l_u, l_v)‖` (toward the
    /// light's side; `du` where the light is along N), the translation is
    /// `(α, β) = (α₀, β₀) + s d` with `s` the root nearest 0 of `N·L'(s) − t`, `N·L'` evaluated
    /// at the point through the patch's whole [`DesignedLight`] at this frame (every entry
    /// picking it, the other operations of the stack, the mask) with the translation replaced.
    /// The root is bracketed by marching outward both ways (steps of a quarter of the distance,
    /// from 1e-4 to at most 0.01, up to 20; past it growing by 1.5), while α and β stay in
    /// [−1e6, 1e6], and bisected.
    ///
    /// Every operation changes only L's tangential part, so `N·L' = N·L / ‖L''‖` keeps the sign
    /// of `N·L`: a threshold of 0 or of the other sign than `N·L` is refused, as is a threshold
    /// no translation in range reaches (outside the entry's mask, say). Errors as well when the
    /// pixel is outside the image or off the model, the patch has no shade entry (or not
    /// `choice.entry`), the entry has no translation, or the patch is not toned by a cel ramp
    /// with that band.
    pub fn place_shade(
        &mut self,
        frame: f64,
        pixel: (f64, f64),
        choice: ShadeChoice,
    ) -> Result<ShadePlacement, PlaceError> {
        let (patch, uv) = self.point_under(frame, pixel)?;
        let shot = &self.shot;
        let name = &shot.library.patches[patch].name;
        let at_pixel = format!("{name}, under pixel ({}, {})", pixel.0, pixel.1);
        let entries = shot.shade_of(patch);
        let Some(&last) = entries.last() else {
            return Err(PlaceError::Shade(format!(
                "{at_pixel}, has no shade entry; add an entry to `shade` whose patches select it"
            )));
        };
        let entry = match choice.entry {
            None => last as usize,
            Some(asked) if entries.contains(&(asked as u32)) => asked,
            Some(asked) => {
                let picking: Vec<String> = entries.iter().map(u32::to_string).collect();
                return Err(PlaceError::Shade(format!(
                    "shade entry {asked} does not pick {at_pixel}; the entries that do: {}",
                    picking.join(", ")
                )));
            }
        };
        let written = shot.shade_written(entry).map_or_else(
            || format!("shade entry {entry}"),
            |(file, index)| format!("shade entry {entry} (shade[{index}] in {})", file.display()),
        );
        let state = shot.at(frame);
        let ramp = match &state.materials[shot.material_of(patch)] {
            MaterialState::Cel(ramp) => ramp,
            MaterialState::XToon(_) => {
                return Err(PlaceError::Shade(format!(
                    "{at_pixel}, is toned by X-Toon, which has no band edge to place; its shade \
                     is moved with the stack's numbers (`glint key`)"
                )))
            }
        };
        if ramp.bands.is_empty() {
            return Err(PlaceError::Shade(format!(
                "{at_pixel}, has a cel material without bands: no band edge to place"
            )));
        }
        let stacks: Vec<ShadeStack> = entries
            .iter()
            .map(|&e| state.shade[e as usize].clone())
            .collect();
        let own = entries
            .iter()
            .position(|&e| e as usize == entry)
            .unwrap_or_default();
        let Some(op) = stacks[own]
            .stack
            .iter()
            .rposition(|o| matches!(o, Op::Translate { .. }))
        else {
            return Err(PlaceError::Shade(format!(
                "{written} has no Translate to place; add one to its stack, such as \
                 Translate(alpha: 0.0, beta: 0.0)"
            )));
        };
        let before = match stacks[own].stack[op] {
            Op::Translate { alpha, beta } => Vec2::new(alpha, beta),
            Op::Rotate { .. } | Op::Scale { .. } | Op::Split { .. } | Op::Square { .. } => {
                Vec2::ZERO
            }
        };
        let surface = &state.library.patches[patch].surface;
        let point = SurfacePoint::new(surface, uv, &state.camera, &state.light);
        let l = state.light.direction(point.position, point.frame.n);
        let local = point.frame.to_local(l);
        let uv32 = Vec2::new(uv.0 as f32, uv.1 as f32);
        let with = |t: Vec2| -> Result<f32, PlaceError> {
            let prepared = stacks
                .iter()
                .enumerate()
                .map(|(i, s)| {
                    let mut s = s.clone();
                    if i == own {
                        s.stack[op] = Op::Translate {
                            alpha: t.x,
                            beta: t.y,
                        };
                    }
                    s.prepare()
                })
                .collect::<Result<Vec<_>, _>>()
                .map_err(|e| PlaceError::Shade(format!("{written} at frame {frame}: {e}")))?;
            Ok(DesignedLight::new(prepared).n_dot_l(&point.frame, uv32, l))
        };
        let now = with(before)?;
        let n_dot_l = local.z;
        let reachable = |t: f32| t != 0.0 && n_dot_l != 0.0 && (t > 0.0) == (n_dot_l > 0.0);
        let band = match choice.band {
            Some(k) if k < ramp.bands.len() => k,
            Some(k) => {
                return Err(PlaceError::Shade(format!(
                    "{at_pixel}, has a cel material of {} band(s), numbered from 0, so no band {k}",
                    ramp.bands.len()
                )))
            }
            None => (0..ramp.bands.len())
                .filter(|&k| reachable(ramp.bands[k].0))
                .min_by(|&a, &b| {
                    let gap = |k: usize| (ramp.bands[k].0 - now).abs();
                    gap(a).total_cmp(&gap(b))
                })
                .unwrap_or(0),
        };
        let threshold = ramp.bands[band].0;
        let side = if n_dot_l > 0.0 { "lit" } else { "unlit" };
        if threshold == 0.0 {
            return Err(PlaceError::Shade(format!(
                "band {band}'s edge is at N·L' = 0, the terminator, which no translation of the \
                 light moves (every operation keeps the sign of N·L); give the band a threshold \
                 above 0, on the light's side"
            )));
        }
        if !reachable(threshold) {
            return Err(PlaceError::Shade(format!(
                "{at_pixel}, faces the {side} side (N·L = {}) and band {band}'s edge is at \
                 N·L' = {threshold}, on the other: no translation of the light changes the sign \
                 of N·L; point at a point on the light's side, with a band threshold above 0",
                rounded(n_dot_l)
            )));
        }
        let tangential = Vec2::new(local.x, local.y);
        let direction = if tangential.length() > 1e-6 {
            tangential.normalize()
        } else {
            Vec2::X
        };
        let g = |s: f64| -> Result<f32, PlaceError> {
            Ok(with(before + direction * s as f32)? - threshold)
        };
        let root = nearest_root(&g, before, direction)?.ok_or_else(|| {
            PlaceError::Shade(format!(
                "no translation of {written} with α and β in [-1e6, 1e6] brings N·L' to band \
                 {band}'s threshold {threshold} at {at_pixel} (N·L' is {} there now){}",
                rounded(now),
                if stacks[own].mask.is_some() {
                    "; the point may lie outside the entry's mask"
                } else {
                    ""
                }
            ))
        })?;
        let translation = before + direction * root as f32;
        Ok(ShadePlacement {
            frame,
            pixel,
            patch,
            uv,
            entry,
            op,
            band,
            threshold,
            n_dot_l_before: now,
            before,
            translation,
            n_dot_l: with(translation)?,
        })
    }
}

/// The root nearest 0 of `g` along `before + s d` with both coordinates in [−MAX_STEP,
/// MAX_STEP] (`None` when there is none there): a root at 0, or on each side the first bracket
/// of the outward march whose bisection meets `|g| < ROOT_TOLERANCE`; of the two sides, the
/// smaller `|s|`.
fn nearest_root(
    g: &dyn Fn(f64) -> Result<f32, PlaceError>,
    before: Vec2,
    d: Vec2,
) -> Result<Option<f64>, PlaceError> {
    let at_zero = g(0.0)?;
    if at_zero.abs() < ROOT_TOLERANCE {
        return Ok(Some(0.0));
    }
    let in_range = |s: f64| {
        let t = before.as_dvec2() + d.as_dvec2() * s;
        t.x.abs() <= f64::from(MAX_STEP) && t.y.abs() <= f64::from(MAX_STEP)
    };
    let mut best: Option<f64> = None;
    for sign in [1.0, -1.0] {
        let (mut s0, mut g0) = (0.0_f64, at_zero);
        let mut step = FIRST_STEP;
        loop {
            let s1 = sign * step;
            if best.is_some_and(|b: f64| b.abs() <= s0.abs()) || !in_range(s1) {
                break;
            }
            let g1 = g(s1)?;
            if (g0 > 0.0) != (g1 > 0.0) {
                let (mut lo, mut hi, mut g_lo) = (s0, s1, g0);
                for _ in 0..BISECTIONS {
                    let mid = 0.5 * (lo + hi);
                    let g_mid = g(mid)?;
                    if (g_mid > 0.0) == (g_lo > 0.0) {
                        (lo, g_lo) = (mid, g_mid);
                    } else {
                        hi = mid;
                    }
                }
                let root = if g(lo)?.abs() <= g(hi)?.abs() { lo } else { hi };
                if g(root)?.abs() < ROOT_TOLERANCE {
                    if best.is_none_or(|b| root.abs() < b.abs()) {
                        best = Some(root);
                    }
                    break;
                }
            }
            (s0, g0) = (s1, g1);
            step = next_reach(step);
        }
    }
    Ok(best)
}

/// The distance out after `reach`: a quarter further, by at least `FIRST_STEP` and at most
/// `FINE_STEP`, within `FINE_REACH`; `STEP_RATIO` times further past it.
fn next_reach(reach: f64) -> f64 {
    if reach < FINE_REACH {
        reach + (0.25 * reach).clamp(FIRST_STEP, FINE_STEP)
    } else {
        reach * STEP_RATIO
    }
}

/// A number as messages show it: six significant digits.
fn rounded(x: f32) -> String {
    crate::shot::rounded_number_text(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_root_nearest_zero_is_found_on_either_side() {
        // g(s) = (s − 0.3)(s + 0.1): roots at 0.3 and −0.1; the nearer is −0.1.
        let g = |s: f64| Ok(((s - 0.3) * (s + 0.1)) as f32);
        let root = nearest_root(&g, Vec2::ZERO, Vec2::X).unwrap().unwrap();
        assert!((root + 0.1).abs() < 1e-5, "{root}");
        let g = |s: f64| Ok((s - 2.5) as f32);
        let root = nearest_root(&g, Vec2::ZERO, Vec2::X).unwrap().unwrap();
        assert!((root - 2.5).abs() < 1e-5, "{root}");
    }

    #[test]
    fn a_narrow_hump_is_not_stepped_over() {
        // Above 0 only for s in (−1.03, −0.97): the edge of a band the point can reach only
        // where the line passes near L' = N.
        let g = |s: f64| Ok((0.03 - (s + 1.0).abs()) as f32);
        let root = nearest_root(&g, Vec2::ZERO, Vec2::X).unwrap().unwrap();
        assert!((root + 0.97).abs() < 1e-5, "{root}");
    }

    #[test]
    fn a_jump_is_not_a_root_and_no_root_in_range_is_none() {
        // A jump from −1.2 to 1 at s = 0.2 changes sign without a root; the root is at −1.
        let g = |s: f64| Ok(if s >= 0.2 { 1.0 } else { -(s + 1.0) as f32 });
        let root = nearest_root(&g, Vec2::ZERO, Vec2::X).unwrap().unwrap();
        assert!((root + 1.0).abs() < 1e-5, "{root}");
        let g = |s: f64| Ok(if s >= 0.2 { 1.0 } else { -1.0 });
        assert_eq!(nearest_root(&g, Vec2::ZERO, Vec2::X).unwrap(), None);
        let g = |s: f64| Ok((s * s + 1.0) as f32);
        assert_eq!(nearest_root(&g, Vec2::ZERO, Vec2::Y).unwrap(), None);
        // The range stops the march: a root beyond 1e6 from the start is not reached.
        let g = |s: f64| Ok((s - 2e6) as f32);
        assert_eq!(nearest_root(&g, Vec2::ZERO, Vec2::X).unwrap(), None);
    }
}
