//! Reading a shot, step by step: parse it, follow its includes, place its instances, match its
//! selectors, build its materials, and check every track at every frame it can take — all
//! before any frame is rendered.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use super::every_frame::check_every_frame;
use super::file::{
    CameraSpec, HighlightSpec, InstanceSpec, LooksFile, MaterialSpec, RenderSpec, ShadeSpec,
    ShotFile,
};
use super::glob;
use super::line_styles::select_lines;
use super::moving_parts::{check_reach, pose_of};
use super::no_match::no_match_message;
use super::output::{check_numbered, resolve_path};
use super::pin::resolve_pins;
use super::pose::{Deform, InstancePose, Timing};
use super::source::Source;
use super::validated::{Accuracy, Instance, Material, Shot};
use super::written::Written;
use super::{ShotError, MAX_FRAMES};
use crate::formats::parts::{parts_file, resolve_groups};
use crate::formats::ron_location::closest_name;
use crate::formats::ron_paths::Step::{Entry, Field, Index};
use crate::formats::{load_model, read_toon_texture, Model, UsdMotion};
use crate::geom::{NamedPatch, PatchGroup, PatchLibrary, MAX_COORDINATE};
use crate::render::Settings;
use crate::toon::{AbstractShape, Abstraction, ToonTexture, XToon};

/// The largest time code, and time codes per frame, a frame may be mapped with: beyond it the
/// frame's time code loses its fraction.
const MAX_TIME_CODE: f64 = 1e12;

/// The most files an include chain may nest.
const MAX_INCLUDE_DEPTH: usize = 16;

/// Reads, checks and prepares the shot at `path`.
pub fn load_shot(path: &Path) -> Result<Shot, ShotError> {
    load_source(Source::read(path)?)
}

/// Checks and prepares the shot as if the file at `path` held `text`: what
/// [`load_shot`] gives once `text` is written there. Includes, patch files and textures are
/// still read from disk, relative to `path`; the file at `path` itself is not read.
pub fn load_shot_text(path: &Path, text: String) -> Result<Shot, ShotError> {
    load_source(Source::new(path, text))
}

/// Checks and prepares the shot whose file is `source`.
fn load_source(source: Source) -> Result<Shot, ShotError> {
    let path = source.path.clone();
    let path = path.as_path();
    let mut reader = Reader {
        sources: vec![source],
        included: HashSet::new(),
        inputs: Inputs::default(),
        looks: Looks::default(),
    };
    let file: ShotFile = reader.sources[0].parse()?;
    let mut chain = vec![canonical(path)];
    for (index, include) in file.includes.iter().enumerate() {
        reader.read_include(0, index, include, &mut chain)?;
    }
    reader.add_looks(
        0,
        file.materials.into_iter().collect(),
        file.highlights,
        file.shade,
    )?;
    let Reader {
        sources,
        included: _,
        mut inputs,
        looks,
    } = reader;
    let shot_source = &sources[0];

    let output = check_frames_and_output(&file.frames, file.fps, &file.output, shot_source)?;
    let first_frame = file.frames.0 as f64;
    let placed = place_instances(
        &file.instances,
        (first_frame, file.fps),
        &looks,
        shot_source,
        &mut inputs,
    )?;
    let patch_highlight = select_highlights(&looks.highlights, &placed.library, &sources)?;
    let pins = resolve_pins(&looks.highlights, &placed.library, &sources)?;
    let patch_shade = select_shade(&looks.shade, &placed.library, &sources)?;
    let (accuracy, settings) = render_settings(&file.render, file.resolution, shot_source)?;
    if file.render.outlines.is_none() && !file.lines.is_empty() {
        return Err(shot_source.error_at(
            &[Field("lines")],
            "line styles need lines on: add `outlines: ()` (or your defaults) to `render`"
                .to_string(),
        ));
    }

    check_eye(&file.camera, shot_source)?;

    let mut assets = Assets::default();
    let mut materials = Vec::with_capacity(looks.materials.len());
    let mut material_sources = Vec::with_capacity(looks.materials.len());
    for (name, spec, source) in looks.materials {
        let material =
            assets.material(spec, &name, &sources[source], &placed.library, &mut inputs)?;
        materials.push((name, material));
        material_sources.push(source);
    }
    let material_names: Vec<&str> = materials.iter().map(|(n, _)| n.as_str()).collect();
    let patch_lines = select_lines(
        &file.lines,
        &placed.library,
        &placed.patch_material,
        &material_names,
        shot_source,
    )?;
    let (highlights, highlights_written): (Vec<_>, Vec<_>) = looks.highlights.into_iter().unzip();
    let (shade, shade_written): (Vec<_>, Vec<_>) = looks.shade.into_iter().unzip();
    let shade_written_in = shade_written
        .iter()
        .map(|w: &Written| (sources[w.source].path.clone(), w.index))
        .collect();
    let written_in = highlights_written
        .iter()
        .map(|w: &Written| (sources[w.source].path.clone(), w.index))
        .collect();
    let mut files = sources.iter().map(|s| s.path.clone()).collect::<Vec<_>>();
    let shot_files = files.len();
    files.extend(inputs.paths);
    let shot = Shot {
        path: path.to_path_buf(),
        inputs: files,
        shot_files,
        frames: file.frames,
        fps: file.fps,
        output,
        library: Arc::new(placed.library),
        instances: placed.instances,
        settings,
        accuracy,
        outlines: file.render.outlines,
        lines: file.lines,
        patch_lines,
        aovs: file.render.aovs.clone(),
        camera: file.camera,
        light: file.light,
        materials,
        highlights,
        patch_material: placed.patch_material,
        poses: placed.poses,
        patch_highlight,
        pins,
        highlights_written: written_in,
        shade,
        patch_shade,
        shade_written: shade_written_in,
    };
    check_every_frame(
        &shot,
        &sources,
        &material_sources,
        &highlights_written,
        &shade_written,
    )?;
    Ok(shot)
}

