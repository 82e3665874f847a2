//! Hostile input replayed through every reader: the checked-in corpus (`tests/fuzz/corpus/`,
//! inputs that once broke a reader, shrunk) and seeded mutations of every shipped shot, look
//! library, patch file and toon texture, each loaded and, when it loads, rendered at 8 × 8 —
//! no panic, no NaN or infinite pixel, every error one line. The same readers are the targets
//! of `cargo fuzz` (`fuzz/`), which searches far wider; what it finds is shrunk into the corpus.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::{Path, PathBuf};

use glint::formats::{parse_bpt, parse_patch_ron, parse_usda, toon_texture_from_png};
use glint::job::{parse_frames, Overrides, RenderJob};
use glint::shot::{load_shot_text, Preset};

use crate::common::{glint, repo_file, stderr};

/// How many refused shots are also given to `glint render`, to see the refusal as a user does.
const REFUSALS_THROUGH_THE_BINARY: usize = 40;

/// Mutations of each shipped text file; `GLINT_FUZZ_CASES` asks for more.
const CASES_PER_FILE: usize = 300;

fn cases_per_file() -> usize {
    std::env::var("GLINT_FUZZ_CASES")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(CASES_PER_FILE)
}

/// A small seeded generator (xorshift64*), so that every run tries the same inputs.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_f491_4f6c_dd1d)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// Numbers that sit on a boundary of some range, or beyond every one.
const NUMBERS: &[&str] = &[
    "0", "-0.0", "1", "-1", "0.5", "2", "1e-300", "1e300", "-1e308", "1e6", "1000001", "1e38",
    "3.4e38", "NaN", "inf", "-inf", "65536", "16385", "999999", "-999999", "0.0001",
];

/// Tokens that break structure: brackets, separators, quotes, comments, includes.
const TOKENS: &[&str] = &[
    "(",
    ")",
    "[",
    "]",
    "{",
    "}",
    ",",
    ":",
    "\"",
    "//",
    "/*",
    "\n",
    "Some(",
    "None",
    "\u{0}",
    "é",
    "includes: [\"/dev/zero\"],",
    "includes: [\"fuzz.ron\"],",
    "[(1, 0.0), (1, 1.0)]",
    "[(1e300, 0.0)]",
    "\"*\"",
    "\"\"",
];

/// `text` changed in one or two places: a number replaced by a boundary value, a span
/// deleted or doubled, a token inserted, two lines swapped, a character replaced.
fn mutate(text: &str, rng: &mut Rng) -> String {
    let mut bytes = text.as_bytes().to_vec();
    for _ in 0..1 + rng.below(4) / 2 {
        let len = bytes.len().max(1);
        let at = rng.below(len).min(bytes.len());
        match rng.below(6) {
            0 => {
                // The number that starts at or after `at`.
                let Some(start) = (at..bytes.len()).find(|&i| bytes[i].is_ascii_digit()) else {
                    continue;
                };
                let end = (start..bytes.len())
                    .find(|&i| !(bytes[i].is_ascii_alphanumeric() || b".-+".contains(&bytes[i])))
                    .unwrap_or(bytes.len());
                let number = NUMBERS[rng.below(NUMBERS.len())].as_bytes();
                bytes.splice(start..end, number.iter().copied());
            }
            1 => {
                let end = (at + 1 + rng.below(24)).min(bytes.len());
                bytes.drain(at..end);
            }
            2 => {
                let end = (at + 1 + rng.below(64)).min(bytes.len());
                let span = bytes[at..end].to_vec();
                bytes.splice(at..at, span);
            }
            3 => {
                let token = TOKENS[rng.below(TOKENS.len())].as_bytes();
                bytes.splice(at..at, token.iter().copied());
            }
            4 => {
                let text = String::from_utf8_lossy(&bytes).into_owned();
                let mut lines: Vec<&str> = text.lines().collect();
                if lines.len() > 1 {
                    let (a, b) = (rng.below(lines.len()), rng.below(lines.len()));
                    lines.swap(a, b);
                }
                bytes = lines.join("\n").into_bytes();
            }
            _ => {
                if at < bytes.len() {
                    bytes[at] = b" ,:()[]{}\"0123456789.-eE_aZ"[rng.below(27)];
                }
            }
        }
    }
    String::from_utf8_lossy(&bytes).into_owned()
}

