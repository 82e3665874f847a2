//! The accuracy ladder measured (docs/accuracy.md): each rung — tessellation density, interpolated,
//! exact or refined frames, edge anti-aliasing — rendered on the exact NURBS sphere and compared
//! with the analytic sphere ray-cast per pixel, with its time per frame; the geometry's own
//! error and cost; and how frame time scales with resolution, patches and threads.
//!
//! The measuring logic lives here; the command line's `glint bench accuracy` runs it, prints the
//! tables and writes the CSV files and the plot.

pub mod case;
pub mod closed_form;
pub mod closed_form_ops;
pub mod geometry;
pub mod metrics;
pub mod reference;
mod renderer_highlight;
pub mod scaling;
pub mod sphere_highlight;
pub mod sphere_point;
pub mod stack;
pub mod sweep;
pub mod timing;

pub use closed_form::ClosedForm;
pub use reference::AnalyticSphere;
pub use sphere_highlight::SphereHighlight;
