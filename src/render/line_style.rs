//! How a patch's lines are drawn: their width, colour, kinds and taper, and how they draw
//! where a surface hides them.

use glam::Vec3;
use serde::Deserialize;

/// The kinds of line: what decided that a curve is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Deserialize)]
pub enum LineKind {
    /// Where the surface turns from facing the eye to facing away (`N·(P − E) = 0`).
    Silhouette,
    /// Where two patches meet at an angle above the crease angle.
    Crease,
    /// A patch's boundary that no other patch continues, or (with patch borders on) one where
    /// two patches meet.
    Border,
    /// Where two patches pass through each other.
    Intersection,
    /// Where two patches of different materials meet.
    MaterialBorder,
    /// The cel terminator: where the tone's `N·L` (`N·L'` under designed shade) crosses one of
    /// the patch's band thresholds.
    LightContour,
}

impl LineKind {
    /// Every kind, in the order the docs list them.
    pub const ALL: [LineKind; 6] = [
        LineKind::Silhouette,
        LineKind::Crease,
        LineKind::Border,
        LineKind::Intersection,
        LineKind::MaterialBorder,
        LineKind::LightContour,
    ];
}

/// A set of [`LineKind`]s.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct LineKinds {
    pub silhouette: bool,
    pub crease: bool,
    pub border: bool,
    pub intersection: bool,
    pub material_border: bool,
    pub light_contour: bool,
}

/// Every field, but the kinds drawn only when named (material borders, light contours) only
/// when the set holds them: a set of the four kinds drawn by default prints as sets did before
/// there were more, so that a frame's fingerprint stays the same for shots that do not name
/// them.
impl std::fmt::Debug for LineKinds {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut set = f.debug_struct("LineKinds");
        set.field("silhouette", &self.silhouette)
            .field("crease", &self.crease)
            .field("border", &self.border)
            .field("intersection", &self.intersection);
        if self.material_border {
            set.field("material_border", &true);
        }
        if self.light_contour {
            set.field("light_contour", &true);
        }
        set.finish()
    }
}

impl LineKinds {
    /// Every kind of line.
    pub const ALL: LineKinds = LineKinds {
        silhouette: true,
        crease: true,
        border: true,
        intersection: true,
        material_border: true,
        light_contour: true,
    };

    /// The kinds drawn where a style names none: the four the surface's shape decides
    /// (silhouettes, creases, borders, intersections). Material borders and light contours are
    /// drawn where a style names them.
    pub const DEFAULT: LineKinds = LineKinds {
        material_border: false,
        light_contour: false,
        ..Self::ALL
    };

    /// No line at all.
    pub const NONE: LineKinds = LineKinds {
        silhouette: false,
        crease: false,
        border: false,
        intersection: false,
        material_border: false,
        light_contour: false,
    };

    /// The set holding exactly `kinds`.
    #[must_use]
    pub fn of(kinds: &[LineKind]) -> Self {
        kinds.iter().fold(Self::NONE, |mut set, &kind| {
            *set.flag(kind) = true;
            set
        })
    }

    /// Whether the set holds `kind`.
    #[must_use]
    pub fn holds(self, kind: LineKind) -> bool {
        match kind {
            LineKind::Silhouette => self.silhouette,
            LineKind::Crease => self.crease,
            LineKind::Border => self.border,
            LineKind::Intersection => self.intersection,
            LineKind::MaterialBorder => self.material_border,
            LineKind::LightContour => self.light_contour,
        }
    }

    fn flag(&mut self, kind: LineKind) -> &mut bool {
        match kind {
            LineKind::Silhouette => &mut self.silhouette,
            LineKind::Crease => &mut self.crease,
            LineKind::Border => &mut self.border,
            LineKind::Intersection => &mut self.intersection,
            LineKind::MaterialBorder => &mut self.material_border,
            LineKind::LightContour => &mut self.light_contour,
        }
    }
}

/// The most entries a dash pattern holds.
pub const MAX_DASHES: usize = 8;

/// The least a dash pattern's lengths add up to, in pixels.
pub const MIN_DASH_CYCLE: f32 = 1.0;

/// The most surfaces hidden lines are drawn behind.
pub const MAX_OCCLUSION_LEVEL: u32 = 16;

/// A dash pattern: lengths in pixels along a line, drawn and left out in turn from the start
/// of each stretch, the first drawn; an odd count repeats once more to make an even one (as
/// SVG's `stroke-dasharray`). Empty: a solid line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Dash {
    lengths: [f32; MAX_DASHES],
    count: u8,
}

impl Dash {
    /// A solid line.
    pub const SOLID: Dash = Dash {
        lengths: [0.0; MAX_DASHES],
        count: 0,
    };

