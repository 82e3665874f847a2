//! One frame, stage by stage, as the plan decides: tessellate (cached) ▸ rasterize ▸ G-buffer ▸
//! detail ▸ edge widths ▸ trim edges ▸ shade ▸ outline ▸ supersample ▸ AOVs ▸ resolve
//! ([`Stage`]), the first three reused from the previous frame when its surfaces are the same.

use std::sync::Arc;

use glam::{Mat4, Vec3, Vec4};
use rayon::prelude::*;
use rayon::ThreadPool;

use super::antialias::{self, SupersampleInput};
use super::aov::{collect_aovs, AovImages};
use super::colour::resolve;
use super::edges::one_sample::OneSampleEdges;
use super::edges::trim_edge::{composite, find_trim_edges};
use super::gbuffer::{Earlier, GBuffer, PIXELS_PER_JOB};
use super::line_style::{LineKind, LineStyle};
use super::lines::{
    self, draw_lines, IntersectionsFound, KeptSilhouettes, LineImage, LineInput, MeshLines,
    VectorLines,
};
use super::plan::{Plan, Surfaces};
use super::raster::{
    Cut, LayerCopy, RasterOptions, RasterStats, Rasterizer, Viewport, VisibilityBuffer,
};
use super::scene::{Outlines, PatchLook, Scene};
use super::settings::{Antialias, FrameMode, Settings};
use super::shade::{shade, Edges, ShadeBuffers, Shaded};
use super::stage::Stage;
use super::static_layer::{triangle_ranges, StaticLayer};
use super::stats::{timed, RenderStats};
use super::surface_key::SurfaceKey;
use super::tessellate::{vertex_count, Mesh, Segments, Tessellator};
use super::trim_cut::MeshCut;
use super::visibility_shade::shade_visibility;
use super::xtoon_tone::{self, Views, XToonDetail};
use super::RenderError;
use crate::geom::PatchLibrary;
use crate::highlight::Light;

/// A rendered frame at output resolution.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderedFrame {
    pub width: u32,
    pub height: u32,
    /// Linear RGB with straight alpha (0 on the background), rows from the top.
    pub colour: Vec<Vec4>,
    pub aovs: AovImages,
    /// The frame's lines as strokes, when it draws lines.
    pub lines: Option<std::sync::Arc<VectorLines>>,
    pub stats: RenderStats,
}

/// Renders frames of one model, keeping its tessellation, working memory and worker threads
/// between frames. A frame whose camera, image and accuracy settings are the previous frame's
/// (only materials, highlights, the light or outline settings changed) reuses its mesh,
/// visibility buffer and G-buffer: only the stages those changes touch run
/// ([`Plan::reusing_surfaces`]), and the bytes are those of a fresh renderer's frame. A frame
/// where some patches moved under the same camera and settings rasterizes only the moved
/// patches, over the kept visibility of the others, with the same bytes.
pub struct Renderer {
    library: Arc<PatchLibrary>,
    buffers: StageBuffers,
    pool: Option<(usize, ThreadPool)>,
    /// The most vertices a frame's mesh may have; None: no limit.
    max_vertices: Option<u64>,
}

/// What the stages keep from one frame to the next: the mesh, and every buffer whose size
/// depends only on the image and the mesh, so that a frame allocates just the images it returns.
struct StageBuffers {
    /// What the mesh, visibility buffer and G-buffer now hold, once a frame has filled them.
    kept: Option<KeptSurfaces>,
    tessellator: Tessellator,
    /// The mesh's vertices in clip space.
    clip: Vec<Vec4>,
    rasterizer: Rasterizer,
    visibility: VisibilityBuffer,
    /// What `visibility` holds of the static layer it was last drawn over.
    visibility_copy: LayerCopy,
    /// Per patch, whether it moved or deformed since the last frame rasterized.
    moved: Vec<bool>,
    /// The visibility of the patches that did not move, while it serves.
    static_layer: Option<StaticLayer>,
    /// How many static layers were made.
    layers_made: u64,
    /// The last frame's visibility and G-buffer while this frame's are made: the G-buffer's
    /// texels on the patches of the static layer both frames drew over are kept where the
    /// visibility stayed.
    earlier_visibility: VisibilityBuffer,
    earlier_visibility_copy: LayerCopy,
    earlier_gbuffer: GBuffer,
    /// The key of the frame the G-buffer was last filled for and the static layer its
    /// visibility was drawn over; None when it was drawn over none, or not filled.
    filled_over: Option<(SurfaceKey, u64)>,
    gbuffer: GBuffer,
    shading: ShadeBuffers,
    /// What the lines found on the mesh and keep while it stays.
    mesh_lines: MeshLines,
    /// The last frame's silhouettes, patch by patch, kept for the patches the next sees alike.
    silhouettes: KeptSilhouettes,
    /// The last frame's lines and what they were drawn with.
    kept_lines: Option<KeptLines>,
}

