//! Reading a shot: parse, follow includes, load and place patch files, match selectors, and
//! check every track at every frame it can take — all before any frame is rendered.

use std::collections::{BTreeSet, HashMap};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use glam::DVec3;
use serde::de::DeserializeOwned;

use super::file::{HighlightSpec, LightSpec, LooksFile, MaterialSpec, ProjectionSpec, ShotFile};
use super::glob;
use super::output::{check_numbered, resolve_path};
use super::validated::{placement, Accuracy, Instance, Material, MaterialState, Shot};
use super::{FrameState, ShotError, MAX_FRAMES};
use crate::formats::ron_location::{closest_name, explain, position_of, start_of_value_closed_at};
use crate::formats::{load_patches, read_toon_texture};
use crate::geom::{NamedPatch, PatchLibrary};
use crate::toon::{AbstractShape, Abstraction, ToonTexture, XToon};

/// The most files an include chain may nest.
const MAX_INCLUDE_DEPTH: usize = 16;

/// A file read for the shot: its path, its name as shown in messages, its folder and its text.
struct Source {
    path: PathBuf,
    shown: String,
    folder: PathBuf,
    text: String,
}

impl Source {
    fn read(path: &Path) -> Result<Self, ShotError> {
        let shown = path.display().to_string();
        let text = std::fs::read_to_string(path).map_err(|e| ShotError::File {
            path: shown.clone(),
            message: format!("cannot read the file: {e}"),
        })?;
        Ok(Self {
            path: path.to_path_buf(),
            shown,
            folder: path.parent().map(Path::to_path_buf).unwrap_or_default(),
            text,
        })
    }

    /// An error at byte `offset` of this file.
    fn error_at(&self, offset: usize, message: impl Into<String>) -> ShotError {
        let (line, col) = position_of(&self.text, offset);
        ShotError::At {
            path: self.shown.clone(),
            line,
            col,
            message: message.into(),
        }
    }

    /// An error at where `field: "value"` is written (or, failing that, `"value"` or `field`).
    fn error_at_string(&self, field: &str, value: &str, message: impl Into<String>) -> ShotError {
        self.error_at(self.find_string(field, value, 0), message)
    }

    /// An error at the second place `field: "value"` is written (a name defined twice).
    fn error_at_repeat(&self, field: &str, value: &str, message: impl Into<String>) -> ShotError {
        self.error_at(self.find_string(field, value, 1), message)
    }

    /// An error at where `field:` is first written.
    fn error_at_field(&self, field: &str, message: impl Into<String>) -> ShotError {
        self.error_at(self.find_field(field), message)
    }

    /// The offset of the first `field` followed by `:`, else 0.
    fn find_field(&self, field: &str) -> usize {
        self.text
            .match_indices(field)
            .map(|(i, _)| i)
            .find(|&i| self.text[i + field.len()..].trim_start().starts_with(':'))
            .unwrap_or(0)
    }

    /// The offset of the `"value"` written right after `field:` (possibly inside a list),
    /// skipping `skip` such places; else of the first `"value"`, else of the first `field`,
    /// else 0.
    fn find_string(&self, field: &str, value: &str, skip: usize) -> usize {
        let quoted = format!("\"{value}\"");
        let text = &self.text;
        let after_field = |at: usize| {
            let before = text[..at].trim_end_matches(|c: char| c.is_whitespace() || c == '[');
            let before = before.trim_end_matches(|c: char| c != ':' && c != '\n');
            before
                .strip_suffix(':')
                .is_some_and(|b| b.trim_end().ends_with(field))
        };
        text.match_indices(&quoted)
            .map(|(i, _)| i)
            .filter(|&i| after_field(i))
            .nth(skip)
            .or_else(|| text.find(&quoted))
            .unwrap_or_else(|| self.find_field(field))
    }

    /// Parses the text as `T`, with errors placed where they are written.
    fn parse<T: DeserializeOwned>(&self) -> Result<T, ShotError> {
        let options = ron::Options::default()
            .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
        options.from_str(&self.text).map_err(|e| {
            let mut at = (e.span.start.line, e.span.start.col);
            if matches!(
                e.code,
                ron::Error::Message(_) | ron::Error::MissingStructField { .. }
            ) {
                // A value that failed its own checks, or lacks a field, is reported at its
                // closing bracket.
                at = start_of_value_closed_at(&self.text, at).unwrap_or(at);
            }
            ShotError::At {
                path: self.shown.clone(),
                line: at.0,
                col: at.1,
                message: explain(&e.code),
            }
        })
    }
}

