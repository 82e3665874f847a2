//! A file's tracks asked after by parameter path: which there are, where each is written, how
//! each reads on one line.

use std::ops::Range;

use super::error::EditError;
use super::param_path::ParamPath;
use super::param_sites::TrackMut;
use super::read::read_file;
use super::resolve::{resolve, unknown_path_without_list};
use super::track_line::{default_text, one_line, written_track};
use crate::formats::ron_paths::try_span;
use crate::formats::ron_paths::Step::Index;

/// Every parameter path of the file `text`, in the order written: the camera's and light's
/// tracks, each material's, each highlight layer's (entries by index), and after a whole
/// `colour` or `focus` each of its components. Tracks left to their default are included.
pub fn param_paths(text: &str) -> Result<Vec<ParamPath>, EditError> {
    Ok(read_file(text)?.paths())
}

/// Every parameter path of the file `text` ([`param_paths`]) with its track on one line
/// ([`track_text`]).
pub fn track_texts(text: &str) -> Result<Vec<(ParamPath, String)>, EditError> {
    let mut file = read_file(text)?;
    let mut tracks = Vec::new();
    file.for_each_site(&mut |site| {
        let shown = match try_span(text, &site.steps) {
            Some(span) => one_line(&text[span]),
            None => default_text(&site.track),
        };
        tracks.push((site.path.clone(), shown));
        if let TrackMut::Triple(components) = &site.track {
            for (c, component) in components.iter().enumerate() {
                let mut steps = site.steps.clone();
                steps.push(Index(c));
                let shown = match try_span(text, &steps) {
                    Some(span) => one_line(&text[span]),
                    None => written_track(component, |&x| vec![x]),
                };
                if let Some(path) = site.path.try_with_component(c) {
                    tracks.push((path, shown));
                }
            }
        }
    });
    Ok(tracks)
}

/// The bytes of `text` the track at `path` is written in, or `None` for a track left to its
/// default. For a whole `colour` or `focus`, the span of all three.
pub fn track_span(text: &str, path: &ParamPath) -> Result<Option<Range<usize>>, EditError> {
    let mut file = read_file(text)?;
    let path = resolve(&mut file, path)?;
    let site = file
        .site(&path)
        .ok_or_else(|| unknown_path_without_list(&path))?;
    Ok(try_span(text, &site.steps))
}

/// The track at `path` of the file `text` on one line, as written there (comments and line
/// breaks dropped), or, left to its default, as it would be written (`none` for no feather).
pub fn track_text(text: &str, path: &ParamPath) -> Result<String, EditError> {
    let mut file = read_file(text)?;
    let path = resolve(&mut file, path)?;
    let site = file
        .site(&path)
        .ok_or_else(|| unknown_path_without_list(&path))?;
    Ok(match try_span(text, &site.steps) {
        Some(span) => one_line(&text[span]),
        None => default_text(&site.track),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shot::fixtures::{param_path, STYLED_SHOT};
    use crate::shot::parse_param_path;

    #[test]
    fn paths_name_every_track_in_the_order_written() {
        let layer0 = "highlights[0].layers[0]";
        let layer1 = "highlights[0].layers[1]";
        let layer2 = "highlights[1].layers[0]";
        let mut expected: Vec<String> = [
            "camera.eye",
            "camera.target",
            "camera.up",
            "camera.projection.height",
            "light.towards",
            "materials{\"m\"}.base",
            "materials{\"m\"}.bands[0].threshold",
            "materials{\"m\"}.bands[0].colour",
        ]
        .map(String::from)
        .to_vec();
        let layer = |prefix: &str, fields: &[&str]| -> Vec<String> {
            fields.iter().map(|f| format!("{prefix}.{f}")).collect()
        };
        let colour = ["colour", "colour[0]", "colour[1]", "colour[2]"];
        expected.extend(layer(
            layer0,
            &["stack[0].delta", "stack[0].axis", "epsilon"],
        ));
        expected.extend(layer(layer0, &colour));
        expected.extend(layer(layer0, &["opacity", "feather"]));
        expected.extend(layer(
            layer1,
            &["stack[0].alpha", "stack[0].beta", "epsilon"],
        ));
        expected.extend(layer(layer1, &colour));
        expected.extend(layer(
            layer1,
            &[
                "opacity",
                "feather",
                "mask.u[0]",
                "mask.u[1]",
                "mask.v[0]",
                "mask.v[1]",
            ],
        ));
        expected.extend(
            layer(layer1, &["mask.feather", "epsilon"])
                .into_iter()
                .take(1),
        );
        expected.extend(layer(layer2, &["epsilon"]));
        expected.extend(layer(layer2, &colour));
        expected.extend(layer(layer2, &["opacity", "feather"]));
        let paths: Vec<String> = param_paths(STYLED_SHOT)
            .unwrap()
            .iter()
            .map(ToString::to_string)
            .collect();
        assert_eq!(paths, expected);
        for written in &expected {
            assert_eq!(
                parse_param_path(STYLED_SHOT, written),
                Ok(param_path(written))
            );
        }
    }

    #[test]
    fn a_track_is_shown_on_one_line() {
        assert_eq!(
            track_text(STYLED_SHOT, &param_path("light.towards")).unwrap(),
            "[(1, (0.0, -1.0, 0.0)), (24, (1.0, 0.0, 0.0))]"
        );
        assert_eq!(
            track_text(STYLED_SHOT, &param_path("camera.up")).unwrap(),
            "(0.0, 0.0, 1.0)"
        );
        assert_eq!(
            track_text(STYLED_SHOT, &param_path("highlights[1].layers[0].feather")).unwrap(),
            "none"
        );
        let texts = track_texts(STYLED_SHOT).unwrap();
        assert_eq!(texts.len(), param_paths(STYLED_SHOT).unwrap().len());
        for (path, text) in texts {
            assert_eq!(track_text(STYLED_SHOT, &path), Ok(text));
        }
    }

    #[test]
    fn a_track_s_span_is_where_it_is_written_and_none_where_it_is_left_to_its_default() {
        let span = |written: &str| track_span(STYLED_SHOT, &param_path(written)).unwrap();
        let text = |written: &str| span(written).map(|s| &STYLED_SHOT[s]);
        assert_eq!(text("camera.target"), Some("(0.0, 0.0, 0.0)"));
        assert_eq!(
            text("highlights[0].layers[1].stack[0].alpha"),
            Some("[(1, 0.6), (24, 0.15)]")
        );
        assert_eq!(text("highlights[0].layers[1].feather"), Some("0.01"));
        // Left to their defaults: no bytes.
        assert_eq!(span("camera.up"), None);
        assert_eq!(span("highlights[1].layers[0].feather"), None);
        // Selected by pattern, as by index.
        assert_eq!(
            span("highlights[\"ball/*\"].layers[0].epsilon"),
            span("highlights[0].layers[0].epsilon")
        );
        assert!(track_span(STYLED_SHOT, &param_path("shade[0].mask.feather")).is_err());
    }
}
