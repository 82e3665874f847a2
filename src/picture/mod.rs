//! Pictures for people to read: text labels drawn on images, the patch map of a model, sheets
//! of tiles with captions, and marks over a frame being tuned. Built on rendered frames; nothing here writes files.

pub mod framing;
pub mod label_placement;
pub mod overlay;
pub mod patch_map;
pub mod sheet;
pub mod text;

pub use framing::try_three_quarter_camera;
pub use patch_map::{
    draw_patch_map, part_legend, patch_labels, render_patch_map, MapLabel, MapPixels, PatchMap,
};
pub use sheet::{Sheet, SheetError, SheetLayout, MAX_TILES};
pub use text::{block_size, draw_block, draw_label, label_size, LabelStyle, PixelRect};