/// The lines of a frame, kept for the next: while the surfaces are reused and the outlines,
/// every patch's line style and what else the lines read ([`LineReads`]) stay the same, they
/// are the next frame's lines too.
struct KeptLines {
    outlines: Outlines,
    styles: Vec<LineStyle>,
    reads: LineReads,
    image: LineImage,
}

/// What a frame's lines read besides the surfaces, the outlines and the styles: the patches'
/// materials (for material borders) and, where light contours are drawn, the light and every
/// patch's look (its tone's thresholds and designed light).
struct LineReads {
    materials: Vec<u32>,
    light: Option<(Light, Vec<PatchLook>)>,
}

impl LineReads {
    /// What the lines of `scene`, drawn in `styles`, read.
    fn of(scene: &Scene, styles: &[LineStyle]) -> Self {
        Self {
            materials: scene.materials.clone(),
            light: lines::draws(styles, LineKind::LightContour)
                .then(|| (scene.light, scene.looks.clone())),
        }
    }

    /// Whether the lines of `scene`, drawn in `styles`, read these.
    fn hold_for(&self, scene: &Scene, styles: &[LineStyle]) -> bool {
        let light = match &self.light {
            Some((light, looks)) => *light == scene.light && *looks == scene.looks,
            None => !lines::draws(styles, LineKind::LightContour),
        };
        light && self.materials == scene.materials
    }
}

