//! `glint render --watch` end to end: the binary renders a tiny shot, renders it again after
//! an edit saved as editors save (a new file renamed over the old), prints one error line for
//! a broken edit and keeps watching, renders the fix, and exits 0 on Ctrl-C. Each event is
//! waited for up to a generous deadline; no duration is asserted.

use std::io::{BufRead, BufReader, Read};
use std::path::Path;
use std::process::{Child, Stdio};
use std::sync::mpsc::{self, Receiver};
use std::time::{Duration, Instant};

use crate::common::ball_shot::{save_as_an_editor_does, BallShot};
use crate::common::{glint, repo_file};

/// How long any one event may take to show: far beyond what it needs, so that only an event
/// that never comes fails the test.
const DEADLINE: Duration = Duration::from_secs(60);

/// The watching process, killed when the test ends however it ends.
struct Watching {
    child: Child,
    lines: Receiver<String>,
    /// Every line read so far, for failure messages.
    seen: Vec<String>,
}

impl Drop for Watching {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Watching {
    fn start(shot: &Path) -> Self {
        let mut child = glint()
            .args(["render", shot.to_str().unwrap(), "--watch"])
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("the glint binary runs");
        let (sender, lines) = mpsc::channel();
        let stdout = child.stdout.take().unwrap();
        let stderr = child.stderr.take().unwrap();
        for (stream, tag) in [
            (Box::new(stdout) as Box<dyn Read + Send>, "out"),
            (Box::new(stderr), "err"),
        ] {
            let sender = sender.clone();
            std::thread::spawn(move || {
                for line in BufReader::new(stream).lines().map_while(Result::ok) {
                    if sender.send(format!("{tag}: {line}")).is_err() {
                        break;
                    }
                }
            });
        }
        Self {
            child,
            lines,
            seen: Vec::new(),
        }
    }

    /// The next line that `wanted` accepts, waiting up to [`DEADLINE`].
    fn wait_for(&mut self, what: &str, wanted: impl Fn(&str) -> bool) -> String {
        let until = Instant::now() + DEADLINE;
        loop {
            let left = until.saturating_duration_since(Instant::now());
            match self.lines.recv_timeout(left) {
                Ok(line) => {
                    self.seen.push(line.clone());
                    if wanted(&line) {
                        return line;
                    }
                }
                Err(_) => panic!("no {what} within {DEADLINE:?}; lines: {:#?}", self.seen),
            }
        }
    }

    /// Sends Ctrl-C (SIGINT) and waits for the exit code.
    fn interrupt(&mut self) -> Option<i32> {
        let sent = std::process::Command::new("kill")
            .args(["-INT", &self.child.id().to_string()])
            .status()
            .expect("kill runs");
        assert!(sent.success());
        let until = Instant::now() + DEADLINE;
        while Instant::now() < until {
            if let Some(status) = self.child.try_wait().unwrap() {
                return status.code();
            }
            std::thread::sleep(Duration::from_millis(20));
        }
        panic!("glint did not stop on Ctrl-C; lines: {:#?}", self.seen);
    }
}

/// The one-frame shot of the ball, 24×24, with a highlight of width `epsilon`.
fn shot_text(epsilon: f32) -> String {
    BallShot {
        size: (24, 24),
        epsilon,
        lit: "(0.2, 0.3, 0.7)",
        include: None,
        preset: Some("Preview"),
    }
    .text()
}

fn is_frame_line(line: &str) -> bool {
    line.starts_with("out: ") && line.contains("1 frame written")
}

#[test]
fn edits_render_a_broken_edit_prints_its_error_and_the_fix_renders() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(
        repo_file("patches/sphere.ron"),
        dir.path().join("sphere.ron"),
    )
    .unwrap();
    let shot = dir.path().join("ball.ron");
    let frame = dir.path().join("out/ball.1.png");
    save_as_an_editor_does(&shot, &shot_text(0.02));

    let mut watching = Watching::start(&shot);
    watching.wait_for("first frame", is_frame_line);
    watching.wait_for("watching line", |l| l.starts_with("out: watching 2 files"));
    let first = std::fs::read(&frame).unwrap();

    save_as_an_editor_does(&shot, &shot_text(0.15));
    let line = watching.wait_for("frame after the edit", is_frame_line);
    assert!(line.contains("ball.ron changed"), "{line}");
    assert!(
        line.contains("reused tessellate, rasterize, gbuffer"),
        "a highlight edit reuses the surfaces: {line}"
    );
    let edited = std::fs::read(&frame).unwrap();
    assert_ne!(first, edited, "the wider highlight is in the new frame");

    save_as_an_editor_does(&shot, &shot_text(0.15).replace("epsilon", "epsilom"));
    let error = watching.wait_for("error line", |l| l.starts_with("err: "));
    assert!(
        error.starts_with(&format!("err: error: {}:", shot.display())),
        "one line naming the file: {error}"
    );
    assert!(error.contains("epsilom"), "{error}");

    save_as_an_editor_does(&shot, &shot_text(0.3));
    watching.wait_for("frame after the fix", is_frame_line);
    let fixed = std::fs::read(&frame).unwrap();
    assert!(fixed != edited && fixed != first);

    assert_eq!(watching.interrupt(), Some(0), "Ctrl-C ends the watch");
}

#[test]
fn a_shot_that_is_not_there_is_bad_input_at_once() {
    let out = glint()
        .args(["render", "shots/no_such_shot.ron", "--watch"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.starts_with("error: shots/no_such_shot.ron: cannot read the file"),
        "{stderr}"
    );
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
}
