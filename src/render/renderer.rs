//! One frame, stage by stage, as the plan decides: tessellate (cached) ▸ rasterize ▸ G-buffer ▸
//! detail ▸ edge widths ▸ trim edges ▸ shade ▸ outline ▸ supersample ▸ AOVs ▸ resolve
//! ([`Stage`]), the first three reused from the previous frame when its surfaces are the same.

use std::ops::{Add, Mul};
use std::sync::Arc;

use glam::{Mat4, Vec2, Vec3, Vec4};
use rayon::prelude::*;
use rayon::ThreadPool;

use super::band_edge::{band_edges, settle_straight_edges, BandEdge};
use super::edge_width::{edge_widths_of, signed_values, EdgeWidths, SignedValues};
use super::gbuffer::{GBuffer, EMPTY, PIXELS_PER_JOB};
use super::highlight_edge::{highlight_edges, HighlightEdge, HighlightEdges};
use super::line_style::{LineKind, LineStyle};
use super::lines::{self, draw_lines, LineImage, LineInput, MeshLines};
use super::neighbourhood::around;
use super::plan::{Plan, Surfaces};
use super::raster::{Cut, RasterOptions, Rasterizer, Viewport, VisibilityBuffer};
use super::scene::{Outlines, Scene, Tone};
use super::settings::{Antialias, FrameMode, Settings};
use super::settled::Settled;
use super::shade::{shade, Edges, ShadeBuffers, Shaded};
use super::stage::Stage;
use super::stats::{timed, RenderStats};
use super::supersample;
use super::surface_key::SurfaceKey;
use super::tessellate::{Mesh, Tessellator};
use super::trim_cut::MeshCut;
use super::trim_edge::{self, trim_edges, TrimEdges};
use super::visibility_shade::shade_visibility;
use super::xtoon_tone::{self, Ahead};
use super::RenderError;
use crate::geom::PatchLibrary;

/// A rendered frame at output resolution.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderedFrame {
    pub width: u32,
    pub height: u32,
    /// Linear RGB with straight alpha (0 on the background), rows from the top.
    pub colour: Vec<Vec4>,
    pub aovs: AovImages,
    pub stats: RenderStats,
}

/// The AOVs a scene asked for (`None` for the others). Under supersampling the matte is the
/// average of a pixel's samples; the others are taken from its central sample.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AovImages {
    pub matte: Option<Vec<f32>>,
    /// Patch index per pixel, `u32::MAX` on the background.
    pub patch_id: Option<Vec<u32>>,
    /// NDC depth per pixel, `f32::INFINITY` on the background.
    pub depth: Option<Vec<f32>>,
    pub normal: Option<Vec<Vec3>>,
    pub uv: Option<Vec<Vec2>>,
    /// `N·H` of the initial half vector, 0 on the background.
    pub n_dot_h: Option<Vec<f32>>,
    /// The lines alone: linear RGB, straight alpha their coverage.
    pub outline: Option<Vec<Vec4>>,
}

impl AovImages {
    /// How many AOV images there are.
    #[must_use]
    pub fn count(&self) -> usize {
        [
            self.matte.is_some(),
            self.patch_id.is_some(),
            self.depth.is_some(),
            self.normal.is_some(),
            self.uv.is_some(),
            self.n_dot_h.is_some(),
            self.outline.is_some(),
        ]
        .iter()
        .filter(|&&on| on)
        .count()
    }
}

/// Renders frames of one model, keeping its tessellation, working memory and worker threads
/// between frames. A frame whose camera, image and accuracy settings are the previous frame's
/// (only materials, highlights, the light or outline settings changed) reuses its mesh,
/// visibility buffer and G-buffer: only the stages those changes touch run
/// ([`Plan::reusing_surfaces`]), and the bytes are those of a fresh renderer's frame.
pub struct Renderer {
    library: Arc<PatchLibrary>,
    stages: Stages,
    pool: Option<(usize, ThreadPool)>,
    /// The most vertices a frame's mesh may have; None: no limit.
    max_vertices: Option<u64>,
}

