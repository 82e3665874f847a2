//! Parameter paths checked to name a track of a file, with the nearest valid path when one
//! names none.

use super::error::EditError;
use super::param_path::{HighlightRef, OpParam, ParamPath, ShadeParam};
use super::param_sites::ParsedFile;
use super::read::read_file;

/// The path `written` as a path of the file `text`: read, and naming a track of it. Otherwise a
/// [`EditError::BadPath`] with the valid path closest to what was written.
pub fn parse_param_path(text: &str, written: &str) -> Result<ParamPath, EditError> {
    let mut file = read_file(text)?;
    let path = written
        .parse::<ParamPath>()
        .map_err(|e| bad_path(&mut file, written, e.reason))?;
    resolve(&mut file, &path)?;
    Ok(path)
}

/// `path` with a highlight named by its pattern named by its index instead, checked to name a
/// track of `file`.
pub(super) fn resolve(file: &mut ParsedFile, path: &ParamPath) -> Result<ParamPath, EditError> {
    let resolved = match path {
        ParamPath::Highlight {
            entry: HighlightRef::Selector(pattern),
            layer,
            param,
        } => {
            let index = match file.entries_selected_by(pattern)[..] {
                [index] => index,
                [] => {
                    let reason = format!("no highlight entry of this file picks \"{pattern}\"");
                    return Err(bad_path(file, &path.to_string(), reason));
                }
                ref several => {
                    let named: Vec<String> =
                        several.iter().map(|i| format!("highlights[{i}]")).collect();
                    let reason = format!(
                        "more than one highlight entry picks \"{pattern}\"; name one by its index: {}",
                        named.join(", ")
                    );
                    return Err(bad_path(file, &path.to_string(), reason));
                }
            };
            ParamPath::Highlight {
                entry: HighlightRef::Index(index),
                layer: *layer,
                param: *param,
            }
        }
        ParamPath::Highlight { .. }
        | ParamPath::Camera(_)
        | ParamPath::Light(_)
        | ParamPath::Material { .. }
        | ParamPath::Shade { .. } => path.clone(),
    };
    if file.site(&resolved).is_none() {
        return Err(unknown_path(file, path));
    }
    Ok(resolved)
}

/// A [`EditError::BadPath`] for `path`, which names no track of `file`.
fn unknown_path(file: &mut ParsedFile, path: &ParamPath) -> EditError {
    let reason = match path {
        ParamPath::Material { name, .. } if !file.material_names().contains(&name.as_str()) => {
            let includes = file.includes();
            if includes.is_empty() {
                format!("this file defines no material \"{name}\"")
            } else {
                format!(
                    "this file defines no material \"{name}\"; the materials of its includes ({}) are edited in those files",
                    includes.join(", ")
                )
            }
        }
        ParamPath::Shade { entry, param } => missing_shade(file, *entry, *param),
        ParamPath::Camera(_)
        | ParamPath::Light(_)
        | ParamPath::Material { .. }
        | ParamPath::Highlight { .. } => "this file has no such track".to_string(),
    };
    bad_path(file, &path.to_string(), reason)
}

/// Why `shade[entry].…param` names no track of `file`: no such entry, no such operation, an
/// operation without that number, or no mask.
fn missing_shade(file: &ParsedFile, entry: usize, param: ShadeParam) -> String {
    let shade = file.shade();
    let Some(spec) = shade.get(entry) else {
        return match shade.len() {
            0 => format!("this file has no shade entry, so no shade[{entry}]"),
            1 => format!("this file has one shade entry, shade[0], so no shade[{entry}]"),
            n => format!(
                "this file has {n} shade entries, shade[0] to shade[{}], so no shade[{entry}]",
                n - 1
            ),
        };
    };
    match param {
        ShadeParam::Op { index, param } => match spec.stack.get(index) {
            None => format!(
                "shade[{entry}]'s stack has {} operation(s), numbered from 0, so no stack[{index}]",
                spec.stack.len()
            ),
            Some(crate::highlight::Op::Scale { .. }) if param == OpParam::Axis => format!(
                "shade[{entry}].stack[{index}]'s axis is `U` or `V`, which has no number; `Angle(φ)` has one"
            ),
            Some(op) => format!(
                "shade[{entry}].stack[{index}] is a {}, which has no `{}`",
                op.name(),
                param.name()
            ),
        },
        ShadeParam::MaskU(_) | ShadeParam::MaskV(_) | ShadeParam::MaskFeather => {
            format!("shade[{entry}] has no mask")
        }
    }
}

