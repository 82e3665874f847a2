//! glint: a cel-animation renderer for NURBS patch models with designed, keyframed stylized
//! highlights (Anjyo & Hiramitsu 2003).

pub mod geom;
pub mod highlight;