/// What the includes and the shot contribute, each item with the file it came from.
#[derive(Default)]
struct Looks {
    materials: Vec<(String, MaterialSpec, usize)>,
    /// Where each material name is in `materials`.
    material_index: HashMap<String, usize>,
    highlights: Vec<(HighlightSpec, Written)>,
    shade: Vec<(ShadeSpec, Written)>,
}

/// The files read so far, and the looks they define.
struct Reader {
    sources: Vec<Source>,
    /// The included files read so far (canonical paths): each is read once, however many
    /// files include it.
    included: HashSet<PathBuf>,
    inputs: Inputs,
    looks: Looks,
}

impl Reader {
    /// Reads the include `name`, written as item `index` of the includes of `sources[from]`,
    /// and its own includes, depth first.
    fn read_include(
        &mut self,
        from: usize,
        index: usize,
        name: &str,
        chain: &mut Vec<PathBuf>,
    ) -> Result<(), ShotError> {
        let path = self.sources[from].folder.join(name);
        let key = canonical(&path);
        let at = |sources: &[Source], message: String| {
            sources[from].error_at(&[Field("includes"), Index(index)], message)
        };
        if chain.contains(&key) {
            return Err(at(
                &self.sources,
                format!("including \"{name}\" here makes a cycle: it includes, directly or through others, the file that includes it"),
            ));
        }
        if self.included.contains(&key) {
            // Already read through another include: its looks are in once.
            return Ok(());
        }
        if chain.len() > MAX_INCLUDE_DEPTH {
            return Err(at(
                &self.sources,
                format!("includes nest more than {MAX_INCLUDE_DEPTH} deep"),
            ));
        }
        let source = match Source::read(&path) {
            Ok(source) => source,
            Err(_) if !path.exists() => {
                return Err(at(
                    &self.sources,
                    format!("the included file {} does not exist", path.display()),
                ))
            }
            Err(e) => return Err(e),
        };
        let file: LooksFile = source.parse()?;
        self.included.insert(key.clone());
        self.sources.push(source);
        let source = self.sources.len() - 1;
        chain.push(key);
        for (index, include) in file.includes.iter().enumerate() {
            self.read_include(source, index, include, chain)?;
        }
        chain.pop();
        self.add_looks(
            source,
            file.materials.into_iter().collect(),
            file.highlights,
            file.shade,
        )
    }