    /// The pattern of `lengths` (pixels), checked: at most [`MAX_DASHES`] entries, each
    /// from 0 to 1e4, adding up to at least [`MIN_DASH_CYCLE`] (so that a line is cut into at
    /// most a few pieces per pixel).
    pub fn try_new(lengths: &[f32]) -> Result<Self, String> {
        if lengths.len() > MAX_DASHES {
            return Err(format!(
                "a dash pattern holds at most {MAX_DASHES} lengths, not {}",
                lengths.len()
            ));
        }
        if let Some(bad) = lengths.iter().find(|l| !(0.0..=1e4).contains(*l)) {
            return Err(format!(
                "dash length {bad} must be between 0 and 1e4 pixels"
            ));
        }
        let total: f32 = lengths.iter().sum();
        if !lengths.is_empty() && total < MIN_DASH_CYCLE {
            return Err(format!(
                "a dash pattern's lengths must add up to at least {MIN_DASH_CYCLE} pixel, not \
                 {total} (leave it empty for a solid line)"
            ));
        }
        let mut dash = Self::SOLID;
        dash.lengths[..lengths.len()].copy_from_slice(lengths);
        dash.count = lengths.len() as u8;
        Ok(dash)
    }

    /// The lengths as written.
    #[must_use]
    pub fn lengths(&self) -> &[f32] {
        &self.lengths[..self.count as usize]
    }

    /// Whether the line is solid: no pattern.
    #[must_use]
    pub fn is_solid(&self) -> bool {
        self.count == 0
    }

    /// The `k`th length of the pattern laid end to end from the start of a line, and whether
    /// it is drawn: the lengths in turn, drawn and left out by turns, the pattern gone through
    /// twice when its count is odd (as SVG's `stroke-dasharray` does).
    #[must_use]
    pub fn step(&self, k: usize) -> (f32, bool) {
        let pattern = self.lengths();
        (pattern[k % pattern.len()], k % 2 == 0)
    }

    /// The number of steps before the pattern repeats.
    #[must_use]
    pub fn cycle(&self) -> usize {
        let n = self.count as usize;
        if n % 2 == 1 {
            2 * n
        } else {
            n
        }
    }

    /// The drawn intervals of `[0, length]` (pixels along a line from its start): the whole
    /// for a solid line; else the pattern's drawn [steps](Self::step).
    #[must_use]
    pub fn drawn(&self, length: f32) -> Vec<(f32, f32)> {
        if self.is_solid() {
            return vec![(0.0, length)];
        }
        let mut out = Vec::new();
        let (mut at, mut k) = (0.0f32, 0);
        while at < length {
            let (step, drawn) = self.step(k);
            if drawn {
                // A dash of length 0 is a dot: the round caps draw it.
                out.push((at, (at + step).min(length)));
            }
            at += step;
            k = (k + 1) % self.cycle();
        }
        out
    }
}

/// How a patch's lines draw where surfaces hide them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HiddenLines {
    /// Drawn behind at most this many surfaces (each sheet the line of sight crosses between
    /// the eye and the line counts: a closed body in front counts twice, its near and far
    /// side), in [1, [`MAX_OCCLUSION_LEVEL`]].
    pub levels: u32,
    /// Width in pixels, in [0, 64].
    pub width: f32,
    /// Linear RGB.
    pub colour: Vec3,
    pub dash: Dash,
}

/// How the lines of one patch are drawn.
#[derive(Clone, Copy, PartialEq)]
pub struct LineStyle {
    /// Width in pixels, in [0, 64]; 0 draws nothing.
    pub width: f32,
    /// Linear RGB.
    pub colour: Vec3,
    /// The kinds of line drawn.
    pub kinds: LineKinds,
    /// Over this many pixels from each end of a drawn stretch of line, the width grows
    /// linearly from nothing to the full width; 0 draws blunt (round) ends.
    pub taper: f32,
    /// How its lines draw where surfaces hide them; None: they are not drawn there.
    pub hidden: Option<HiddenLines>,
}

/// Every field, but `hidden` only when there are hidden lines: a style without them prints as
/// styles did before they had them, so that a frame's fingerprint stays the same for shots
/// that draw none.
impl std::fmt::Debug for LineStyle {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut style = f.debug_struct("LineStyle");
        style
            .field("width", &self.width)
            .field("colour", &self.colour)
            .field("kinds", &self.kinds)
            .field("taper", &self.taper);
        if let Some(hidden) = &self.hidden {
            style.field("hidden", hidden);
        }
        style.finish()
    }
}

/// The widest a line may be, in pixels.
pub const MAX_LINE_WIDTH: f32 = 64.0;

/// The longest taper, in pixels.
pub const MAX_TAPER: f32 = 1e4;

impl LineStyle {
    /// A line of `width` and `colour`, the [default kinds](LineKinds::DEFAULT) drawn, without
    /// taper or hidden lines.
    #[must_use]
    pub const fn new(width: f32, colour: Vec3) -> Self {
        Self {
            width,
            colour,
            kinds: LineKinds::DEFAULT,
            taper: 0.0,
            hidden: None,
        }
    }

