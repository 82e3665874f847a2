//! A shot's line styles: the outlines' own, and the `lines` entries that restyle the patches
//! they pick — which patches each entry picks, what each sets at a frame, and the style each
//! patch ends with.

use glam::Vec3;

use super::file::{HiddenSpec, LineSpec, OutlinesSpec};
use super::glob;
use super::no_match::no_match_message;
use super::source::Source;
use super::ShotError;
use crate::anim::Keyed;
use crate::formats::ron_location::closest_name;
use crate::formats::ron_paths::Step::{Field, Index};
use crate::geom::PatchLibrary;
use crate::render::{Dash, HiddenLines, LineKinds, LineStyle, Outlines};

/// The fields a `lines` entry sets, read at one frame; None where it leaves the field as the
/// outlines (or an earlier entry) set it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineFields {
    pub width: Option<f32>,
    pub colour: Option<Vec3>,
    pub kinds: Option<LineKinds>,
    pub taper: Option<f32>,
    pub hidden: Option<HiddenFields>,
}

/// What an entry's `hidden` sets, read at one frame; None where the width or colour is the
/// style's own.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HiddenFields {
    pub levels: u32,
    pub width: Option<f32>,
    pub colour: Option<Vec3>,
    pub dash: Dash,
}

impl HiddenFields {
    /// The hidden lines of a style of `width` and `colour`.
    #[must_use]
    pub fn of(&self, width: f32, colour: Vec3) -> HiddenLines {
        HiddenLines {
            levels: self.levels,
            width: self.width.unwrap_or(width),
            colour: self.colour.unwrap_or(colour),
            dash: self.dash,
        }
    }
}

impl HiddenSpec {
    /// What it sets at `frame`; a dash pattern that cannot be used is solid here (the shot's
    /// checks refuse it, [`Dash::try_new`]).
    #[must_use]
    pub fn at(&self, frame: f64) -> HiddenFields {
        HiddenFields {
            levels: self.levels,
            width: self.width.as_ref().map(|t| t.at(frame)),
            colour: self.colour.as_ref().map(|t| t.at(frame)),
            dash: Dash::try_new(&self.dash).unwrap_or(Dash::SOLID),
        }
    }

    /// Calls `f` with each of its tracks.
    fn for_each_param(&self, f: &mut dyn FnMut(&dyn Keyed)) {
        let HiddenSpec {
            levels: _,
            width,
            colour,
            dash: _,
        } = self;
        if let Some(width) = width {
            f(width);
        }
        if let Some(colour) = colour {
            f(colour);
        }
    }
}

impl LineFields {
    /// `style` with the fields this entry sets replaced; hidden lines the entry sets take the
    /// width and colour of the style it leaves where they set none.
    #[must_use]
    pub fn over(&self, style: LineStyle) -> LineStyle {
        let width = self.width.unwrap_or(style.width);
        let colour = self.colour.unwrap_or(style.colour);
        LineStyle {
            width,
            colour,
            kinds: self.kinds.unwrap_or(style.kinds),
            taper: self.taper.unwrap_or(style.taper),
            hidden: self.hidden.map(|h| h.of(width, colour)).or(style.hidden),
        }
    }
}

impl LineSpec {
    /// The fields this entry sets, read at `frame`.
    #[must_use]
    pub fn at(&self, frame: f64) -> LineFields {
        LineFields {
            width: self.width.as_ref().map(|t| t.at(frame)),
            colour: self.colour.as_ref().map(|t| t.at(frame)),
            kinds: self.kinds.as_deref().map(LineKinds::of),
            taper: self.taper.as_ref().map(|t| t.at(frame)),
            hidden: self.hidden.as_ref().map(|h| h.at(frame)),
        }
    }

    /// Calls `f` with each track the entry sets.
    pub(super) fn for_each_param(&self, f: &mut dyn FnMut(&dyn Keyed)) {
        let LineSpec {
            patches: _,
            material: _,
            width,
            colour,
            kinds: _,
            taper,
            hidden,
        } = self;
        if let Some(width) = width {
            f(width);
        }
        if let Some(colour) = colour {
            f(colour);
        }
        if let Some(taper) = taper {
            f(taper);
        }
        if let Some(hidden) = hidden {
            hidden.for_each_param(f);
        }
    }
}