/// What the includes and the shot contribute, each item with the file it came from.
#[derive(Default)]
struct Looks {
    materials: Vec<(String, MaterialSpec, usize)>,
    highlights: Vec<(HighlightSpec, usize)>,
}

/// Reads, checks and prepares the shot at `path`.
pub fn load_shot(path: &Path) -> Result<Shot, ShotError> {
    let mut sources = vec![Source::read(path)?];
    let mut inputs = Inputs::default();
    let file: ShotFile = sources[0].parse()?;
    let mut looks = Looks::default();
    let mut chain = vec![canonical(path)];
    for include in &file.includes {
        read_include(&mut sources, 0, include, &mut chain, &mut looks)?;
    }
    add_looks(
        &mut looks,
        &sources,
        0,
        file.materials.into_iter().collect(),
        file.highlights,
    )?;
    let shot_source = &sources[0];

    let (first, last) = file.frames;
    if first > last {
        return Err(shot_source.error_at_field(
            "frames",
            format!("the frame range ({first}, {last}) is backwards; write the first frame first"),
        ));
    }
    if i128::from(last) - i128::from(first) >= i128::from(MAX_FRAMES) {
        return Err(shot_source.error_at_field(
            "frames",
            format!("the frame range ({first}, {last}) is longer than {MAX_FRAMES} frames"),
        ));
    }
    if !(file.fps.is_finite() && file.fps > 0.0) {
        return Err(shot_source.error_at_field(
            "fps",
            format!("fps is {}, but it must be greater than 0", file.fps),
        ));
    }
    let output = resolve_path(&shot_source.folder, Path::new(&file.output));
    let frame_count = usize::try_from(last - first).map_or(usize::MAX, |n| n + 1);
    check_numbered(&output, frame_count)
        .map_err(|message| shot_source.error_at_string("output", &file.output, message))?;

    // Instances and the model.
    let mut models: HashMap<PathBuf, PatchLibrary> = HashMap::new();
    let mut library = PatchLibrary {
        patches: Vec::new(),
    };
    let mut instances: Vec<Instance> = Vec::new();
    let mut patch_material = Vec::new();
    for spec in &file.instances {
        let name_error = |message: String| shot_source.error_at_string("name", &spec.name, message);
        if spec.name.is_empty() || spec.name.contains('/') {
            return Err(name_error(format!(
                "the instance name \"{}\" must be non-empty and without `/` (patches are named INSTANCE/PATCH)",
                spec.name
            )));
        }
        if instances.iter().any(|i| i.name == spec.name) {
            return Err(shot_source.error_at_repeat(
                "name",
                &spec.name,
                format!(
                    "the instance name \"{}\" is used twice; instance names must be unique",
                    spec.name
                ),
            ));
        }
        let material = looks
            .materials
            .iter()
            .position(|(name, _, _)| *name == spec.material)
            .ok_or_else(|| {
                let names: Vec<&str> = looks.materials.iter().map(|m| m.0.as_str()).collect();
                shot_source.error_at_string(
                    "material",
                    &spec.material,
                    unknown("material", &spec.material, &names),
                )
            })?;
        let t = &spec.transform;
        let axis = DVec3::from(t.axis);
        let translate = DVec3::from(t.translate);
        let placeable = t.scale.is_finite()
            && t.scale > 0.0
            && translate.is_finite()
            && t.degrees.is_finite()
            && axis.is_finite()
            && axis.length_squared() > 0.0;
        if !placeable {
            return Err(name_error(format!(
                "the transform of instance \"{}\" needs a finite translation and angle, a non-zero axis and a scale greater than 0",
                spec.name
            )));
        }
        let model_path = shot_source.folder.join(&spec.file);
        let key = canonical(&model_path);
        if !models.contains_key(&key) {
            let model = load_patches(&model_path).map_err(|e| {
                let message = match &e {
                    crate::formats::FormatError::Io { source, .. } => format!(
                        "cannot read the patch file {}: {source}",
                        model_path.display()
                    ),
                    other => format!("in the patch file: {other}"),
                };
                shot_source.error_at_string("file", &spec.file, message)
            })?;
            inputs.add(&model_path);
            models.insert(key.clone(), model);
        }
        let place = placement(translate, axis, t.degrees, t.scale);
        let start = library.patches.len();
        for patch in &models[&key].patches {
            library.patches.push(NamedPatch {
                name: format!("{}/{}", spec.name, patch.name),
                surface: patch.surface.map_points(&place),
            });
            patch_material.push(material);
        }
        instances.push(Instance {
            name: spec.name.clone(),
            patches: start..library.patches.len(),
        });
    }

    // Selectors: every pattern picks at least one patch; later entries win.
    let mut patch_highlight = vec![None; library.patches.len()];
    for (index, (spec, origin)) in looks.highlights.iter().enumerate() {
        for pattern in spec.patches.patterns() {
            let mut any = false;
            for (patch, slot) in library.patches.iter().zip(&mut patch_highlight) {
                if glob::matches(pattern, &patch.name) {
                    *slot = Some(index);
                    any = true;
                }
            }
            if !any {
                let names: Vec<&str> = library.patches.iter().map(|p| p.name.as_str()).collect();
                let mut message = format!("the selector \"{pattern}\" matches no patch");
                match closest_name(pattern, &names) {
                    Some(close) => message.push_str(&format!("; did you mean \"{close}\"?")),
                    None => message.push_str(&format!(
                        "; patches are named INSTANCE/PATCH, e.g. \"{}\"",
                        names.first().copied().unwrap_or("ball/0")
                    )),
                }
                return Err(sources[*origin].error_at_string("patches", pattern, message));
            }
        }
    }

    let render = &file.render;
    let accuracy = Accuracy {
        preset: render.preset,
        tessellation: render.tessellation,
        frames: render.frames,
        antialias: render.antialias,
    };
    let settings = accuracy.settings(None, file.resolution);
    settings
        .validate()
        .map_err(|e| shot_source.error_at_field("resolution", e.to_string()))?;
    let outlines = render.outlines.as_ref().map(Into::into);
    if let Some(o) = &render.outlines {
        if !((1.0..=64.0).contains(&o.width) && o.crease_degrees.is_finite()) {
            return Err(shot_source.error_at_field(
                "outlines",
                format!(
                    "outline width {} must be between 1 and 64 pixels, and crease_degrees finite",
                    o.width
                ),
            ));
        }
    }

    let mut assets = Assets::default();
    let mut materials = Vec::with_capacity(looks.materials.len());
    let mut material_origins = Vec::with_capacity(looks.materials.len());
    for (name, spec, origin) in looks.materials {
        let material = assets.material(spec, &name, &sources[origin], &library, &mut inputs)?;
        materials.push((name, material));
        material_origins.push(origin);
    }
    let (highlights, highlight_origins): (Vec<_>, Vec<_>) = looks.highlights.into_iter().unzip();
    let mut files = sources.iter().map(|s| s.path.clone()).collect::<Vec<_>>();
    files.extend(inputs.0);
    let shot = Shot {
        path: path.to_path_buf(),
        inputs: files,
        frames: file.frames,
        fps: file.fps,
        output,
        library: Arc::new(library),
        instances,
        settings,
        accuracy,
        outlines,
        aovs: render.aovs.clone(),
        camera: file.camera,
        light: file.light,
        materials,
        highlights,
        patch_material,
        patch_highlight,
    };
    check_every_frame(&shot, &sources, &material_origins, &highlight_origins)?;
    Ok(shot)
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
                    source.error_at_string(
                        "texture",
                        &texture_name,
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
                            source.error_at_string(
                                "materials",
                                name,
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

/// Reads the include `name` written in `sources[from]`, and its includes, depth first.
fn read_include(
    sources: &mut Vec<Source>,
    from: usize,
    name: &str,
    chain: &mut Vec<PathBuf>,
    looks: &mut Looks,
) -> Result<(), ShotError> {
    let path = sources[from].folder.join(name);
    let key = canonical(&path);
    let at = |sources: &[Source], message: String| {
        sources[from].error_at_string("includes", name, message)
    };
    if chain.contains(&key) {
        return Err(at(
            sources,
            format!("including \"{name}\" here makes a cycle: it includes, directly or through others, the file that includes it"),
        ));
    }
    if chain.len() > MAX_INCLUDE_DEPTH {
        return Err(at(
            sources,
            format!("includes nest more than {MAX_INCLUDE_DEPTH} deep"),
        ));
    }
    let source = match Source::read(&path) {
        Ok(source) => source,
        Err(_) if !path.exists() => {
            return Err(at(
                sources,
                format!("the included file {} does not exist", path.display()),
            ))
        }
        Err(e) => return Err(e),
    };
    let file: LooksFile = source.parse()?;
    sources.push(source);
    let index = sources.len() - 1;
    chain.push(key);
    for include in &file.includes {
        read_include(sources, index, include, chain, looks)?;
    }
    chain.pop();
    add_looks(
        looks,
        sources,
        index,
        file.materials.into_iter().collect(),
        file.highlights,
    )
}

/// Adds the materials and highlights of `sources[origin]`; a material name defined twice is an
/// error at its second definition.
fn add_looks(
    looks: &mut Looks,
    sources: &[Source],
    origin: usize,
    materials: Vec<(String, MaterialSpec)>,
    highlights: Vec<HighlightSpec>,
) -> Result<(), ShotError> {
    for (name, spec) in materials {
        if let Some((_, _, first)) = looks.materials.iter().find(|m| m.0 == name) {
            return Err(sources[origin].error_at_string(
                "materials",
                &name,
                format!(
                    "the material \"{name}\" is already defined in {}; material names must be unique",
                    sources[*first].shown
                ),
            ));
        }
        looks.materials.push((name, spec, origin));
    }
    looks
        .highlights
        .extend(highlights.into_iter().map(|h| (h, origin)));
    Ok(())
}

/// Checks the camera, light, materials and highlights at every frame of the range and at every
/// key: between keys every value moves linearly, so the ranges (intervals) hold everywhere.
fn check_every_frame(
    shot: &Shot,
    sources: &[Source],
    material_origins: &[usize],
    highlight_origins: &[usize],
) -> Result<(), ShotError> {
    let mut frames: BTreeSet<u64> = (shot.frames.0..=shot.frames.1)
        .map(|f| (f as f64).to_bits())
        .collect();
    let mut add = |keys: &mut dyn Iterator<Item = f64>| {
        frames.extend(keys.map(f64::to_bits));
    };
    let camera = &shot.camera;
    add(&mut camera.eye.key_frames());
    add(&mut camera.target.key_frames());
    add(&mut camera.up.key_frames());
    match &camera.projection {
        ProjectionSpec::Perspective { fov_y_degrees: t }
        | ProjectionSpec::Orthographic { height: t } => add(&mut t.key_frames()),
    }
    match &shot.light {
        LightSpec::Directional { towards } => add(&mut towards.key_frames()),
        LightSpec::Point { position } => add(&mut position.key_frames()),
    }
    for (_, m) in &shot.materials {
        match m {
            Material::Cel { base, bands } => {
                add(&mut base.key_frames());
                for (threshold, colour) in bands {
                    add(&mut threshold.key_frames());
                    add(&mut colour.key_frames());
                }
            }
            Material::XToon { tone, .. } => {
                let mut keys = Vec::new();
                let _ = tone.map(|t| keys.extend(t.key_frames()));
                add(&mut keys.into_iter());
            }
        }
    }
    for h in &shot.highlights {
        let mut keys = Vec::new();
        let _ = h.expr.map(|t| keys.extend(t.key_frames()));
        add(&mut keys.into_iter());
    }

    let shot_source = &sources[0];
    for frame in frames.into_iter().map(f64::from_bits) {
        let state: FrameState = shot.at(frame);
        state
            .camera
            .validate()
            .map_err(|e| shot_source.error_at_field("camera", format!("at frame {frame}: {e}")))?;
        if let crate::highlight::Light::Point { position } = state.light {
            if !position.is_finite() {
                return Err(shot_source.error_at_field(
                    "light",
                    format!("at frame {frame}: the light position must be finite"),
                ));
            }
        }
        for ((material, name), &origin) in state
            .materials
            .iter()
            .zip(shot.material_names())
            .zip(material_origins)
        {
            let valid = match material {
                MaterialState::Cel(ramp) => ramp.validate().map_err(|e| e.to_string()),
                MaterialState::XToon(tone) => tone.validate().map_err(|e| e.to_string()),
            };
            valid.map_err(|e| {
                sources[origin].error_at_string(
                    "materials",
                    name,
                    format!("material \"{name}\" at frame {frame}: {e}"),
                )
            })?;
        }
        for ((expr, spec), &origin) in state
            .highlights
            .iter()
            .zip(&shot.highlights)
            .zip(highlight_origins)
        {
            expr.validate().map_err(|e| {
                let pattern = &spec.patches.patterns()[0];
                sources[origin].error_at_string(
                    "patches",
                    pattern,
                    format!("the highlight on \"{pattern}\" at frame {frame}: {e}"),
                )
            })?;
        }
    }
    Ok(())
}

/// "unknown KIND "NAME"; did you mean …? / the KINDs are …".
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
struct Inputs(Vec<PathBuf>);

impl Inputs {
    fn add(&mut self, path: &Path) {
        if !self.0.iter().any(|p| canonical(p) == canonical(path)) {
            self.0.push(path.to_path_buf());
        }
    }
}

/// The path with `.` and `..` resolved through the file system where it exists.
fn canonical(path: &Path) -> PathBuf {
    path.canonicalize().unwrap_or_else(|_| path.to_path_buf())
}
