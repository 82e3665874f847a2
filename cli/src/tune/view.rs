//! What the page is told about the shot: its frames and size, and for each highlight layer and
//! each shade entry of the shot file its operations and parameters, each with its value at the
//! frame, its keys, the range it must lie in and the span its slider covers.

use serde::Serialize;

use glint::anim::Track;
use glint::highlight::Shape;
use glint::param::Bounds;
use glint::shot::{
    param_readings, HighlightRef, LayerParam, OpParam, ParamPath, ParamReading, ShadeParam, Shot,
};

use super::error::TuneError;

/// The state of a session at one frame, as JSON for the page.
#[derive(Clone, Debug, Serialize)]
pub struct StateView {
    /// Grows with every change of the file, by the page or elsewhere.
    pub version: u64,
    /// The shot file.
    pub file: String,
    pub frame: f64,
    /// The first and last frame.
    pub frames: [i64; 2],
    pub fps: f64,
    /// The preview's size in pixels.
    pub size: [u32; 2],
    /// How many changes can be undone and redone.
    pub undo: usize,
    pub redo: usize,
    /// The last edit of the file made elsewhere that does not load, if the file is in that
    /// state now (the page keeps the last good state and shows this).
    pub disk_error: Option<String>,
    /// Why nothing can be undone, when an edit of the file made elsewhere cleared the history
    /// (until the next change made here).
    pub history_note: Option<String>,
    pub highlights: Vec<HighlightView>,
    /// The shade entries, includes first.
    pub shade: Vec<ShadeView>,
    /// The operation kinds a layer can be given.
    pub op_kinds: [&'static str; 5],
}

/// One highlight entry of the shot.
#[derive(Clone, Debug, Serialize)]
pub struct HighlightView {
    /// Its index among the shot's entries (includes first), as `pick` names it.
    pub entry: usize,
    /// Its index in the shot file's own `highlights`, which changes name; `None` for an entry
    /// written in an include, which the page shows but does not change.
    pub file_index: Option<usize>,
    /// The file it is written in.
    pub written_in: String,
    /// Its patch selectors.
    pub patches: Vec<String>,
    pub layers: Vec<LayerView>,
}

/// One shade entry of the shot: the operations it applies to its patches' light.
#[derive(Clone, Debug, Serialize)]
pub struct ShadeView {
    /// Its index among the shot's entries (includes first), as `pick` names it.
    pub entry: usize,
    /// Its index in the shot file's own `shade`; `None` for an entry written in an include.
    pub file_index: Option<usize>,
    /// The file it is written in.
    pub written_in: String,
    /// Its patch selectors.
    pub patches: Vec<String>,
    pub ops: Vec<OpView>,
    /// The mask's numbers, where it has one.
    pub params: Vec<ParamView>,
    /// The index of its placing translation (its last `Translate`), which a drag solves.
    pub translation: Option<usize>,
}

/// One layer of a highlight entry.
#[derive(Clone, Debug, Serialize)]
pub struct LayerView {
    pub index: usize,
    pub ops: Vec<OpView>,
    /// ε, colour, opacity, feather, and the mask's and pin's numbers where it has them.
    pub params: Vec<ParamView>,
    pub has_mask: bool,
    /// The patch the layer is pinned to, if pinned.
    pub pinned_to: Option<String>,
    /// The frame whose shape the layer's pin holds, if it holds one.
    pub holds: Option<i64>,
    /// What H′ is tested against: `disc`, `outline` or `keyed outline`.
    pub shape: &'static str,
    /// The frames of a keyed outline's keys; empty otherwise.
    pub shape_keys: Vec<f64>,
}

/// The name of a layer's shape for the page, and a keyed outline's key frames.
#[must_use]
pub fn shape_view(shape: &Shape<Track<f32>>) -> (&'static str, Vec<f64>) {
    match shape {
        Shape::Disc => ("disc", Vec::new()),
        Shape::Outline(_) => ("outline", Vec::new()),
        Shape::Morph(morph) => ("keyed outline", morph.key_frames().collect()),
    }
}

/// One operation of a layer's stack.
#[derive(Clone, Debug, Serialize)]
pub struct OpView {
    pub index: usize,
    pub name: &'static str,
    pub params: Vec<ParamView>,
}

/// One animatable number (or colour) of a layer.
#[derive(Clone, Debug, Serialize)]
pub struct ParamView {
    /// Its parameter path in the shot file.
    pub path: String,
    /// Its name as written (`alpha`, `epsilon`, `mask.u[0]`).
    pub name: String,
    /// Its value at the frame, component by component; empty for a feather left out.
    pub value: Vec<f32>,
    /// The frames of its keys; empty for a constant.
    pub keys: Vec<f64>,
    /// The range it must lie in (`None`: unbounded on that side) and whether each end is
    /// excluded.
    pub min: Option<f32>,
    pub max: Option<f32>,
    pub min_open: bool,
    pub max_open: bool,
    /// The span its slider covers: the useful values, widened to hold its value now.
    pub slider: [f32; 2],
    /// Whether the slider moves on a logarithmic scale ([`is_logarithmic`]): each step
    /// multiplies the value, so that small values get as much of its length as large ones.
    pub log: bool,
}

/// The span of an operation parameter's slider (see [`slider_span`]).
#[must_use]
pub fn op_slider_span(param: OpParam) -> [f32; 2] {
    match param {
        OpParam::Alpha | OpParam::Beta => [-1.0, 1.0],
        OpParam::Degrees | OpParam::Axis => [-180.0, 180.0],
        OpParam::Delta | OpParam::Sigma => [0.0, 1.0],
        OpParam::GammaU | OpParam::GammaV => [0.0, 1.0],
        OpParam::N => [0.25, 8.0],
    }
}

/// Whether an operation parameter's slider is logarithmic: a squaring's `n`, a positive
/// exponent whose useful values run from a quarter to eight.
#[must_use]
pub fn op_is_logarithmic(param: OpParam) -> bool {
    match param {
        OpParam::N => true,
        OpParam::Alpha
        | OpParam::Beta
        | OpParam::Degrees
        | OpParam::Axis
        | OpParam::Delta
        | OpParam::Sigma
        | OpParam::GammaU
        | OpParam::GammaV => false,
    }
}

/// Whether a parameter's slider is logarithmic: ε, whose useful values on a small or flat
/// patch lie far below those on a sphere (10⁻⁴ to 2, its legal range less what no disc shows),
/// and the scale-like operation parameters ([`op_is_logarithmic`]).
#[must_use]
pub fn is_logarithmic(param: LayerParam) -> bool {
    match param {
        LayerParam::Epsilon => true,
        LayerParam::Op { param, .. } => op_is_logarithmic(param),
        LayerParam::Colour(_)
        | LayerParam::Opacity
        | LayerParam::Feather
        | LayerParam::MaskU(_)
        | LayerParam::MaskV(_)
        | LayerParam::MaskFeather
        | LayerParam::PinU
        | LayerParam::PinV => false,
    }
}

/// The span of a parameter's slider: where its useful values lie. Translations past ±1 make H
/// nearly tangent; a split past 1 pushes the pieces off a sphere; ε runs over its legal range
/// (0, 2] from 10⁻⁴, on a logarithmic slider ([`is_logarithmic`]).
#[must_use]
pub fn slider_span(param: LayerParam) -> [f32; 2] {
    match param {
        LayerParam::Epsilon => [1e-4, 2.0],
        LayerParam::Colour(_) | LayerParam::Opacity => [0.0, 1.0],
        LayerParam::Feather => [0.0, 0.05],
        LayerParam::MaskU(_) | LayerParam::MaskV(_) | LayerParam::PinU | LayerParam::PinV => {
            [0.0, 1.0]
        }
        LayerParam::MaskFeather => [0.0, 0.5],
        LayerParam::Op { param, .. } => op_slider_span(param),
    }
}

/// The span of a shade entry parameter's slider, as a layer's of the same kind.
#[must_use]
pub fn shade_slider_span(param: ShadeParam) -> [f32; 2] {
    match param {
        ShadeParam::MaskU(_) | ShadeParam::MaskV(_) => [0.0, 1.0],
        ShadeParam::MaskFeather => [0.0, 0.5],
        ShadeParam::Op { param, .. } => op_slider_span(param),
    }
}

/// Whether a shade entry parameter's slider is logarithmic, as a layer's of the same kind.
#[must_use]
pub fn shade_is_logarithmic(param: ShadeParam) -> bool {
    match param {
        ShadeParam::MaskU(_) | ShadeParam::MaskV(_) | ShadeParam::MaskFeather => false,
        ShadeParam::Op { param, .. } => op_is_logarithmic(param),
    }
}

/// The name a shade entry parameter is written with inside its entry or operation.
fn shade_param_name(param: ShadeParam) -> String {
    match param {
        ShadeParam::MaskU(i) => format!("mask.u[{i}]"),
        ShadeParam::MaskV(i) => format!("mask.v[{i}]"),
        ShadeParam::MaskFeather => "mask.feather".to_string(),
        ShadeParam::Op { param, .. } => param.name().to_string(),
    }
}

/// The name a layer parameter is written with inside its layer or operation.
fn param_name(param: LayerParam) -> String {
    match param {
        LayerParam::Epsilon => "epsilon".to_string(),
        LayerParam::Colour(None) => "colour".to_string(),
        LayerParam::Colour(Some(c)) => format!("colour[{c}]"),
        LayerParam::Opacity => "opacity".to_string(),
        LayerParam::Feather => "feather".to_string(),
        LayerParam::MaskU(i) => format!("mask.u[{i}]"),
        LayerParam::MaskV(i) => format!("mask.v[{i}]"),
        LayerParam::MaskFeather => "mask.feather".to_string(),
        LayerParam::PinU => "pin.u".to_string(),
        LayerParam::PinV => "pin.v".to_string(),
        LayerParam::Op { param, .. } => param.name().to_string(),
    }
}

fn param_view(param: LayerParam, reading: &ParamReading) -> ParamView {
    view_of(
        reading,
        param_name(param),
        param.bounds(),
        (slider_span(param), is_logarithmic(param)),
    )
}

/// A parameter read at a frame, with its name, bounds, and slider span and scale, for the
/// page: the span widened to hold its value now.
fn view_of(
    reading: &ParamReading,
    name: String,
    bounds: Bounds,
    (span, log): ([f32; 2], bool),
) -> ParamView {
    let mut slider = span;
    for &v in &reading.value {
        slider = [slider[0].min(v), slider[1].max(v)];
    }
    ParamView {
        path: reading.path.to_string(),
        name,
        value: reading.value.clone(),
        keys: reading.keys.clone(),
        min: bounds.min.is_finite().then_some(bounds.min),
        max: bounds.max.is_finite().then_some(bounds.max),
        min_open: bounds.min_open,
        max_open: bounds.max_open,
        slider,
        log,
    }
}

/// Everything the page shows of `shot`, whose file's text is `text`, at `frame`.
pub fn highlight_views(
    shot: &Shot,
    text: &str,
    frame: f64,
) -> Result<Vec<HighlightView>, TuneError> {
    let readings = param_readings(text, frame)
        .map_err(|e| TuneError::Bad(e.in_file(&shot.path).to_string()))?;
    let own = std::fs::canonicalize(&shot.path).unwrap_or_else(|_| shot.path.clone());
    let selectors: Vec<&[String]> = shot.highlight_selectors().collect();
    let mut views = Vec::new();
    for entry in 0..shot.highlight_count() {
        let (written_in, file_index) = match shot.highlight_written(entry) {
            Some((file, index)) => {
                let same = std::fs::canonicalize(file).is_ok_and(|f| f == own);
                (file.display().to_string(), same.then_some(index))
            }
            None => (shot.path.display().to_string(), None),
        };
        let layers = shot
            .highlight_layers(entry)
            .into_iter()
            .enumerate()
            .map(|(k, layer)| {
                let mine = |reading: &&ParamReading| match &reading.path {
                    ParamPath::Highlight {
                        entry: HighlightRef::Index(i),
                        layer,
                        ..
                    } => Some(*i) == file_index && *layer == k,
                    _ => false,
                };
                let params_of = |keep: &dyn Fn(LayerParam) -> bool| -> Vec<ParamView> {
                    readings
                        .iter()
                        .filter(mine)
                        .filter_map(|r| match r.path {
                            ParamPath::Highlight { param, .. } if keep(param) => {
                                Some(param_view(param, r))
                            }
                            _ => None,
                        })
                        .collect()
                };
                let ops = layer
                    .stack
                    .iter()
                    .enumerate()
                    .map(|(j, op)| OpView {
                        index: j,
                        name: op.name(),
                        params: params_of(
                            &|p| matches!(p, LayerParam::Op { index, .. } if index == j),
                        ),
                    })
                    .collect();
                let params = params_of(&|p| {
                    !matches!(p, LayerParam::Op { .. } | LayerParam::Colour(Some(_)))
                });
                let (shape, shape_keys) = shape_view(&layer.shape);
                LayerView {
                    index: k,
                    shape,
                    shape_keys,
                    ops,
                    params,
                    has_mask: layer.mask.is_some(),
                    pinned_to: shot
                        .pinned_patch(entry, k)
                        .map(|p| shot.library.patches[p].name.clone()),
                    holds: layer.pin.as_ref().and_then(|pin| pin.hold),
                }
            })
            .collect();
        views.push(HighlightView {
            entry,
            file_index,
            written_in,
            patches: selectors.get(entry).map(|s| s.to_vec()).unwrap_or_default(),
            layers,
        });
    }
    Ok(views)
}

/// Every shade entry of `shot`, whose file's text is `text`, at `frame`.
pub fn shade_views(shot: &Shot, text: &str, frame: f64) -> Result<Vec<ShadeView>, TuneError> {
    let readings = param_readings(text, frame)
        .map_err(|e| TuneError::Bad(e.in_file(&shot.path).to_string()))?;
    let own = std::fs::canonicalize(&shot.path).unwrap_or_else(|_| shot.path.clone());
    let selectors: Vec<&[String]> = shot.shade_selectors().collect();
    let mut views = Vec::new();
    for entry in 0..shot.shade_count() {
        let (written_in, file_index) = match shot.shade_written(entry) {
            Some((file, index)) => {
                let same = std::fs::canonicalize(file).is_ok_and(|f| f == own);
                (file.display().to_string(), same.then_some(index))
            }
            None => (shot.path.display().to_string(), None),
        };
        let params_of = |keep: &dyn Fn(ShadeParam) -> bool| -> Vec<ParamView> {
            readings
                .iter()
                .filter_map(|r| match r.path {
                    ParamPath::Shade { entry: i, param }
                        if Some(i) == file_index && keep(param) =>
                    {
                        Some(view_of(
                            r,
                            shade_param_name(param),
                            param.bounds(),
                            (shade_slider_span(param), shade_is_logarithmic(param)),
                        ))
                    }
                    _ => None,
                })
                .collect()
        };
        let Some(stack) = shot.shade_stack(entry) else {
            continue;
        };
        let ops = stack
            .stack
            .iter()
            .enumerate()
            .map(|(j, op)| OpView {
                index: j,
                name: op.name(),
                params: params_of(&|p| matches!(p, ShadeParam::Op { index, .. } if index == j)),
            })
            .collect();
        views.push(ShadeView {
            entry,
            file_index,
            written_in,
            patches: selectors.get(entry).map(|s| s.to_vec()).unwrap_or_default(),
            ops,
            params: params_of(&|p| !matches!(p, ShadeParam::Op { .. })),
            translation: stack
                .stack
                .iter()
                .rposition(|op| matches!(op, glint::highlight::Op::Translate { .. })),
        });
    }
    Ok(views)
}

/// The value a pinned layer's pin has at `frame`: `(u, v)`.
#[must_use]
pub fn pin_at(layer: &glint::highlight::Layer<Track<f32>>, frame: f64) -> Option<(f64, f64)> {
    let pin = layer.pin.as_ref()?;
    Some((f64::from(pin.u.at(frame)), f64::from(pin.v.at(frame))))
}
