//! `glint sheet`: one PNG of captioned tiles — a shot's frames over time, or variants of one
//! frame with parameters set to chosen values.

use std::path::{Path, PathBuf};

use anyhow::anyhow;
use clap::{ArgGroup, Args};
use image::RgbaImage;

use super::render::{frame_list_arg, parse_size, FrameListArg, PresetArg};
use super::vary::{combination_count, combinations, parse_vary, short_names, variant_label, Vary};
use super::CliError;
use glint::formats::image_encoding::colour_rgba8;
use glint::formats::png::{write_png, PngLayout};
use glint::job::{JobError, Overrides, RenderJob};
use glint::picture::{Sheet, SheetError, SheetLayout, MAX_TILES};
use glint::shot::{
    edit_text, load_shot, load_shot_text, parse_param_path, EditError, Preset, Shot, TrackEdit,
};

/// The width of a tile when --tile is not given; its height keeps the shot's aspect.
pub const DEFAULT_TILE_WIDTH: u32 = 320;

/// Render a sheet of tiles to one PNG: a shot's frames, or variants of one frame.
///
/// With --frames, one tile per frame, captioned `frame N`. With --vary PATH=V1,V2,…
/// (repeatable), one tile per combination of the values of every --vary (the last one changing
/// fastest), each showing --frame with those values set, captioned with them
/// (`alpha=0.2 beta=0.1`). Every parameter path `glint key` takes can be varied, a shade
/// entry's (`shade[0].stack[0].alpha`) as a highlight layer's. Values are written as in the
/// shot file; a tuple such as `(1.0, 0.9, 0.8)` is one value. A sheet holds at most 64 tiles.
///
/// Each tile is the frame exactly as `glint render --size WxH --preset P` renders it (the
/// background transparent), with its caption in a strip beneath. With --crop X,Y,W,H each tile
/// shows only that rectangle of the frame (in the shot's own pixels, from the top left), drawn
/// again at the tile's size rather than enlarged: the frame is rendered at the shot's size times
/// the tile's width over W, and the rectangle cut from it, so small highlights can be compared
/// at a zoom. The sheet is written atomically. Exit code 2 for bad input (the shot, the options, too many tiles), 1 when
/// rendering or writing failed.
#[derive(Debug, Args)]
#[command(group(ArgGroup::new("tiles").required(true).args(["frames", "vary"])))]
#[command(after_help = "Examples:
  glint sheet shots/sphere_ops.ron --frames 1-96x8 --out out/sphere_ops.sheet.png
  glint sheet shots/teapot_turntable.ron --frames 1,33,65,96 --tile 480x270 --columns 2 \\
      --out out/turntable.sheet.png
  glint sheet shots/teapot_lid_opens.ron --frames 1-48x6 --crop 240,60,180,135 \\
      --tile 240x180 --out out/lid_glint.sheet.png
  glint sheet shots/crescent.ron --frame 36 \\
      --vary 'highlights[0].layers[1].stack[1].alpha=0.1,0.3,0.5' \\
      --vary 'highlights[0].layers[0].colour=(1, 1, 1),(1, 0.8, 0.6)' --out out/crescent.png
  glint sheet shots/shade_design.ron --frame 48 \\
      --vary 'shade[0].stack[0].alpha=0.0,0.3,0.6' --out out/shade_design.sheet.png