    /// Adds the materials, highlights and shade entries of `sources[source]`; a material name defined twice
    /// is an error at its second definition.
    fn add_looks(
        &mut self,
        source: usize,
        materials: Vec<(String, MaterialSpec)>,
        highlights: Vec<HighlightSpec>,
        shade: Vec<ShadeSpec>,
    ) -> Result<(), ShotError> {
        for (name, spec) in materials {
            if let Some(&first) = self.looks.material_index.get(&name) {
                let (_, _, first) = self.looks.materials[first];
                return Err(self.sources[source].error_at(
                    &[Field("materials"), Entry(&name)],
                    format!(
                        "the material \"{name}\" is already defined in {}; material names must be unique",
                        self.sources[first].shown
                    ),
                ));
            }
            self.looks
                .material_index
                .insert(name.clone(), self.looks.materials.len());
            self.looks.materials.push((name, spec, source));
        }
        let written = |index| Written { source, index };
        self.looks.highlights.extend(
            highlights
                .into_iter()
                .enumerate()
                .map(|(index, h)| (h, written(index))),
        );
        self.looks.shade.extend(
            shade
                .into_iter()
                .enumerate()
                .map(|(index, h)| (h, written(index))),
        );
        Ok(())
    }
}

/// Checks the frame range and the frame rate, and resolves the output pattern against the
/// shot's folder.
fn check_frames_and_output(
    &(first, last): &(i64, i64),
    fps: f64,
    output: &str,
    source: &Source,
) -> Result<PathBuf, ShotError> {
    if first > last {
        return Err(source.error_at(
            &[Field("frames")],
            format!("the frame range ({first}, {last}) is backwards; write the first frame first"),
        ));
    }
    if i128::from(last) - i128::from(first) >= i128::from(MAX_FRAMES) {
        return Err(source.error_at(
            &[Field("frames")],
            format!("the frame range ({first}, {last}) is longer than {MAX_FRAMES} frames"),
        ));
    }
    if !(fps.is_finite() && fps > 0.0) {
        return Err(source.error_at(
            &[Field("fps")],
            format!("fps is {fps}, but it must be greater than 0"),
        ));
    }
    let resolved = resolve_path(&source.folder, Path::new(output));
    let frame_count = usize::try_from(last - first).map_or(usize::MAX, |n| n + 1);
    check_numbered(&resolved, frame_count)
        .map_err(|message| source.error_at(&[Field("output")], message))?;
    Ok(resolved)
}

/// The instances placed: one library of every patch, named `INSTANCE/PATCH`.
struct Placed {
    library: PatchLibrary,
    instances: Vec<Instance>,
    patch_material: Vec<usize>,
    /// How each instance is placed at any frame.
    poses: Vec<InstancePose>,
}