/// What the replay saw.
#[derive(Default)]
struct Tally {
    inputs: usize,
    loaded: usize,
    rendered: usize,
    failures: Vec<String>,
}

impl Tally {
    /// Runs `case` on the input `name`, catching a panic; `Err` is a reader's refusal (which
    /// the command line prints on one line, with any line break in a name escaped: checked
    /// through the binary on a sample).
    fn run(
        &mut self,
        name: &str,
        input: &str,
        case: impl FnOnce(&mut Tally) -> Result<(), String>,
    ) {
        self.inputs += 1;
        let outcome = catch_unwind(AssertUnwindSafe(|| {
            let mut tally = Tally::default();
            let result = case(&mut tally);
            (result, tally.loaded, tally.rendered, tally.failures)
        }));
        let failure = match outcome {
            Ok((result, loaded, rendered, failures)) => {
                self.loaded += loaded;
                self.rendered += rendered;
                self.failures.extend(failures);
                match result {
                    Err(message) if message.is_empty() => Some("an empty refusal".to_string()),
                    Err(_) | Ok(()) => None,
                }
            }
            Err(_) => Some("a panic".to_string()),
        };
        if let Some(what) = failure {
            let dir = repo_file("target/fuzz-failures");
            std::fs::create_dir_all(&dir).unwrap();
            let kept = dir.join(format!("{}-{}", self.inputs, name.replace('/', "_")));
            std::fs::write(&kept, input).unwrap();
            self.failures.push(format!("{what} on {}", kept.display()));
        }
    }
}

/// Loads `text` as the shot at `path` and, when it loads, renders its first frame at 8 × 8.
fn shot_case(path: &Path, text: &str, tally: &mut Tally) -> Result<(), String> {
    let shot = load_shot_text(path, text.to_string()).map_err(|e| e.to_string())?;
    tally.loaded += 1;
    let first = shot.frames.0;
    let overrides = Overrides {
        frames: Some(vec![first]),
        size: Some((8, 8)),
        preset: Some(Preset::Preview),
        threads: Some(1),
        max_memory: Some(1 << 30),
        ..Overrides::default()
    };
    let mut job = RenderJob::new(shot, &overrides).map_err(|e| e.to_string())?;
    let frame = job.render_frame(first as f64).map_err(|e| e.to_string())?;
    tally.rendered += 1;
    if frame.colour.iter().any(|c| !c.is_finite()) {
        tally.failures.push(format!(
            "a pixel that is not finite, from {}",
            path.display()
        ));
    }
    Ok(())
}

/// The shipped files of `folder` ending in `extension`.
fn shipped(folder: &str, extension: &str) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(repo_file(folder))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == extension))
        .collect();
    files.sort();
    files
}