/// What the stages keep from one frame to the next: the mesh, and every buffer whose size
/// depends only on the image and the mesh, so that a frame allocates just the images it returns.
struct Stages {
    /// What the mesh, visibility buffer and G-buffer now hold, once a frame has filled them.
    kept: Option<KeptSurfaces>,
    tessellator: Tessellator,
    /// The mesh's vertices in clip space.
    clip: Vec<Vec4>,
    rasterizer: Rasterizer,
    visibility: VisibilityBuffer,
    gbuffer: GBuffer,
    shading: ShadeBuffers,
    /// What the lines found on the mesh and keep while it stays.
    mesh_lines: MeshLines,
    /// The last frame's lines and what they were drawn with.
    kept_lines: Option<KeptLines>,
}

/// The lines of a frame, kept for the next: while the surfaces are reused and the outlines
/// and every patch's line style stay the same, they are the next frame's lines too.
struct KeptLines {
    outlines: Outlines,
    styles: Vec<LineStyle>,
    image: LineImage,
}

impl Renderer {
    /// A renderer of `library`'s patches.
    pub fn new(library: impl Into<Arc<PatchLibrary>>) -> Self {
        let library = library.into();
        Self {
            stages: Stages {
                kept: None,
                tessellator: Tessellator::new(Arc::clone(&library)),
                clip: Vec::new(),
                rasterizer: Rasterizer::new(),
                visibility: VisibilityBuffer::default(),
                gbuffer: GBuffer::default(),
                shading: ShadeBuffers::default(),
                mesh_lines: MeshLines::default(),
                kept_lines: None,
            },
            library,
            pool: None,
            max_vertices: None,
        }
    }

    /// Refuses, from now on, a frame whose mesh would have more than `most` vertices
    /// ([`RenderError::MeshTooLarge`]), before making it; None lifts the limit.
    pub fn set_max_mesh_vertices(&mut self, most: Option<u64>) {
        self.max_vertices = most;
    }

    /// How many vertices the mesh for `scene`'s view with `settings` has: what the
    /// tessellation stage would make.
    #[must_use]
    pub fn mesh_vertices(&self, camera: &super::Camera, settings: &Settings) -> u64 {
        let aspect = settings.width as f32 / settings.height as f32;
        self.stages.tessellator.vertices(
            settings.density,
            camera.view_projection(aspect),
            settings.width,
            settings.height,
        )
    }

    /// The model this renderer draws.
    #[must_use]
    pub fn library(&self) -> &Arc<PatchLibrary> {
        &self.library
    }

    /// Renders `scene` with `settings`; the scene must show this renderer's model.
    pub fn render(
        &mut self,
        scene: &Scene,
        settings: &Settings,
    ) -> Result<RenderedFrame, RenderError> {
        settings.validate()?;
        scene.camera.validate()?;
        if !std::ptr::eq(scene.library, &*self.library) {
            return Err(RenderError::OtherModel);
        }
        if scene.looks.len() != self.library.patches.len() {
            return Err(RenderError::LooksPerPatch {
                patches: self.library.patches.len(),
                looks: scene.looks.len(),
            });
        }
        if let Some(most) = self.max_vertices {
            let vertices = self.mesh_vertices(&scene.camera, settings);
            if vertices > most {
                return Err(RenderError::MeshTooLarge { vertices, most });
            }
        }
        let (stages, library) = (&mut self.stages, &*self.library);
        if settings.threads == 0 {
            return Ok(stages.render(library, scene, settings));
        }
        if self
            .pool
            .as_ref()
            .is_none_or(|(n, _)| *n != settings.threads)
        {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(settings.threads)
                .build()
                .map_err(|e| RenderError::Threads {
                    threads: settings.threads,
                    reason: e.to_string(),
                })?;
            self.pool = Some((settings.threads, pool));
        }
        let pool = &self.pool.as_ref().expect("the pool was just made").1;
        Ok(pool.install(|| stages.render(library, scene, settings)))
    }
}

/// The surfaces the stages' buffers hold: their key, and the samples the rasterizer covered.
#[derive(Clone, Copy)]
struct KeptSurfaces {
    key: SurfaceKey,
    covered: u64,
}

/// What a frame is drawn at: its image in samples and the scene's view.
#[derive(Clone, Copy)]
struct Frame {
    /// Samples per pixel side.
    k: u32,
    /// The image in samples.
    samples: Viewport,
    view_projection: Mat4,
}

