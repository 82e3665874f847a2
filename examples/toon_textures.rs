//! Writes the 2D toon textures of the X-Toon effect families (`glint::toon::texture_families`)
//! as editable PNGs. The shipped ones in `textures/` are made this way, and a test checks they
//! still match the generator.
//!
//! `cargo run --example toon_textures -- [OUT_DIR]` (default `textures`).

use std::path::PathBuf;

use glint::formats::png::{write_png, PngLayout};
use glint::toon::texture_families::Family;

fn main() -> anyhow::Result<()> {
    let out = PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| "textures".into()));
    std::fs::create_dir_all(&out)?;
    for family in Family::ALL {
        let image = family.image();
        let path = out.join(format!("{}.png", family.name()));
        write_png(
            &path,
            image.width as u32,
            image.height as u32,
            PngLayout::Rgba8,
            &image.rgba,
        )?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
