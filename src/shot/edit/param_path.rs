//! The name of one animatable parameter of a shot or look file, as written on the command line:
//! `camera.eye`, `materials{"porcelain"}.bands[0].threshold`,
//! `highlights[1].layers[0].stack[0].alpha`, `shade[0].stack[0].alpha` (docs/shot-format.md,
//! "Parameter paths").

use std::fmt;
use std::str::FromStr;

use thiserror::Error;

/// One animatable parameter of a shot or look file, named as in docs/shot-format.md: the
/// camera's and light's tracks, a material's, one of a highlight layer's, or one of a shade
/// entry's.
///
/// A path is always relative to the file it is used on: the materials and highlights of an
/// include are named in the include.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum ParamPath {
    /// `camera.…`.
    Camera(CameraParam),
    /// `light.…`.
    Light(LightParam),
    /// `materials{"NAME"}.…`: a material of the file's `materials` map.
    Material { name: String, param: MaterialParam },
    /// `highlights[N].layers[K].…`: the K-th `Layer(…)` (from 0) of an entry's expression,
    /// counted left to right through its Booleans.
    Highlight {
        entry: HighlightRef,
        layer: usize,
        param: LayerParam,
    },
    /// `shade[N].…`: a number of the N-th entry (from 0) of the file's `shade` list.
    Shade { entry: usize, param: ShadeParam },
}

/// A track of the camera.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum CameraParam {
    /// `eye`.
    Eye,
    /// `target`.
    Target,
    /// `up`.
    Up,
    /// `projection.fov_y_degrees` of a perspective camera.
    FovYDegrees,
    /// `projection.height` of an orthographic camera.
    Height,
    /// `orbit.azimuth` of an orbiting camera.
    OrbitAzimuth,
    /// `orbit.elevation` of a camera orbiting on a sphere.
    OrbitElevation,
    /// `orbit.distance` of a camera orbiting on a sphere.
    OrbitDistance,
    /// `orbit.radius` of a camera orbiting on a cylinder.
    OrbitRadius,
    /// `orbit.height` of a camera orbiting on a cylinder.
    OrbitHeight,
}

/// A track of the light.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LightParam {
    /// `towards` of a directional light.
    Towards,
    /// `position` of a point light.
    Position,
}

/// A track of a material.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MaterialParam {
    /// `base`, a cel material's shadow colour.
    Base,
    /// `bands[I].threshold`.
    Threshold(usize),
    /// `bands[I].colour`.
    BandColour(usize),
    /// `detail.…`, a number of an X-Toon material's detail map.
    Detail(DetailParam),
    /// `shape.weight`, an X-Toon material's shape-detail weight.
    ShapeWeight,
}

/// A number of an X-Toon detail map.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DetailParam {
    /// `z_min`.
    ZMin,
    /// `r`.
    R,
    /// `s`.
    S,
    /// `focus`, three tracks edited together, or `focus[I]`, one of them.
    Focus(Option<usize>),
}

/// Which entry of the file's `highlights` list.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub enum HighlightRef {
    /// `highlights[N]`: the N-th entry, from 0.
    Index(usize),
    /// `highlights["PATTERN"]`: the entry whose `patches` is that pattern or a list holding it.
    Selector(String),
}

/// A track of a highlight layer.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LayerParam {
    /// `epsilon`.
    Epsilon,
    /// `colour`, three tracks edited together, or `colour[I]`, one of them.
    Colour(Option<usize>),
    /// `opacity`.
    Opacity,
    /// `feather`.
    Feather,
    /// `mask.u[I]`.
    MaskU(usize),
    /// `mask.v[I]`.
    MaskV(usize),
    /// `mask.feather`.
    MaskFeather,
    /// `pin.u`.
    PinU,
    /// `pin.v`.
    PinV,
    /// `stack[J].…`: a number of the J-th operation of the stack, from 0.
    Op { index: usize, param: OpParam },
}