#[test]
fn mutated_shots_patches_and_textures_never_panic_or_render_nan() {
    let cases = cases_per_file();
    let mut tally = Tally::default();
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    let mut refused = Vec::new();
    // Shots and look libraries, each mutated where it lies, so that what it names resolves.
    let mut texts = shipped("shots", "ron");
    texts.extend(shipped("shots/looks", "ron"));
    for path in &texts {
        let text = std::fs::read_to_string(path).unwrap();
        let is_shot = text.contains("Shot(");
        for _ in 0..cases {
            let mutated = mutate(&text, &mut rng);
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            if is_shot {
                if refused.len() < REFUSALS_THROUGH_THE_BINARY
                    && load_shot_text(path, mutated.clone()).is_err()
                {
                    refused.push(mutated.clone());
                }
                tally.run(&name, &mutated, |t| shot_case(path, &mutated, t));
            } else {
                // A look library, included by a shot that uses nothing of it.
                let dir = tempfile::tempdir().unwrap();
                std::fs::write(dir.path().join("looks.ron"), &mutated).unwrap();
                let shot = dir.path().join("shot.ron");
                let sphere = repo_file("patches/sphere.ron");
                let text = sphere_shot("includes: [\"looks.ron\"],", &sphere.display().to_string());
                tally.run(&name, &mutated, |t| shot_case(&shot, &text, t));
            }
        }
    }
    // Patch files, read and rendered in a shot of their own.
    for path in shipped("patches", "ron")
        .into_iter()
        .chain(shipped("patches", "bpt"))
        .chain(shipped("patches", "usda"))
    {
        let text = std::fs::read_to_string(&path).unwrap();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if name.ends_with(".parts.ron") {
            continue;
        }
        let extension = path.extension().unwrap().to_string_lossy().into_owned();
        for _ in 0..cases {
            let mutated = mutate(&text, &mut rng);
            tally.run(&name, &mutated, |t| {
                let read = match extension.as_str() {
                    "bpt" => parse_bpt(&mutated, &name),
                    "usda" => parse_usda(&mutated, &name),
                    _ => parse_patch_ron(&mutated, &name),
                };
                read.map_err(|e| e.to_string())?;
                let dir = tempfile::tempdir().unwrap();
                let model = dir.path().join(format!("model.{extension}"));
                std::fs::write(&model, &mutated).unwrap();
                let shot = dir.path().join("shot.ron");
                let text = sphere_shot("", model.to_str().unwrap());
                shot_case(&shot, &text, t)
            });
        }
    }
    // Toon textures: bytes flipped, cut short or doubled.
    for path in shipped("textures", "png") {
        let bytes = std::fs::read(&path).unwrap();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        for _ in 0..cases / 4 {
            let mut mutated = bytes.clone();
            for _ in 0..1 + rng.below(4) {
                let at = rng.below(mutated.len());
                match rng.below(3) {
                    0 => mutated[at] ^= 1 << rng.below(8),
                    1 => mutated.truncate(at.max(8)),
                    _ => {
                        let span = mutated[at..(at + 64).min(mutated.len())].to_vec();
                        mutated.splice(at..at, span);
                    }
                }
            }
            tally.run(&name, &String::from_utf8_lossy(&mutated), |t| {
                let texture = toon_texture_from_png(&mutated, &name).map_err(|e| e.to_string())?;
                t.loaded += 1;
                let (w, h) = (texture.width(), texture.height());
                for (x, y) in [(0, 0), (w - 1, h - 1), (w / 2, h / 2)] {
                    if !texture.texel(x, y).is_finite() {
                        t.failures
                            .push(format!("a texel that is not finite in {name}"));
                    }
                }
                Ok(())
            });
        }
    }
    // Frame lists: short strings of the characters they are written with.
    for _ in 0..cases * 4 {
        let spec: String = (0..1 + rng.below(16))
            .map(|_| "0123456789-,x 9"[rng.below(15)..].chars().next().unwrap())
            .collect();
        tally.run("frames", &spec, |_| {
            let frames = parse_frames(&spec)?;
            assert!(frames.len() <= 1_000_000, "{spec}: {} frames", frames.len());
            Ok(())
        });
    }
    println!(
        "{} inputs: {} loaded, {} rendered, {} failures",
        tally.inputs,
        tally.loaded,
        tally.rendered,
        tally.failures.len()
    );
    assert!(tally.failures.is_empty(), "{}", tally.failures.join("\n"));
    refusals_are_one_line_through_the_binary(&refused);
    // The mutations must reach the renderer, not only the parser's first error.
    assert!(
        tally.rendered * 10 >= tally.inputs,
        "{} of {} rendered",
        tally.rendered,
        tally.inputs
    );
}