/// Reads each patch file once and places a copy of it for each instance.
fn place_instances(
    specs: &[InstanceSpec],
    (first_frame, fps): (f64, f64),
    looks: &Looks,
    source: &Source,
    inputs: &mut Inputs,
) -> Result<Placed, ShotError> {
    let within = |x: f64| x.is_finite() && x.abs() <= MAX_COORDINATE;
    let mut models: HashMap<PathBuf, (Arc<PatchLibrary>, Option<UsdMotion>)> = HashMap::new();
    let mut placed = Placed {
        library: PatchLibrary {
            patches: Vec::new(),
            groups: Vec::new(),
        },
        instances: Vec::new(),
        patch_material: Vec::new(),
        poses: Vec::new(),
    };
    let mut instance_names = HashSet::new();
    for (index, spec) in specs.iter().enumerate() {
        let at = |field, message: String| {
            source.error_at(&[Field("instances"), Index(index), Field(field)], message)
        };
        if spec.name.is_empty() || spec.name.contains('/') {
            return Err(at("name", format!(
                "the instance name \"{}\" must be non-empty and without `/` (patches are named INSTANCE/PATCH)",
                spec.name
            )));
        }
        if !instance_names.insert(spec.name.as_str()) {
            return Err(at(
                "name",
                format!(
                    "the instance name \"{}\" is used twice; instance names must be unique",
                    spec.name
                ),
            ));
        }
        let material = looks
            .material_index
            .get(&spec.material)
            .copied()
            .ok_or_else(|| {
                let names: Vec<&str> = looks.materials.iter().map(|m| m.0.as_str()).collect();
                at("material", unknown("material", &spec.material, &names))
            })?;
        spec.transform.check().map_err(|(field, message)| {
            source.error_at(
                &[
                    Field("instances"),
                    Index(index),
                    Field("transform"),
                    Field(field),
                ],
                format!("instance \"{}\": {message}", spec.name),
            )
        })?;
        let model_path = source.folder.join(&spec.file);
        let key = canonical(&model_path);
        if !models.contains_key(&key) {
            let Model {
                library: model,
                motion,
            } = load_model(&model_path).map_err(|e| {
                let message = match &e {
                    crate::formats::FormatError::Io { source, .. } => format!(
                        "cannot read the patch file {}: {source}",
                        model_path.display()
                    ),
                    other => format!("in the patch file: {other}"),
                };
                at("file", message)
            })?;
            inputs.add(&model_path);
            let parts = parts_file(&model_path);
            if parts.is_file() {
                inputs.add(&parts);
            }
            models.insert(key.clone(), (Arc::new(model), motion));
        }
        let (model, motion) = &models[&key];
        let deform = deform_of(spec, index, motion.as_ref(), fps, first_frame, source)?;
        let own = resolve_groups(&spec.groups, &model.patches, &model.groups).map_err(|e| {
            let to_groups = [Field("instances"), Index(index), Field("groups")];
            source.error_at(&e.path(&to_groups), e.message.clone())
        })?;
        let start = placed.library.patches.len();
        for group in model.groups.iter().chain(&own) {
            placed.library.groups.push(PatchGroup {
                name: format!("{}/{}", spec.name, group.name),
                patches: group.patches.iter().map(|p| start + p).collect(),
            });
        }
        let all_groups: Vec<&PatchGroup> = model.groups.iter().chain(&own).collect();
        let pose = pose_of(
            spec,
            index,
            (model, deform, &model_path),
            &all_groups,
            source,
            start,
        )?;
        if pose.moves() {
            check_reach(&pose, spec, index, source)?;
        }
        let material_names: Vec<&str> = looks.materials.iter().map(|m| m.0.as_str()).collect();
        let materials = part_materials(
            spec,
            (index, material),
            (&looks.material_index, &material_names, &all_groups),
            model.patches.len(),
            source,
        )?;
        for (k, patch) in model.patches.iter().enumerate() {
            let material = materials[k];
            let surface = pose.place(k, first_frame);
            if !pose.moves()
                && !surface
                    .control_points()
                    .all(|p| p.to_array().into_iter().all(within))
            {
                return Err(at("transform", format!(
                    "the transform of instance \"{}\" places the patch \"{}\" beyond ±{MAX_COORDINATE:e}, where coordinates lose their precision; scale or move the instance less",
                    spec.name, patch.name
                )));
            }
            placed.library.patches.push(NamedPatch {
                name: format!("{}/{}", spec.name, patch.name),
                trim: patch.trim.clone(),
                surface,
            });
            placed.patch_material.push(material);
        }
        placed.poses.push(pose);
        placed.instances.push(Instance {
            name: spec.name.clone(),
            patches: start..placed.library.patches.len(),
        });
    }
    Ok(placed)
}

/// How instance `spec` (item `index` of the shot's instances) deforms with its model's
/// `motion`, an animated USD layer's: which time code each frame shows,
/// `start + (frame − first) · per_frame`, by default from the layer's `startTimeCode` (0 when
/// it has none) and `timeCodesPerSecond ÷ fps`. `time_codes` on a model that does not move, or
/// a mapping that is not finite, is refused.
fn deform_of(
    spec: &InstanceSpec,
    index: usize,
    motion: Option<&UsdMotion>,
    fps: f64,
    first: f64,
    source: &Source,
) -> Result<Option<Deform>, ShotError> {
    let at = |message: String| {
        source.error_at(
            &[Field("instances"), Index(index), Field("time_codes")],
            message,
        )
    };
    let Some(motion) = motion else {
        return match spec.time_codes {
            None => Ok(None),
            Some(_) => Err(at(format!(
                "the model of instance \"{}\" has no time samples, so there are no time codes to map; leave out time_codes",
                spec.name
            ))),
        };
    };
    let written = spec.time_codes.unwrap_or_default();
    let layer = motion.time_codes();
    let timing = Timing {
        first,
        start: written.start.or(layer.start).unwrap_or(0.0),
        per_frame: written.per_frame.unwrap_or(layer.per_second / fps),
    };
    let finite = |x: f64| x.is_finite() && x.abs() <= MAX_TIME_CODE;
    if !(finite(timing.start) && finite(timing.per_frame)) {
        return Err(at(format!(
            "instance \"{}\" maps frames to time codes as {} + (frame − {first}) · {}, which is not finite; give time_codes a start and a per_frame within ±{MAX_TIME_CODE:e}",
            spec.name, timing.start, timing.per_frame
        )));
    }
    Ok(Some(Deform {
        motion: motion.clone(),
        timing,
    }))
}