impl Renderer {
    /// A renderer of `library`'s patches.
    pub fn new(library: impl Into<Arc<PatchLibrary>>) -> Self {
        let library = library.into();
        Self {
            buffers: StageBuffers {
                kept: None,
                tessellator: Tessellator::new(Arc::clone(&library)),
                clip: Vec::new(),
                rasterizer: Rasterizer::new(),
                visibility: VisibilityBuffer::default(),
                visibility_copy: LayerCopy::default(),
                moved: Vec::new(),
                static_layer: None,
                layers_made: 0,
                earlier_visibility: VisibilityBuffer::default(),
                earlier_visibility_copy: LayerCopy::default(),
                earlier_gbuffer: GBuffer::default(),
                filled_over: None,
                gbuffer: GBuffer::default(),
                shading: ShadeBuffers::default(),
                mesh_lines: MeshLines::default(),
                silhouettes: KeptSilhouettes::default(),
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
        vertex_count(&self.library, &self.segments(camera, settings))
    }

    /// The segments per span of every patch in the mesh for `camera`'s view with `settings`
    /// ([`Tessellator::segments`]).
    fn segments(&self, camera: &super::Camera, settings: &Settings) -> Vec<Segments> {
        let aspect = settings.width as f32 / settings.height as f32;
        self.buffers.tessellator.segments(
            settings.density,
            camera.view_projection(aspect),
            settings.width,
            settings.height,
        )
    }

    /// Draws `pose`, this renderer's model with some patches moved or deformed, from now on:
    /// the tessellation evaluates the grids of the moved patches again and keeps the others',
    /// and the next frame's surfaces are made again. [`RenderError::OtherModel`] when `pose` is
    /// not this model ([`PatchLibrary::try_moved_in`]).
    fn repose(&mut self, pose: &PatchLibrary) -> Result<(), RenderError> {
        let moved = self
            .library
            .try_moved_in(pose)
            .ok_or(RenderError::OtherModel)?;
        if moved.iter().any(|&m| m) {
            let library = Arc::new(pose.clone());
            self.buffers
                .tessellator
                .repose(Arc::clone(&library), &moved);
            self.buffers.kept = None;
            let since = &mut self.buffers.moved;
            since.resize(moved.len(), false);
            for (since, &m) in since.iter_mut().zip(&moved) {
                *since |= m;
            }
            self.library = library;
        }
        Ok(())
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
            self.repose(scene.library)?;
        }
        if scene.looks.len() != self.library.patches.len() {
            return Err(RenderError::LooksPerPatch {
                patches: self.library.patches.len(),
                looks: scene.looks.len(),
            });
        }
        // The segments the guard counts are the ones the tessellation stage meshes.
        let segments = match self.max_vertices {
            Some(most) => {
                let segments = self.segments(&scene.camera, settings);
                let vertices = vertex_count(&self.library, &segments);
                if vertices > most {
                    return Err(RenderError::MeshTooLarge { vertices, most });
                }
                Some(segments)
            }
            None => None,
        };
        let (buffers, library) = (&mut self.buffers, &*self.library);
        if settings.threads == 0 {
            return Ok(buffers.render(library, scene, settings, segments));
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
        Ok(pool.install(|| buffers.render(library, scene, settings, segments)))
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
struct SampleGrid {
    /// Samples per pixel side.
    k: u32,
    /// The image in samples.
    samples: Viewport,
    view_projection: Mat4,
}

impl StageBuffers {
    /// The frame of `scene` with `settings`; with `segments`, the mesh's segments per span as
    /// the memory guard counted them, meshed without counting them again.
    fn render(
        &mut self,
        library: &PatchLibrary,
        scene: &Scene,
        settings: &Settings,
        segments: Option<Vec<Segments>>,
    ) -> RenderedFrame {
        let (mut frame, total) = timed(|| self.stages(library, scene, settings, segments));
        frame.stats.total_seconds = total;
        frame
    }

    /// The stages the plan calls for, in order.
    fn stages(
        &mut self,
        library: &PatchLibrary,
        scene: &Scene,
        settings: &Settings,
        segments: Option<Vec<Segments>>,
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
            && self.kept_lines.as_ref().is_some_and(|kept| {
                Some(kept.outlines) == scene.outlines
                    && kept.styles == styles
                    && kept.reads.hold_for(scene, &styles)
            });
        let plan = if reuse_lines {
            plan.reusing_lines()
        } else {
            plan
        };
        let mut stats = RenderStats::new(plan);
        let k = settings.samples_per_side();
        let grid = SampleGrid {
            k,
            samples: Viewport {
                width: settings.width * k,
                height: settings.height * k,
            },
            view_projection: scene
                .camera
                .view_projection(settings.width as f32 / settings.height as f32),
        };
        let StageBuffers {
            kept,
            tessellator,
            clip,
            rasterizer,
            visibility,
            visibility_copy,
            moved,
            static_layer,
            layers_made,
            earlier_visibility,
            earlier_visibility_copy,
            earlier_gbuffer,
            filled_over,
            gbuffer,
            shading,
            mesh_lines,
            silhouettes,
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
                let mesh = tessellate(tessellator, settings, &grid, segments, &mut stats);
                generation += u64::from(stats.tessellation_rebuilt);
                std::mem::swap(visibility, earlier_visibility);
                std::mem::swap(visibility_copy, earlier_visibility_copy);
                let covered = rasterize(
                    (rasterizer, mesh, library, &grid),
                    (key, moved, static_layer, layers_made),
                    clip,
                    (visibility, visibility_copy),
                    &mut stats,
                );
                let over = static_layer.as_ref().map(|layer| (key, layer.id));
                let kept_from = filled_over.take();
                if plan.runs(Stage::GBuffer) {
                    // The last fill's texels serve where both frames drew over this layer.
                    let layer = static_layer
                        .as_ref()
                        .filter(|_| over.is_some() && kept_from == over);
                    if layer.is_some() {
                        std::mem::swap(gbuffer, earlier_gbuffer);
                    }
                    let earlier = layer.map(|layer| Earlier {
                        visibility: earlier_visibility,
                        gbuffer: earlier_gbuffer,
                        patches: layer.held(),
                    });
                    fill_gbuffer(
                        (gbuffer, earlier),
                        visibility,
                        mesh,
                        library,
                        scene,
                        plan.frames,
                        grid.view_projection,
                        &mut stats,
                    );
                    *filled_over = over;
                }
                *kept = Some(KeptSurfaces { key, covered });
                (mesh, covered)
            }
        };
        let (mut shaded, edges) = match plan.surfaces {
            Surfaces::Visibility => (
                shade_from_visibility(visibility, mesh, scene, covered, &mut stats),
                OneSampleEdges::default(),
            ),
            Surfaces::Texels => {
                let views = xtoon_tone::views(scene);
                let detailed = plan
                    .runs(Stage::Detail)
                    .then(|| detail(gbuffer, scene, &views, &mut stats));
                // Highlights see the abstracted frames of the X-Toon patches that ask for them.
                let highlight_gbuffer = detailed.as_ref().map_or(&*gbuffer, |d| &d.gbuffer);
                let mut edges = OneSampleEdges::default();
                if plan.runs(Stage::EdgeWidths) {
                    let settle = (plan.frames != settings.frames)
                        .then_some((grid.view_projection, settings.frames));
                    edges = edge_widths(highlight_gbuffer, scene, settings, settle, &mut stats);
                    if plan.runs(Stage::TrimEdges) {
                        let input = (highlight_gbuffer, scene, grid.view_projection);
                        trim_edges(input, &mut edges, &mut stats);
                    }
                    edge_widths_beside_undrawn(highlight_gbuffer, &mut edges, &mut stats);
                }
                let tones = detailed.as_ref().map(|d| d.tones.as_slice());
                let input = (highlight_gbuffer, scene, &views, tones);
                let shaded = shade_texels(input, &edges, settings, shading, &mut stats);
                (shaded, edges)
            }
        };
        outline(
            (&plan, scene, styles),
            (library, mesh, generation),
            (visibility, &grid, settings),
            (mesh_lines, silhouettes, kept_lines),
            &mut stats,
        );
        let lines = kept_lines.as_ref().map(|kept| &kept.image);
        if let (true, Antialias::Adaptive(k)) = (plan.runs(Stage::Supersample), settings.antialias)
        {
            let widths = edges.widths.as_ref();
            let straddles = widths.map(|w| gbuffer.gather(&w.straddles, false));
            let input = SupersampleInput {
                library,
                scene,
                mesh,
                clip,
                view_projection: grid.view_projection,
                frames: settings.frames,
                k,
                image: grid.samples,
                detail: plan.uses(Stage::Detail),
                widths: widths.is_some(),
                straddles: straddles.as_deref(),
                gbuffer,
                footprints: widths.map(|w| w.footprints.as_slice()),
                drawn: edges.drawn.as_deref(),
                drawn_pixels: edges.trims.as_ref().map(|t| t.drawn.as_slice()),
                lines,
            };
            supersample(&input, &mut shaded, &mut stats);
        }
        let aovs = if plan.runs(Stage::Aov) {
            aov(scene, gbuffer, lines, &mut shaded, settings, &mut stats)
        } else {
            AovImages::default()
        };
        let mut colour = if plan.runs(Stage::Resolve) {
            resolve_stage(&shaded.colour, settings, &grid, &mut stats)
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
            lines: lines.map(|l| std::sync::Arc::clone(&l.vector)),
            stats,
        }
    }
}

/// [`Stage::Tessellate`]: the mesh for this view, rebuilt only when its segment counts change;
/// of `segments` where they were counted already.
fn tessellate<'t>(
    tessellator: &'t mut Tessellator,
    settings: &Settings,
    grid: &SampleGrid,
    segments: Option<Vec<Segments>>,
    stats: &mut RenderStats,
) -> &'t Mesh {
    let (rebuilt, seconds) = timed(|| match segments {
        Some(segments) => tessellator.mesh_of(segments).1,
        None => {
            tessellator
                .mesh(
                    settings.density,
                    grid.view_projection,
                    settings.width,
                    settings.height,
                )
                .1
        }
    });
    let tessellator: &'t Tessellator = tessellator;
    let mesh = tessellator
        .cached_mesh()
        .expect("the tessellator has just made its mesh");
    stats.tessellation_rebuilt = rebuilt;
    if rebuilt {
        stats.grids_evaluated = tessellator.evaluated();
        stats.grids_kept = mesh.grids.len() - stats.grids_evaluated;
    }
    stats.triangles = mesh.triangles.len();
    stats.record(Stage::Tessellate, mesh.triangles.len() as u64, seconds);
    mesh
}

/// [`Stage::Rasterize`]: the mesh's vertices to clip space, then its triangles into the
/// visibility buffer at the sample resolution, less what the patches' trims cut away. Where
/// `static_layer` shows the patches it holds as they are now (under `key`), only the others
/// are drawn, over it; else, where patches `moved` since the last frame rasterized, the others
/// are drawn into a new layer and the moved ones over it; else the whole mesh is drawn. `copy`
/// is what `visibility` holds of the layer it was last drawn over, and is kept up to date.
/// Returns the samples covered.
fn rasterize(
    (rasterizer, mesh, library, grid): (&mut Rasterizer, &Mesh, &PatchLibrary, &SampleGrid),
    (key, moved, static_layer, layers_made): (
        SurfaceKey,
        &mut Vec<bool>,
        &mut Option<StaticLayer>,
        &mut u64,
    ),
    clip: &mut Vec<Vec4>,
    (visibility, copy): (&mut VisibilityBuffer, &mut LayerCopy),
    stats: &mut RenderStats,
) -> u64 {
    let (raster, seconds) = timed(|| {
        mesh.positions
            .par_iter()
            .with_min_len(PIXELS_PER_JOB)
            .map(|p| grid.view_projection * p.extend(1.0))
            .collect_into_vec(clip);
        let cut = MeshCut::of(mesh, library);
        let cut = cut.as_ref().map(|c| c as &dyn Cut);
        let triangles = &mesh.triangles[..];
        moved.resize(mesh.grids.len(), false);
        if static_layer
            .as_ref()
            .is_none_or(|l| !l.holds(&key, mesh, moved))
        {
            let recycled = static_layer.take().map(|l| l.layer);
            if moved.iter().any(|&m| m) {
                let held: Vec<bool> = moved.iter().map(|&m| !m).collect();
                let ranges = triangle_ranges(mesh, |p| held[p]);
                let mut layer = recycled.unwrap_or_default();
                let inputs = (triangles, &ranges[..]);
                let made =
                    rasterizer.rasterize_layer_into(grid.samples, clip, inputs, cut, &mut layer);
                *layers_made += 1;
                *static_layer = Some(StaticLayer::of(*layers_made, key, mesh, held, layer));
                stats.triangles_rasterized += made.triangles_in;
            }
        }
        moved.fill(false);
        let raster = match static_layer {
            Some(layer) => {
                let ranges = layer.unheld(mesh);
                rasterizer.rasterize_over_keeping(
                    grid.samples,
                    clip,
                    (triangles, &ranges),
                    (cut, &layer.layer),
                    (visibility, copy),
                )
            }
            None => {
                copy.forget();
                let options = RasterOptions {
                    threads: 0,
                    ..RasterOptions::default()
                };
                rasterizer.rasterize_cut_into(
                    grid.samples,
                    clip,
                    triangles,
                    cut,
                    &options,
                    visibility,
                )
            }
        };
        stats.triangles_rasterized += raster.triangles_in;
        raster
    });
    let raster: RasterStats = raster;
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
        n_dot_l: None,
        shaded: covered,
        highlighted: 0,
        xtoon: 0,
    }
}