/// A shot of the model at `model` (an absolute path) under a plain camera and light, with
/// `extra` fields.
fn sphere_shot(extra: &str, model: &str) -> String {
    format!(
        r#"Shot(
    resolution: (8, 8), frames: (1, 1), fps: 24, output: "out/f.####.png", {extra}
    instances: [(name: "m", file: "{model}", material: "c")],
    materials: {{"c": Cel(base: (0.1, 0.1, 0.1), bands: [(0.0, (0.5, 0.5, 0.5))])}},
    camera: (eye: (0.0, -8.0, 2.0), target: (0.0, 0.0, 0.0), projection: Perspective(fov_y_degrees: 40.0)),
    light: Directional(towards: (0.3, -1.0, 0.5)),
    highlights: [(patches: "m/*", expr: Layer((stack: [Translate(alpha: 0.1, beta: 0.0)], epsilon: 0.05, colour: (1.0, 1.0, 1.0))))],
    render: (outlines: (width: 1.0, colour: (0.0, 0.0, 0.0))),
)"#
    )
}

#[test]
fn the_corpus_of_inputs_that_once_broke_a_reader_is_refused_or_rendered_cleanly() {
    let mut tally = Tally::default();
    let corpus = repo_file("tests/fuzz/corpus");
    let mut files: Vec<PathBuf> = std::fs::read_dir(&corpus)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    files.sort();
    assert!(files.len() >= 8, "{files:?}");
    for path in files {
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        let text = String::from_utf8_lossy(&std::fs::read(&path).unwrap()).into_owned();
        // A shot of the corpus reads the shipped models as a shot in `shots/` would.
        let as_shot = repo_file("shots").join(&name);
        match name.split('-').next().unwrap() {
            "shot" => tally.run(&name, &text, |t| shot_case(&as_shot, &text, t)),
            "patch" => tally.run(&name, &text, |_| {
                parse_patch_ron(&text, &name)
                    .map(|_| ())
                    .map_err(|e| e.to_string())
            }),
            "bpt" => tally.run(&name, &text, |_| {
                parse_bpt(&text, &name)
                    .map(|_| ())
                    .map_err(|e| e.to_string())
            }),
            "usda" => tally.run(&name, &text, |_| {
                parse_usda(&text, &name)
                    .map(|_| ())
                    .map_err(|e| e.to_string())
            }),
            "frames" => tally.run(&name, &text, |_| parse_frames(text.trim()).map(|_| ())),
            other => panic!("{name}: no reader for corpus files named {other}-…"),
        }
    }
    assert!(tally.failures.is_empty(), "{}", tally.failures.join("\n"));
}

/// Renders each of `shots` (refused by the loader) with the binary, from a folder beside links
/// to the shipped models and textures: exit 2, one line, nothing written.
fn refusals_are_one_line_through_the_binary(shots: &[String]) {
    let dir = tempfile::tempdir().unwrap();
    for folder in ["patches", "textures"] {
        std::os::unix::fs::symlink(repo_file(folder), dir.path().join(folder)).unwrap();
    }
    std::fs::create_dir(dir.path().join("shots")).unwrap();
    std::fs::create_dir(dir.path().join("shots/looks")).unwrap();
    std::fs::copy(
        repo_file("shots/looks/studio.ron"),
        dir.path().join("shots/looks/studio.ron"),
    )
    .unwrap();
    for (k, text) in shots.iter().enumerate() {
        let shot = dir.path().join(format!("shots/refused{k}.ron"));
        std::fs::write(&shot, text).unwrap();
        let out = glint()
            .current_dir(dir.path())
            .args([
                "render",
                shot.to_str().unwrap(),
                "--size",
                "8x8",
                "--out",
                "out/f.####.png",
            ])
            .output()
            .unwrap();
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{}: {err}", shot.display());
        assert_eq!(err.lines().count(), 1, "{}: {err:?}", shot.display());
        assert!(
            !dir.path().join("out").exists(),
            "{}: output written",
            shot.display()
        );
    }
}