Frame lists: 12 | 1-48 | 1-48x2 (every second frame) | 1,5,9-12.")]
pub struct SheetArgs {
    /// The shot file (RON)
    shot: PathBuf,
    /// The frames to show, one tile each, as `glint render --frames` lists them
    #[arg(long, value_name = "SPEC", value_parser = frame_list_arg, allow_hyphen_values = true, conflicts_with_all = ["frame", "vary"])]
    frames: Option<FrameListArg>,
    /// The frame the variants show (fractional frames allowed) [default: the shot's first frame]
    #[arg(long, value_name = "F", requires = "vary")]
    frame: Option<f64>,
    /// A parameter of the shot and the values it takes in turn, PATH=V1,V2,… (repeatable)
    #[arg(long, value_name = "PATH=V1,V2,…", value_parser = parse_vary)]
    vary: Vec<Vary>,
    /// Each tile's size [default: 320 pixels wide at the shot's aspect, or at the crop's]
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    tile: Option<(u32, u32)>,
    /// Show only this rectangle of each frame, X,Y,W,H in the shot's pixels from the top left,
    /// rendered again at the tile's size (a zoom of tile width / W)
    #[arg(long, value_name = "X,Y,W,H", value_parser = parse_crop)]
    crop: Option<Crop>,
    /// Tiles per row [default: the grid nearest a square]
    #[arg(long, value_name = "N")]
    columns: Option<u32>,
    /// Accuracy preset of the tiles; the shot's explicit settings still refine it
    #[arg(long, value_enum, default_value = "preview")]
    preset: PresetArg,
    /// The sheet's PNG file
    #[arg(long, value_name = "SHEET.png")]
    out: PathBuf,
}

/// One tile of a sheet: the shot text it is rendered from, the frame it shows, its caption.
struct Variant {
    label: String,
    frame: f64,
    text: String,
}

/// What the tiles show before their texts are made: each one's caption and frame, and for
/// variants the index of each --vary's value.
struct Plan {
    captions: Vec<String>,
    frames: Vec<f64>,
    combinations: Option<Vec<Vec<usize>>>,
}

pub fn run(args: &SheetArgs) -> Result<(), CliError> {
    let bad = |message: String| CliError::BadInput(anyhow!(message));
    let shot = load_shot(&args.shot).map_err(|e| CliError::BadInput(e.into()))?;
    let shown = args.shot.display();
    let plan = plan(args, &shot).map_err(bad)?;
    let (first, last) = shot.frames;
    if let Some(outside) = plan
        .frames
        .iter()
        .find(|&&f| !(f >= first as f64 && f <= last as f64))
    {
        return Err(bad(format!(
            "{shown}: frame {outside} is outside the shot's frame range {first}-{last}"
        )));
    }
    let tile = args.tile.unwrap_or_else(|| default_tile(&shot, args.crop));
    let zoom = match args.crop {
        Some(crop) => Some(crop.zoom(&shot, tile).map_err(bad)?),
        None => None,
    };
    let layout = SheetLayout::new(&plan.captions, tile, args.columns)
        .map_err(|e: SheetError| bad(e.to_string()))?;
    let file_text = std::fs::read_to_string(&args.shot)
        .map_err(|e| bad(format!("{shown}: cannot read the file: {e}")))?;
    let variants = variants(plan, &args.vary, &args.shot, &file_text)?;
    if let Some(folder) = args.out.parent().filter(|f| !f.as_os_str().is_empty()) {
        std::fs::create_dir_all(folder).map_err(|e| {
            bad(format!(
                "cannot make the folder {} for the sheet: {e}",
                folder.display()
            ))
        })?;
    }

    let preset = Preset::from(args.preset);
    let overrides = Overrides {
        size: Some(zoom.map_or(tile, |z| z.render)),
        preset: Some(preset),
        aovs: Some(Vec::new()),
        // The sheet renders the frames checked above and writes no frame files.
        frames: Some(Vec::new()),
        ..Overrides::default()
    };
    let failed = |e: JobError| {
        if e.is_bad_input() {
            CliError::BadInput(e.into())
        } else {
            CliError::Failed(e.into())
        }
    };
    let mut sheet = Sheet::new(layout);
    let mut current = (file_text, RenderJob::new(shot, &overrides).map_err(failed)?);
    for (index, variant) in variants.iter().enumerate() {
        if variant.text != current.0 {
            let shot = load_edited(&args.shot, &variant.text)?;
            current = (
                variant.text.clone(),
                RenderJob::new(shot, &overrides).map_err(failed)?,
            );
        }
        let frame = current.1.render_frame(variant.frame).map_err(failed)?;
        let image = RgbaImage::from_raw(frame.width, frame.height, colour_rgba8(&frame.colour))
            .ok_or_else(|| {
                CliError::Failed(anyhow!(
                    "{}: the frame's pixels do not make a {}×{} image",
                    variant.label,
                    frame.width,
                    frame.height
                ))
            })?;
        let image = match zoom {
            Some(z) => {
                image::imageops::crop_imm(&image, z.origin.0, z.origin.1, tile.0, tile.1).to_image()
            }
            None => image,
        };
        sheet.put(index, &image, &variant.label);
    }
    let image = sheet.into_image();
    write_png(
        &args.out,
        image.width(),
        image.height(),
        PngLayout::Rgba8,
        image.as_raw(),
    )
    .map_err(|e| CliError::Failed(e.into()))?;
    println!(
        "{}: {} tiles of {}×{} in {} columns",
        args.out.display(),
        variants.len(),
        tile.0,
        tile.1,
        layout.columns
    );
    Ok(())
}

