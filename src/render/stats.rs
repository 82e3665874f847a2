//! Render statistics: what each stage of a frame did and how long it took. A stage the plan
//! leaves out reports that it did not run, and one whose previous result served, that it was
//! reused.

use std::ops::Index;
use std::time::Instant;

use serde::ser::{Serialize, SerializeMap, SerializeStruct, Serializer};

use super::plan::Plan;
use super::stage::Stage;

/// One stage's work.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct StageStats {
    /// Pixels (or samples, under supersampling) the stage processed; for
    /// [`Stage::Tessellate`], the triangles of the mesh.
    pub pixels: u64,
    /// Wall-clock time in seconds.
    pub seconds: f64,
}

/// Per-stage statistics of one rendered frame.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderStats {
    /// The stages the frame ran and reused.
    pub plan: Plan,
    /// Per stage, in [`Stage::ALL`] order; zero for a stage that did not run (reused or not
    /// called for).
    stages: [StageStats; Stage::COUNT],
    /// Whether the mesh had to be rebuilt (false when the cached one served, or the
    /// tessellation was reused).
    pub tessellation_rebuilt: bool,
    /// Patches whose grid of vertices the tessellation evaluated for this frame's mesh: new
    /// segment counts, or moved or deformed since the last frame.
    pub grids_evaluated: usize,
    /// Patches whose grid was kept from an earlier frame into a rebuilt mesh (0 when the mesh
    /// was not rebuilt).
    pub grids_kept: usize,
    /// Pairs of patches whose intersection lines were kept from the mesh they were last found
    /// on, neither patch's grid having changed since (0 unless this frame found them again).
    pub intersection_pairs_kept: usize,
    /// Pairs of patches intersected triangle by triangle for this frame's lines: those with a
    /// changed grid whose bounds overlap and which share no vertex position (0 unless this
    /// frame found the intersections again).
    pub intersection_pairs_tested: usize,
    /// Patches whose silhouette pieces were kept from the frame before rather than found again:
    /// the camera and the patch, its grid bit for bit, are as they were (0 when the lines were
    /// not found again).
    pub silhouettes_kept: usize,
    pub triangles: usize,
    /// Triangles drawn into the visibility buffer (or the kept visibility of the patches that
    /// did not move) for this frame: fewer than [`RenderStats::triangles`] when the triangles
    /// of patches that did not move were kept from an earlier frame; 0 when the rasterize
    /// stage did not run.
    pub triangles_rasterized: usize,
    /// G-buffer texels kept from the previous frame rather than made again: on patches that
    /// did not move, where the visibility buffer is the previous frame's (0 when the G-buffer
    /// was not filled).
    pub texels_kept: u64,
    /// NURBS frames evaluated per pixel (exact and refined frames).
    pub exact_frames: u64,
    /// Samples on highlighted patches: the only ones a half vector was built for.
    pub highlight_pixels: u64,
    /// Samples on X-Toon patches, whose shading normal, detail and texture colour were computed
    /// (0 without X-Toon): by the shade stage, or ahead of it by [`Stage::Detail`].
    pub xtoon_pixels: u64,
    /// The whole frame.
    pub total_seconds: f64,
    /// The stages that recorded work though the plan left them out, one bit per stage (none,
    /// unless the renderer strays from its plan).
    unplanned: u64,
}

impl RenderStats {
    /// Empty statistics of a frame that runs `plan`.
    #[must_use]
    pub fn new(plan: Plan) -> Self {
        Self {
            plan,
            stages: [StageStats::default(); Stage::COUNT],
            tessellation_rebuilt: false,
            grids_evaluated: 0,
            grids_kept: 0,
            intersection_pairs_kept: 0,
            silhouettes_kept: 0,
            intersection_pairs_tested: 0,
            triangles: 0,
            triangles_rasterized: 0,
            texels_kept: 0,
            exact_frames: 0,
            highlight_pixels: 0,
            xtoon_pixels: 0,
            total_seconds: 0.0,
            unplanned: 0,
        }
    }

    /// Whether `stage` ran.
    #[must_use]
    pub fn ran(&self, stage: Stage) -> bool {
        self.plan.runs(stage) || self.unplanned & (1 << stage.index()) != 0
    }

    /// Whether `stage` did not run because the previous frame's result served
    /// ([`Plan::reusing_surfaces`]).
    #[must_use]
    pub fn reused(&self, stage: Stage) -> bool {
        self.plan.reuses(stage)
    }

    /// The stages that ran, in pipeline order, with what each did.
    pub fn ran_stages(&self) -> impl Iterator<Item = (Stage, StageStats)> + '_ {
        self.plan.stages().map(|stage| (stage, self[stage]))
    }

    /// Records what `stage` did. A stage the plan leaves out that records anyway is reported
    /// by [`ran`](Self::ran) all the same, so that what it reports is what ran.
    pub(crate) fn record(&mut self, stage: Stage, pixels: u64, seconds: f64) {
        if !self.plan.runs(stage) {
            self.unplanned |= 1 << stage.index();
        }
        self.stages[stage.index()] = StageStats { pixels, seconds };
    }

    /// Adds `seconds` to what `stage` took: a stage whose work is split over the frame.
    pub(crate) fn add_seconds(&mut self, stage: Stage, seconds: f64) {
        self.stages[stage.index()].seconds += seconds;
    }
}

impl Index<Stage> for RenderStats {
    type Output = StageStats;

    fn index(&self, stage: Stage) -> &StageStats {
        &self.stages[stage.index()]
    }
}

/// As JSON: `stages` maps the name of each stage that ran to its work, in pipeline order;
/// `reused` lists the stages whose previous result served; the counts follow.
impl Serialize for RenderStats {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        struct Stages<'a>(&'a RenderStats);
        impl Serialize for Stages<'_> {
            fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
                let mut map = serializer.serialize_map(None)?;
                for (stage, stats) in self.0.ran_stages() {
                    map.serialize_entry(stage.name(), &stats)?;
                }
                map.end()
            }
        }
        let reused: Vec<&str> = self.plan.reused_stages().map(Stage::name).collect();
        let mut s = serializer.serialize_struct("RenderStats", 15)?;
        s.serialize_field("stages", &Stages(self))?;
        s.serialize_field("reused", &reused)?;
        s.serialize_field("tessellation_rebuilt", &self.tessellation_rebuilt)?;
        s.serialize_field("grids_evaluated", &self.grids_evaluated)?;
        s.serialize_field("grids_kept", &self.grids_kept)?;
        s.serialize_field("intersection_pairs_kept", &self.intersection_pairs_kept)?;
        s.serialize_field("intersection_pairs_tested", &self.intersection_pairs_tested)?;
        s.serialize_field("silhouettes_kept", &self.silhouettes_kept)?;
        s.serialize_field("triangles", &self.triangles)?;
        s.serialize_field("triangles_rasterized", &self.triangles_rasterized)?;
        s.serialize_field("texels_kept", &self.texels_kept)?;
        s.serialize_field("exact_frames", &self.exact_frames)?;
        s.serialize_field("highlight_pixels", &self.highlight_pixels)?;
        s.serialize_field("xtoon_pixels", &self.xtoon_pixels)?;
        s.serialize_field("total_seconds", &self.total_seconds)?;
        s.end()
    }
}

/// Runs `work` and returns its result with the seconds it took.
pub(crate) fn timed<T>(work: impl FnOnce() -> T) -> (T, f64) {
    let start = Instant::now();
    let value = work();
    (value, start.elapsed().as_secs_f64())
}
