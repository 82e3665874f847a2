//! Rendering: a [`Scene`] to a [`RenderedFrame`], stage by stage as the [`Plan`] decides.
//!
//! ```text
//! Tessellate ▸ Rasterize ▸ GBuffer ▸ Detail ▸ EdgeWidths ▸ TrimEdges ▸ Shade ▸ Outline
//! ▸ Supersample ▸ Aov ▸ Resolve
//! ```
//!
//! A stage the scene does not use does not run, and [`RenderStats`] shows it. Writing the
//! images to files is not rendering: see [`crate::formats`].

mod antialias;
mod aov;
pub mod camera;
mod colour;
mod directions;
mod edges;
mod facing;
#[cfg(test)]
mod fixtures;
mod gbuffer;
mod line_style;
mod lines;
mod neighbourhood;
mod plan;
mod probe;
pub mod raster;
mod renderer;
mod scene;
mod settings;
mod shade;
mod stage;
mod static_layer;
mod stats;
mod surface_key;
mod surface_point;
pub mod tessellate;
mod trim_cut;
mod visibility_shade;
mod xtoon_tone;

pub use aov::AovImages;
pub use camera::{Camera, Projection};
pub use facing::facing_frame;
pub use line_style::{
    Dash, HiddenLines, LineKind, LineKinds, LineStyle, MAX_DASHES, MAX_LINE_WIDTH,
    MAX_OCCLUSION_LEVEL, MAX_TAPER, MIN_DASH_CYCLE,
};
pub use lines::{part_of, VectorLines, VectorStroke};
pub use plan::{Plan, Surfaces, FINE_MESH_PIXELS};
pub use renderer::{RenderedFrame, Renderer};
pub use scene::{Aovs, Outlines, PatchLook, Scene, Tone};
pub use settings::{Antialias, FrameMode, Settings, MAX_SIDE, MAX_THREADS};
pub use stage::Stage;
pub use stats::{RenderStats, StageStats};
pub use surface_point::SurfacePoint;

use thiserror::Error;

/// A map for the frame's own bookkeeping, keyed by points, edges or pairs of patches: a fast
/// hasher for small keys, seeded per process. What the renderer makes never depends on the
/// order such a map is walked in.
pub(crate) type FastMap<K, V> = std::collections::HashMap<K, V, foldhash::fast::RandomState>;

/// The set kind of [`FastMap`].
pub(crate) type FastSet<K> = std::collections::HashSet<K, foldhash::fast::RandomState>;

/// A scene or setting the renderer cannot use.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum RenderError {
    /// The camera defines no view.
    #[error("camera: {0}")]
    Camera(String),
    /// An image size, sampling or tessellation setting out of range.
    #[error("settings: {0}")]
    Settings(String),
    /// The worker threads could not be started.
    #[error("settings: cannot start {threads} threads: {reason}")]
    Threads { threads: usize, reason: String },
    /// The scene shows another model than the renderer was made for.
    #[error("scene: the scene shows another model than this renderer was made for")]
    OtherModel,
    /// The mesh for this view would take more memory than allowed.
    #[error("the mesh for this view would have {vertices} vertices, more than the {most} the memory ceiling leaves room for; coarsen the tessellation, or raise the ceiling with --max-memory")]
    MeshTooLarge { vertices: u64, most: u64 },
    /// The scene's looks do not match the model's patches one to one.
    #[error("scene: the scene must give one look for each of the model's {patches} patches, got {looks}")]
    LooksPerPatch { patches: usize, looks: usize },
}