impl Stages {
    fn render(
        &mut self,
        library: &PatchLibrary,
        scene: &Scene,
        settings: &Settings,
    ) -> RenderedFrame {
        let (mut frame, total) = timed(|| self.stages(library, scene, settings));
        frame.stats.total_seconds = total;
        frame
    }

    /// The stages the plan calls for, in order.
    fn stages(
        &mut self,
        library: &PatchLibrary,
        scene: &Scene,
        settings: &Settings,
    ) -> RenderedFrame {
        let plan = Plan::new(scene, settings);
        let key = SurfaceKey::new(&scene.camera, settings, &plan);
        let reuse = self.kept.is_some_and(|kept| kept.key == key);
        let plan = if reuse { plan.reusing_surfaces() } else { plan };
        let styles: Vec<LineStyle> = scene.outlines.map_or_else(Vec::new, |outlines| {
            scene
                .looks
                .iter()
                .map(|look| look.lines.unwrap_or(outlines.style()))
                .collect()
        });
        let reuse_lines = reuse
            && self
                .kept_lines
                .as_ref()
                .is_some_and(|kept| Some(kept.outlines) == scene.outlines && kept.styles == styles);
        let plan = if reuse_lines {
            plan.reusing_lines()
        } else {
            plan
        };
        let mut stats = RenderStats::new(plan);
        let k = settings.samples_per_side();
        let frame = Frame {
            k,
            samples: Viewport {
                width: settings.width * k,
                height: settings.height * k,
            },
            view_projection: scene
                .camera
                .view_projection(settings.width as f32 / settings.height as f32),
        };
        let Stages {
            kept,
            tessellator,
            clip,
            rasterizer,
            visibility,
            gbuffer,
            shading,
            mesh_lines,
            kept_lines,
        } = self;

        // The generation of the mesh the frame draws: the cached one's, one more if rebuilt.
        let mut generation = tessellator.generation();
        let (mesh, covered) = match kept.filter(|_| reuse) {
            Some(surfaces) => {
                let mesh = tessellator
                    .cached_mesh()
                    .expect("kept surfaces were made from the cached mesh");
                stats.triangles = mesh.triangles.len();
                (mesh, surfaces.covered)
            }
            None => {
                // Until the buffers are filled again they hold no frame's surfaces.
                *kept = None;
                let mesh = tessellate(tessellator, settings, &frame, &mut stats);
                generation += u64::from(stats.tessellation_rebuilt);
                let covered = rasterize(
                    rasterizer, mesh, library, &frame, clip, visibility, &mut stats,
                );
                if plan.runs(Stage::GBuffer) {
                    fill_gbuffer(
                        gbuffer,
                        visibility,
                        mesh,
                        library,
                        scene,
                        plan.frames,
                        frame.view_projection,
                        &mut stats,
                    );
                }
                *kept = Some(KeptSurfaces { key, covered });
                (mesh, covered)
            }
        };
        let (mut shaded, edges) = match plan.surfaces {
            Surfaces::Visibility => (
                shade_from_visibility(visibility, mesh, scene, covered, &mut stats),
                Edged::default(),
            ),
            Surfaces::Texels => {
                let views = xtoon_tone::views(scene);
                let ahead = plan
                    .runs(Stage::Detail)
                    .then(|| detail(gbuffer, scene, &views, &mut stats));
                // Highlights see the abstracted frames of the X-Toon patches that ask for them.
                let highlight_gbuffer = ahead.as_ref().map_or(&*gbuffer, |a| &a.gbuffer);
                let edges = if plan.runs(Stage::EdgeWidths) {
                    let settle = (plan.frames != settings.frames)
                        .then_some((frame.view_projection, settings.frames));
                    let adaptive = matches!(settings.antialias, Antialias::Adaptive(_));
                    let view_projection = frame.view_projection;
                    let input = (highlight_gbuffer, scene, view_projection);
                    let draw_trims = plan.runs(Stage::TrimEdges);
                    widths(input, adaptive, draw_trims, settle, &mut stats)
                } else {
                    Edged::default()
                };
                let tones = ahead.as_ref().map(|a| a.tones.as_slice());
                let (shaded, seconds) = timed(|| {
                    let mut shaded = shade(
                        highlight_gbuffer,
                        scene,
                        &views,
                        tones,
                        edges.shading(settings.antialias),
                        shading,
                    );
                    if let Some(trims) = &edges.trims {
                        let hard = Edges {
                            widths: None,
                            bands: None,
                            highlights: None,
                            settled: None,
                            signed: None,
                        };
                        let mut buffers = ShadeBuffers::default();
                        let two = |g: &GBuffer| shade(g, scene, &views, None, hard, &mut buffers);
                        trim_edge::composite(trims, two, &mut shaded);
                    }
                    shaded
                });
                stats.record(Stage::Shade, shaded.shaded, seconds);
                stats.highlight_pixels = shaded.highlighted;
                stats.xtoon_pixels = shaded.xtoon;
                (shaded, edges)
            }
        };
        match (plan.runs(Stage::Outline), &scene.outlines) {
            (true, Some(outlines)) => {
                let (intersections, seconds) = timed(|| {
                    if lines::draws(&styles, LineKind::Intersection) {
                        mesh_lines.intersections(mesh, library, generation)
                    } else {
                        &[]
                    }
                });
                let input = LineInput {
                    library,
                    mesh,
                    intersections,
                    camera: &scene.camera,
                    view_projection: frame.view_projection,
                    visibility,
                    k,
                    size: (settings.width, settings.height),
                    styles: &styles,
                };
                let recycled = kept_lines.take().map(|kept| kept.image);
                let image = outline(&input, outlines, recycled, &mut stats);
                stats.add_seconds(Stage::Outline, seconds);
                *kept_lines = Some(KeptLines {
                    outlines: *outlines,
                    styles,
                    image,
                });
            }
            (false, Some(_)) if plan.reuses(Stage::Outline) => {}
            (_, _) => *kept_lines = None,
        }
        let lines = kept_lines.as_ref().map(|kept| &kept.image);
        if let (true, Antialias::Adaptive(k)) = (plan.runs(Stage::Supersample), settings.antialias)
        {
            let widths = edges.widths.as_ref();
            let straddles = widths.map(|w| gbuffer.gather(&w.straddles, false));
            let input = supersample::Frame {
                library,
                scene,
                mesh,
                clip,
                view_projection: frame.view_projection,
                frames: settings.frames,
                k,
                image: frame.samples,
                detail: plan.uses(Stage::Detail),
                widths: widths.is_some(),
                straddles: straddles.as_deref(),
                gbuffer,
                footprints: widths.map(|w| w.footprints.as_slice()),
                drawn: edges.drawn.as_deref(),
                drawn_pixels: edges.trims.as_ref().map(|t| t.drawn.as_slice()),
                lines,
            };
            let (done, seconds) = timed(|| supersample::supersample(&input, &mut shaded));
            stats.record(Stage::Supersample, done.pixels, seconds);
            stats.exact_frames += done.frames;
        }
        let aovs = if plan.runs(Stage::Aov) {
            aov(scene, gbuffer, lines, &mut shaded, settings, &mut stats)
        } else {
            AovImages::default()
        };
        let mut colour = if plan.runs(Stage::Resolve) {
            resolve_stage(&shaded.colour, settings, &frame, &mut stats)
        } else {
            shaded.colour
        };
        if let Some(lines) = lines {
            let (_, seconds) = timed(|| lines.composite(&mut colour));
            stats.add_seconds(Stage::Outline, seconds);
        }
        RenderedFrame {
            width: settings.width,
            height: settings.height,
            colour,
            aovs,
            stats,
        }
    }
}

