//! The shot file as written: serde types, every numeric parameter of what is animated a
//! [`Track`]. `docs/shot-format.md` describes each field with an annotated example.

use std::collections::BTreeMap;

use glam::{DVec3, Vec3};
use serde::Deserialize;

use super::orbit::OrbitSpec;
use crate::anim::{Direction, Track};
use crate::formats::parts::GroupsSpec;
use crate::highlight::{Expr, HighlightLight, Mask, Op, ShadeStack};
use crate::render::tessellate::Density;
use crate::render::{Antialias, FrameMode, LineKind};
use crate::toon::{DetailMap, ShapeDetail};

/// A shot: `Shot(resolution: …, frames: …, …)`.
#[derive(Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, rename = "Shot")]
pub struct ShotFile {
    /// Image size in pixels, `(width, height)`.
    pub resolution: (u32, u32),
    /// The first and last frame, inclusive.
    pub frames: (i64, i64),
    /// Frames per second (for players; tracks are keyed in frames).
    pub fps: f64,
    /// Where frames go: a path with a run of `#` replaced by the zero-padded frame number,
    /// relative to the shot file unless absolute.
    pub output: String,
    /// Look libraries whose materials and highlights this shot uses, relative to this file.
    #[serde(default)]
    pub includes: Vec<String>,
    /// Patch files placed in the scene.
    pub instances: Vec<InstanceSpec>,
    /// Named cel materials.
    #[serde(default)]
    pub materials: BTreeMap<String, MaterialSpec>,
    pub camera: CameraSpec,
    pub light: LightSpec,
    /// Designed highlights, each on the patches its selector picks; a later entry replaces an
    /// earlier one on the patches both pick.
    #[serde(default)]
    pub highlights: Vec<HighlightSpec>,
    /// Designed shade: shade stacks, each on the patches its selector picks; the stacks of the
    /// entries that pick a patch act on its light one after the other, in the order written.
    #[serde(default)]
    pub shade: Vec<ShadeSpec>,
    /// Line styles, each on the patches its selector or material picks; a later entry
    /// overrides, on the patches both pick, the fields it sets.
    #[serde(default)]
    pub lines: Vec<LineSpec>,
    #[serde(default)]
    pub render: RenderSpec,
}

/// A look library: materials, highlights and shade shared between shots.
#[derive(Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, rename = "Looks")]
pub struct LooksFile {
    #[serde(default)]
    pub includes: Vec<String>,
    #[serde(default)]
    pub materials: BTreeMap<String, MaterialSpec>,
    #[serde(default)]
    pub highlights: Vec<HighlightSpec>,
    #[serde(default)]
    pub shade: Vec<ShadeSpec>,
}

/// One placement of a patch file: its patches are named `NAME/PATCH`.
#[derive(Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InstanceSpec {
    pub name: String,
    /// A patch library (`.ron`) or Bezier patches (`.bpt`), relative to the file that names it.
    pub file: String,
    /// The material of every patch of the instance but those of `part_materials`.
    pub material: String,
    /// Parts of the instance in other materials: a part's name (without the instance's) and
    /// a material's; a patch in several of them takes the smallest's.
    #[serde(default)]
    pub part_materials: BTreeMap<String, String>,
    #[serde(default)]
    pub transform: TransformSpec,
    /// Parts of this instance that move against it: each a part's name (without the
    /// instance's) and its transform in the model's coordinates, applied before the instance's.
    #[serde(default)]
    pub parts: BTreeMap<String, TransformSpec>,
    /// Which time code of an animated USD layer each frame shows (default: the layer's own
    /// timing).
    #[serde(default)]
    pub time_codes: Option<TimeCodesSpec>,
    /// Named parts besides the model's own: each a list of patch names or 0-based indices,
    /// selected as `NAME/PART`.
    #[serde(default)]
    pub groups: GroupsSpec,
}

