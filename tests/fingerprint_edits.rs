//! A frame's fingerprint changes when what the frame renders changes, and only then: edits of every
//! kind of input a shot has — its instances' materials, transforms and parts, the parts file, an
//! included look library, selectors, pins, masks, shade entries and the light a highlight
//! reads, line styles, a texture, a patch file, the
//! render settings, keys at and away from a frame, comments and spacing — drawn at random, each
//! rendered at a small size before and after.

use std::path::PathBuf;
use std::sync::OnceLock;

use glint::job::{Overrides, RenderJob};
use glint::render::RenderedFrame;
use proptest::prelude::*;

use crate::common::repo_file;

/// The frames compared: the first, two between keys, and the last.
const FRAMES: [i64; 4] = [1, 4, 9, 12];

/// The shot edited: a teapot whose lid opens on its hinge, a ring that holds, then drives; a
/// highlight on the body (keyed, masked) and one pinned on the lid; a line style on the spout;
/// an included look library with a textured X-Toon material.
const SHOT: &str = r#"// The shot the fingerprint edits start from.
Shot(
    resolution: (64, 36),
    frames: (1, 12),
    fps: 24,
    output: "../out/e.####.png",
    includes: ["looks/base.ron"],
    instances: [
        (
            name: "teapot",
            file: "../patches/teapot.bpt",
            material: "clay",
            parts: {
                "lid": (pivot: (-1.4, 0.0, 2.45), axis: (0, 1, 0), degrees: [(1, 0), (12, -30)]),
            },
        ),
        (
            name: "ring",
            file: "../patches/torus.ron",
            material: "plastic",
            transform: (translate: [(1, (2.6, -1.4, 0.4)), (6, (2.6, -1.4, 0.4)), (12, (2.2, -1.6, 0.6))]),
        ),
    ],
    camera: (eye: (0.8, -9.2, 5.0), target: (0.6, 0.0, 1.1), projection: Perspective(fov_y_degrees: 34.0)),
    light: Directional(towards: (-0.352, -0.553, 0.755)),
    highlights: [
        (
            patches: "teapot/body",
            expr: Layer((
                stack: [Translate(alpha: [(1, 0.0), (12, 0.3)], beta: 0.1)],
                epsilon: 0.08,
                colour: (1.0, 1.0, 1.0),
                mask: (u: (0.0, 0.8), v: (0.0, 1.0), feather: 0.05),
            )),
        ),
        (
            patches: "teapot/lid",
            expr: Layer((
                stack: [],
                epsilon: 0.05,
                colour: (1.0, 0.9, 0.6),
                pin: (patch: "teapot/25", u: 0.3, v: 0.5),
            )),
        ),
    ],
    lines: [(patches: ["teapot/spout"], width: 2.0, colour: (0.3, 0.1, 0.0))],
    render: (
        preset: Preview,
        outlines: (width: 1.0, colour: (0.0, 0.0, 0.0), crease_degrees: 70.0),
    ),
)
"#;

/// The look library the shot includes.
const LOOKS: &str = r#"Looks(
    materials: {
        "clay": Cel(base: (0.30, 0.10, 0.06), bands: [(0.05, (0.75, 0.35, 0.20))]),
        "porcelain": Cel(base: (0.10, 0.16, 0.32), bands: [(0.0, (0.30, 0.45, 0.80))]),
        "plastic": XToon(texture: "../../textures/plastic_highlight.png", detail: Highlight(s: 8.0)),
        "clay_twin": Cel(base: (0.3, 0.1, 0.06), bands: [(0.05, (0.75, 0.35, 0.2))]),
    },
)
"#;

/// A second look library an edit includes: a highlight on the spout.
const EXTRA_LOOKS: &str = r#"Looks(
    highlights: [
        (patches: "teapot/spout", expr: Layer((stack: [], epsilon: 0.15, colour: (0.2, 1.0, 0.2)))),
    ],
)
"#;

/// A folder holding the shot and every file it reads.
struct Fixture {
    dir: tempfile::TempDir,
}

impl Fixture {
    fn new() -> Self {
        let dir = tempfile::tempdir().unwrap();
        for sub in ["shots/looks", "patches", "textures"] {
            std::fs::create_dir_all(dir.path().join(sub)).unwrap();
        }
        for file in [
            "patches/teapot.bpt",
            "patches/teapot.parts.ron",
            "patches/torus.ron",
            "textures/plastic_highlight.png",
        ] {
            std::fs::copy(repo_file(file), dir.path().join(file)).unwrap();
        }
        let fixture = Self { dir };
        fixture.write("shots/edit.ron", SHOT);
        fixture.write("shots/looks/base.ron", LOOKS);
        fixture.write("shots/looks/extra.ron", EXTRA_LOOKS);
        fixture
    }

