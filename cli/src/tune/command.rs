//! `glint tune`: a shot's highlights tuned in a browser — a local page that shows the frame,
//! follows the pointer with the highlight, and writes every accepted change to the shot file.

use std::io::Write;
use std::net::IpAddr;
use std::path::PathBuf;
use std::sync::mpsc;

use anyhow::anyhow;
use clap::Args;

use crate::render::parse_size;
use crate::tune::{ServerOptions, Session, TuneServer};
use crate::watch::{follow, next_change, Message};
use crate::watched::WatchedFiles;
use crate::CliError;

/// Tune a shot's highlights in a browser: drag them on the surface, move their parameters, key
/// them.
///
/// Serves one page on this machine and prints its address (with the session's token; every
/// request must carry it). The page shows the frame at preview quality after every change and
/// at final quality when you pause; a timeline scrubs frames and shows where the selected
/// parameter has keys. Click the model to select a patch and the highlight layer on it; drag
/// on the surface and the highlight's centre follows the pointer (its translation solved as
/// `glint place` solves it, or its pin moved); releasing keys it at the current frame. The
/// panel has a slider per parameter within its legal range, a key button for each, and buttons
/// to add, remove and reorder operations and to add a mask. "draw outline" (D) draws the
/// layer's outline: click its corners on the surface, drag or Shift+click them to edit, Enter
/// writes it (keyed at the current frame when the outline is keyed or you ask). Overlays show
/// patch seams, the highlight matte and pins.
///
/// Every accepted change is written to the shot file at once, through the same editor as
/// `glint key` (comments and formatting kept), so the file is always the truth; undo and redo
/// write it back. Editing the file in a text editor meanwhile updates the page. Nothing else is
/// written: highlights written in an include are shown but not changed.
///
/// The server listens on 127.0.0.1 only, unless --bind names another address; requests must
/// carry the token and name this server in their Host and Origin headers. Ctrl-C stops it.
#[derive(Debug, Args)]
#[command(after_help = "Examples:
  glint tune shots/sphere_ops.ron
  glint tune shots/teapot_turntable.ron --port 8400 --no-open
  glint tune shots/teapot_turntable.ron --size 960x540
  glint tune shots/crescent.ron --bind 192.168.1.20 --allow-host studio-ws-12 --no-open")]
pub struct TuneArgs {
    /// The shot file (RON) to tune; it is rewritten as you accept changes
    shot: PathBuf,
    /// The port to listen on [default: a free one, chosen by the system]
    #[arg(long, value_name = "N", default_value_t = 0)]
    port: u16,
    /// Print the address but do not open a browser
    #[arg(long)]
    no_open: bool,
    /// Listen on this address instead of 127.0.0.1 (for another machine's browser: anyone
    /// who can reach it and has the token can change the shot file)
    #[arg(long, value_name = "ADDRESS")]
    bind: Option<IpAddr>,
    /// Another host name the page may be opened by (with --bind: this machine's name on the
    /// network); may be given several times
    #[arg(long = "allow-host", value_name = "NAME")]
    allow_hosts: Vec<String>,
    /// Preview image size instead of the shot's resolution
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    size: Option<(u32, u32)>,
}

pub fn run(args: &TuneArgs) -> Result<(), CliError> {
    let session = Session::open(&args.shot, args.size).map_err(|e| {
        if e.is_bad_input() {
            CliError::BadInput(e.into())
        } else {
            CliError::Failed(e.into())
        }
    })?;
    let options = ServerOptions {
        bind: args.bind.unwrap_or(IpAddr::from([127, 0, 0, 1])),
        port: args.port,
        hosts: args.allow_hosts.clone(),
    };
    let inputs = {
        let shot = glint::shot::load_shot(&args.shot).map_err(|e| CliError::BadInput(e.into()))?;
        shot.inputs
    };
    let server = TuneServer::start(session, &options).map_err(|e| {
        CliError::BadInput(anyhow!(
            "cannot listen on {}:{}: {e}",
            options.bind,
            options.port
        ))
    })?;
    let url = server.url();
    {
        let mut out = std::io::stdout().lock();
        let _ = writeln!(out, "glint tune: {url}");
        let _ = writeln!(out, "tuning {}; Ctrl-C stops", args.shot.display());
        let _ = out.flush();
    }
    if !args.no_open {
        open_browser(&url);
    }

    let (sender, messages) = mpsc::channel();
    let on_stop = sender.clone();
    ctrlc::set_handler(move || {
        let _ = on_stop.send(Message::Stop);
    })
    .map_err(|e| CliError::Failed(anyhow!("cannot catch Ctrl-C: {e}")))?;
    let mut watcher = notify::recommended_watcher(move |event| {
        let _ = sender.send(Message::Files(event));
    })
    .map_err(|e| CliError::Failed(anyhow!("cannot watch files: {e}")))?;
    let mut watched = WatchedFiles::default();
    follow(&mut watcher, &mut watched, inputs).map_err(CliError::Failed)?;
    while next_change(&messages, &watched).is_some() {
        server.inputs_changed();
        if let Ok(shot) = glint::shot::load_shot(&args.shot) {
            if let Err(e) = follow(&mut watcher, &mut watched, shot.inputs) {
                eprintln!("error: {e:#}");
            }
        }
    }
    server.stop();
    Ok(())
}

/// Opens `url` in the desktop's browser, if there is one; nothing happens otherwise (the
/// address is printed).
fn open_browser(url: &str) {
    let opener = if cfg!(target_os = "macos") {
        "open"
    } else if cfg!(target_os = "windows") {
        "explorer"
    } else {
        "xdg-open"
    };
    let _ = std::process::Command::new(opener)
        .arg(url)
        .stdin(std::process::Stdio::null())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn();
}