/// [`Stage::GBuffer`]: the texels of the covered samples, their frames as `frames` (the
/// plan's, [`Plan::first_frames`]) gives them; those of `earlier` kept where it allows.
#[allow(clippy::too_many_arguments)]
fn fill_gbuffer(
    (gbuffer, earlier): (&mut GBuffer, Option<Earlier>),
    visibility: &VisibilityBuffer,
    mesh: &Mesh,
    library: &PatchLibrary,
    scene: &Scene,
    frames: FrameMode,
    view_projection: Mat4,
    stats: &mut RenderStats,
) {
    let ((exact, kept), seconds) = timed(|| {
        gbuffer.fill_keeping(
            (visibility, mesh, library),
            &scene.camera,
            view_projection,
            frames,
            None,
            earlier,
        )
    });
    stats.exact_frames = exact;
    stats.texels_kept = kept;
    stats.record(Stage::GBuffer, gbuffer.texels.len() as u64, seconds);
}

/// [`Stage::Detail`]: the X-Toon tones and abstracted frames ahead of shading.
fn detail(gbuffer: &GBuffer, scene: &Scene, views: &Views, stats: &mut RenderStats) -> XToonDetail {
    let (detailed, seconds) = timed(|| xtoon_tone::detail(gbuffer, scene, views));
    stats.record(Stage::Detail, detailed.toned, seconds);
    detailed
}