/// The captions and frames of the tiles `args` ask for: `frame N` for each of --frames, or
/// one per combination of the --vary values at --frame (default the shot's first), at most
/// [`MAX_TILES`].
fn plan(args: &SheetArgs, shot: &Shot) -> Result<Plan, String> {
    if let Some(FrameListArg(frames)) = &args.frames {
        if frames.len() > MAX_TILES {
            return Err(SheetError::TooManyTiles {
                count: frames.len(),
            }
            .to_string());
        }
        return Ok(Plan {
            captions: frames.iter().map(|f| format!("frame {f}")).collect(),
            frames: frames.iter().map(|&f| f as f64).collect(),
            combinations: None,
        });
    }
    let varies = &args.vary;
    for (i, vary) in varies.iter().enumerate() {
        if varies[..i].iter().any(|v| v.path == vary.path) {
            return Err(format!(
                "--vary {} is given twice; list all its values in one --vary",
                vary.path
            ));
        }
    }
    let count = combination_count(varies).unwrap_or(usize::MAX);
    if count > MAX_TILES {
        let factors: Vec<String> = varies.iter().map(|v| v.values.len().to_string()).collect();
        return Err(format!(
            "--vary makes {} variants ({}), more than the {MAX_TILES} a sheet holds; give fewer values",
            if count == usize::MAX {
                "too many".to_string()
            } else {
                count.to_string()
            },
            factors.join(" × ")
        ));
    }
    if args.frame.is_some_and(|f| !f.is_finite()) {
        return Err("--frame must be a finite number".into());
    }
    let frame = args.frame.unwrap_or(shot.frames.0 as f64);
    let paths: Vec<&str> = varies.iter().map(|v| v.path.as_str()).collect();
    let names = short_names(&paths);
    let combinations = combinations(varies);
    Ok(Plan {
        captions: combinations
            .iter()
            .map(|c| variant_label(&names, varies, c))
            .collect(),
        frames: vec![frame; combinations.len()],
        combinations: Some(combinations),
    })
}

/// The tiles of `plan`: the shot's own text for frames, and for variants the text with each
/// --vary's path set to the combination's value.
fn variants(
    plan: Plan,
    varies: &[Vary],
    file: &Path,
    file_text: &str,
) -> Result<Vec<Variant>, CliError> {
    let Plan {
        captions,
        frames,
        combinations,
    } = plan;
    let texts = match combinations {
        None => vec![file_text.to_owned(); captions.len()],
        Some(combinations) => combinations
            .iter()
            .map(|combination| {
                varies
                    .iter()
                    .zip(combination)
                    .try_fold(file_text.to_owned(), |text, (vary, &i)| {
                        edit_value(file, &text, &vary.path, &vary.values[i])
                    })
            })
            .collect::<Result<_, _>>()?,
    };
    Ok(captions
        .into_iter()
        .zip(frames)
        .zip(texts)
        .map(|((label, frame), text)| Variant { label, frame, text })
        .collect())
}

/// The shot text `text` with the track at parameter path `path` set to the constant `value`.
/// Errors name `file`, the shot the text is read from.
fn edit_value(file: &Path, text: &str, path: &str, value: &str) -> Result<String, CliError> {
    let bad = |e: EditError| CliError::BadInput(e.in_file(file).into());
    let path = parse_param_path(text, path).map_err(bad)?;
    edit_text(text, &path, &TrackEdit::Set(value.to_owned())).map_err(bad)
}

