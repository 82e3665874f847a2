//! `glint render --watch`: a shot's frames rendered, then rendered again each time a file the
//! shot is made from changes, until Ctrl-C.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, Receiver, RecvTimeoutError};
use std::sync::Arc;
use std::time::{Duration, Instant};

use anyhow::anyhow;
use notify::{RecommendedWatcher, RecursiveMode, Watcher};

use super::stats_report::stats_report;
use super::watched::WatchedFiles;
use super::CliError;
use glint::formats::atomic::Durability;
use glint::job::{JobError, Overrides, RenderJob};
use glint::render::Stage;

/// How long the inputs must stay unchanged after a change before the shot is loaded again: an
/// editor's save (a new file written, renamed over the old one) is one change, not several.
pub(super) const QUIET: Duration = Duration::from_millis(100);

/// What reaches the watch loop.
pub(super) enum Message {
    /// A file-system event, or the watcher's error.
    Files(notify::Result<notify::Event>),
    /// Ctrl-C.
    Stop,
}

/// What the watch prints besides errors.
#[derive(Clone, Copy, Debug)]
pub(super) struct Printing {
    /// Each frame's per-stage statistics, as `glint render --stats` prints them.
    pub stats: bool,
    /// Nothing but errors.
    pub quiet: bool,
}

/// Renders the frames of the shot at `shot` as `overrides` ask, then again after every change
/// to one of its input files, until Ctrl-C (exit 0). A change is acted on once the inputs have
/// been quiet for [`QUIET`]. A shot that fails to load, render or write prints its error line
/// and the watch goes on; the next good save renders. Only a shot file that cannot be read at
/// the start, or a watch that cannot be set up, ends the command.
pub(super) fn run(shot: &Path, overrides: &Overrides, printing: Printing) -> Result<(), CliError> {
    std::fs::metadata(shot).map_err(|e| {
        CliError::BadInput(anyhow!("{}: cannot read the file: {e}", shot.display()))
    })?;
    let (sender, messages) = mpsc::channel();
    let stop = Arc::new(AtomicBool::new(false));
    let on_stop = sender.clone();
    let stop_flag = Arc::clone(&stop);
    ctrlc::set_handler(move || {
        stop_flag.store(true, Ordering::SeqCst);
        let _ = on_stop.send(Message::Stop);
    })
    .map_err(|e| CliError::Failed(anyhow!("cannot catch Ctrl-C: {e}")))?;
    let mut watcher = notify::recommended_watcher(move |event| {
        let _ = sender.send(Message::Files(event));
    })
    .map_err(|e| CliError::Failed(anyhow!("cannot watch files: {e}")))?;

    let mut session = Session {
        shot: shot.to_path_buf(),
        overrides: overrides.clone(),
        job: None,
        printing,
        stop,
    };
    let mut watched = WatchedFiles::default();
    session.render(&[]);
    follow(&mut watcher, &mut watched, session.inputs()).map_err(CliError::Failed)?;
    if !printing.quiet {
        let (files, folders) = (watched.len(), watched.folders().count());
        println!(
            "watching {files} file{} in {folders} folder{}; Ctrl-C stops",
            plural(files),
            plural(folders)
        );
    }
    while let Some(changed) = next_change(&messages, &watched) {
        session.render(&changed);
        if let Err(e) = follow(&mut watcher, &mut watched, session.inputs()) {
            eprintln!("error: {e:#}");
        }
    }
    Ok(())
}

/// Waits for a change to a file of `watched` and then for [`QUIET`] without another; returns
/// the files changed, or `None` on Ctrl-C.
pub(super) fn next_change(
    messages: &Receiver<Message>,
    watched: &WatchedFiles,
) -> Option<Vec<PathBuf>> {
    let mut changed: Vec<PathBuf> = Vec::new();
    let mut deadline: Option<Instant> = None;
    loop {
        let message = match deadline {
            None => messages.recv().ok()?,
            Some(at) => match messages.recv_timeout(at.saturating_duration_since(Instant::now())) {
                Ok(message) => message,
                Err(RecvTimeoutError::Timeout) => return Some(changed),
                Err(RecvTimeoutError::Disconnected) => return None,
            },
        };
        match message {
            Message::Stop => return None,
            Message::Files(Err(e)) => eprintln!("error: watching files: {e}"),
            Message::Files(Ok(event)) => {
                let paths = watched.changed_by(&event);
                if !paths.is_empty() {
                    for path in paths {
                        if !changed.iter().any(|p| p == path) {
                            changed.push(path.to_path_buf());
                        }
                    }
                    deadline = Some(Instant::now() + QUIET);
                }
            }
        }
    }
}