/// [`Stage::Tessellate`]: the mesh for this view, rebuilt only when its segment counts change.
fn tessellate<'t>(
    tessellator: &'t mut Tessellator,
    settings: &Settings,
    frame: &Frame,
    stats: &mut RenderStats,
) -> &'t Mesh {
    let ((mesh, rebuilt), seconds) = timed(|| {
        tessellator.mesh(
            settings.density,
            frame.view_projection,
            settings.width,
            settings.height,
        )
    });
    stats.tessellation_rebuilt = rebuilt;
    stats.triangles = mesh.triangles.len();
    stats.record(Stage::Tessellate, mesh.triangles.len() as u64, seconds);
    mesh
}

/// [`Stage::Rasterize`]: the mesh's vertices to clip space, then its triangles into the
/// visibility buffer at the sample resolution, less what the patches' trims cut away. Returns
/// the samples covered.
fn rasterize(
    rasterizer: &mut Rasterizer,
    mesh: &Mesh,
    library: &PatchLibrary,
    frame: &Frame,
    clip: &mut Vec<Vec4>,
    visibility: &mut VisibilityBuffer,
    stats: &mut RenderStats,
) -> u64 {
    let (raster, seconds) = timed(|| {
        mesh.positions
            .par_iter()
            .with_min_len(PIXELS_PER_JOB)
            .map(|p| frame.view_projection * p.extend(1.0))
            .collect_into_vec(clip);
        let options = RasterOptions {
            threads: 0,
            ..RasterOptions::default()
        };
        let cut = MeshCut::of(mesh, library);
        rasterizer.rasterize_cut_into(
            frame.samples,
            clip,
            &mesh.triangles,
            cut.as_ref().map(|c| c as &dyn Cut),
            &options,
            visibility,
        )
    });
    stats.record(Stage::Rasterize, raster.pixels_covered, seconds);
    raster.pixels_covered
}