/// The highlight entry of each patch: every pattern picks at least one patch; later entries
/// win.
fn select_highlights(
    highlights: &[(HighlightSpec, Written)],
    library: &PatchLibrary,
    sources: &[Source],
) -> Result<Vec<Option<usize>>, ShotError> {
    let mut patch_highlight = vec![None; library.patches.len()];
    for (entry, (spec, written)) in highlights.iter().enumerate() {
        for (index, pattern) in spec.patches.patterns().iter().enumerate() {
            let any = glob::pick_each(pattern, library, |patch| {
                patch_highlight[patch] = Some(entry);
            });
            if !any {
                let message = no_match_message(pattern, library);
                return Err(sources[written.source].error_at(
                    &[
                        Field("highlights"),
                        Index(written.index),
                        Field("patches"),
                        Index(index),
                    ],
                    message,
                ));
            }
        }
    }
    Ok(patch_highlight)
}

/// The shade entries of each patch, in the order written: every pattern picks at least one
/// patch.
fn select_shade(
    shade: &[(ShadeSpec, Written)],
    library: &PatchLibrary,
    sources: &[Source],
) -> Result<Vec<Vec<u32>>, ShotError> {
    let mut patch_shade: Vec<Vec<u32>> = vec![Vec::new(); library.patches.len()];
    for (entry, (spec, written)) in shade.iter().enumerate() {
        let entry = entry as u32;
        for (index, pattern) in spec.patches.patterns().iter().enumerate() {
            let any = glob::pick_each(pattern, library, |patch| {
                // Two patterns of one entry may pick the same patch: its stack acts once.
                if patch_shade[patch].last() != Some(&entry) {
                    patch_shade[patch].push(entry);
                }
            });
            if !any {
                let message = no_match_message(pattern, library);
                return Err(sources[written.source].error_at(
                    &[
                        Field("shade"),
                        Index(written.index),
                        Field("patches"),
                        Index(index),
                    ],
                    message,
                ));
            }
        }
    }
    Ok(patch_shade)
}

/// The accuracy the shot asks for, its settings at `resolution`, and its outlines.
fn render_settings(
    render: &RenderSpec,
    resolution: (u32, u32),
    source: &Source,
) -> Result<(Accuracy, Settings), ShotError> {
    let accuracy = Accuracy {
        preset: render.preset,
        tessellation: render.tessellation,
        frames: render.frames,
        antialias: render.antialias,
    };
    let settings = accuracy.settings(None, resolution);
    settings
        .validate()
        .map_err(|e| source.error_at(&[Field("resolution")], e.to_string()))?;
    if let Some(o) = &render.outlines {
        if !o.crease_degrees.is_finite() {
            return Err(source.error_at(
                &[Field("render"), Field("outlines"), Field("crease_degrees")],
                format!("crease_degrees {} must be finite", o.crease_degrees),
            ));
        }
    }
    Ok((accuracy, settings))
}

/// Toon textures and abstracted shapes, each read or built once however many materials use it.
#[derive(Default)]
struct Assets {
    textures: HashMap<PathBuf, Arc<ToonTexture>>,
    shapes: Vec<(Abstraction, Arc<AbstractShape>)>,
}

impl Assets {
    /// The material `spec` (named `name`, written in `source`) with its texture and shape.
    fn material(
        &mut self,
        spec: MaterialSpec,
        name: &str,
        source: &Source,
        library: &PatchLibrary,
        inputs: &mut Inputs,
    ) -> Result<Material, ShotError> {
        let (texture_name, detail, invert, shape) = match spec {
            MaterialSpec::Cel { base, bands } => return Ok(Material::Cel { base, bands }),
            MaterialSpec::XToon {
                texture,
                detail,
                invert,
                shape,
            } => (texture, detail, invert, shape),
        };
        let path = resolve_path(&source.folder, Path::new(&texture_name));
        let texture = match self.textures.get(&canonical(&path)) {
            Some(texture) => Arc::clone(texture),
            None => {
                let texture = Arc::new(read_toon_texture(&path).map_err(|e| {
                    source.error_at(
                        &[Field("materials"), Entry(name), Field("texture")],
                        format!("cannot use the toon texture: {e}"),
                    )
                })?);
                inputs.add(&path);
                self.textures.insert(canonical(&path), Arc::clone(&texture));
                texture
            }
        };
        let built = match &shape {
            None => None,
            Some(detail) => Some(
                match self.shapes.iter().find(|s| s.0 == detail.abstraction) {
                    Some((_, built)) => Arc::clone(built),
                    None => {
                        let built = detail.abstraction.build(library).map_err(|e| {
                            source.error_at(
                                &[Field("materials"), Entry(name)],
                                format!("material \"{name}\": {e}"),
                            )
                        })?;
                        self.shapes.push((detail.abstraction, Arc::clone(&built)));
                        built
                    }
                },
            ),
        };
        Ok(Material::XToon {
            tone: XToon {
                detail,
                invert,
                shape,
            },
            texture,
            shape: built,
        })
    }
}