/// Makes `watcher` watch the folders of `inputs` and no others, and `watched` follow them.
pub(super) fn follow(
    watcher: &mut RecommendedWatcher,
    watched: &mut WatchedFiles,
    inputs: Vec<PathBuf>,
) -> anyhow::Result<()> {
    let next = WatchedFiles::new(inputs.iter().map(PathBuf::as_path));
    for gone in watched
        .folders()
        .filter(|f| !next.folders().any(|n| n == *f))
    {
        // A folder that was removed is no longer watched anyway.
        let _ = watcher.unwatch(gone);
    }
    let mut result = Ok(());
    for folder in next.folders() {
        if !watched.folders().any(|f| f == folder) {
            if let Err(e) = watcher.watch(folder, RecursiveMode::NonRecursive) {
                result = Err(anyhow!("cannot watch {}: {e}", folder.display()));
            }
        }
    }
    *watched = next;
    result
}

/// The shot being watched and its job, once it has loaded.
struct Session {
    shot: PathBuf,
    overrides: Overrides,
    /// The last job that loaded: its renderer keeps the model's tessellation and the last
    /// frame's surfaces, and its inputs are followed while the shot is broken.
    job: Option<RenderJob>,
    printing: Printing,
    stop: Arc<AtomicBool>,
}

impl Session {
    /// The files to follow: the job's inputs, or the shot file alone until it has loaded.
    fn inputs(&self) -> Vec<PathBuf> {
        self.job
            .as_ref()
            .map_or_else(|| vec![self.shot.clone()], |job| job.inputs().to_vec())
    }

    /// Loads the shot (again, after `changed` changed) and renders its frames, printing one
    /// line for the whole render, or the error line.
    fn render(&mut self, changed: &[PathBuf]) {
        let started = Instant::now();
        match self.try_render() {
            Ok(summary) if !self.printing.quiet => {
                println!("{}", summary.line(changed, started.elapsed()));
            }
            Ok(_) => {}
            Err(e) => eprintln!("error: {:#}", cli_error(e)),
        }
    }

    fn try_render(&mut self) -> Result<Summary, JobError> {
        let job = match &mut self.job {
            Some(job) => {
                job.reload()?;
                job
            }
            None => {
                let job = self
                    .job
                    .insert(RenderJob::load(&self.shot, &self.overrides)?);
                // Previews, made again at the next save: atomic, but not waiting for the disk.
                job.set_durability(Durability::Unsynced);
                job
            }
        };
        job.check_writable()?;
        let mut summary = Summary::default();
        for frame in job.frames().to_vec() {
            if self.stop.load(Ordering::SeqCst) {
                break;
            }
            let image = job.render_frame(frame as f64)?;
            job.write_frame(frame, &image)?;
            for stage in Stage::ALL {
                summary.ran[stage.index()] |= image.stats.ran(stage);
                summary.reused[stage.index()] |= image.stats.reused(stage);
            }
            summary.written.push(job.frame_path(frame));
            if self.printing.stats {
                println!("{}", stats_report(frame, &image.stats));
            }
        }
        Ok(summary)
    }
}

/// What one render of the watch did.
#[derive(Default)]
struct Summary {
    written: Vec<PathBuf>,
    /// Per stage, whether it ran in some frame.
    ran: [bool; Stage::COUNT],
    /// Per stage, whether some frame reused it.
    reused: [bool; Stage::COUNT],
}

impl Summary {
    /// `[CHANGED changed: ]N frames written in T ms: FIRST[ … LAST]; ran STAGES; reused
    /// STAGES`.
    fn line(&self, changed: &[PathBuf], elapsed: Duration) -> String {
        let mut line = String::new();
        if !changed.is_empty() {
            let names: Vec<String> = changed.iter().map(|p| p.display().to_string()).collect();
            line.push_str(&format!("{} changed: ", names.join(", ")));
        }
        let n = self.written.len();
        line.push_str(&format!(
            "{n} frame{} written in {:.0} ms",
            plural(n),
            elapsed.as_secs_f64() * 1e3
        ));
        match self.written.as_slice() {
            [] => {}
            [one] => line.push_str(&format!(": {}", one.display())),
            [first, .., last] => {
                line.push_str(&format!(": {} … {}", first.display(), last.display()));
            }
        }
        let stages = |flags: &[bool; Stage::COUNT]| {
            let names: Vec<&str> = Stage::ALL
                .iter()
                .filter(|s| flags[s.index()])
                .map(|s| s.name())
                .collect();
            if names.is_empty() {
                "none".to_string()
            } else {
                names.join(", ")
            }
        };
        line.push_str(&format!(
            "; ran {}; reused {}",
            stages(&self.ran),
            stages(&self.reused)
        ));
        line
    }
}

/// `"s"` unless there is one.
fn plural(n: usize) -> &'static str {
    if n == 1 {
        ""
    } else {
        "s"
    }
}

/// The command's error for `e`, as `glint render` reports it: bad input (exit 2 there) or a
/// failure (exit 1).
fn cli_error(e: JobError) -> CliError {
    if e.is_bad_input() {
        CliError::BadInput(e.into())
    } else {
        CliError::Failed(e.into())
    }
}
