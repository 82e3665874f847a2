//! Rendering: turning tessellated geometry into pixels.

pub mod raster;