impl OutlinesSpec {
    /// The outlines at `frame`, and the style of a patch no `lines` entry restyles.
    #[must_use]
    pub fn at(&self, frame: f64) -> (Outlines, LineStyle) {
        let outlines = Outlines {
            width: self.width.at(frame),
            colour: self.colour.at(frame),
            crease_degrees: self.crease_degrees,
            patch_borders: self.patch_borders,
        };
        let base = outlines.style();
        let style = LineStyle {
            kinds: self
                .kinds
                .as_deref()
                .map_or(LineKinds::DEFAULT, LineKinds::of),
            taper: self.taper.at(frame),
            hidden: self
                .hidden
                .as_ref()
                .map(|h| h.at(frame).of(base.width, base.colour)),
            ..base
        };
        (outlines, style)
    }

    /// Calls `f` with each of its tracks.
    pub(super) fn for_each_param(&self, f: &mut dyn FnMut(&dyn Keyed)) {
        let OutlinesSpec {
            width,
            colour,
            crease_degrees: _,
            patch_borders: _,
            kinds: _,
            taper,
            hidden,
        } = self;
        f(width);
        f(colour);
        f(taper);
        if let Some(hidden) = hidden {
            hidden.for_each_param(f);
        }
    }
}

/// Per patch of `library`, the `lines` entries (indices into `lines`) that pick it, in the
/// order written: an entry picks the patches its `patches` selector names (patches or parts,
/// as a highlight's selector does) or the patches of its `material` (`patch_material` and
/// `materials` name each patch's). An entry must set exactly one of the two, and pick some
/// patch.
pub(super) fn select_lines(
    lines: &[LineSpec],
    library: &PatchLibrary,
    patch_material: &[usize],
    materials: &[&str],
    source: &Source,
) -> Result<Vec<Vec<u32>>, ShotError> {
    let mut picked: Vec<Vec<u32>> = vec![Vec::new(); library.patches.len()];
    for (entry, spec) in lines.iter().enumerate() {
        let at = |steps: &[crate::formats::ron_paths::Step], message: String| {
            let mut path = vec![Field("lines"), Index(entry)];
            path.extend_from_slice(steps);
            source.error_at(&path, message)
        };
        let mut pick = |patch: usize| {
            if picked[patch].last() != Some(&(entry as u32)) {
                picked[patch].push(entry as u32);
            }
        };
        match (&spec.patches, &spec.material) {
            (Some(selector), None) => {
                for (index, pattern) in selector.patterns().iter().enumerate() {
                    let any = glob::pick_each(pattern, library, &mut pick);
                    if !any {
                        return Err(at(
                            &[Field("patches"), Index(index)],
                            no_match_message(pattern, library),
                        ));
                    }
                }
            }
            (None, Some(name)) => {
                let Some(material) = materials.iter().position(|m| m == name) else {
                    let mut message = format!("the shot has no material \"{name}\"");
                    if let Some(close) = closest_name(name, materials) {
                        message.push_str(&format!("; did you mean \"{close}\"?"));
                    }
                    return Err(at(&[Field("material")], message));
                };
                let mut any = false;
                for (patch, _) in patch_material
                    .iter()
                    .enumerate()
                    .filter(|&(_, &m)| m == material)
                {
                    pick(patch);
                    any = true;
                }
                if !any {
                    return Err(at(
                        &[Field("material")],
                        format!("no instance uses the material \"{name}\", so this entry styles nothing"),
                    ));
                }
            }
            (Some(_), Some(_)) | (None, None) => {
                return Err(at(
                    &[],
                    "a lines entry picks its patches by `patches: \"PATTERN\"` or by \
                     `material: \"NAME\"`: give exactly one"
                        .to_string(),
                ));
            }
        }
    }
    Ok(picked)
}
