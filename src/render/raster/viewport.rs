//! The pixel grid a rasterizer draws.

/// The pixel grid rendered to. Pixel (0, 0) is the top-left; NDC y = +1 is the top row.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Viewport {
    pub width: u32,
    pub height: u32,
}