/// `p ↦ translate + pivot + R(axis, degrees) (scale · (p − pivot))`, every number a track
/// (docs/shot-format.md, "Moving instances and parts").
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TransformSpec {
    #[serde(default = "origin")]
    pub translate: Track<DVec3>,
    #[serde(default = "z_axis")]
    pub axis: Track<DVec3>,
    #[serde(default = "no_turn")]
    pub degrees: Track<f64>,
    #[serde(default = "one")]
    pub scale: Track<f64>,
    /// The point the rotation and the scale keep fixed.
    #[serde(default = "origin")]
    pub pivot: Track<DVec3>,
}

impl Default for TransformSpec {
    fn default() -> Self {
        Self {
            translate: origin(),
            axis: z_axis(),
            degrees: no_turn(),
            scale: one(),
            pivot: origin(),
        }
    }
}

fn origin() -> Track<DVec3> {
    Track::Constant(DVec3::ZERO)
}

fn z_axis() -> Track<DVec3> {
    Track::Constant(DVec3::Z)
}

fn no_turn() -> Track<f64> {
    Track::Constant(0.0)
}

fn one() -> Track<f64> {
    Track::Constant(1.0)
}

/// How an instance's frames map to the time codes of its animated USD layer:
/// `time code = start + (frame − first frame) · per_frame`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TimeCodesSpec {
    /// The time code at the shot's first frame (default: the layer's `startTimeCode`, or 0).
    #[serde(default)]
    pub start: Option<f64>,
    /// Time codes per frame (default: the layer's `timeCodesPerSecond` ÷ the shot's fps).
    #[serde(default)]
    pub per_frame: Option<f64>,
}

/// A material: a cel ramp, or an X-Toon tone (docs/xtoon.md), every number a track.
#[derive(Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum MaterialSpec {
    /// Flat bands over `n·l`.
    Cel {
        /// Linear RGB below every threshold.
        base: Track<Vec3>,
        /// `(threshold, linear RGB)` in increasing threshold order.
        #[serde(default)]
        bands: Vec<(Track<f32>, Track<Vec3>)>,
    },
    /// A 2D toon texture over `(n'·l, D)`.
    XToon {
        /// The texture (PNG), relative to the file that names it.
        texture: String,
        detail: DetailMap<Track<f32>>,
        #[serde(default)]
        invert: bool,
        #[serde(default)]
        shape: Option<ShapeDetail<Track<f32>>>,
    },
}

/// A camera whose placement and lens are tracks. The eye is given once: as a point (`eye`), or
/// by an orbit about the target (`orbit`); the shot reader refuses both or neither.
#[derive(Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CameraSpec {
    #[serde(default)]
    pub eye: Option<Track<Vec3>>,
    #[serde(default)]
    pub orbit: Option<OrbitSpec>,
    pub target: Track<Vec3>,
    #[serde(default = "z_up")]
    pub up: Track<Vec3>,
    pub projection: ProjectionSpec,
    #[serde(default = "near")]
    pub near: f32,
    #[serde(default = "far")]
    pub far: f32,
}

fn z_up() -> Track<Vec3> {
    Track::Constant(Vec3::Z)
}

fn near() -> f32 {
    0.1
}

fn far() -> f32 {
    1000.0
}

#[derive(Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum ProjectionSpec {
    Perspective { fov_y_degrees: Track<f32> },
    Orthographic { height: Track<f32> },
}

/// The light for tone and highlights.
#[derive(Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum LightSpec {
    /// Light arriving from the direction `towards` points to (keys turn along great circles).
    Directional { towards: Track<Direction> },
    /// A point light.
    Point { position: Track<Vec3> },
}

/// A highlight expression on the patches a selector picks.
#[derive(Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HighlightSpec {
    pub patches: Selector,
    pub expr: Expr<Track<f32>>,
    /// The light the highlight reads: the scene's (the default), or the designed light of
    /// the shade entries on its patches (`light: Designed`).
    #[serde(default)]
    pub light: HighlightLight,
}

