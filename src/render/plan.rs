//! The plan of a frame: which stages the scene and settings call for, decided before any stage
//! runs, and which of them the previous frame's results serve. A stage the plan leaves out does
//! not run, and [`RenderStats`](super::RenderStats) shows it.

use super::scene::{Aovs, Scene, Tone};
use super::settings::{Antialias, FrameMode, Settings};
use super::stage::Stage;
use super::tessellate::Density;

/// The screen tolerance, in pixels, of the finest meshes whose interpolated frames find a
/// frame's edges for adaptive anti-aliasing ([`Plan::first_frames`]): `final`'s 0.05 px, with
/// room. At 0.25 px the marking misses pixels that refined frames would mark (the worst view
/// of the accuracy ladder at 256 × 256 falls from 0.9913 to 0.9882).
pub const FINE_MESH_PIXELS: f32 = 0.1;

/// Where the shade stage finds the surface at each pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Surfaces {
    /// The G-buffer: per covered pixel its patch, (u, v), position and shading frame.
    Texels,
    /// The visibility buffer alone: the vertex normal interpolated at the pixel, which is all
    /// the cel tone over `N·L` needs when frames are interpolated. No G-buffer is built.
    Visibility,
}

/// The stages one frame runs: the one place that decides them.
///
/// A stage the frame calls for either runs or, when its result depends only on what the
/// previous frame's did ([`Plan::depends_on_surfaces_only`]) and that is unchanged, is reused:
/// the previous frame's result serves, and the stage does no work.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Plan {
    /// Where the shade stage reads the surface.
    pub surfaces: Surfaces,
    /// The frames the G-buffer of the frame's one sample a pixel holds ([`Plan::first_frames`]).
    pub frames: FrameMode,
    /// Per stage in [`Stage::ALL`] order, whether it runs.
    runs: [bool; Stage::COUNT],
    /// Per stage in [`Stage::ALL`] order, whether the previous frame's result serves instead.
    reused: [bool; Stage::COUNT],
}

impl Plan {
    /// The plan for `scene` under `settings`:
    ///
    /// - tessellation, rasterization and shading always run;
    /// - the G-buffer is built unless the only effect is the cel tone over interpolated frames
    ///   (with or without lines, which are found on the mesh) with hard band edges: highlights
    ///   need the frame's tangents and (u, v), and so does a designed light, AOVs read stored texels, X-Toon reads each
    ///   texel's position and frame, analytic band edges the normals around each texel, and
    ///   exact or refined frames are evaluated per texel;
    /// - the X-Toon detail runs as a stage of its own only when some patch's designed highlight
    ///   is evaluated in its X-Toon tone's abstracted frame (the highlights then need every
    ///   abstracted frame before they start);
    /// - edge widths only under analytic or adaptive anti-aliasing on a frame with highlights or
    ///   band edges; the trim edges with them under adaptive anti-aliasing when some patch with
    ///   a cel tone is trimmed;
    /// - outlines and AOVs when the scene asks for them, the resolve under supersampling, and
    ///   the supersampling of the pixels that need it under adaptive anti-aliasing;
    /// - the G-buffer holds the frames [`Plan::first_frames`] decides.
    #[must_use]
    pub fn new(scene: &Scene, settings: &Settings) -> Self {
        let highlights = scene.has_highlights();
        let bands = scene.has_band_edges();
        let outlines = scene.outlines.is_some();
        let aovs = scene.aovs != Aovs::default();
        // The AOVs read from texels: all but the lines.
        let texel_aovs = Aovs {
            outline: false,
            ..scene.aovs
        } != Aovs::default();
        let xtoon = scene
            .looks
            .iter()
            .any(|look| matches!(look.tone, Tone::XToon(_)));
        let abstracted_highlights = scene.looks.iter().any(|look| {
            look.highlight.is_some()
                && matches!(&look.tone, Tone::XToon(tone) if tone.abstracts_highlights())
        });
        let analytic = match settings.antialias {
            Antialias::Analytic | Antialias::Adaptive(_) => true,
            Antialias::None | Antialias::Supersample(_) => false,
        };
        let analytic_bands = analytic && bands;
        // A designed light reads each texel's frame and (u, v), which the visibility buffer has not.
        let designed = scene.has_designed_light();
        let tone_only = !(highlights || texel_aovs || xtoon || analytic_bands || designed);
        let surfaces = if tone_only && settings.frames == FrameMode::Interpolated {
            Surfaces::Visibility
        } else {
            Surfaces::Texels
        };
        let texels = surfaces == Surfaces::Texels;
        let edge_widths = texels && (highlights || bands) && analytic;
        let adaptive = match settings.antialias {
            Antialias::Adaptive(_) => true,
            Antialias::None | Antialias::Analytic | Antialias::Supersample(_) => false,
        };
        let trimmed_cel = scene
            .library
            .patches
            .iter()
            .zip(&scene.looks)
            .any(|(patch, look)| patch.trim.is_some() && matches!(look.tone, Tone::Cel(_)));
        let runs = Stage::ALL.map(|stage| match stage {
            Stage::Tessellate | Stage::Rasterize | Stage::Shade => true,
            Stage::GBuffer => texels,
            Stage::Detail => texels && abstracted_highlights,
            Stage::EdgeWidths => edge_widths,
            Stage::TrimEdges => edge_widths && adaptive && trimmed_cel,
            Stage::Outline => outlines,
            Stage::Supersample => adaptive,
            Stage::Aov => aovs,
            Stage::Resolve => settings.samples_per_side() > 1,
        });
        Self {
            surfaces,
            frames: Self::first_frames(scene, settings),
            runs,
            reused: [false; Stage::COUNT],
        }
    }