/// [`Stage::Shade`] straight from the visibility buffer (the plan's
/// [`Surfaces::Visibility`]), which covers `covered` samples.
fn shade_from_visibility(
    visibility: &VisibilityBuffer,
    mesh: &Mesh,
    scene: &Scene,
    covered: u64,
    stats: &mut RenderStats,
) -> Shaded {
    let (colour, seconds) = timed(|| shade_visibility(visibility, mesh, scene));
    stats.record(Stage::Shade, covered, seconds);
    Shaded {
        colour,
        matte: None,
        n_dot_h: None,
        shaded: covered,
        highlighted: 0,
        xtoon: 0,
    }
}

/// [`Stage::GBuffer`]: the texels of the covered samples, their frames as `frames` (the
/// plan's, [`Plan::first_frames`]) gives them.
#[allow(clippy::too_many_arguments)]
fn fill_gbuffer(
    gbuffer: &mut GBuffer,
    visibility: &VisibilityBuffer,
    mesh: &Mesh,
    library: &PatchLibrary,
    scene: &Scene,
    frames: FrameMode,
    view_projection: Mat4,
    stats: &mut RenderStats,
) {
    let (exact, seconds) = timed(|| {
        gbuffer.fill(
            visibility,
            mesh,
            library,
            &scene.camera,
            view_projection,
            frames,
            None,
        )
    });
    stats.exact_frames = exact;
    stats.record(Stage::GBuffer, gbuffer.texels.len() as u64, seconds);
}

/// [`Stage::Detail`]: the X-Toon tones and abstracted frames ahead of shading.
fn detail(
    gbuffer: &GBuffer,
    scene: &Scene,
    views: &xtoon_tone::Views,
    stats: &mut RenderStats,
) -> Ahead {
    let (ahead, seconds) = timed(|| xtoon_tone::run_ahead(gbuffer, scene, views));
    stats.record(Stage::Detail, ahead.toned, seconds);
    ahead
}

/// What [`Stage::EdgeWidths`] finds per texel.
#[derive(Default)]
struct Edged<'s> {
    /// Each highlight layer's signed value, on a frame with highlights: the shade stage's, for
    /// the texels it shades with hard edges.
    signed: Option<SignedValues<'s>>,
    /// The highlight's edge widths, on a frame with highlights.
    widths: Option<EdgeWidths>,
    /// How the tone's band edges meet the pixel, on a frame with banded cel ramps.
    bands: Option<Vec<BandEdge>>,
    /// How the highlight's edges meet the pixel, on a frame with highlights under adaptive
    /// anti-aliasing.
    highlights: Option<HighlightEdges>,
    /// Whether the pixel's colour is right as drawn at one sample, under adaptive
    /// anti-aliasing ([`drawn`]).
    drawn: Option<Vec<bool>>,
    /// Where the G-buffer's frames are interpolated, the texels the one-sample pass draws its
    /// edges from, with the settings' frames: the centres of the pixels a band edge crosses
    /// straight, and the neighbourhoods of those a highlight edge crosses smoothly.
    settled: Settled,
    /// The pixels about the rims of trims drawn right at one sample, under adaptive
    /// anti-aliasing on a frame with trimmed patches ([`trim_edges`]).
    trims: Option<TrimEdges>,
}

