//! `glint tune`: a local web page that shows a shot's frame and lets the animator drag a
//! highlight on the surface, move its parameters and key them, every accepted change written
//! to the shot file (docs/tune.md).
//!
//! [`session`] is the work, synchronous and free of HTTP; [`server`] answers HTTP requests with
//! it, behind the [`guard`]'s checks.

pub mod change;
pub(crate) mod command;
pub mod error;
pub mod guard;
pub mod history;
pub mod server;
pub mod session;
pub mod view;

pub use change::{apply_changes, Change, OpKind};
pub use error::TuneError;
pub use guard::{Guard, Refusal};
pub use server::{ServerOptions, TuneServer};
pub use session::{
    DragRequest, DrawRequest, FrameImage, FrameRequest, Overlays, Pick, Quality, Session,
    ShadeDragRequest,
};
pub use view::StateView;