/// A track of a shade entry.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ShadeParam {
    /// `mask.u[I]`.
    MaskU(usize),
    /// `mask.v[I]`.
    MaskV(usize),
    /// `mask.feather`.
    MaskFeather,
    /// `stack[J].…`: a number of the J-th operation of the stack, from 0.
    Op { index: usize, param: OpParam },
}

/// A number of a highlight operation, by the name it is written with.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum OpParam {
    /// `alpha` of `Translate`.
    Alpha,
    /// `beta` of `Translate`.
    Beta,
    /// `degrees` of `Rotate`.
    Degrees,
    /// `delta` of `Scale`.
    Delta,
    /// `axis` of `Scale`, when it is `Angle(φ)`: φ.
    Axis,
    /// `gamma_u` of `Split`.
    GammaU,
    /// `gamma_v` of `Split`.
    GammaV,
    /// `sigma` of `Square`.
    Sigma,
    /// `n` of `Square`.
    N,
}

impl OpParam {
    /// Every operation number, in the order the operations and their fields are declared.
    pub const ALL: [OpParam; 9] = [
        OpParam::Alpha,
        OpParam::Beta,
        OpParam::Degrees,
        OpParam::Delta,
        OpParam::Axis,
        OpParam::GammaU,
        OpParam::GammaV,
        OpParam::Sigma,
        OpParam::N,
    ];

    /// The field's name as written in the operation.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            OpParam::Alpha => "alpha",
            OpParam::Beta => "beta",
            OpParam::Degrees => "degrees",
            OpParam::Delta => "delta",
            OpParam::Axis => "axis",
            OpParam::GammaU => "gamma_u",
            OpParam::GammaV => "gamma_v",
            OpParam::Sigma => "sigma",
            OpParam::N => "n",
        }
    }
}

/// A string that is not a parameter path, with what was expected where it went wrong.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
#[error("`{written}` is not a parameter path: {reason}")]
pub struct ParamPathError {
    /// The path as written.
    pub written: String,
    /// What was expected where it went wrong.
    pub reason: String,
}

/// One piece of a written path: `.name`, `[3]`, `["pattern"]` or `{"name"}`.
#[derive(Clone, Debug, PartialEq, Eq)]
enum Piece {
    Name(String),
    Index(usize),
    Quoted(String),
    Braced(String),
}

impl fmt::Display for Piece {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Piece::Name(name) => write!(f, "`{name}`"),
            Piece::Index(index) => write!(f, "`[{index}]`"),
            Piece::Quoted(text) => write!(f, "`[{}]`", quoted(text)),
            Piece::Braced(text) => write!(f, "`{{{}}}`", quoted(text)),
        }
    }
}

/// `text` in double quotes, with `"` and `\` escaped by a backslash.
fn quoted(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 2);
    out.push('"');
    for c in text.chars() {
        if matches!(c, '"' | '\\') {
            out.push('\\');
        }
        out.push(c);
    }
    out.push('"');
    out
}

/// Splits a written path into its pieces: names joined by `.`, then `[N]`, `["…"]` or `{"…"}`
/// right after a name or another bracket.
fn pieces(written: &str) -> Result<Vec<Piece>, String> {
    let mut pieces = Vec::new();
    let mut rest = written;
    while !rest.is_empty() {
        if let Some(after) = rest.strip_prefix('[') {
            let (piece, after) = match after.strip_prefix('"') {
                Some(string) => {
                    let (text, after) = string_until_quote(string)?;
                    (Piece::Quoted(text), after)
                }
                None => {
                    let digits = after
                        .find(|c: char| !c.is_ascii_digit())
                        .unwrap_or(after.len());
                    let index = after[..digits]
                        .parse()
                        .map_err(|_| "a `[` must hold an index such as `[0]`".to_string())?;
                    (Piece::Index(index), &after[digits..])
                }
            };
            rest = after
                .strip_prefix(']')
                .ok_or_else(|| format!("{piece} is not closed with `]`"))?;
            pieces.push(piece);
        } else if let Some(after) = rest.strip_prefix('{') {
            let string = after
                .strip_prefix('"')
                .ok_or_else(|| "a `{` must hold a quoted name such as `{\"clay\"}`".to_string())?;
            let (text, after) = string_until_quote(string)?;
            rest = after
                .strip_prefix('}')
                .ok_or_else(|| "a `{\"…\"` is not closed with `}`".to_string())?;
            pieces.push(Piece::Braced(text));
        } else {
            let body = if pieces.is_empty() {
                rest
            } else {
                rest.strip_prefix('.').ok_or_else(|| {
                    format!(
                        "expected `.`, `[` or `{{` after {}",
                        pieces.last().map_or_else(String::new, Piece::to_string)
                    )
                })?
            };
            let len = body
                .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .unwrap_or(body.len());
            if len == 0 {
                return Err("expected a name such as `camera` or `epsilon`".to_string());
            }
            pieces.push(Piece::Name(body[..len].to_string()));
            rest = &body[len..];
        }
    }
    Ok(pieces)
}