impl Edged<'_> {
    /// What the one-sample shading takes of them under `antialias`: under analytic
    /// anti-aliasing the highlight footprints of every pixel; under adaptive anti-aliasing the
    /// highlight edges that cross a pixel smoothly alone, since a pixel any other highlight
    /// edge crosses is drawn again at k × k samples, each with its own footprint (hard edges
    /// there mark only the pixels the edges cross, where analytic ones also mark their
    /// neighbours, which a partly covered pixel beside them differs from).
    fn shading(&self, antialias: Antialias) -> Edges<'_> {
        let adaptive = match antialias {
            Antialias::Adaptive(_) => true,
            Antialias::None | Antialias::Analytic | Antialias::Supersample(_) => false,
        };
        Edges {
            widths: self
                .widths
                .as_ref()
                .filter(|_| !adaptive)
                .map(|w| w.footprints.as_slice()),
            bands: self.bands.as_deref(),
            highlights: self.highlights.as_ref(),
            settled: Some(&self.settled),
            signed: self.signed.as_ref(),
        }
    }
}

/// [`Stage::EdgeWidths`]: per texel, the highlight's edge width over the pixel's footprint
/// and how the tone's band edges meet the pixel; under `adaptive` anti-aliasing also how the
/// highlight's edges meet it and whether it is [`drawn`] right at one sample, and with
/// `draw_trims`, [`Stage::TrimEdges`]: which pixels about the rims of trimmed patches are
/// drawn right ([`trim_edges`], seen through `view_projection`), timed apart. With `settle`,
/// the view-projection and the settings' frames where the G-buffer's are interpolated, the
/// texels the straight band edges and smooth highlight edges are drawn from are evaluated
/// again in those frames ([`Settled`]).
fn widths<'s>(
    (gbuffer, scene, view_projection): (&GBuffer, &'s Scene, Mat4),
    adaptive: bool,
    draw_trims: bool,
    settle: Option<(Mat4, FrameMode)>,
    stats: &mut RenderStats,
) -> Edged<'s> {
    let mut frames = 0;
    let mut trim_seconds = 0.0;
    let mut judged = 0;
    let (edged, seconds) = timed(|| {
        // The texels' patches side by side: the neighbours are looked up by patch, and the
        // texels themselves are large.
        let patches: Vec<u32> = gbuffer.texels.iter().map(|t| t.patch).collect();
        let signed = scene
            .has_highlights()
            .then(|| signed_values(gbuffer, scene));
        let mut highlights = signed
            .as_ref()
            .filter(|_| adaptive)
            .map(|s| highlight_edges(gbuffer, s, &patches));
        let mut bands = scene
            .has_band_edges()
            .then(|| band_edges(gbuffer, scene, &patches));
        let settled = match settle {
            Some((view_projection, mode)) => {
                // The centres of the pixels a band edge crosses straight, and the
                // neighbourhoods of those a highlight edge crosses smoothly.
                let mut picked = vec![false; gbuffer.texels.len()];
                for (pick, band) in picked.iter_mut().zip(bands.iter().flatten()) {
                    *pick = matches!(band, BandEdge::Straight { .. });
                }
                for slot in highlights.iter().flat_map(|h| h.neighbourhoods(gbuffer)) {
                    picked[slot] = true;
                }
                let (settled, evaluated) =
                    Settled::evaluate(gbuffer, scene, view_projection, mode, &picked);
                frames = evaluated;
                if let Some(bands) = &mut bands {
                    settle_straight_edges(bands, &settled, scene);
                }
                if let (Some(highlights), Some(signed)) = (&mut highlights, &signed) {
                    highlights.settle(gbuffer, scene, signed, &settled);
                }
                settled
            }
            None => Settled::default(),
        };
        let mut drawn = adaptive.then(|| {
            let kinds = highlights.as_ref().map(|h| h.kinds.as_slice());
            drawn(gbuffer, scene, bands.as_deref(), kinds)
        });
        let trims = drawn.as_mut().filter(|_| draw_trims).and_then(|drawn| {
            let (trims, seconds) = timed(|| trim_edges(gbuffer, scene, view_projection, drawn));
            trim_seconds = seconds;
            let trims = trims?;
            judged = trims.judged;
            for (&slot, _) in gbuffer.slot.iter().zip(&trims.drawn).filter(|(_, &d)| d) {
                if slot != EMPTY {
                    drawn[slot as usize] = true;
                }
            }
            frames += trims.frames;
            Some(trims)
        });
        // Under adaptive anti-aliasing the widths serve the samples of the pixels that are
        // not drawn (started from the texels around them) and mark those a highlight may
        // cross unseen: they are wanted only beside such pixels.
        let wanted = drawn.as_ref().map(|drawn| beside_undrawn(gbuffer, drawn));
        let widths = signed
            .as_ref()
            .map(|s| edge_widths_of(gbuffer, s, &patches, wanted.as_deref()));
        Edged {
            signed,
            widths,
            bands,
            highlights,
            drawn,
            settled,
            trims,
        }
    });
    stats.record(
        Stage::EdgeWidths,
        gbuffer.texels.len() as u64,
        seconds - trim_seconds,
    );
    if draw_trims {
        stats.record(Stage::TrimEdges, judged, trim_seconds);
    }
    stats.exact_frames += frames;
    edged
}