/// [`Stage::EdgeWidths`], up to the widths ([`OneSampleEdges::find`]): how the edges of the
/// tone's bands and of the highlights meet each pixel, under adaptive anti-aliasing whether it
/// is drawn right at one sample; with `settle`, the view-projection and the settings' frames
/// where the G-buffer's are interpolated, the texels those edges are drawn from are evaluated
/// again in those frames. The widths follow [`Stage::TrimEdges`]
/// ([`edge_widths_beside_undrawn`]).
fn edge_widths<'s>(
    gbuffer: &GBuffer,
    scene: &'s Scene,
    settings: &Settings,
    settle: Option<(Mat4, FrameMode)>,
    stats: &mut RenderStats,
) -> OneSampleEdges<'s> {
    let adaptive = matches!(settings.antialias, Antialias::Adaptive(_));
    let ((edges, frames), seconds) =
        timed(|| OneSampleEdges::find(gbuffer, scene, adaptive, settle));
    stats.record(Stage::EdgeWidths, gbuffer.texels.len() as u64, seconds);
    stats.exact_frames += frames;
    edges
}

/// [`Stage::TrimEdges`]: which pixels about the rims of trimmed patches are drawn right at one
/// sample ([`find_trim_edges`], seen through `view_projection`), added to those `edges` draws
/// right.
fn trim_edges(
    (gbuffer, scene, view_projection): (&GBuffer, &Scene, Mat4),
    edges: &mut OneSampleEdges,
    stats: &mut RenderStats,
) {
    let (trims, seconds) = timed(|| {
        let drawn = edges.drawn.as_deref()?;
        find_trim_edges(gbuffer, scene, view_projection, drawn)
    });
    let judged = trims.as_ref().map_or(0, |t| t.judged);
    stats.record(Stage::TrimEdges, judged, seconds);
    if let Some(trims) = trims {
        stats.exact_frames += trims.frames;
        edges.add_trims(gbuffer, trims);
    }
}