/// The string before the closing `"` of `text` (escapes `\"` and `\\` read), and what follows
/// the quote.
fn string_until_quote(text: &str) -> Result<(String, &str), String> {
    let mut out = String::new();
    let mut chars = text.char_indices();
    while let Some((i, c)) = chars.next() {
        match c {
            '"' => return Ok((out, &text[i + 1..])),
            '\\' => match chars.next() {
                Some((_, escaped)) => out.push(escaped),
                None => break,
            },
            c => out.push(c),
        }
    }
    Err("a quoted name is not closed with `\"`".to_string())
}

/// Reads pieces one at a time, with errors naming what was expected.
struct Reader {
    pieces: std::vec::IntoIter<Piece>,
    after: String,
}

impl Reader {
    fn next(&mut self, expected: &str) -> Result<Piece, String> {
        let piece = self
            .pieces
            .next()
            .ok_or_else(|| format!("expected {expected} after {}", self.after))?;
        self.after = piece.to_string();
        Ok(piece)
    }

    /// The next piece, which must be one of the names `choices`.
    fn name(&mut self, choices: &[&'static str]) -> Result<&'static str, String> {
        self.choose(choices, |c| c)
    }

    /// The next piece, which must be the name (`name_of`) of one of `choices`.
    fn choose<T: Copy>(
        &mut self,
        choices: &[T],
        name_of: impl Fn(T) -> &'static str,
    ) -> Result<T, String> {
        let list = choices
            .iter()
            .map(|&c| format!("`{}`", name_of(c)))
            .collect::<Vec<_>>()
            .join(", ");
        let after = self.after.clone();
        match self.next(&format!("one of {list}"))? {
            Piece::Name(name) => choices
                .iter()
                .find(|&&c| name_of(c) == name)
                .copied()
                .ok_or_else(|| format!("unknown `{name}` after {after}; expected one of {list}")),
            other => Err(format!(
                "expected one of {list} after {after}, found {other}"
            )),
        }
    }

    /// The next piece, which must be an index `[N]`.
    fn index(&mut self) -> Result<usize, String> {
        let after = self.after.clone();
        match self.next("an index such as `[0]`")? {
            Piece::Index(index) => Ok(index),
            other => Err(format!(
                "expected an index such as `[0]` after {after}, found {other}"
            )),
        }
    }

    /// An optional last index `[N]` below `count`.
    fn optional_component(&mut self, count: usize) -> Result<Option<usize>, String> {
        if self.pieces.as_slice().is_empty() {
            return Ok(None);
        }
        let index = self.index()?;
        if index >= count {
            return Err(format!(
                "the index [{index}] is beyond the {count} components"
            ));
        }
        Ok(Some(index))
    }

    fn end(mut self) -> Result<(), String> {
        match self.pieces.next() {
            None => Ok(()),
            Some(extra) => Err(format!("nothing may follow {}, found {extra}", self.after)),
        }
    }
}

impl FromStr for ParamPath {
    type Err = ParamPathError;

    fn from_str(written: &str) -> Result<Self, ParamPathError> {
        let parsed = pieces(written).and_then(|pieces| {
            let mut reader = Reader {
                pieces: pieces.into_iter(),
                after: "the start".to_string(),
            };
            let path = read_path(&mut reader)?;
            reader.end()?;
            Ok(path)
        });
        parsed.map_err(|reason| ParamPathError {
            written: written.to_string(),
            reason,
        })
    }
}

fn read_path(r: &mut Reader) -> Result<ParamPath, String> {
    Ok(
        match r.name(&["camera", "light", "materials", "highlights", "shade"])? {
            "camera" => ParamPath::Camera(
                match r.name(&["eye", "orbit", "target", "up", "projection"])? {
                    "eye" => CameraParam::Eye,
                    "target" => CameraParam::Target,
                    "up" => CameraParam::Up,
                    "orbit" => {
                        match r.name(&["azimuth", "elevation", "distance", "radius", "height"])? {
                            "azimuth" => CameraParam::OrbitAzimuth,
                            "elevation" => CameraParam::OrbitElevation,
                            "distance" => CameraParam::OrbitDistance,
                            "radius" => CameraParam::OrbitRadius,
                            _ => CameraParam::OrbitHeight,
                        }
                    }
                    _ => match r.name(&["fov_y_degrees", "height"])? {
                        "fov_y_degrees" => CameraParam::FovYDegrees,
                        _ => CameraParam::Height,
                    },
                },
            ),
            "light" => ParamPath::Light(match r.name(&["towards", "position"])? {
                "towards" => LightParam::Towards,
                _ => LightParam::Position,
            }),
            "materials" => {
                let name = match r.next("a material's name such as `{\"clay\"}`")? {
                Piece::Braced(name) => name,
                other => {
                    return Err(format!(
                        "expected a material's name such as `{{\"clay\"}}` after `materials`, found {other}"
                    ))
                }
            };
                ParamPath::Material {
                    name,
                    param: read_material(r)?,
                }
            }
            "shade" => {
                let entry = r.index()?;
                ParamPath::Shade {
                    entry,
                    param: read_shade(r)?,
                }
            }
            _ => {
                let entry = match r.next("an entry such as `[0]` or `[\"teapot/*\"]`")? {
                Piece::Index(index) => HighlightRef::Index(index),
                Piece::Quoted(pattern) => HighlightRef::Selector(pattern),
                other => {
                    return Err(format!(
                        "expected an entry such as `[0]` or `[\"teapot/*\"]` after `highlights`, found {other}"
                    ))
                }
            };
                r.name(&["layers"])?;
                let layer = r.index()?;
                ParamPath::Highlight {
                    entry,
                    layer,
                    param: read_layer(r)?,
                }
            }
        },
    )
}

fn read_material(r: &mut Reader) -> Result<MaterialParam, String> {
    Ok(match r.name(&["base", "bands", "detail", "shape"])? {
        "base" => MaterialParam::Base,
        "bands" => {
            let band = r.index()?;
            match r.name(&["threshold", "colour"])? {
                "threshold" => MaterialParam::Threshold(band),
                _ => MaterialParam::BandColour(band),
            }
        }
        "detail" => MaterialParam::Detail(match r.name(&["z_min", "r", "s", "focus"])? {
            "z_min" => DetailParam::ZMin,
            "r" => DetailParam::R,
            "s" => DetailParam::S,
            _ => DetailParam::Focus(r.optional_component(3)?),
        }),
        _ => {
            r.name(&["weight"])?;
            MaterialParam::ShapeWeight
        }
    })
}

fn read_layer(r: &mut Reader) -> Result<LayerParam, String> {
    let fields = [
        "epsilon", "colour", "opacity", "feather", "mask", "pin", "stack",
    ];
    Ok(match r.name(&fields)? {
        "epsilon" => LayerParam::Epsilon,
        "colour" => LayerParam::Colour(r.optional_component(3)?),
        "opacity" => LayerParam::Opacity,
        "feather" => LayerParam::Feather,
        "mask" => match r.name(&["u", "v", "feather"])? {
            "u" => LayerParam::MaskU(bound(r)?),
            "v" => LayerParam::MaskV(bound(r)?),
            _ => LayerParam::MaskFeather,
        },
        "pin" => match r.name(&["u", "v"])? {
            "u" => LayerParam::PinU,
            _ => LayerParam::PinV,
        },
        _ => {
            let index = r.index()?;
            let param = r.choose(&OpParam::ALL, OpParam::name)?;
            LayerParam::Op { index, param }
        }
    })
}

fn read_shade(r: &mut Reader) -> Result<ShadeParam, String> {
    Ok(match r.name(&["stack", "mask"])? {
        "stack" => {
            let index = r.index()?;
            let param = r.choose(&OpParam::ALL, OpParam::name)?;
            ShadeParam::Op { index, param }
        }
        _ => match r.name(&["u", "v", "feather"])? {
            "u" => ShadeParam::MaskU(bound(r)?),
            "v" => ShadeParam::MaskV(bound(r)?),
            _ => ShadeParam::MaskFeather,
        },
    })
}

/// The `[0]` or `[1]` of a mask's bounds.
fn bound(r: &mut Reader) -> Result<usize, String> {
    match r.index()? {
        index @ (0 | 1) => Ok(index),
        index => Err(format!(
            "a mask's bounds are `[0]` and `[1]`, not `[{index}]`"
        )),
    }
}

impl ParamPath {
    /// The path of the whole `colour` or `focus` that a component path (`colour[1]`) names one
    /// track of, with the component; any other path as it is, with none.
    #[must_use]
    pub fn without_component(&self) -> (ParamPath, Option<usize>) {
        let mut whole = self.clone();
        let component = whole.component_slot().and_then(Option::take);
        (whole, component)
    }

    /// The same path with `component` of the whole it names (`colour` → `colour[1]`); `None`
    /// unless it names a whole `colour` or `focus`.
    #[must_use]
    pub fn try_with_component(&self, component: usize) -> Option<ParamPath> {
        let mut part = self.clone();
        let slot = part.component_slot()?;
        if slot.is_some() {
            return None;
        }
        *slot = Some(component);
        Some(part)
    }

    /// The component of a `colour` or `focus` path (`None` for the whole); `None` for a path
    /// that names no three tracks.
    fn component_slot(&mut self) -> Option<&mut Option<usize>> {
        match self {
            ParamPath::Material {
                param: MaterialParam::Detail(DetailParam::Focus(component)),
                ..
            }
            | ParamPath::Highlight {
                param: LayerParam::Colour(component),
                ..
            } => Some(component),
            ParamPath::Camera(_)
            | ParamPath::Light(_)
            | ParamPath::Material { .. }
            | ParamPath::Highlight { .. }
            | ParamPath::Shade { .. } => None,
        }
    }
}

impl fmt::Display for ParamPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let component = |c: Option<usize>| c.map_or_else(String::new, |i| format!("[{i}]"));
        match self {
            ParamPath::Camera(param) => f.write_str(match param {
                CameraParam::Eye => "camera.eye",
                CameraParam::Target => "camera.target",
                CameraParam::Up => "camera.up",
                CameraParam::FovYDegrees => "camera.projection.fov_y_degrees",
                CameraParam::Height => "camera.projection.height",
                CameraParam::OrbitAzimuth => "camera.orbit.azimuth",
                CameraParam::OrbitElevation => "camera.orbit.elevation",
                CameraParam::OrbitDistance => "camera.orbit.distance",
                CameraParam::OrbitRadius => "camera.orbit.radius",
                CameraParam::OrbitHeight => "camera.orbit.height",
            }),
            ParamPath::Light(param) => f.write_str(match param {
                LightParam::Towards => "light.towards",
                LightParam::Position => "light.position",
            }),
            ParamPath::Material { name, param } => {
                write!(f, "materials{{{}}}.", quoted(name))?;
                match param {
                    MaterialParam::Base => f.write_str("base"),
                    MaterialParam::Threshold(band) => write!(f, "bands[{band}].threshold"),
                    MaterialParam::BandColour(band) => write!(f, "bands[{band}].colour"),
                    MaterialParam::Detail(DetailParam::ZMin) => f.write_str("detail.z_min"),
                    MaterialParam::Detail(DetailParam::R) => f.write_str("detail.r"),
                    MaterialParam::Detail(DetailParam::S) => f.write_str("detail.s"),
                    MaterialParam::Detail(DetailParam::Focus(c)) => {
                        write!(f, "detail.focus{}", component(*c))
                    }
                    MaterialParam::ShapeWeight => f.write_str("shape.weight"),
                }
            }
            ParamPath::Highlight {
                entry,
                layer,
                param,
            } => {
                match entry {
                    HighlightRef::Index(index) => write!(f, "highlights[{index}]")?,
                    HighlightRef::Selector(pattern) => {
                        write!(f, "highlights[{}]", quoted(pattern))?;
                    }
                }
                write!(f, ".layers[{layer}].")?;
                match param {
                    LayerParam::Epsilon => f.write_str("epsilon"),
                    LayerParam::Colour(c) => write!(f, "colour{}", component(*c)),
                    LayerParam::Opacity => f.write_str("opacity"),
                    LayerParam::Feather => f.write_str("feather"),
                    LayerParam::MaskU(i) => write!(f, "mask.u[{i}]"),
                    LayerParam::MaskV(i) => write!(f, "mask.v[{i}]"),
                    LayerParam::MaskFeather => f.write_str("mask.feather"),
                    LayerParam::PinU => f.write_str("pin.u"),
                    LayerParam::PinV => f.write_str("pin.v"),
                    LayerParam::Op { index, param } => {
                        write!(f, "stack[{index}].{}", param.name())
                    }
                }
            }
            ParamPath::Shade { entry, param } => {
                write!(f, "shade[{entry}].")?;
                match param {
                    ShadeParam::MaskU(i) => write!(f, "mask.u[{i}]"),
                    ShadeParam::MaskV(i) => write!(f, "mask.v[{i}]"),
                    ShadeParam::MaskFeather => f.write_str("mask.feather"),
                    ShadeParam::Op { index, param } => {
                        write!(f, "stack[{index}].{}", param.name())
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn written_paths_read_back_as_written() {
        for written in [
            "camera.eye",
            "camera.target",
            "camera.up",
            "camera.orbit.azimuth",
            "camera.orbit.elevation",
            "camera.orbit.distance",
            "camera.orbit.radius",
            "camera.orbit.height",
            "camera.projection.fov_y_degrees",
            "camera.projection.height",
            "light.towards",
            "light.position",
            "materials{\"porcelain\"}.base",
            "materials{\"porcelain\"}.bands[0].threshold",
            "materials{\"porcelain\"}.bands[1].colour",
            "materials{\"steel\"}.detail.z_min",
            "materials{\"steel\"}.detail.r",
            "materials{\"steel\"}.detail.s",
            "materials{\"dof\"}.detail.focus",
            "materials{\"dof\"}.detail.focus[2]",
            "materials{\"a \\\"b\\\" \\\\ c\"}.shape.weight",
            "highlights[1].layers[0].stack[0].alpha",
            "highlights[1].layers[2].stack[2].axis",
            "highlights[1].layers[2].stack[1].beta",
            "highlights[1].layers[2].stack[1].degrees",
            "highlights[1].layers[2].stack[1].delta",
            "highlights[1].layers[2].stack[1].gamma_u",
            "highlights[1].layers[2].stack[1].sigma",
            "highlights[1].layers[2].stack[1].n",
            "highlights[0].layers[0].pin.u",
            "highlights[0].layers[0].pin.v",
            "highlights[0].layers[0].epsilon",
            "highlights[0].layers[0].colour",
            "highlights[0].layers[0].colour[1]",
            "highlights[0].layers[0].opacity",
            "highlights[0].layers[0].feather",
            "highlights[0].layers[0].mask.u[0]",
            "highlights[0].layers[0].mask.v[1]",
            "highlights[0].layers[0].mask.feather",
            "highlights[\"teapot/body\"].layers[0].stack[3].gamma_v",
            "shade[0].stack[0].alpha",
            "shade[2].stack[1].axis",
            "shade[1].stack[3].n",
            "shade[0].mask.u[1]",
            "shade[0].mask.v[0]",
            "shade[0].mask.feather",
        ] {
            let path: ParamPath = written.parse().unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(path.to_string(), written);
        }
        let path: ParamPath = "highlights[1].layers[0].stack[0].alpha".parse().unwrap();
        assert_eq!(
            path,
            ParamPath::Highlight {
                entry: HighlightRef::Index(1),
                layer: 0,
                param: LayerParam::Op {
                    index: 0,
                    param: OpParam::Alpha
                }
            }
        );
        let shade: ParamPath = "shade[3].stack[1].sigma".parse().unwrap();
        assert_eq!(
            shade,
            ParamPath::Shade {
                entry: 3,
                param: ShadeParam::Op {
                    index: 1,
                    param: OpParam::Sigma
                }
            }
        );
        assert_eq!(shade.try_with_component(0), None);
        let colour: ParamPath = "highlights[0].layers[1].colour".parse().unwrap();
        let green = colour.try_with_component(1).unwrap();
        assert_eq!(green.to_string(), "highlights[0].layers[1].colour[1]");
        assert_eq!(green.without_component(), (colour.clone(), Some(1)));
        assert_eq!(colour.without_component(), (colour, None));
        assert_eq!(green.try_with_component(2), None);
        assert_eq!(path.try_with_component(0), None);
        let named: ParamPath = "materials{\"a \\\"b\\\" \\\\ c\"}.base".parse().unwrap();
        assert!(matches!(named, ParamPath::Material { ref name, .. } if name == "a \"b\" \\ c"));
    }

    #[test]
    fn malformed_paths_say_what_was_expected() {
        let reason = |written: &str| written.parse::<ParamPath>().unwrap_err().reason;
        assert!(reason("").contains("one of `camera`"), "{}", reason(""));
        assert!(reason("camera.eyes").contains("unknown `eyes` after `camera`"));
        assert!(reason("camera").contains("expected one of `eye`"));
        assert!(reason("camera.eye.x").contains("nothing may follow `eye`"));
        assert!(reason("highlights[0].layers[0].epsilom").contains("`epsilon`"));
        assert!(reason("highlights[0].layer[0].epsilon").contains("`layers`"));
        assert!(reason("highlights.layers[0].epsilon").contains("`[\"teapot/*\"]`"));
        assert!(reason("materials[\"clay\"].base").contains("{\"clay\"}"));
        assert!(reason("highlights[0].layers[0].colour[3]").contains("beyond"));
        assert!(reason("highlights[0].layers[0].mask.u[2]").contains("[0]` and `[1]`"));
        assert!(reason("highlights[0].layers[x].epsilon").contains("index"));
        assert!(reason("materials{\"clay").contains("not closed"));
        assert!(reason("camera..eye").contains("expected a name"));
        assert!(reason("highlights[0].layers[0].stack[0].alpha2").contains("unknown `alpha2`"));
        assert!(reason("shade.stack[0].alpha").contains("an index such as `[0]`"));
        assert!(reason("shade[\"teapot/*\"].stack[0].alpha").contains("an index"));
        assert!(reason("shade[0].layers[0].epsilon").contains("`stack`, `mask`"));
        assert!(reason("shade[0].stack[0].epsilon").contains("unknown `epsilon`"));
        assert!(reason("shade[0].mask.u[2]").contains("[0]` and `[1]`"));
        assert!(reason("shade[0].mask").contains("expected one of `u`"));
    }
}