/// A shade stack on the patches a selector picks: the highlight operations applied to the
/// light its tone reads ([`ShadeStack`](crate::highlight::ShadeStack)), every number a track.
#[derive(Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ShadeSpec {
    pub patches: Selector,
    pub stack: Vec<Op<Track<f32>>>,
    #[serde(default)]
    pub mask: Option<Mask<Track<f32>>>,
}

impl ShadeSpec {
    /// The entry's stack and mask, every number a track.
    #[must_use]
    pub fn stack(&self) -> ShadeStack<Track<f32>> {
        ShadeStack {
            stack: self.stack.clone(),
            mask: self.mask.clone(),
        }
    }

    /// The entry's stack and mask read at `frame`.
    #[must_use]
    pub fn at(&self, frame: f64) -> ShadeStack {
        ShadeStack {
            stack: self
                .stack
                .iter()
                .map(|op| op.map(|t| t.at(frame)))
                .collect(),
            mask: self.mask.as_ref().map(|m| m.map(|t| t.at(frame))),
        }
    }
}

/// Patch names (`INSTANCE/PATCH`) as one glob pattern or a list of them: `*` any run of
/// characters, `?` one character, `[a-c]` one of a set.
#[derive(Clone, Debug, PartialEq)]
pub enum Selector {
    One(String),
    Any(Vec<String>),
}

impl<'de> Deserialize<'de> for Selector {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct SelectorVisitor;
        impl<'de> serde::de::Visitor<'de> for SelectorVisitor {
            type Value = Selector;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a patch name pattern such as \"teapot/*\", or a list of them")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<Selector, E> {
                Ok(Selector::One(v.to_string()))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<Selector, A::Error> {
                let mut patterns = Vec::new();
                while let Some(p) = seq.next_element()? {
                    patterns.push(p);
                }
                if patterns.is_empty() {
                    return Err(serde::de::Error::custom(
                        "an empty list of patch patterns picks nothing; name at least one",
                    ));
                }
                Ok(Selector::Any(patterns))
            }
        }
        deserializer.deserialize_any(SelectorVisitor)
    }
}

impl Selector {
    pub fn patterns(&self) -> &[String] {
        match self {
            Selector::One(p) => std::slice::from_ref(p),
            Selector::Any(ps) => ps,
        }
    }
}

/// How frames are rendered.
#[derive(Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RenderSpec {
    /// The accuracy preset the other fields refine (default `Final`).
    #[serde(default)]
    pub preset: Preset,
    #[serde(default)]
    pub tessellation: Option<Density>,
    #[serde(default)]
    pub frames: Option<FrameMode>,
    #[serde(default)]
    pub antialias: Option<Antialias>,
    #[serde(default)]
    pub outlines: Option<OutlinesSpec>,
    /// Extra images written beside each frame.
    #[serde(default)]
    pub aovs: Vec<Aov>,
}

/// The accuracy presets of docs/accuracy.md.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
pub enum Preset {
    /// Fast feedback: coarse tessellation, interpolated frames, no anti-aliasing.
    Preview,
    /// Finished frames: fine tessellation, refined frames, adaptive anti-aliasing.
    #[default]
    Final,
}

/// Lines on (docs/rendering.md, "Lines"), and the style of every patch no `lines` entry
/// styles.
#[derive(Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OutlinesSpec {
    #[serde(default = "outline_width")]
    pub width: Track<f32>,
    /// Linear RGB.
    #[serde(default = "black")]
    pub colour: Track<Vec3>,
    #[serde(default = "crease_degrees")]
    pub crease_degrees: f32,
    #[serde(default)]
    pub patch_borders: bool,
    /// The kinds of line drawn (default: silhouettes, creases, borders and intersections).
    #[serde(default)]
    pub kinds: Option<Vec<LineKind>>,
    /// Pixels over which a line narrows to its ends (default 0: round ends).
    #[serde(default = "no_taper")]
    pub taper: Track<f32>,
    /// Lines drawn where surfaces hide them (default: none).
    #[serde(default)]
    pub hidden: Option<HiddenSpec>,
}