/// Per texel of `gbuffer`, whether some texel of its 3 × 3 neighbourhood is not `drawn` (per
/// texel): the neighbourhoods of the few texels that are not, marked from each. A texel beside
/// an uncovered pixel is never drawn right, so it marks itself.
#[must_use]
fn beside_undrawn(gbuffer: &GBuffer, drawn: &[bool]) -> Vec<bool> {
    let size = (gbuffer.width as usize, gbuffer.height as usize);
    let mut beside = vec![false; drawn.len()];
    for (t, _) in gbuffer.texels.iter().zip(drawn).filter(|(_, &d)| !d) {
        for n in around(t.pixel as usize, size) {
            let slot = gbuffer.slot[n];
            if slot != EMPTY {
                beside[slot as usize] = true;
            }
        }
    }
    beside
}

/// Per texel of `gbuffer`, whether its pixel's colour is right as drawn at one sample: its box
/// lies inside one patch, its tone is a cel ramp whose band edges are clear of the box or
/// cross it straight (any cel ramp without `bands`), its highlight's edges are clear of the box
/// or cross it smoothly (any highlight without `highlights`), and not both a band edge and a
/// highlight edge cross it. More samples would not change such a pixel; at least one of `bands`
/// and `highlights` is given, each of which sees whether the box lies inside one patch.
#[must_use]
fn drawn(
    gbuffer: &GBuffer,
    scene: &Scene,
    bands: Option<&[BandEdge]>,
    highlights: Option<&[HighlightEdge]>,
) -> Vec<bool> {
    gbuffer
        .texels
        .par_iter()
        .enumerate()
        .with_min_len(PIXELS_PER_JOB)
        .map(|(k, t)| {
            let band = match bands {
                Some(bands) => bands[k],
                None => match scene.looks[t.patch as usize].tone {
                    Tone::Cel(_) => BandEdge::Clear,
                    Tone::XToon(_) => BandEdge::Hard,
                },
            };
            let highlight = highlights.map_or(HighlightEdge::Clear, |h| h[k]);
            let both = matches!(
                (band, highlight),
                (BandEdge::Straight { .. }, HighlightEdge::Smooth)
            );
            band.is_drawn() && highlight.is_drawn() && !both
        })
        .collect()
}

/// [`Stage::Outline`]: the lines, found on the mesh and tested against the frame's depth, as
/// coverage at output resolution (composited over the colour once it is resolved).
fn outline(
    input: &LineInput,
    outlines: &Outlines,
    recycled: Option<LineImage>,
    stats: &mut RenderStats,
) -> LineImage {
    let (lines, seconds) = timed(|| draw_lines(input, outlines, recycled));
    stats.record(Stage::Outline, lines.inked, seconds);
    lines
}

/// [`Stage::Aov`]: the AOVs the scene asked for, at output resolution.
fn aov(
    scene: &Scene,
    gbuffer: &GBuffer,
    lines: Option<&LineImage>,
    shaded: &mut Shaded,
    settings: &Settings,
    stats: &mut RenderStats,
) -> AovImages {
    let (images, seconds) = timed(|| collect_aovs(scene, gbuffer, lines, shaded, settings));
    let pixels = u64::from(settings.width) * u64::from(settings.height);
    stats.record(Stage::Aov, images.count() as u64 * pixels, seconds);
    images
}

