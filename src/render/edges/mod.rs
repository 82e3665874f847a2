//! The edges at one sample: [`Stage::EdgeWidths`](super::Stage::EdgeWidths) and
//! [`Stage::TrimEdges`](super::Stage::TrimEdges) — how the edges of the tone's bands, of the
//! highlights and of the trims meet each pixel, and which pixels are drawn right at one sample.

pub(super) mod band_edge;
pub(super) mod edge_width;
pub(super) mod highlight_edge;
pub(super) mod one_sample;
pub(super) mod settled;
pub(super) mod trim_edge;