/// The rest of [`Stage::EdgeWidths`], once [`Stage::TrimEdges`] has drawn what it draws: the
/// highlight's edge widths, under adaptive anti-aliasing beside the pixels not drawn right at
/// one sample alone ([`OneSampleEdges::take_widths`]), timed with the stage.
fn edge_widths_beside_undrawn(
    gbuffer: &GBuffer,
    edges: &mut OneSampleEdges,
    stats: &mut RenderStats,
) {
    let ((), seconds) = timed(|| edges.take_widths(gbuffer));
    stats.add_seconds(Stage::EdgeWidths, seconds);
}

/// [`Stage::Shade`] from the texels: each texel's tone and highlight with the edges as
/// [`OneSampleEdges::shading`] gives them for the settings' anti-aliasing, then the pixels the
/// rims of trims cross, from one sample on each side ([`composite`]).
fn shade_texels(
    (gbuffer, scene, views, tones): (&GBuffer, &Scene, &Views, Option<&[Vec3]>),
    edges: &OneSampleEdges,
    settings: &Settings,
    shading: &mut ShadeBuffers,
    stats: &mut RenderStats,
) -> Shaded {
    let (shaded, seconds) = timed(|| {
        let mut shaded = shade(
            gbuffer,
            scene,
            views,
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
            let two = |g: &GBuffer| shade(g, scene, views, None, hard, &mut buffers);
            composite(trims, two, &mut shaded);
        }
        shaded
    });
    stats.record(Stage::Shade, shaded.shaded, seconds);
    stats.highlight_pixels = shaded.highlighted;
    stats.xtoon_pixels = shaded.xtoon;
    shaded
}

