//! glint: a cel-animation renderer for NURBS patch models with designed, keyframed stylized
//! highlights (Anjyo & Hiramitsu 2003).
//!
//! # Rendering a shot
//!
//! A shot file ([`shot`], described in `docs/shot-format.md`) names the models, materials,
//! camera, light and highlights, every number a track over frames. A [`job::RenderJob`] loads
//! it with what the user overrides, and renders any frame to images and statistics; writing
//! the files is a separate step ([`job::RenderJob::write_frame`]).
//!
//! ```
//! use glint::job::{Overrides, RenderJob};
//! use glint::render::Stage;
//! use glint::shot::Preset;
//!
//! let overrides = Overrides {
//!     size: Some((64, 48)),
//!     preset: Some(Preset::Preview),
//!     ..Overrides::default()
//! };
//! let mut job = RenderJob::load("shots/sphere_ops.ron".as_ref(), &overrides)?;
//! // The shot file and the patch file it places: a change to either changes frames.
//! assert_eq!(job.inputs().len(), 2);
//! let frame = job.render_frame(30.5)?;
//! assert_eq!(frame.colour.len(), 64 * 48);
//! // Linear RGB with straight alpha: the sphere covers the middle of the image.
//! assert_eq!(frame.colour[24 * 64 + 32].w, 1.0);
//! // Only what the shot calls for ran: no X-Toon detail, no supersampling at the preview preset.
//! assert!(frame.stats.ran(Stage::Shade) && !frame.stats.ran(Stage::Detail));
//! assert!(!frame.stats.ran(Stage::Resolve));
//! # Ok::<(), glint::job::JobError>(())
//! ```
//!
//! Underneath, [`shot::Shot::at`] reads every track at a frame, [`shot::FrameState::scene`]
//! makes the [`render::Scene`] of that state, and a [`render::Renderer`] draws it stage by stage
//! ([`render::Stage`]) as the [`render::Plan`] decides. The highlight model ([`highlight`]) and
//! the tone ([`toon`]) are pure math over a surface frame, usable on their own.
//!
//! # The geometry underneath
//!
//! Exact NURBS surfaces and the frame `(du, dv, N)` the highlight operations work in.
//!
//! ```
//! use glam::DVec3;
//! use glint::geom::shapes;
//!
//! // On the sphere u runs east and v from the south to the north pole, so that
//! // (du, dv, N) = (east, north, outward).
//! let sphere = shapes::sphere(DVec3::ZERO, 2.0).unwrap();
//! let f = sphere.frame(0.25, 0.5); // 90° east, on the equator
//! assert!((f.point - DVec3::new(0.0, 2.0, 0.0)).length() < 1e-12);
//! assert!((f.du - DVec3::NEG_X).length() < 1e-12);
//! assert!((f.dv - DVec3::Z).length() < 1e-12);
//!
//! // At a pole Su × Sv vanishes; the frame is the limit from inside the patch.
//! let pole = sphere.frame(0.0, 1.0);
//! assert!(pole.degenerate && (pole.normal - DVec3::Z).length() < 1e-12);
//! ```

pub mod accuracy;
pub mod anim;
pub mod formats;
pub mod geom;
pub mod highlight;
pub mod job;
pub mod math;
pub mod param;
pub mod picture;
pub mod render;
pub mod shot;
pub mod toon;