    fn path(&self, file: &str) -> PathBuf {
        self.dir.path().join(file)
    }

    fn read(&self, file: &str) -> String {
        std::fs::read_to_string(self.path(file)).unwrap()
    }

    fn write(&self, file: &str, text: &str) {
        std::fs::write(self.path(file), text).unwrap();
    }

    /// Replaces the one `from` in `file` with `to`.
    fn replace(&self, file: &str, from: &str, to: &str) {
        let text = self.read(file);
        assert_eq!(text.matches(from).count(), 1, "{from:?} once in {file}");
        self.write(file, &text.replacen(from, to, 1));
    }

    /// Each compared frame's fingerprint and rendered colour and AOVs, as bits.
    fn frames(&self) -> Vec<(String, Vec<u32>)> {
        let overrides = Overrides {
            frames: Some(FRAMES.to_vec()),
            ..Overrides::default()
        };
        let mut job = RenderJob::load(&self.path("shots/edit.ron"), &overrides).unwrap();
        FRAMES
            .iter()
            .map(|&f| {
                let fingerprint = job.fingerprint(f).unwrap().0;
                let frame = job.render_frame(f as f64).unwrap();
                (fingerprint, bits(&frame))
            })
            .collect()
    }
}

/// A frame's colour and AOVs, bit for bit.
fn bits(frame: &RenderedFrame) -> Vec<u32> {
    let mut bits: Vec<u32> = frame
        .colour
        .iter()
        .flat_map(|c| c.to_array().map(f32::to_bits))
        .collect();
    bits.extend(format!("{:?}", frame.aovs).bytes().map(u32::from));
    bits
}

/// The unedited fixture's frames, rendered once.
fn unedited() -> &'static [(String, Vec<u32>)] {
    static FRAMES: OnceLock<Vec<(String, Vec<u32>)>> = OnceLock::new();
    FRAMES.get_or_init(|| Fixture::new().frames())
}

