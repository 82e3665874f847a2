//! A frame's lines as an SVG document: one stroked path per stroke, in pixel coordinates,
//! grouped by kind and by part so that an ink-and-paint artist can select them.
//!
//! ```text
//! <svg width="W" height="H" viewBox="0 0 W H">
//!   <g id="silhouette" class="lines silhouette">          one group per kind drawn
//!     <g id="silhouette.teapot-lid" class="part" data-part="teapot/lid">
//!       <path d="M x y L x y …" stroke="#rrggbb" stroke-width="w"/>
//!       <path class="taper" d="M … Z" fill="#rrggbb"/>
//!   <g id="hidden-silhouette" class="lines hidden silhouette">   hidden lines, kind by kind
//!     <g id="hidden-silhouette.teapot-lid" class="part" data-part="teapot/lid">
//!       <path d="…" stroke="#rrggbb" stroke-width="w" stroke-dasharray="4 3"
//!             stroke-dashoffset="o"/>
//! ```
//!
//! A stroke of one width is a stroked path with round caps and joins, as the frame draws it; a
//! closed line ends with `Z`. A taper (a stroke whose width changes along it) is a filled
//! outline, class `taper`: the polyline offset by half its width on either side, each point
//! along the mean of its two neighbours' directions. Coordinates are pixels with the origin
//! at the image's top left corner, to 1/1000 px. A hidden line is a stroked path in its dash
//! pattern, its offset where along its stretch it starts, so that its dashes fall where the
//! frame's do.

use std::fmt::Write as _;

use glam::Vec2;

use super::srgb::{byte, linear_to_srgb};
use crate::render::{LineKind, VectorLines, VectorStroke};

/// The attribute a stamp (a frame's fingerprint) is stored under, on the document's
/// `<metadata>` element: `<metadata data-key="KEY">VALUE</metadata>`.
const STAMP: &str = "data-key";

/// The word a kind's group is named by.
#[must_use]
pub fn kind_name(kind: LineKind) -> &'static str {
    match kind {
        LineKind::Silhouette => "silhouette",
        LineKind::Crease => "crease",
        LineKind::Border => "border",
        LineKind::Intersection => "intersection",
        LineKind::MaterialBorder => "material-border",
        LineKind::LightContour => "light-contour",
    }
}

/// `text` made a valid XML name part: every character but ASCII letters, digits, `-`, `_` and
/// `.` becomes `-`.
fn id_part(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '-' | '_' | '.') {
                c
            } else {
                '-'
            }
        })
        .collect()
}

/// `text` with `&`, `<`, `>` and `"` escaped for an attribute value.
fn escaped(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A coordinate or width to 1/1000, without trailing zeros.
fn number(v: f32) -> String {
    let text = format!("{:.3}", v);
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".to_string()
    } else {
        text.to_string()
    }
}

/// The SVG document of `lines`, with the `(key, value)` stamps of `tags` in its metadata.
#[must_use]
pub fn svg_document(lines: &VectorLines, tags: &[(&str, &str)]) -> String {
    let (w, h) = lines.size;
    let mut out = String::new();
    out.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let _ = writeln!(
        out,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" \
         viewBox=\"0 0 {w} {h}\">"
    );
    for (key, value) in tags {
        let _ = writeln!(
            out,
            "  <metadata {STAMP}=\"{}\">{}</metadata>",
            escaped(key),
            escaped(value)
        );
    }
    let mut ids: Vec<String> = Vec::new();
    for (hidden, kind) in [false, true]
        .into_iter()
        .flat_map(|h| LineKind::ALL.map(|k| (h, k)))
    {
        let of_group = |s: &&VectorStroke| s.kind == kind && s.hidden == hidden;
        if !lines.strokes.iter().any(|s| of_group(&s)) {
            continue;
        }
        let name = if hidden {
            format!("hidden-{}", kind_name(kind))
        } else {
            kind_name(kind).to_string()
        };
        let class = if hidden {
            format!("lines hidden {}", kind_name(kind))
        } else {
            format!("lines {name}")
        };
        let _ = writeln!(
            out,
            "  <g id=\"{name}\" class=\"{class}\" fill=\"none\" stroke-linecap=\"round\" \
             stroke-linejoin=\"round\">"
        );
        for (p, part) in lines.parts.iter().enumerate() {
            let strokes: Vec<_> = lines
                .strokes
                .iter()
                .filter(|s| of_group(s) && s.part as usize == p)
                .collect();
            if strokes.is_empty() {
                continue;
            }
            // Ids stay distinct when two part names differ only in characters ids cannot hold.
            let mut id = format!("{name}.{}", id_part(part));
            if ids.contains(&id) {
                id = format!("{id}.{p}");
            }
            ids.push(id.clone());
            let _ = writeln!(
                out,
                "    <g id=\"{id}\" class=\"part\" data-part=\"{}\">",
                escaped(part)
            );
            for s in strokes {
                write_stroke(&mut out, s);
            }
            out.push_str("    </g>\n");
        }
        out.push_str("  </g>\n");
    }
    out.push_str("</svg>\n");
    out
}

