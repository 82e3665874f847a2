//! Every track of a parsed shot or look file with its [`ParamPath`] and the path of RON steps to
//! where it is written: the one walk that listing, reading and replacing a track by its path
//! share.

use std::collections::BTreeMap;

use glam::Vec3;

use super::param_path::{
    CameraParam, DetailParam, HighlightRef, LayerParam, LightParam, MaterialParam, OpParam,
    ParamPath, ShadeParam,
};
use crate::anim::{Direction, Track};
use crate::formats::ron_paths::top_level_name;
use crate::formats::ron_paths::Step::{self, Entry, Field, Index};
use crate::highlight::{Axis, Expr, Layer, Mask, Op};
use crate::shot::file::{
    CameraSpec, HighlightSpec, LightSpec, LooksFile, MaterialSpec, ProjectionSpec, ShadeSpec,
    ShotFile,
};
use crate::shot::orbit::OrbitSpec;
use crate::shot::source::Source;
use crate::shot::ShotError;
use crate::toon::DetailMap;

/// A shot or look file as parsed, before anything it names is read.
#[derive(Debug, PartialEq)]
pub(super) enum ParsedFile {
    Shot(Box<ShotFile>),
    Looks(LooksFile),
}

/// A track of a parsed file, to read and to replace, by the type it is written as.
pub(super) enum TrackMut<'a> {
    /// A number.
    Scalar(&'a mut Track<f32>),
    /// A number that may be left out (`None`: not written, and no track).
    Optional(&'a mut Option<Track<f32>>),
    /// A point, vector or colour `(x, y, z)`, one track.
    Point(&'a mut Track<Vec3>),
    /// A direction `(x, y, z)`, one track, normalized when read.
    Direction(&'a mut Track<Direction>),
    /// Three numbers `(a, b, c)`, each its own track.
    Triple(&'a mut [Track<f32>; 3]),
}

/// One track of a parsed file: its path, where it is written, and the track.
pub(super) struct Site<'a> {
    pub path: ParamPath,
    pub steps: Vec<Step<'a>>,
    pub track: TrackMut<'a>,
}

impl ParsedFile {
    /// Parses `text` as a look file when its top-level value is named `Looks`, as a shot file
    /// otherwise (and as a look file when it is unnamed and only that parses); errors are placed
    /// as when the shot is loaded.
    pub fn parse(text: &str) -> Result<Self, ShotError> {
        let source = Source::new("".as_ref(), text.to_string());
        match top_level_name(text) {
            Some("Looks") => source.parse().map(ParsedFile::Looks),
            Some(_) => source.parse().map(|shot| ParsedFile::Shot(Box::new(shot))),
            None => source
                .parse()
                .map(|shot| ParsedFile::Shot(Box::new(shot)))
                .or_else(|e| source.parse().map(ParsedFile::Looks).map_err(|_| e)),
        }
    }

    /// The names of the file's own materials.
    pub fn material_names(&self) -> Vec<&str> {
        let materials = match self {
            ParsedFile::Shot(shot) => &shot.materials,
            ParsedFile::Looks(looks) => &looks.materials,
        };
        materials.keys().map(String::as_str).collect()
    }

    /// The files the file includes, as written.
    pub fn includes(&self) -> &[String] {
        match self {
            ParsedFile::Shot(shot) => &shot.includes,
            ParsedFile::Looks(looks) => &looks.includes,
        }
    }

    fn highlights(&self) -> &[HighlightSpec] {
        match self {
            ParsedFile::Shot(shot) => &shot.highlights,
            ParsedFile::Looks(looks) => &looks.highlights,
        }
    }

    /// The file's own shade entries, in order.
    pub fn shade(&self) -> &[ShadeSpec] {
        match self {
            ParsedFile::Shot(shot) => &shot.shade,
            ParsedFile::Looks(looks) => &looks.shade,
        }
    }

    /// The indices of the highlight entries whose `patches` is `pattern` or a list holding it.
    pub fn entries_selected_by(&self, pattern: &str) -> Vec<usize> {
        (self.highlights().iter().enumerate())
            .filter(|(_, h)| h.patches.patterns().iter().any(|p| p == pattern))
            .map(|(index, _)| index)
            .collect()
    }

    /// The patterns of each highlight entry, in order.
    pub fn entry_patterns(&self) -> Vec<&[String]> {
        self.highlights()
            .iter()
            .map(|h| h.patches.patterns())
            .collect()
    }

    /// Every parameter path of the file: each track (highlights named by index), and each
    /// component of a `colour` or `focus` after the whole, in the order written.
    pub fn paths(&mut self) -> Vec<ParamPath> {
        let mut paths = Vec::new();
        self.for_each_site(&mut |site| {
            let components = matches!(site.track, TrackMut::Triple(_));
            paths.push(site.path.clone());
            if components {
                paths.extend((0..3).filter_map(|c| site.path.try_with_component(c)));
            }
        });
        paths
    }

    /// The track at `path` (a highlight named by index), or `None` when the file has none there.
    pub fn site(&mut self, path: &ParamPath) -> Option<Site<'_>> {
        let (whole, component) = path.without_component();
        let mut found = None;
        self.for_each_site(&mut |site| {
            if site.path == whole {
                found = Some(site);
            }
        });
        let mut site = found?;
        if let Some(c) = component {
            let TrackMut::Triple(tracks) = site.track else {
                return None;
            };
            site.track = TrackMut::Scalar(&mut tracks[c]);
            site.steps.push(Index(c));
            site.path = path.clone();
        }
        Some(site)
    }

    /// Layer `layer` (left to right through the Booleans) of highlight entry `entry` of the file,
    /// with the steps to where it is written; `None` when the file has no such layer.
    pub fn layer_mut(
        &mut self,
        entry: usize,
        layer: usize,
    ) -> Option<(&mut Layer<Track<f32>>, Vec<Step<'static>>)> {
        let highlights = match self {
            ParsedFile::Shot(shot) => &mut shot.highlights,
            ParsedFile::Looks(looks) => &mut looks.highlights,
        };
        let expr = &mut highlights.get_mut(entry)?.expr;
        let steps = vec![Field("highlights"), Index(entry), Field("expr")];
        find_layer(expr, steps, &mut 0, layer)
    }

    /// Calls `f` with every track of the file: the camera's, the light's, each material's (by
    /// name), each highlight layer's and each shade entry's, in that order.
    pub fn for_each_site<'a>(&'a mut self, f: &mut dyn FnMut(Site<'a>)) {
        let (materials, highlights, shade) = match self {
            ParsedFile::Shot(shot) => {
                camera_sites(&mut shot.camera, f);
                light_sites(&mut shot.light, f);
                (&mut shot.materials, &mut shot.highlights, &mut shot.shade)
            }
            ParsedFile::Looks(looks) => (
                &mut looks.materials,
                &mut looks.highlights,
                &mut looks.shade,
            ),
        };
        material_sites(materials, f);
        for (entry, highlight) in highlights.iter_mut().enumerate() {
            let steps = vec![Field("highlights"), Index(entry), Field("expr")];
            expr_sites(&mut highlight.expr, steps, entry, &mut 0, f);
        }
        for (entry, spec) in shade.iter_mut().enumerate() {
            shade_sites(spec, entry, f);
        }
    }
}

fn camera_sites<'a>(camera: &'a mut CameraSpec, f: &mut dyn FnMut(Site<'a>)) {
    let CameraSpec {
        eye,
        orbit,
        target,
        up,
        projection,
        near: _,
        far: _,
    } = camera;
    let mut site = |param, steps: &[Step<'a>], track| {
        let mut path = vec![Field("camera")];
        path.extend_from_slice(steps);
        f(Site {
            path: ParamPath::Camera(param),
            steps: path,
            track,
        });
    };
    if let Some(eye) = eye {
        site(CameraParam::Eye, &[Field("eye")], TrackMut::Point(eye));
    }
    let orbit_tracks = match orbit {
        Some(OrbitSpec::Sphere {
            azimuth,
            elevation,
            distance,
        }) => vec![
            (CameraParam::OrbitAzimuth, "azimuth", azimuth),
            (CameraParam::OrbitElevation, "elevation", elevation),
            (CameraParam::OrbitDistance, "distance", distance),
        ],
        Some(OrbitSpec::Cylinder {
            azimuth,
            radius,
            height,
        }) => vec![
            (CameraParam::OrbitAzimuth, "azimuth", azimuth),
            (CameraParam::OrbitRadius, "radius", radius),
            (CameraParam::OrbitHeight, "height", height),
        ],
        None => Vec::new(),
    };
    for (param, field, track) in orbit_tracks {
        site(
            param,
            &[Field("orbit"), Field(field)],
            TrackMut::Scalar(track),
        );
    }
    site(
        CameraParam::Target,
        &[Field("target")],
        TrackMut::Point(target),
    );
    site(CameraParam::Up, &[Field("up")], TrackMut::Point(up));
    let projection_step = Field("projection");
    match projection {
        ProjectionSpec::Perspective { fov_y_degrees } => site(
            CameraParam::FovYDegrees,
            &[projection_step, Field("fov_y_degrees")],
            TrackMut::Scalar(fov_y_degrees),
        ),
        ProjectionSpec::Orthographic { height } => site(
            CameraParam::Height,
            &[projection_step, Field("height")],
            TrackMut::Scalar(height),
        ),
    }
}

fn light_sites<'a>(light: &'a mut LightSpec, f: &mut dyn FnMut(Site<'a>)) {
    let (param, field, track) = match light {
        LightSpec::Directional { towards } => {
            (LightParam::Towards, "towards", TrackMut::Direction(towards))
        }
        LightSpec::Point { position } => {
            (LightParam::Position, "position", TrackMut::Point(position))
        }
    };
    f(Site {
        path: ParamPath::Light(param),
        steps: vec![Field("light"), Field(field)],
        track,
    });
}

fn material_sites<'a>(
    materials: &'a mut BTreeMap<String, MaterialSpec>,
    f: &mut dyn FnMut(Site<'a>),
) {
    for (name, material) in materials.iter_mut() {
        let mut site = |param, steps: &[Step<'a>], track| {
            let mut path = vec![Field("materials"), Entry(name.as_str())];
            path.extend_from_slice(steps);
            f(Site {
                path: ParamPath::Material {
                    name: name.clone(),
                    param,
                },
                steps: path,
                track,
            });
        };
        match material {
            MaterialSpec::Cel { base, bands } => {
                site(MaterialParam::Base, &[Field("base")], TrackMut::Point(base));
                for (band, (threshold, colour)) in bands.iter_mut().enumerate() {
                    let at = [Field("bands"), Index(band)];
                    site(
                        MaterialParam::Threshold(band),
                        &[at[0], at[1], Index(0)],
                        TrackMut::Scalar(threshold),
                    );
                    site(
                        MaterialParam::BandColour(band),
                        &[at[0], at[1], Index(1)],
                        TrackMut::Point(colour),
                    );
                }
            }
            MaterialSpec::XToon {
                texture: _,
                detail,
                invert: _,
                shape,
            } => {
                let mut number = |param, field, track| {
                    site(
                        MaterialParam::Detail(param),
                        &[Field("detail"), Field(field)],
                        track,
                    );
                };
                match detail {
                    DetailMap::Depth { z_min, r } => {
                        number(DetailParam::ZMin, "z_min", TrackMut::Scalar(z_min));
                        number(DetailParam::R, "r", TrackMut::Scalar(r));
                    }
                    DetailMap::DepthOfField { focus, z_min, r } => {
                        number(DetailParam::Focus(None), "focus", TrackMut::Triple(focus));
                        number(DetailParam::ZMin, "z_min", TrackMut::Scalar(z_min));
                        number(DetailParam::R, "r", TrackMut::Scalar(r));
                    }
                    DetailMap::NearSilhouette { r } => {
                        number(DetailParam::R, "r", TrackMut::Scalar(r));
                    }
                    DetailMap::Highlight { s } => {
                        number(DetailParam::S, "s", TrackMut::Scalar(s));
                    }
                }
                if let Some(shape) = shape {
                    site(
                        MaterialParam::ShapeWeight,
                        &[Field("shape"), Field("weight")],
                        TrackMut::Scalar(&mut shape.weight),
                    );
                }
            }
        }
    }
}

/// Layer `wanted` of `expr`, whose layers are numbered from `*seen` on, with the steps to it.
fn find_layer<'e>(
    expr: &'e mut Expr<Track<f32>>,
    mut steps: Vec<Step<'static>>,
    seen: &mut usize,
    wanted: usize,
) -> Option<(&'e mut Layer<Track<f32>>, Vec<Step<'static>>)> {
    match expr {
        Expr::Layer(l) => {
            *seen += 1;
            steps.push(Index(0));
            (*seen - 1 == wanted).then_some((l, steps))
        }
        Expr::Union(a, b) | Expr::Subtract(a, b) | Expr::Intersect(a, b) => {
            let mut right = steps.clone();
            steps.push(Index(0));
            right.push(Index(1));
            if let Some(found) = find_layer(a, steps, seen, wanted) {
                return Some(found);
            }
            find_layer(b, right, seen, wanted)
        }
    }
}

/// The layers of `expr`, numbered from `*layer` on, left to right through the Booleans.
fn expr_sites<'a>(
    expr: &'a mut Expr<Track<f32>>,
    mut steps: Vec<Step<'a>>,
    entry: usize,
    layer: &mut usize,
    f: &mut dyn FnMut(Site<'a>),
) {
    match expr {
        Expr::Layer(l) => {
            steps.push(Index(0));
            layer_sites(l, &steps, entry, *layer, f);
            *layer += 1;
        }
        Expr::Union(a, b) | Expr::Subtract(a, b) | Expr::Intersect(a, b) => {
            let mut right = steps.clone();
            steps.push(Index(0));
            right.push(Index(1));
            expr_sites(a, steps, entry, layer, f);
            expr_sites(b, right, entry, layer, f);
        }
    }
}

fn layer_sites<'a>(
    l: &'a mut Layer<Track<f32>>,
    to_layer: &[Step<'a>],
    entry: usize,
    layer: usize,
    f: &mut dyn FnMut(Site<'a>),
) {
    let mut site = |param, steps: &[Step<'a>], track| {
        let mut path = to_layer.to_vec();
        path.extend_from_slice(steps);
        f(Site {
            path: ParamPath::Highlight {
                entry: HighlightRef::Index(entry),
                layer,
                param,
            },
            steps: path,
            track,
        });
    };
    let Layer {
        stack,
        epsilon,
        colour,
        opacity,
        feather,
        mask,
        pin,
        // The frame's axis has no parameter path yet: `glint key` and `tune` cannot name it.
        frame: _,
        // Nor has a drawn outline's points.
        shape: _,
        // A held shape's map is solved, never written.
        shape_map: _,
    } = l;
    op_sites(stack, &mut |index, param, steps, track| {
        site(LayerParam::Op { index, param }, &steps, track);
    });
    site(
        LayerParam::Epsilon,
        &[Field("epsilon")],
        TrackMut::Scalar(epsilon),
    );
    site(
        LayerParam::Colour(None),
        &[Field("colour")],
        TrackMut::Triple(colour),
    );
    site(
        LayerParam::Opacity,
        &[Field("opacity")],
        TrackMut::Scalar(opacity),
    );
    site(
        LayerParam::Feather,
        &[Field("feather")],
        TrackMut::Optional(feather),
    );
    if let Some(mask) = mask {
        mask_sites(mask, &mut |number, steps, track| {
            let param = match number {
                MaskNumber::U(i) => LayerParam::MaskU(i),
                MaskNumber::V(i) => LayerParam::MaskV(i),
                MaskNumber::Feather => LayerParam::MaskFeather,
            };
            site(param, &steps, track);
        });
    }
    if let Some(pin) = pin {
        site(
            LayerParam::PinU,
            &[Field("pin"), Field("u")],
            TrackMut::Scalar(&mut pin.u),
        );
        site(
            LayerParam::PinV,
            &[Field("pin"), Field("v")],
            TrackMut::Scalar(&mut pin.v),
        );
    }
}

/// The tracks of shade entry `entry` of the file: its operations' numbers, then its mask's.
fn shade_sites<'a>(spec: &'a mut ShadeSpec, entry: usize, f: &mut dyn FnMut(Site<'a>)) {
    let ShadeSpec {
        patches: _,
        stack,
        mask,
    } = spec;
    let mut site = |param, steps: Vec<Step<'a>>, track| {
        let mut path = vec![Field("shade"), Index(entry)];
        path.extend(steps);
        f(Site {
            path: ParamPath::Shade { entry, param },
            steps: path,
            track,
        });
    };
    op_sites(stack, &mut |index, param, steps, track| {
        site(ShadeParam::Op { index, param }, steps, track);
    });
    if let Some(mask) = mask {
        mask_sites(mask, &mut |number, steps, track| {
            let param = match number {
                MaskNumber::U(i) => ShadeParam::MaskU(i),
                MaskNumber::V(i) => ShadeParam::MaskV(i),
                MaskNumber::Feather => ShadeParam::MaskFeather,
            };
            site(param, steps, track);
        });
    }
}

/// Calls `f` with each number of the operations of `stack`: the operation's index, the number,
/// the steps to it from the stack's owner (`stack[J].NAME`, `[0]` after `axis` for `Angle(φ)`)
/// and its track.
fn op_sites<'a>(
    stack: &'a mut [Op<Track<f32>>],
    f: &mut dyn FnMut(usize, OpParam, Vec<Step<'a>>, TrackMut<'a>),
) {
    for (index, op) in stack.iter_mut().enumerate() {
        let mut number = |param, track, more: &[Step<'a>]| {
            let mut steps = vec![Field("stack"), Index(index), Field(OpParam::name(param))];
            steps.extend_from_slice(more);
            f(index, param, steps, TrackMut::Scalar(track));
        };
        match op {
            Op::Translate { alpha, beta } => {
                number(OpParam::Alpha, alpha, &[]);
                number(OpParam::Beta, beta, &[]);
            }
            Op::Rotate { degrees } => number(OpParam::Degrees, degrees, &[]),
            Op::Scale { delta, axis } => {
                number(OpParam::Delta, delta, &[]);
                match axis {
                    Axis::Angle(phi) => number(OpParam::Axis, phi, &[Index(0)]),
                    Axis::U | Axis::V => {}
                }
            }
            Op::Split { gamma_u, gamma_v } => {
                number(OpParam::GammaU, gamma_u, &[]);
                number(OpParam::GammaV, gamma_v, &[]);
            }
            Op::Square { sigma, n, style: _ } => {
                number(OpParam::Sigma, sigma, &[]);
                number(OpParam::N, n, &[]);
            }
        }
    }
}

/// A number of a mask: a bound `u[I]`, `v[I]`, or its feather.
#[derive(Clone, Copy)]
enum MaskNumber {
    U(usize),
    V(usize),
    Feather,
}

/// Calls `f` with each number of `mask`, the steps to it from the mask's owner
/// (`mask.u[I]`, `mask.v[I]`, `mask.feather`) and its track.
fn mask_sites<'a>(
    mask: &'a mut Mask<Track<f32>>,
    f: &mut dyn FnMut(MaskNumber, Vec<Step<'a>>, TrackMut<'a>),
) {
    let Mask { u, v, feather } = mask;
    let bounds = [
        (MaskNumber::U(0), "u", 0, &mut u.0),
        (MaskNumber::U(1), "u", 1, &mut u.1),
        (MaskNumber::V(0), "v", 0, &mut v.0),
        (MaskNumber::V(1), "v", 1, &mut v.1),
    ];
    for (number, field, index, track) in bounds {
        f(
            number,
            vec![Field("mask"), Field(field), Index(index)],
            TrackMut::Scalar(track),
        );
    }
    f(
        MaskNumber::Feather,
        vec![Field("mask"), Field("feather")],
        TrackMut::Scalar(feather),
    );
}
