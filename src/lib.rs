//! glint: a cel-animation renderer for NURBS patch models with designed, keyframed stylized
//! highlights (Anjyo & Hiramitsu 2003).
//!
//! The geometry underneath: exact NURBS surfaces and the frame `(du, dv, N)` the highlight
//! operations work in.
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
pub mod cli;
pub mod formats;
pub mod geom;
pub mod highlight;
pub mod param;
pub mod render;
pub mod scene;
pub mod toon;