/// One stroke as a `<path>` element: stroked at one width (dashed in its pattern, from its
/// offset along it), or filled as the outline of a taper.
fn write_stroke(out: &mut String, s: &VectorStroke) {
    let c = s.colour.to_array().map(|v| byte(linear_to_srgb(v)));
    let colour = format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2]);
    match s.uniform_width() {
        Some(width) => {
            let d = path_data(&s.points, s.closed);
            let _ = write!(
                out,
                "      <path d=\"{d}\" stroke=\"{colour}\" stroke-width=\"{}\"",
                number(width)
            );
            if !s.dash.is_solid() {
                let lengths: Vec<String> = s.dash.lengths().iter().map(|&l| number(l)).collect();
                let _ = write!(out, " stroke-dasharray=\"{}\"", lengths.join(" "));
                if s.dash_offset > 0.0 {
                    let _ = write!(out, " stroke-dashoffset=\"{}\"", number(s.dash_offset));
                }
            }
        }
        None => {
            let d = path_data(&outline(&s.points, &s.widths), true);
            let _ = write!(
                out,
                "      <path class=\"taper\" d=\"{d}\" fill=\"{colour}\" stroke=\"none\""
            );
        }
    }
    if s.opacity < 1.0 {
        let _ = write!(out, " opacity=\"{}\"", number(s.opacity));
    }
    out.push_str("/>\n");
}

/// `M x y L x y …`, with `Z` when `closed`.
fn path_data(points: &[Vec2], closed: bool) -> String {
    let mut d = String::new();
    for (k, point) in points.iter().enumerate() {
        let command = if k == 0 { 'M' } else { 'L' };
        let _ = write!(d, "{command}{} {}", number(point.x), number(point.y));
    }
    if closed {
        d.push('Z');
    }
    d
}

/// The outline of a polyline of `widths`: along its left side, `pᵢ + nᵢ wᵢ / 2`, and back
/// along its right, `pᵢ − nᵢ wᵢ / 2`, where `nᵢ` is the unit normal of `pᵢ₊₁ − pᵢ₋₁` (one-sided
/// at the ends; the last good one where points repeat).
fn outline(points: &[Vec2], widths: &[f32]) -> Vec<Vec2> {
    let n = points.len();
    let mut normal = Vec2::Y;
    let normals: Vec<Vec2> = (0..n)
        .map(|i| {
            let along = points[(i + 1).min(n - 1)] - points[i.saturating_sub(1)];
            if let Some(unit) = along.try_normalize() {
                normal = unit.perp();
            }
            normal
        })
        .collect();
    let side = |sign: f32, i: usize| points[i] + normals[i] * (sign * widths[i] / 2.0);
    (0..n)
        .map(|i| side(1.0, i))
        .chain((0..n).rev().map(|i| side(-1.0, i)))
        .collect()
}