    /// How its lines of `kind` draw where surfaces hide them: its [`HiddenLines`] when it
    /// draws `kind`, behind one surface or more, at a width above 0.
    #[must_use]
    pub fn hidden_lines(&self, kind: LineKind) -> Option<&HiddenLines> {
        self.hidden
            .as_ref()
            .filter(|h| self.draws(kind) && h.levels > 0 && h.width > 0.0)
    }

    /// Whether lines of `kind` are drawn in this style: it holds the kind, at a width above 0.
    #[must_use]
    pub fn draws(&self, kind: LineKind) -> bool {
        self.width > 0.0 && self.kinds.holds(kind)
    }

    /// Checks the ranges: the width in [0, [`MAX_LINE_WIDTH`]], each colour component in
    /// [0, 1e4], the taper in [0, [`MAX_TAPER`]]; for hidden lines, the levels in
    /// [0, [`MAX_OCCLUSION_LEVEL`]] and their width and colour as a line's.
    pub fn validate(&self) -> Result<(), String> {
        check_width(self.width, "line width")?;
        check_colour(self.colour, "line colour")?;
        if let Some(hidden) = &self.hidden {
            if hidden.levels > MAX_OCCLUSION_LEVEL {
                return Err(format!(
                    "hidden lines' levels {} must be from 0 to {MAX_OCCLUSION_LEVEL} surfaces",
                    hidden.levels
                ));
            }
            check_width(hidden.width, "hidden lines' width")?;
            check_colour(hidden.colour, "hidden lines' colour")?;
        }
        if !(0.0..=MAX_TAPER).contains(&self.taper) {
            return Err(format!(
                "line taper {} must be between 0 and {MAX_TAPER:e} pixels",
                self.taper
            ));
        }
        Ok(())
    }
}

/// Checks that `width` is in [0, [`MAX_LINE_WIDTH`]]; `what` names it.
fn check_width(width: f32, what: &str) -> Result<(), String> {
    if (0.0..=MAX_LINE_WIDTH).contains(&width) {
        Ok(())
    } else {
        Err(format!(
            "{what} {width} must be between 0 and {MAX_LINE_WIDTH} pixels"
        ))
    }
}

/// Checks that each component of `c` is in [0, 1e4]; `what` names it.
fn check_colour(c: Vec3, what: &str) -> Result<(), String> {
    if c.is_finite() && c.min_element() >= 0.0 && c.max_element() <= 1e4 {
        Ok(())
    } else {
        Err(format!(
            "{what} ({}, {}, {}) must have components from 0 to 1e4",
            c.x, c.y, c.z
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_set_holds_exactly_the_kinds_it_was_made_of() {
        for mask in 0..64u32 {
            let kinds: Vec<LineKind> = LineKind::ALL
                .into_iter()
                .enumerate()
                .filter(|(i, _)| mask & (1 << i) != 0)
                .map(|(_, k)| k)
                .collect();
            let set = LineKinds::of(&kinds);
            for kind in LineKind::ALL {
                assert_eq!(set.holds(kind), kinds.contains(&kind), "{mask} {kind:?}");
            }
        }
    }
}

#[cfg(test)]
mod dash_tests {
    use super::*;

    #[test]
    fn a_dash_pattern_alternates_drawn_and_left_out_lengths_from_the_start() {
        let dash = Dash::try_new(&[4.0, 2.0]).unwrap();
        assert_eq!(
            dash.drawn(15.0),
            vec![(0.0, 4.0), (6.0, 10.0), (12.0, 15.0)]
        );
        // An odd count goes round twice: 3 drawn, 1 out, 2 drawn, 3 out, 1 drawn, 2 out.
        let odd = Dash::try_new(&[3.0, 1.0, 2.0]).unwrap();
        assert_eq!(
            odd.drawn(14.0),
            vec![(0.0, 3.0), (4.0, 6.0), (9.0, 10.0), (12.0, 14.0)]
        );
        assert_eq!(Dash::SOLID.drawn(7.5), vec![(0.0, 7.5)]);
        // Dots: drawn lengths of 0.
        assert_eq!(
            Dash::try_new(&[0.0, 2.0]).unwrap().drawn(5.0),
            vec![(0.0, 0.0), (2.0, 2.0), (4.0, 4.0)]
        );
    }

    #[test]
    fn a_dash_pattern_without_a_positive_length_or_with_a_bad_one_is_refused() {
        assert!(Dash::try_new(&[0.0, 0.0])
            .unwrap_err()
            .contains("add up to at least 1"));
        assert!(Dash::try_new(&[0.25, 0.5]).is_err());
        assert!(Dash::try_new(&[f32::NAN, 1.0]).is_err());
        assert!(Dash::try_new(&[-1.0, 1.0]).is_err());
        assert!(Dash::try_new(&[1.0; MAX_DASHES + 1]).is_err());
        assert!(Dash::try_new(&[]).unwrap().is_solid());
    }
}