    /// The frames of the one-sample G-buffer: the settings' own, except under adaptive
    /// anti-aliasing with exact or refined frames on a frame whose colour is flat between its
    /// edges — every tone a cel ramp, and no AOV that reads a texel's frame, (u, v) or depth
    /// (the normal, `uv`, `depth` and `N·H` AOVs) — where they are interpolated.
    ///
    /// There the exact or refined frames change a pixel's colour only near an edge (of a
    /// highlight, a tone band, a surface), and the pixels near edges are those the supersample
    /// stage draws again, each of their samples with the settings' frames; the interpolated
    /// frames of a mesh within [`FINE_MESH_PIXELS`] of the surface on screen place every edge
    /// within a small part of a pixel of where the exact ones do, so they mark the same
    /// pixels. A coarser mesh, or one of a fixed density whose error on screen is not known,
    /// keeps the settings' frames. X-Toon tones vary continuously over the surface: every
    /// pixel's colour reads its frame, so they keep the settings' frames too.
    #[must_use]
    pub fn first_frames(scene: &Scene, settings: &Settings) -> FrameMode {
        let adaptive = match settings.antialias {
            Antialias::Adaptive(_) => true,
            Antialias::None | Antialias::Analytic | Antialias::Supersample(_) => false,
        };
        let Aovs {
            matte: _,
            patch_id: _,
            outline: _,
            depth,
            normal,
            uv,
            n_dot_h,
            // What the tone read at each texel, in the frames the tone was shaded with.
            n_dot_l: _,
        } = scene.aovs;
        let frames_read = depth || normal || uv || n_dot_h;
        let cel = scene
            .looks
            .iter()
            .all(|look| matches!(look.tone, Tone::Cel(_)));
        let fine = match settings.density {
            Density::ScreenTolerance { pixels } => pixels <= FINE_MESH_PIXELS,
            Density::PerSpan { .. } => false,
        };
        if adaptive && cel && !frames_read && fine {
            FrameMode::Interpolated
        } else {
            settings.frames
        }
    }

    /// Whether `stage`'s result depends only on the model, the camera, the image and accuracy
    /// settings, and where the shade stage reads surfaces — not on any material, highlight,
    /// light or outline setting — so that a frame that changes none of those can reuse it:
    ///
    /// - the mesh, the visibility buffer and the G-buffer (whose frames face the eye, not the
    ///   light) depend on nothing else;
    /// - the X-Toon detail reads the tone's parameters and the light, the edge widths and the
    ///   trim edges the highlight's layers, and the shade stage both; the lines read the
    ///   outlines and the patches' line styles (a frame that keeps those too reuses them:
    ///   [`Plan::reusing_lines`]); the supersampled pixels are chosen by their shaded colour;
    ///   the matte and `N·H` AOVs come from the shade stage, and the resolve averages its
    ///   colour.
    #[must_use]
    pub const fn depends_on_surfaces_only(stage: Stage) -> bool {
        match stage {
            Stage::Tessellate | Stage::Rasterize | Stage::GBuffer => true,
            Stage::Detail
            | Stage::EdgeWidths
            | Stage::TrimEdges
            | Stage::Shade
            | Stage::Outline
            | Stage::Supersample
            | Stage::Aov
            | Stage::Resolve => false,
        }
    }

    /// This plan with every stage it runs that [depends on surfaces
    /// only](Plan::depends_on_surfaces_only) reused instead: what a frame runs when the
    /// previous frame of the same renderer had the same surfaces.
    #[must_use]
    pub fn reusing_surfaces(mut self) -> Self {
        for stage in Stage::ALL {
            let k = stage.index();
            if self.runs[k] && Self::depends_on_surfaces_only(stage) {
                self.runs[k] = false;
                self.reused[k] = true;
            }
        }
        self
    }