/// An edit of one of the shot's inputs.
#[derive(Clone, Debug)]
enum Edit {
    /// The teapot's material, one of the look library's others.
    Material(&'static str),
    /// The ring's last translation key moved along x.
    RingKey(f64),
    /// The lid's last angle.
    LidDegrees(f64),
    /// Patch 25 (where the lid's glint is pinned) moved from the lid to the body in the parts
    /// file.
    PartsFile,
    /// The second look library included.
    Include,
    /// The body highlight's selector.
    Selector(&'static str),
    /// The spout's line width.
    LineWidth(f64),
    /// The pin's u.
    PinU(f64),
    /// The lid's pin holds the shape of this frame.
    Hold(i64),
    /// The mask's upper u bound.
    MaskU(f64),
    /// The X-Toon texture's colours scaled.
    Texture(f32),
    /// The torus's tube radius, in its patch file.
    PatchFile(f64),
    /// One control point of the teapot file moved up.
    TeapotPoint(f64),
    /// The outlines' width.
    OutlineWidth(f64),
    /// The light turned.
    Light(f64),
    /// A material's band colour in the look library.
    BandColour(f64),
    /// A key of the body highlight's translation at a frame between its keys.
    AlphaKey(i64, f64),
    /// A shade entry added on the ring, its light translated by α.
    Shade(f64),
    /// A shade entry added on the lid, pushing its light far enough to move its band edge on
    /// every frame, with the lid's pinned highlight reading the designed light.
    DesignedHighlight,
    /// The teapot's knob in porcelain (`part_materials`).
    PartMaterial,
    /// The teapot's lines drawn where up to this many surfaces hide them, dashed.
    Hidden(u32),
    /// The body's lines: its silhouettes and light contours.
    LightContours,
    /// A key in the ring's hold, at its held value: no frame changes.
    KeyInHold(i64),
    /// A comment and spacing: no frame changes.
    Comment,
}

impl Edit {
    /// Whether the edit can change no frame's input, whatever it is.
    fn changes_nothing(&self) -> bool {
        matches!(self, Edit::KeyInHold(_) | Edit::Comment)
    }

    fn apply(&self, fixture: &Fixture) {
        let shot = "shots/edit.ron";
        match *self {
            Edit::Material(name) => {
                fixture.replace(shot, r#"material: "clay""#, &format!("material: {name:?}"));
            }
            Edit::RingKey(dx) => fixture.replace(
                shot,
                "(12, (2.2, -1.6, 0.6))",
                &format!("(12, ({:?}, -1.6, 0.6))", 2.2 + dx),
            ),
            Edit::LidDegrees(d) => {
                fixture.replace(shot, "(12, -30)", &format!("(12, {d:?})"));
            }
            Edit::PartsFile => {
                let file = "patches/teapot.parts.ron";
                fixture.replace(file, r#""body": [4,"#, r#""body": [25, 4,"#);
                fixture.replace(file, "[24, 25, 26, 27]", "[24, 26, 27]");
            }
            Edit::Include => fixture.replace(
                shot,
                r#"includes: ["looks/base.ron"]"#,
                r#"includes: ["looks/base.ron", "looks/extra.ron"]"#,
            ),
            Edit::Selector(selector) => fixture.replace(
                shot,
                r#"patches: "teapot/body""#,
                &format!("patches: {selector:?}"),
            ),
            Edit::LineWidth(w) => {
                fixture.replace(
                    shot,
                    "width: 2.0, colour: (0.3",
                    &format!("width: {w:?}, colour: (0.3"),
                );
            }
            Edit::PinU(u) => fixture.replace(shot, "u: 0.3, v: 0.5", &format!("u: {u:?}, v: 0.5")),
            Edit::Hold(frame) => {
                fixture.replace(shot, "u: 0.3, v: 0.5)", &format!("u: 0.3, v: 0.5, hold: {frame})"))
            }
            Edit::MaskU(u) => fixture.replace(shot, "u: (0.0, 0.8)", &format!("u: (0.0, {u:?})")),
            Edit::Texture(scale) => {
                let path = fixture.path("textures/plastic_highlight.png");
                let mut image = image::open(&path).unwrap().to_rgb8();
                for p in image.pixels_mut() {
                    p.0 = p.0.map(|c| (f32::from(c) * scale).min(255.0) as u8);
                }
                image.save(&path).unwrap();
            }
            Edit::PatchFile(r) => fixture.replace(
                "patches/torus.ron",
                "minor_radius: 0.35",
                &format!("minor_radius: {r:?}"),
            ),
            Edit::TeapotPoint(dz) => {
                // The first control point of patch 4, of the body, facing the camera.
                let file = "patches/teapot.bpt";
                let text = fixture.read(file);
                let mut lines: Vec<String> = text.lines().map(String::from).collect();
                let line = 1 + 4 * 17 + 1;
                let mut xyz: Vec<f64> = lines[line]
                    .split_whitespace()
                    .map(|x| x.parse().unwrap())
                    .collect();
                xyz[2] += dz;
                lines[line] = format!("{:?} {:?} {:?}", xyz[0], xyz[1], xyz[2]);
                fixture.write(file, &(lines.join("\n") + "\n"));
            }
            Edit::OutlineWidth(w) => fixture.replace(
                shot,
                "outlines: (width: 1.0",
                &format!("outlines: (width: {w:?}"),
            ),
            Edit::Light(x) => fixture.replace(
                shot,
                "towards: (-0.352,",
                &format!("towards: ({:?},", -0.352 + x),
            ),
            Edit::BandColour(r) => fixture.replace(
                "shots/looks/base.ron",
                "(0.05, (0.75, 0.35, 0.20))",
                &format!("(0.05, ({r:?}, 0.35, 0.20))"),
            ),
            Edit::AlphaKey(frame, alpha) => fixture.replace(
                shot,
                "alpha: [(1, 0.0), (12, 0.3)]",
                &format!("alpha: [(1, 0.0), ({frame}, {alpha:?}), (12, 0.3)]"),
            ),
            Edit::Shade(alpha) => fixture.replace(
                shot,
                "    lines: [",
                &format!(
                    "    shade: [(patches: \"ring/*\", stack: [Translate(alpha: {alpha:?}, beta: 0.0)])],\n    lines: ["
                ),
            ),
            Edit::DesignedHighlight => {
                fixture.replace(
                    shot,
                    "    lines: [",
                    "    shade: [(patches: \"teapot/lid\", stack: [Translate(alpha: 3.0, beta: 2.0)])],\n    lines: [",
                );
                fixture.replace(
                    shot,
                    "pin: (patch: \"teapot/25\", u: 0.3, v: 0.5),\n            )),",
                    "pin: (patch: \"teapot/25\", u: 0.3, v: 0.5),\n            )),\n            light: Designed,",
                );
            }
            Edit::PartMaterial => fixture.replace(
                shot,
                r#"material: "clay","#,
                r#"material: "clay", part_materials: {"knob": "porcelain"},"#,
            ),
            Edit::Hidden(levels) => fixture.replace(
                shot,
                "    lines: [",
                &format!(
                    "    lines: [(patches: [\"teapot/*\"], hidden: (levels: {levels}, dash: [4.0, 2.0])), "
                ),
            ),
            Edit::LightContours => fixture.replace(
                shot,
                "    lines: [",
                "    lines: [(patches: [\"teapot/body\"], kinds: [Silhouette, LightContour]), ",
            ),
            Edit::KeyInHold(frame) => fixture.replace(
                shot,
                "(6, (2.6, -1.4, 0.4))",
                &format!("({frame}, (2.6, -1.4, 0.4)), (6, (2.6, -1.4, 0.4))"),
            ),
            Edit::Comment => fixture.replace(
                shot,
                "    lines: [",
                "    // The spout is inked apart.\n\n    lines:  [",
            ),
        }
    }
}

fn edits() -> impl Strategy<Value = Edit> {
    prop_oneof![
        prop::sample::select(vec!["porcelain", "plastic"]).prop_map(Edit::Material),
        (0.1f64..0.6).prop_map(Edit::RingKey),
        (-60.0f64..-35.0).prop_map(Edit::LidDegrees),
        Just(Edit::PartsFile),
        Just(Edit::Include),
        prop::sample::select(vec!["teapot/*", "teapot/spout", "teapot/4"]).prop_map(Edit::Selector),
        (2.5f64..5.0).prop_map(Edit::LineWidth),
        (0.5f64..0.8).prop_map(Edit::PinU),
        (1i64..=12).prop_map(Edit::Hold),
        (0.2f64..0.5).prop_map(Edit::MaskU),
        (0.3f32..0.7).prop_map(Edit::Texture),
        (0.2f64..0.3).prop_map(Edit::PatchFile),
        (0.2f64..0.5).prop_map(Edit::TeapotPoint),
        (2.0f64..4.0).prop_map(Edit::OutlineWidth),
        (0.2f64..0.5).prop_map(Edit::Light),
        (0.1f64..0.5).prop_map(Edit::BandColour),
        (2i64..=11, prop::sample::select(vec![-0.3, 0.6])).prop_map(|(f, a)| Edit::AlphaKey(f, a)),
        (0.2f64..0.6).prop_map(Edit::Shade),
        Just(Edit::DesignedHighlight),
        Just(Edit::PartMaterial),
        (1u32..=3).prop_map(Edit::Hidden),
        Just(Edit::LightContours),
        (2i64..=5).prop_map(Edit::KeyInHold),
        Just(Edit::Comment),
    ]
}

/// The frames at which `changed` holds of the unedited and the edited frames.
fn frames_where(
    before: &[(String, Vec<u32>)],
    after: &[(String, Vec<u32>)],
    changed: impl Fn(&(String, Vec<u32>), &(String, Vec<u32>)) -> bool,
) -> Vec<i64> {
    FRAMES
        .iter()
        .zip(before.iter().zip(after))
        .filter(|(_, (b, a))| changed(b, a))
        .map(|(&f, _)| f)
        .collect()
}

/// The frames whose render and whose fingerprint `edit` changes, applied to a fresh fixture.
fn changed_frames(edit: &Edit) -> (Vec<i64>, Vec<i64>) {
    let fixture = Fixture::new();
    edit.apply(&fixture);
    let after = fixture.frames();
    let before = unedited();
    (
        frames_where(before, &after, |b, a| b.1 != a.1),
        frames_where(before, &after, |b, a| b.0 != a.0),
    )
}

/// Checks that `edit` changes the fingerprint of every frame whose render it changes — no
/// stale frame is ever taken as current — and, when it can change nothing, of none.
/// (An edit may change a frame's input without changing a pixel of it — a highlight moved on a
/// patch out of sight — and then its fingerprint: exactly which frames each kind of edit
/// changes is checked by `every_kind_of_edit_changes_the_frames_it_reaches`.)
fn check(edit: &Edit) -> Result<(), TestCaseError> {
    let (rendered, fingerprinted) = changed_frames(edit);
    prop_assert!(
        rendered.iter().all(|f| fingerprinted.contains(f)),
        "{:?}: renders changed at {:?}, fingerprints only at {:?}",
        edit,
        rendered,
        fingerprinted
    );
    if edit.changes_nothing() {
        prop_assert!(
            fingerprinted.is_empty(),
            "{:?} changed fingerprints at {:?}",
            edit,
            fingerprinted
        );
        prop_assert!(
            rendered.is_empty(),
            "{:?} changed renders at {:?}",
            edit,
            rendered
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn an_edit_changes_the_fingerprint_of_every_frame_whose_render_it_changes(edit in edits()) {
        check(&edit)?;
    }
}

/// Every kind of edit once, so that none is left to chance, with the frames each must change:
/// an edit that changes nothing at a frame would prove nothing there.
#[test]
fn every_kind_of_edit_changes_the_frames_it_reaches() {
    let cases: Vec<(Edit, Vec<i64>)> = vec![
        (Edit::Material("porcelain"), FRAMES.to_vec()),
        (Edit::RingKey(0.5), vec![9, 12]),
        (Edit::LidDegrees(-55.0), vec![4, 9, 12]),
        (Edit::PartsFile, FRAMES.to_vec()),
        (Edit::Include, FRAMES.to_vec()),
        (Edit::Selector("teapot/*"), FRAMES.to_vec()),
        (Edit::LineWidth(4.0), FRAMES.to_vec()),
        (Edit::PinU(0.7), FRAMES.to_vec()),
        (Edit::MaskU(0.3), FRAMES.to_vec()),
        (Edit::Texture(0.5), FRAMES.to_vec()),
        (Edit::PatchFile(0.25), FRAMES.to_vec()),
        (Edit::TeapotPoint(0.4), FRAMES.to_vec()),
        (Edit::OutlineWidth(3.0), FRAMES.to_vec()),
        (Edit::Light(0.4), FRAMES.to_vec()),
        (Edit::BandColour(0.3), FRAMES.to_vec()),
        (Edit::AlphaKey(6, 0.6), vec![4, 9]),
        (Edit::Shade(0.4), FRAMES.to_vec()),
        (Edit::DesignedHighlight, FRAMES.to_vec()),
        (Edit::PartMaterial, FRAMES.to_vec()),
        (Edit::Hidden(2), FRAMES.to_vec()),
        (Edit::LightContours, FRAMES.to_vec()),
        (Edit::KeyInHold(3), vec![]),
        (Edit::Comment, vec![]),
    ];
    for (edit, expected) in cases {
        let (rendered, fingerprinted) = changed_frames(&edit);
        assert_eq!(rendered, expected, "{edit:?}: renders changed");
        assert_eq!(fingerprinted, expected, "{edit:?}: fingerprints changed");
    }
}

/// A pin that holds its shape draws the held frame as it was, and every other frame with the
/// map that holds it: the fingerprint changes on every frame but the held one, and the render
/// of some.
#[test]
fn a_held_shape_changes_every_frame_but_the_held_one() {
    for held in [1, 9] {
        let (rendered, fingerprinted) = changed_frames(&Edit::Hold(held));
        let others: Vec<i64> = FRAMES.iter().copied().filter(|&f| f != held).collect();
        assert_eq!(fingerprinted, others, "hold {held}: fingerprints changed");
        assert!(
            !rendered.is_empty() && rendered.iter().all(|f| others.contains(f)),
            "hold {held}: renders changed at {rendered:?}"
        );
    }
}

/// Material borders read which material each patch has, not only how it looks: a rim in a
/// material that looks exactly like the body's still draws a border where they meet, and its
/// frames are fingerprinted apart.
#[test]
fn a_material_border_between_twin_materials_changes_the_fingerprint() {
    let bordered = |fixture: &Fixture| {
        fixture.replace(
            "shots/edit.ron",
            "    lines: [",
            "    lines: [(patches: [\"teapot/*\"], kinds: [Silhouette, MaterialBorder]), ",
        );
    };
    let one = Fixture::new();
    bordered(&one);
    let twins = Fixture::new();
    bordered(&twins);
    twins.replace(
        "shots/edit.ron",
        r#"material: "clay","#,
        r#"material: "clay", part_materials: {"rim": "clay_twin"},"#,
    );
    let (before, after) = (one.frames(), twins.frames());
    for (k, (b, a)) in before.iter().zip(&after).enumerate() {
        assert_ne!(b.1, a.1, "frame {}: the border is drawn", FRAMES[k]);
        assert_ne!(b.0, a.0, "frame {}: its fingerprint changed", FRAMES[k]);
    }
}