#[must_use]
pub(super) fn unknown_path_without_list(path: &ParamPath) -> EditError {
    EditError::BadPath {
        written: path.to_string(),
        reason: "this file has no such track".to_string(),
        nearest: None,
    }
}

/// A [`EditError::BadPath`] naming the path of `file` closest to `written` (by edit distance),
/// highlights both by index and, where a pattern picks one entry alone, by that pattern.
fn bad_path(file: &mut ParsedFile, written: &str, reason: String) -> EditError {
    let mut candidates = file.paths();
    let patterns: Vec<Option<String>> = file
        .entry_patterns()
        .iter()
        .map(|patterns| {
            patterns
                .iter()
                .find(|p| file.entries_selected_by(p).len() == 1)
                .cloned()
        })
        .collect();
    let by_pattern: Vec<ParamPath> = candidates
        .iter()
        .filter_map(|path| match path {
            ParamPath::Highlight {
                entry: HighlightRef::Index(index),
                layer,
                param,
            } => patterns
                .get(*index)
                .cloned()
                .flatten()
                .map(|pattern| ParamPath::Highlight {
                    entry: HighlightRef::Selector(pattern),
                    layer: *layer,
                    param: *param,
                }),
            ParamPath::Highlight { .. }
            | ParamPath::Camera(_)
            | ParamPath::Light(_)
            | ParamPath::Material { .. }
            | ParamPath::Shade { .. } => None,
        })
        .collect();
    candidates.extend(by_pattern);
    // Paths under the same first name (`camera`, `light`, `materials`, `highlights`, `shade`)
    // first.
    let root = |path: &str| {
        path.split(['.', '[', '{'])
            .next()
            .unwrap_or_default()
            .to_string()
    };
    let nearest = candidates.into_iter().min_by_key(|c| {
        let shown = c.to_string();
        (
            root(&shown) != root(written),
            strsim::levenshtein(written, &shown),
        )
    });
    EditError::BadPath {
        written: written.to_string(),
        reason,
        nearest,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shot::fixtures::STYLED_SHOT;

    /// Why `written` names no track of the file `text`.
    fn refusal(text: &str, written: &str) -> String {
        match parse_param_path(text, written) {
            Err(EditError::BadPath { reason, .. }) => reason,
            other => panic!("{written}: {other:?}"),
        }
    }

    #[test]
    fn a_material_path_that_names_no_track_says_whether_the_file_or_its_includes_define_it() {
        assert!(parse_param_path(STYLED_SHOT, "materials{\"m\"}.bands[0].threshold").is_ok());
        // The file's own material, without the track.
        assert_eq!(
            refusal(STYLED_SHOT, "materials{\"m\"}.bands[3].threshold"),
            "this file has no such track"
        );
        assert_eq!(
            refusal(STYLED_SHOT, "materials{\"clay\"}.base"),
            "this file defines no material \"clay\""
        );
        let including = STYLED_SHOT.replace(
            "    materials: {",
            "    includes: [\"looks/a.ron\", \"looks/b.ron\"],\n    materials: {",
        );
        assert_eq!(
            refusal(&including, "materials{\"clay\"}.base"),
            "this file defines no material \"clay\"; the materials of its includes \
             (looks/a.ron, looks/b.ron) are edited in those files"
        );
        assert_eq!(
            refusal(&including, "materials{\"m\"}.detail.r"),
            "this file has no such track"
        );
    }

    #[test]
    fn a_shade_path_that_names_no_track_says_which_part_is_missing() {
        assert_eq!(
            refusal(STYLED_SHOT, "shade[0].stack[0].alpha"),
            "this file has no shade entry, so no shade[0]"
        );
        let shaded = STYLED_SHOT.replace(
            "    highlights: [",
            "    shade: [(patches: \"ball/*\", stack: [Scale(delta: 0.5, axis: U)])],\n    highlights: [",
        );
        assert!(parse_param_path(&shaded, "shade[0].stack[0].delta").is_ok());
        for (written, reason) in [
            (
                "shade[1].stack[0].delta",
                "this file has one shade entry, shade[0], so no shade[1]",
            ),
            (
                "shade[0].stack[1].delta",
                "shade[0]'s stack has 1 operation(s), numbered from 0, so no stack[1]",
            ),
            (
                "shade[0].stack[0].axis",
                "shade[0].stack[0]'s axis is `U` or `V`, which has no number; `Angle(φ)` has one",
            ),
            (
                "shade[0].stack[0].alpha",
                "shade[0].stack[0] is a Scale, which has no `alpha`",
            ),
            ("shade[0].mask.feather", "shade[0] has no mask"),
        ] {
            assert_eq!(refusal(&shaded, written), reason, "{written}");
        }
    }
}