/// Hidden lines: how a style's lines draw where up to `levels` surfaces hide them.
#[derive(Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HiddenSpec {
    /// Drawn behind at most this many surfaces, from 0 (none) to 16 (default 1).
    #[serde(default = "one_level")]
    pub levels: u32,
    /// Width in pixels (default: the style's own).
    #[serde(default)]
    pub width: Option<Track<f32>>,
    /// Linear RGB (default: the style's own).
    #[serde(default)]
    pub colour: Option<Track<Vec3>>,
    /// Lengths in pixels drawn and left out in turn (default: solid).
    #[serde(default)]
    pub dash: Vec<f32>,
}

fn one_level() -> u32 {
    1
}

fn outline_width() -> Track<f32> {
    Track::Constant(2.0)
}

fn black() -> Track<Vec3> {
    Track::Constant(Vec3::ZERO)
}

fn no_taper() -> Track<f32> {
    Track::Constant(0.0)
}

/// A line style on the patches a selector picks, or on the patches of a material: each field
/// it sets replaces the outlines' (or an earlier entry's) on those patches.
#[derive(Debug, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LineSpec {
    #[serde(default)]
    pub patches: Option<Selector>,
    /// A material's name: every patch of that material.
    #[serde(default)]
    pub material: Option<String>,
    #[serde(default)]
    pub width: Option<Track<f32>>,
    /// Linear RGB.
    #[serde(default)]
    pub colour: Option<Track<Vec3>>,
    #[serde(default)]
    pub kinds: Option<Vec<LineKind>>,
    #[serde(default)]
    pub taper: Option<Track<f32>>,
    /// Lines drawn where surfaces hide them; `(levels: 0)` draws none.
    #[serde(default)]
    pub hidden: Option<HiddenSpec>,
}

fn crease_degrees() -> f32 {
    60.0
}

/// An extra image (arbitrary output variable).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize)]
pub enum Aov {
    /// Final highlight coverage.
    Matte,
    /// Patch index (16-bit) and patches as flat colours.
    PatchId,
    /// NDC depth (16-bit).
    Depth,
    /// Shading normal.
    Normal,
    /// Patch parameters.
    Uv,
    /// `N·H` heat map of the undesigned Blinn highlight.
    NDotH,
    /// `N·L'` the tone reads (of the designed light where shade stacks design it).
    NDotL,
    /// The lines alone, with alpha.
    Outline,
}

impl Aov {
    /// Every AOV, in the order the command line and the docs list them.
    pub const ALL: [Aov; 8] = [
        Aov::Matte,
        Aov::PatchId,
        Aov::Depth,
        Aov::Normal,
        Aov::Uv,
        Aov::NDotH,
        Aov::NDotL,
        Aov::Outline,
    ];

    /// The name on the command line: `matte`, `patch_id`, `depth`, `normal`, `uv`, `n_dot_h`,
    /// `n_dot_l`, `outline`.
    pub fn name(self) -> &'static str {
        match self {
            Aov::Matte => "matte",
            Aov::PatchId => "patch_id",
            Aov::Depth => "depth",
            Aov::Normal => "normal",
            Aov::Uv => "uv",
            Aov::NDotH => "n_dot_h",
            Aov::NDotL => "n_dot_l",
            Aov::Outline => "outline",
        }
    }
}

impl std::str::FromStr for Aov {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        Aov::ALL.into_iter().find(|a| a.name() == s).ok_or_else(|| {
            let names: Vec<&str> = Aov::ALL.iter().map(|a| a.name()).collect();
            format!("unknown AOV `{s}`; choose from {}", names.join(", "))
        })
    }
}
