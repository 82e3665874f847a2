//! How a patch's lines are drawn: their width, colour, kinds and taper.

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
}

impl LineKind {
    /// Every kind, in the order the docs list them.
    pub const ALL: [LineKind; 4] = [
        LineKind::Silhouette,
        LineKind::Crease,
        LineKind::Border,
        LineKind::Intersection,
    ];
}

/// A set of [`LineKind`]s.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct LineKinds {
    pub silhouette: bool,
    pub crease: bool,
    pub border: bool,
    pub intersection: bool,
}

impl LineKinds {
    /// Every kind of line.
    pub const ALL: LineKinds = LineKinds {
        silhouette: true,
        crease: true,
        border: true,
        intersection: true,
    };

    /// No line at all.
    pub const NONE: LineKinds = LineKinds {
        silhouette: false,
        crease: false,
        border: false,
        intersection: false,
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
        }
    }

    fn flag(&mut self, kind: LineKind) -> &mut bool {
        match kind {
            LineKind::Silhouette => &mut self.silhouette,
            LineKind::Crease => &mut self.crease,
            LineKind::Border => &mut self.border,
            LineKind::Intersection => &mut self.intersection,
        }
    }
}

/// How the lines of one patch are drawn.
#[derive(Clone, Copy, Debug, PartialEq)]
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
}

/// The widest a line may be, in pixels.
pub const MAX_LINE_WIDTH: f32 = 64.0;

/// The longest taper, in pixels.
pub const MAX_TAPER: f32 = 1e4;

impl LineStyle {
    /// A line of `width` and `colour`, every kind drawn, without taper.
    #[must_use]
    pub const fn new(width: f32, colour: Vec3) -> Self {
        Self {
            width,
            colour,
            kinds: LineKinds::ALL,
            taper: 0.0,
        }
    }

    /// Whether lines of `kind` are drawn in this style: it holds the kind, at a width above 0.
    #[must_use]
    pub fn draws(&self, kind: LineKind) -> bool {
        self.width > 0.0 && self.kinds.holds(kind)
    }

    /// Checks the ranges: the width in [0, [`MAX_LINE_WIDTH`]], each colour component in
    /// [0, 1e4], the taper in [0, [`MAX_TAPER`]].
    pub fn validate(&self) -> Result<(), String> {
        if !(0.0..=MAX_LINE_WIDTH).contains(&self.width) {
            return Err(format!(
                "line width {} must be between 0 and {MAX_LINE_WIDTH} pixels",
                self.width
            ));
        }
        let c = self.colour;
        if !(c.is_finite() && c.min_element() >= 0.0 && c.max_element() <= 1e4) {
            return Err(format!(
                "line colour ({}, {}, {}) must have components from 0 to 1e4",
                c.x, c.y, c.z
            ));
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_set_holds_exactly_the_kinds_it_was_made_of() {
        for mask in 0..16u32 {
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