/// "unknown KIND "NAME"; did you mean …? / the KINDs are …".
/// Per patch of the model of instance `spec` (the `index`th, of `patches` patches), its
/// material's index: the instance's `material`, or that of the smallest of its
/// `part_materials` holding the patch (`groups` the model's parts, `material_index` the shot's
/// materials by name, `material_names` their names in order).
fn part_materials(
    spec: &InstanceSpec,
    (index, material): (usize, usize),
    (material_index, material_names, groups): (&HashMap<String, usize>, &[&str], &[&PatchGroup]),
    patches: usize,
    source: &Source,
) -> Result<Vec<usize>, ShotError> {
    let mut of_patch = vec![(usize::MAX, material); patches];
    for (part, name) in &spec.part_materials {
        let at = |field: Option<&'static str>, message: String| {
            let mut path = vec![
                Field("instances"),
                Index(index),
                Field("part_materials"),
                Entry(part),
            ];
            path.extend(field.map(Field));
            source.error_at(&path, message)
        };
        let Some(group) = groups.iter().find(|g| g.name == *part) else {
            let names: Vec<&str> = groups.iter().map(|g| g.name.as_str()).collect();
            return Err(at(
                None,
                format!(
                    "instance \"{}\": {}",
                    spec.name,
                    unknown("part", part, &names)
                ),
            ));
        };
        let Some(&m) = material_index.get(name) else {
            return Err(at(None, unknown("material", name, material_names)));
        };
        for &patch in &group.patches {
            if group.patches.len() < of_patch[patch].0 {
                of_patch[patch] = (group.patches.len(), m);
            }
        }
    }
    Ok(of_patch.into_iter().map(|(_, m)| m).collect())
}

fn unknown(kind: &str, name: &str, names: &[&str]) -> String {
    match closest_name(name, names) {
        Some(close) => format!("unknown {kind} \"{name}\"; did you mean \"{close}\"?"),
        None if names.is_empty() => format!("unknown {kind} \"{name}\"; none is defined"),
        None => format!(
            "unknown {kind} \"{name}\"; the {kind}s are {}",
            names
                .iter()
                .map(|n| format!("\"{n}\""))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    }
}

/// The files a shot reads besides its own and its includes: patch files and toon textures,
/// each once.
#[derive(Default)]
struct Inputs {
    paths: Vec<PathBuf>,
    /// The canonical form of each of `paths`.
    seen: HashSet<PathBuf>,
}

impl Inputs {
    fn add(&mut self, path: &Path) {
        if self.seen.insert(canonical(path)) {
            self.paths.push(path.to_path_buf());
        }
    }
}

/// The path with `.` and `..` resolved through the file system where it exists.
fn canonical(path: &Path) -> PathBuf {
    path.canonicalize().unwrap_or_else(|_| path.to_path_buf())
}

/// The camera's eye is given once: by `eye` or by `orbit`, not both and not neither.
fn check_eye(camera: &CameraSpec, source: &Source) -> Result<(), ShotError> {
    match (&camera.eye, &camera.orbit) {
        (Some(_), None) | (None, Some(_)) => Ok(()),
        (Some(_), Some(_)) => Err(source.error_at(
            &[Field("camera"), Field("orbit")],
            "the camera has both an `eye` and an `orbit`; keep one: `eye` places the eye, \
             `orbit` moves it about the target",
        )),
        (None, None) => Err(source.error_at(
            &[Field("camera")],
            "the camera has no eye: add `eye: (x, y, z)` or an orbit about the target, \
             `orbit: Sphere(azimuth: …, elevation: …, distance: …)`",
        )),
    }
}
