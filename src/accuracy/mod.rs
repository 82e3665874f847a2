//! The accuracy ladder measured (docs/accuracy.md): each rung — tessellation density, interpolated,
//! exact or refined frames, edge anti-aliasing — rendered on the exact NURBS sphere and compared
//! with the analytic sphere ray-cast per pixel, with its time per frame; the geometry's own
//! error and cost; and how frame time scales with resolution, patches and threads.
//!
//! The measuring logic lives here; the command line's `glint bench accuracy` runs it, prints the
//! tables and writes the CSV files and the plot.

pub mod case;
pub mod geometry;
pub mod metrics;
pub mod reference;
pub mod scaling;
pub mod stack;
pub mod sweep;
pub mod timing;

pub use reference::AnalyticSphere;