/// [`Stage::Outline`]: the lines, found on the mesh and tested against the frame's depth, as
/// coverage at output resolution (composited over the colour once it is resolved), kept in
/// `kept_lines` with the outlines and `styles` they were drawn with; the previous frame's stay
/// where the plan reuses them, and none are kept where the scene draws none.
fn outline(
    (plan, scene, styles): (&Plan, &Scene, Vec<LineStyle>),
    (library, mesh, generation): (&PatchLibrary, &Mesh, u64),
    (visibility, grid, settings): (&VisibilityBuffer, &SampleGrid, &Settings),
    (mesh_lines, silhouettes, kept_lines): (
        &mut MeshLines,
        &mut KeptSilhouettes,
        &mut Option<KeptLines>,
    ),
    stats: &mut RenderStats,
) {
    match (plan.runs(Stage::Outline), &scene.outlines) {
        (true, Some(outlines)) => {
            let ((intersections, found), seconds) = timed(|| {
                if lines::draws(&styles, LineKind::Intersection) {
                    mesh_lines.intersections(mesh, library, generation)
                } else {
                    (&[][..], IntersectionsFound::Cached)
                }
            });
            if let IntersectionsFound::Again { kept, tested } = found {
                stats.intersection_pairs_kept = kept;
                stats.intersection_pairs_tested = tested;
            }
            let input = LineInput {
                library,
                mesh,
                intersections,
                camera: &scene.camera,
                view_projection: grid.view_projection,
                visibility,
                k: grid.k,
                size: (settings.width, settings.height),
                styles: &styles,
                materials: &scene.materials,
                light: (&scene.light, &scene.looks),
            };
            let recycled = kept_lines.take().map(|kept| kept.image);
            let (image, drawn) =
                timed(|| draw_lines(&input, outlines, (recycled, &mut *silhouettes)));
            stats.silhouettes_kept = silhouettes.kept();
            stats.record(Stage::Outline, image.inked, drawn);
            stats.add_seconds(Stage::Outline, seconds);
            *kept_lines = Some(KeptLines {
                outlines: *outlines,
                reads: LineReads::of(scene, &styles),
                styles,
                image,
            });
        }
        (false, Some(_)) if plan.reuses(Stage::Outline) => {}
        (_, _) => *kept_lines = None,
    }
}

/// [`Stage::Supersample`]: the pixels more samples could change, drawn again at K × K samples
/// ([`antialias::supersample`]).
fn supersample(input: &SupersampleInput, shaded: &mut Shaded, stats: &mut RenderStats) {
    let (done, seconds) = timed(|| antialias::supersample(input, shaded));
    stats.record(Stage::Supersample, done.pixels, seconds);
    stats.exact_frames += done.frames;
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
    grid: &SampleGrid,
    stats: &mut RenderStats,
) -> Vec<Vec4> {
    let (colour, seconds) = timed(|| resolve(samples, settings.width, settings.height, grid.k));
    let pixels = u64::from(settings.width) * u64::from(settings.height);
    stats.record(Stage::Resolve, pixels, seconds);
    colour
}