/// [`Stage::Resolve`]: the samples averaged into pixels.
fn resolve_stage(
    samples: &[Vec4],
    settings: &Settings,
    frame: &Frame,
    stats: &mut RenderStats,
) -> Vec<Vec4> {
    let (colour, seconds) = timed(|| resolve(samples, settings.width, settings.height, frame.k));
    let pixels = u64::from(settings.width) * u64::from(settings.height);
    stats.record(Stage::Resolve, pixels, seconds);
    colour
}

/// Straight alpha to premultiplied: `(α rgb, α)`.
#[inline]
#[must_use]
pub(super) fn premultiplied(c: Vec4) -> Vec4 {
    (c.truncate() * c.w).extend(c.w)
}

/// Premultiplied alpha back to straight: `(rgb / α, α)`, and zero where `α = 0`.
#[inline]
#[must_use]
pub(super) fn straight(p: Vec4) -> Vec4 {
    if p.w > 0.0 {
        (p.truncate() / p.w).extend(p.w)
    } else {
        Vec4::ZERO
    }
}

/// Resolves `k × k` samples per pixel by averaging premultiplied colour:
/// `α = mean(α_s)`, `rgb = mean(α_s rgb_s) / α`.
fn resolve(samples: &[Vec4], width: u32, height: u32, k: u32) -> Vec<Vec4> {
    let premultiplied: Vec<Vec4> = samples.iter().copied().map(premultiplied).collect();
    box_filter(&premultiplied, width, height, k)
        .into_iter()
        .map(straight)
        .collect()
}

/// The mean of each pixel's `k × k` samples, for an output of `width × height` pixels.
fn box_filter<T>(samples: &[T], width: u32, height: u32, k: u32) -> Vec<T>
where
    T: Copy + Default + Add<Output = T> + Mul<f32, Output = T>,
{
    let (width, k) = (width as usize, k as usize);
    let sample_width = width * k;
    let weight = 1.0 / (k * k) as f32;
    (0..width * height as usize)
        .map(|i| {
            let (x, y) = (i % width, i / width);
            let mut sum = T::default();
            for sy in 0..k {
                for sx in 0..k {
                    sum = sum + samples[(y * k + sy) * sample_width + x * k + sx];
                }
            }
            sum * weight
        })
        .collect()
}

/// The AOVs the scene asked for, at output resolution.
fn collect_aovs(
    scene: &Scene,
    gbuffer: &GBuffer,
    lines: Option<&LineImage>,
    shaded: &mut Shaded,
    settings: &Settings,
) -> AovImages {
    let (width, height, k) = (settings.width, settings.height, settings.samples_per_side());
    let centre = |x: u32, y: u32| gbuffer.at(x * k + k / 2, y * k + k / 2);
    let pixels = || (0..height).flat_map(move |y| (0..width).map(move |x| (x, y)));
    let a = scene.aovs;
    AovImages {
        matte: shaded
            .matte
            .take()
            .map(|samples| box_filter(&samples, width, height, k)),
        n_dot_h: shaded
            .n_dot_h
            .take()
            .map(|samples| box_filter(&samples, width, height, k)),
        patch_id: a.patch_id.then(|| {
            pixels()
                .map(|(x, y)| centre(x, y).map_or(u32::MAX, |t| t.patch))
                .collect()
        }),
        depth: a.depth.then(|| {
            pixels()
                .map(|(x, y)| centre(x, y).map_or(f32::INFINITY, |t| t.depth))
                .collect()
        }),
        normal: a.normal.then(|| {
            pixels()
                .map(|(x, y)| centre(x, y).map_or(Vec3::ZERO, |t| t.frame.n))
                .collect()
        }),
        uv: a.uv.then(|| {
            pixels()
                .map(|(x, y)| centre(x, y).map_or(Vec2::ZERO, |t| t.uv))
                .collect()
        }),
        outline: a.outline.then(|| {
            lines.map_or_else(
                || vec![Vec4::ZERO; width as usize * height as usize],
                LineImage::alone,
            )
        }),
    }
}