/// The shot at `path` with `text` read in place of its file's text.
fn load_edited(path: &Path, text: &str) -> Result<Shot, CliError> {
    load_shot_text(path, text.to_owned()).map_err(|e| CliError::BadInput(e.into()))
}

/// [`DEFAULT_TILE_WIDTH`] wide at the shot's aspect: height `max(1, round(320 · h / w))`.
fn default_tile(shot: &Shot, crop: Option<Crop>) -> (u32, u32) {
    let (w, h) = crop.map_or((shot.settings.width, shot.settings.height), |c| {
        (c.width, c.height)
    });
    let height = (f64::from(DEFAULT_TILE_WIDTH) * f64::from(h) / f64::from(w)).round();
    (DEFAULT_TILE_WIDTH, (height as u32).max(1))
}

/// The largest side of the frame a cropped sheet renders before cutting its rectangle out.
pub const MAX_ZOOMED_SIDE: u32 = 16384;

/// A rectangle of a frame, in the shot's pixels from the top left.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Crop {
    x: u32,
    y: u32,
    width: u32,
    height: u32,
}

/// How a cropped tile is made: the size the frame is rendered at, and where the tile is cut
/// from it.
#[derive(Clone, Copy, Debug)]
struct Zoom {
    render: (u32, u32),
    origin: (u32, u32),
}

fn parse_crop(text: &str) -> Result<Crop, String> {
    let numbers: Vec<Option<u32>> = text.split(',').map(|n| n.trim().parse().ok()).collect();
    match numbers[..] {
        [Some(x), Some(y), Some(width), Some(height)] if width > 0 && height > 0 => Ok(Crop {
            x,
            y,
            width,
            height,
        }),
        _ => Err(format!(
            "expected X,Y,W,H, four whole numbers of pixels with W and H above 0, such as \
             300,110,120,90; got '{text}'"
        )),
    }
}

impl Crop {
    /// The render size and cut for tiles of `tile` pixels: the zoom `s = tile width / W` (the
    /// tile must have the crop's aspect, to a pixel), the frame at `s` times the shot's size,
    /// the cut at `s (X, Y)`. Errors when the rectangle leaves the shot's image, the tile's
    /// aspect is not the crop's, or the frame would be larger than [`MAX_ZOOMED_SIDE`].
    fn zoom(self, shot: &Shot, tile: (u32, u32)) -> Result<Zoom, String> {
        let (w, h) = (shot.settings.width, shot.settings.height);
        let Crop {
            x,
            y,
            width,
            height,
        } = self;
        if u64::from(x) + u64::from(width) > u64::from(w)
            || u64::from(y) + u64::from(height) > u64::from(h)
        {
            return Err(format!(
                "--crop {x},{y},{width},{height} leaves the shot's {w}×{h} image"
            ));
        }
        let s = f64::from(tile.0) / f64::from(width);
        let fits = (f64::from(height) * s - f64::from(tile.1)).abs() <= 1.0;
        if !fits {
            return Err(format!(
                "--tile {}x{} does not have the shape of --crop's {width}×{height}; leave --tile out \
                 or give it {}x{}",
                tile.0,
                tile.1,
                tile.0,
                (f64::from(height) * s).round()
            ));
        }
        let render = ((f64::from(w) * s).round(), (f64::from(h) * s).round());
        if render.0.max(render.1) > f64::from(MAX_ZOOMED_SIDE) {
            return Err(format!(
                "--crop {width}×{height} at tiles of {}×{} zooms {s:.1}×: the frame would be \
                 rendered at {}×{}, beyond {MAX_ZOOMED_SIDE} pixels a side; crop more or give a \
                 smaller --tile",
                tile.0, tile.1, render.0, render.1
            ));
        }
        let render = ((render.0 as u32).max(tile.0), (render.1 as u32).max(tile.1));
        // The cut stays inside the frame rendered, whatever the rounding.
        let origin = (
            ((f64::from(x) * s).round() as u32).min(render.0.saturating_sub(tile.0)),
            ((f64::from(y) * s).round() as u32).min(render.1.saturating_sub(tile.1)),
        );
        Ok(Zoom { render, origin })
    }
}