    /// This plan with the lines reused: what a frame runs when it [reuses the
    /// surfaces](Plan::reusing_surfaces) and the previous frame drew its lines with the same
    /// outlines and line styles (the lines depend on nothing else).
    #[must_use]
    pub fn reusing_lines(mut self) -> Self {
        let k = Stage::Outline.index();
        if self.runs[k] {
            self.runs[k] = false;
            self.reused[k] = true;
        }
        self
    }

    /// Whether `stage` runs: it is called for and not reused.
    #[must_use]
    pub fn runs(&self, stage: Stage) -> bool {
        self.runs[stage.index()]
    }

    /// Whether the previous frame's result of `stage` serves this frame instead of running it.
    #[must_use]
    pub fn reuses(&self, stage: Stage) -> bool {
        self.reused[stage.index()]
    }

    /// Whether the frame uses `stage`'s result: it runs or is reused.
    #[must_use]
    pub fn uses(&self, stage: Stage) -> bool {
        self.runs(stage) || self.reuses(stage)
    }

    /// The stages that run, in pipeline order.
    pub fn stages(&self) -> impl Iterator<Item = Stage> + '_ {
        Stage::ALL.into_iter().filter(|&stage| self.runs(stage))
    }

    /// The stages whose previous result is reused, in pipeline order.
    pub fn reused_stages(&self) -> impl Iterator<Item = Stage> + '_ {
        Stage::ALL.into_iter().filter(|&stage| self.reuses(stage))
    }
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::geom::PatchLibrary;
    use crate::render::fixtures::empty_scene;
    use crate::render::PatchLook;
    use crate::toon::CelRamp;

    #[test]
    fn the_one_sample_pass_interpolates_only_a_fine_adaptive_frame_whose_frames_no_aov_reads() {
        let library = PatchLibrary::default();
        let plain = empty_scene(&library, Aovs::default());
        let first = |scene: &Scene, settings: Settings| Plan::new(scene, &settings).frames;
        let final_quality = Settings::final_quality(64, 48);
        assert_eq!(first(&plain, final_quality), FrameMode::Interpolated);
        // Mattes and patch ids read no frame.
        let with = |set: fn(&mut Aovs)| {
            let mut aovs = Aovs::default();
            set(&mut aovs);
            aovs
        };
        let matte = empty_scene(&library, with(|a| (a.matte, a.patch_id) = (true, true)));
        assert_eq!(first(&matte, final_quality), FrameMode::Interpolated);
        for aovs in [
            with(|a| a.normal = true),
            with(|a| a.uv = true),
            with(|a| a.depth = true),
            with(|a| a.n_dot_h = true),
        ] {
            let reading = empty_scene(&library, aovs);
            assert_eq!(
                first(&reading, final_quality),
                FrameMode::Refined,
                "{aovs:?}"
            );
        }
        for density in [
            Density::ScreenTolerance { pixels: 0.25 },
            Density::PerSpan { u: 64, v: 64 },
        ] {
            let coarse = Settings {
                density,
                ..final_quality
            };
            assert_eq!(first(&plain, coarse), FrameMode::Refined, "{density:?}");
        }
        let analytic = Settings {
            antialias: Antialias::Analytic,
            ..final_quality
        };
        assert_eq!(first(&plain, analytic), FrameMode::Refined);
    }

    #[test]
    fn band_edges_run_the_edge_stage_only_under_analytic_edges_and_need_texels() {
        let library = PatchLibrary::default();
        let with_tone = |bands: Vec<(f32, Vec3)>| {
            let mut scene = empty_scene(&library, Aovs::default());
            scene.looks.push(PatchLook {
                designed_light: None,
                tone: Tone::Cel(CelRamp {
                    base: Vec3::ZERO,
                    bands,
                }),
                highlight: None,
                lines: None,
            });
            scene
        };
        let banded = with_tone(vec![(0.1, Vec3::ONE)]);
        let flat = with_tone(Vec::new());
        let interpolated = |antialias| Settings {
            frames: FrameMode::Interpolated,
            antialias,
            ..Settings::preview(64, 48)
        };
        for (scene, settings, edges, surfaces) in [
            (
                &banded,
                Settings::final_quality(64, 48),
                true,
                Surfaces::Texels,
            ),
            (
                &banded,
                interpolated(Antialias::Analytic),
                true,
                Surfaces::Texels,
            ),
            (
                &banded,
                interpolated(Antialias::None),
                false,
                Surfaces::Visibility,
            ),
            (
                &flat,
                interpolated(Antialias::Analytic),
                false,
                Surfaces::Visibility,
            ),
        ] {
            let plan = Plan::new(scene, &settings);
            assert_eq!(plan.runs(Stage::EdgeWidths), edges, "{settings:?}");
            assert_eq!(plan.surfaces, surfaces, "{settings:?}");
        }
    }
}