/// What an SVG document written by [`svg_document`] says of itself: its size, and the value
/// stamped under `key` (None when there is none). Err when it is not such a whole document.
pub fn try_read_svg(text: &str, key: &str) -> Result<((u32, u32), Option<String>), String> {
    let attribute = |name: &str| -> Result<u32, String> {
        let start = text.find("<svg ").ok_or("no <svg> element")?;
        let tag = &text[start..];
        let tag = &tag[..tag.find('>').ok_or("the <svg> element does not end")?];
        let from = tag
            .find(&format!(" {name}=\""))
            .ok_or(format!("the <svg> element has no {name}"))?
            + name.len()
            + 3;
        let value = &tag[from..];
        let value = &value[..value.find('"').ok_or("an attribute does not end")?];
        value
            .parse()
            .map_err(|_| format!("the <svg> element's {name} is not a whole number"))
    };
    let size = (attribute("width")?, attribute("height")?);
    if !text.trim_end().ends_with("</svg>") {
        return Err("the document does not end with </svg> (truncated?)".to_string());
    }
    let marker = format!("<metadata {STAMP}=\"{}\">", escaped(key));
    let stamp = text.find(&marker).and_then(|start| {
        let value = &text[start + marker.len()..];
        value
            .find("</metadata>")
            .map(|end| value[..end].to_string())
    });
    Ok((size, stamp))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::render::{Dash, VectorStroke};
    use glam::{Vec2, Vec3};

    fn lines() -> VectorLines {
        VectorLines {
            size: (64, 32),
            parts: vec!["teapot/lid".to_string(), "teapot<lid>".to_string()],
            strokes: vec![
                VectorStroke {
                    kind: LineKind::Silhouette,
                    part: 0,
                    colour: Vec3::new(1.0, 0.0, 0.2159),
                    opacity: 1.0,
                    points: vec![
                        Vec2::new(1.0, 2.5),
                        Vec2::new(10.125, 3.0),
                        Vec2::new(4.0, 9.0),
                    ],
                    widths: vec![2.0; 3],
                    closed: true,
                    hidden: false,
                    dash: Dash::SOLID,
                    dash_offset: 0.0,
                },
                VectorStroke {
                    kind: LineKind::Crease,
                    part: 1,
                    colour: Vec3::ZERO,
                    opacity: 0.5,
                    points: vec![Vec2::new(0.0, 0.0), Vec2::new(-0.0001, 31.0)],
                    widths: vec![1.25; 2],
                    closed: false,
                    hidden: false,
                    dash: Dash::SOLID,
                    dash_offset: 0.0,
                },
                VectorStroke {
                    kind: LineKind::Silhouette,
                    part: 0,
                    colour: Vec3::new(1.0, 0.0, 0.0),
                    opacity: 1.0,
                    points: vec![Vec2::new(5.0, 5.0), Vec2::new(20.0, 5.0)],
                    widths: vec![1.0; 2],
                    closed: false,
                    hidden: true,
                    dash: Dash::try_new(&[4.0, 2.5]).unwrap(),
                    dash_offset: 3.25,
                },
            ],
        }
    }

    #[test]
    fn strokes_become_paths_grouped_by_kind_and_part() {
        let svg = svg_document(&lines(), &[("glint:fingerprint", "abc")]);
        assert!(svg.contains("viewBox=\"0 0 64 32\""));
        assert!(svg.contains("<g id=\"silhouette\" class=\"lines silhouette\""));
        // A hidden line in a group of its own, dashed from where along its stretch it starts.
        assert!(svg.contains("<g id=\"hidden-silhouette\" class=\"lines hidden silhouette\""));
        assert!(svg.contains(
            "<path d=\"M5 5L20 5\" stroke=\"#ff0000\" stroke-width=\"1\" \
             stroke-dasharray=\"4 2.5\" stroke-dashoffset=\"3.25\"/>"
        ));
        assert!(svg
            .contains("<g id=\"silhouette.teapot-lid\" class=\"part\" data-part=\"teapot/lid\">"));
        assert!(svg
            .contains("<path d=\"M1 2.5L10.125 3L4 9Z\" stroke=\"#ff0080\" stroke-width=\"2\"/>"));
        assert!(svg.contains("data-part=\"teapot&lt;lid&gt;\""));
        assert!(svg.contains(
            "<path d=\"M0 0L0 31\" stroke=\"#000000\" stroke-width=\"1.25\" opacity=\"0.5\"/>"
        ));
        // No group for a kind nothing draws.
        assert!(!svg.contains("id=\"border\""));
        let (size, stamp) = try_read_svg(&svg, "glint:fingerprint").unwrap();
        assert_eq!(size, (64, 32));
        assert_eq!(stamp.as_deref(), Some("abc"));
    }

    #[test]
    fn a_truncated_or_foreign_document_is_refused_and_an_unstamped_one_has_no_stamp() {
        let svg = svg_document(&lines(), &[]);
        assert_eq!(try_read_svg(&svg, "glint:fingerprint").unwrap().1, None);
        assert!(try_read_svg(&svg[..svg.len() / 2], "k").is_err());
        assert!(try_read_svg("<html></html>", "k").is_err());
        assert!(try_read_svg("<svg width=\"a\" height=\"2\"></svg>", "k").is_err());
    }

    #[test]
    fn a_taper_is_a_filled_outline_half_its_width_either_side() {
        let mut l = lines();
        l.strokes.truncate(1);
        l.strokes[0].points = vec![
            Vec2::new(0.0, 10.0),
            Vec2::new(4.0, 10.0),
            Vec2::new(8.0, 10.0),
        ];
        l.strokes[0].widths = vec![2.0, 1.0, 0.0];
        l.strokes[0].closed = false;
        let svg = svg_document(&l, &[]);
        // Left side (y + w/2 along the normal (0, 1)), then the right side back.
        assert!(
            svg.contains(
                "<path class=\"taper\" d=\"M0 11L4 10.5L8 10L8 10L4 9.5L0 9Z\" fill=\"#ff0080\""
            ),
            "{svg}"
        );
    }

    #[test]
    fn ids_that_would_repeat_are_kept_apart() {
        let mut l = lines();
        l.parts = vec!["a/b".to_string(), "a<b".to_string()];
        l.strokes[1].kind = LineKind::Silhouette;
        let svg = svg_document(&l, &[]);
        assert!(svg.contains("id=\"silhouette.a-b\""));
        assert!(svg.contains("id=\"silhouette.a-b.1\""));
    }
}
