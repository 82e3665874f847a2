//! The RON syntax of X-Toon descriptions, their genericity over the parameter type, and the
//! snippets of docs/xtoon.md.

use std::sync::Arc;

use glam::{DVec3, Vec3};
use glint::geom::{shapes, NamedPatch, PatchLibrary};
use glint::toon::{Abstraction, DetailMap, HighlightFrame, ShapeDetail, ToonTexture, XToon};
use serde::Deserialize;

fn sphere() -> PatchLibrary {
    PatchLibrary {
        patches: vec![NamedPatch {
            name: "sphere".into(),
            trim: None,
            surface: shapes::sphere(DVec3::ZERO, 1.0).unwrap(),
        }],
        groups: Vec::new(),
    }
}

fn texture() -> Arc<ToonTexture> {
    Arc::new(ToonTexture::new(1, 1, vec![Vec3::splat(0.5)]).unwrap())
}

#[test]
fn detail_maps_parse_from_ron() {
    let map = |s: &str| ron::from_str::<DetailMap>(s).unwrap_or_else(|e| panic!("{s}: {e}"));
    assert_eq!(
        map("Depth(z_min: 4.0, r: 3.0)"),
        DetailMap::Depth { z_min: 4.0, r: 3.0 }
    );
    assert_eq!(
        map("DepthOfField(focus: (1.0, 2.0, 3.0), z_min: 0.5, r: 4.0)"),
        DetailMap::DepthOfField {
            focus: [1.0, 2.0, 3.0],
            z_min: 0.5,
            r: 4.0
        }
    );
    assert_eq!(
        map("NearSilhouette(r: 2.0)"),
        DetailMap::NearSilhouette { r: 2.0 }
    );
    assert_eq!(map("Highlight(s: 20.0)"), DetailMap::Highlight { s: 20.0 });
    for bad in [
        "Depth(z_min: 4.0)",
        "Depth(z_min: 4.0, r: 3.0, z_max: 9.0)",
        "Fog(density: 1.0)",
        "Highlight(shininess: 20.0)",
    ] {
        assert!(ron::from_str::<DetailMap>(bad).is_err(), "{bad} accepted");
    }
}

#[test]
fn tones_parse_with_their_defaults_and_refuse_unknown_fields() {
    let tone: XToon = ron::from_str("(detail: Highlight(s: 8.0))").unwrap();
    assert!(!tone.invert && tone.shape.is_none());
    let tone: XToon = ron::from_str(
        "(detail: NearSilhouette(r: 1.0), shape: Some((abstraction: Smoothed(iterations: 3), weight: 0.25)))",
    )
    .unwrap();
    assert_eq!(
        tone.shape,
        Some(ShapeDetail {
            abstraction: Abstraction::Smoothed { iterations: 3 },
            weight: 0.25,
            highlight_frame: HighlightFrame::Abstracted,
        })
    );
    for bad in [
        "(detail: Highlight(s: 8.0), texture: \"a.png\")",
        "(detail: Highlight(s: 8.0), shape: Some((abstraction: Cone, weight: 0.5)))",
        "(detail: Highlight(s: 8.0), shape: Some((abstraction: Sphere, weight: 0.5, w: 1.0)))",
    ] {
        assert!(ron::from_str::<XToon>(bad).is_err(), "{bad} accepted");
    }
}

/// A stand-in for an animation track: a constant or `(frame, value)` keys, linear between.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(untagged)]
enum Track {
    Constant(f32),
    Keys(Vec<(f32, f32)>),
}

impl Track {
    fn at(&self, frame: f32) -> f32 {
        match self {
            Track::Constant(v) => *v,
            Track::Keys(k) => {
                let i = k.iter().rposition(|&(f, _)| f <= frame).unwrap_or(0);
                match (k.get(i), k.get(i + 1)) {
                    (Some(&(f0, v0)), Some(&(f1, v1))) if frame >= f0 => {
                        v0 + (v1 - v0) * (frame - f0) / (f1 - f0)
                    }
                    (Some(&(_, v0)), _) => v0,
                    _ => 0.0,
                }
            }
        }
    }
}

#[test]
fn every_number_can_be_a_track() {
    let animated: XToon<Track> = ron::from_str(
        "(detail: DepthOfField(focus: (0.0, [(0.0, 0.0), (10.0, 5.0)], 1.0), z_min: 0.5, r: 4.0),
          shape: Some((abstraction: Sphere, weight: [(0.0, 0.0), (10.0, 1.0)])))",
    )
    .unwrap();
    let mut count = 0;
    let at4: XToon = animated.map(|t| {
        count += 1;
        t.at(4.0)
    });
    assert_eq!(count, 3 + 2 + 1);
    let DetailMap::DepthOfField { focus, .. } = at4.detail else {
        panic!("{at4:?}")
    };
    assert_eq!(focus, [0.0, 2.0, 1.0]);
    assert!((at4.shape.as_ref().unwrap().weight - 0.4).abs() < 1e-6);
    let library = sphere();
    let built = Abstraction::Sphere.build(&library).unwrap();
    let prepared = at4.prepare(texture(), Some(&built)).unwrap();
    assert!(prepared.abstracts_highlights());
    // At frame 0 the weight is 0: no shape to blend, so highlights keep the true frame.
    let at0 = animated.map(|t| t.at(0.0));
    assert!(!at0
        .prepare(texture(), Some(&built))
        .unwrap()
        .abstracts_highlights());
}

#[test]
fn a_shape_detail_without_its_built_shape_is_an_error() {
    let tone: XToon = ron::from_str(
        "(detail: Highlight(s: 8.0), shape: Some((abstraction: Ellipsoid, weight: 0.5)))",
    )
    .unwrap();
    let e = tone.prepare(texture(), None).unwrap_err();
    assert!(e.to_string().contains("Ellipsoid"), "{e}");
}

#[test]
fn the_snippets_of_docs_xtoon_parse_and_prepare() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/xtoon.md");
    let doc = std::fs::read_to_string(path).unwrap();
    let blocks: Vec<&str> = doc
        .split("```ron\n")
        .skip(1)
        .map(|rest| &rest[..rest.find("```").unwrap()])
        .collect();
    assert_eq!(blocks.len(), 2);
    let library = sphere();
    let tone: XToon = ron::from_str(blocks[0]).unwrap();
    let shape = tone.shape.as_ref().unwrap();
    let built = shape.abstraction.build(&library).unwrap();
    tone.prepare(texture(), Some(&built)).unwrap();
    let shape: ShapeDetail = ron::from_str(blocks[1]).unwrap();
    assert_eq!(shape.highlight_frame, HighlightFrame::True);
    shape
        .prepare(&shape.abstraction.build(&library).unwrap())
        .unwrap();
    // Every detail map of the table parses and prepares, one of each kind.
    let mut kinds = Vec::new();
    for row in doc.lines().filter(|l| l.starts_with("| ")) {
        let cells: Vec<&str> = row.split(" | ").collect();
        if let Some(map) = cells
            .get(1)
            .and_then(|c| c.strip_prefix('`')?.strip_suffix('`'))
        {
            if let Ok(map) = ron::from_str::<DetailMap>(map) {
                map.prepare(false).unwrap();
                kinds.push(std::mem::discriminant(&map));
            }
        }
    }
    kinds.dedup();
    assert_eq!(kinds.len(), 4);
}
