//! How a job fingerprints its frames: what the whole job shares, hashed once, and each frame's
//! values.

use std::fmt::Write as _;

use sha2::{Digest, Sha256};

use super::fingerprint::Fingerprint;
use super::RenderJob;
use crate::geom::PatchLibrary;

/// The part of every frame's fingerprint that the whole job shares: glint's version, the
/// settings (not the thread count, which changes no byte), the AOVs asked for, the model as
/// placed when nothing moves (a moving shot's model is each frame's own, [`frame_model`]), and
/// the bytes of every patch file and texture but animated USD layers (whose every frame's model
/// is hashed instead). `None` when an asset cannot be read (the job's
/// frames then have no fingerprint, and are never taken as current).
fn job_digest(job: &RenderJob) -> Option<Sha256> {
    let shot = job.shot();
    let mut settings = *job.settings();
    settings.threads = 0;
    let mut hash = Sha256::new();
    let mut text = String::new();
    let _ = write!(
        text,
        "glint {}\n{settings:?}\n{:?}\n",
        env!("CARGO_PKG_VERSION"),
        shot.aovs,
    );
    if !shot.moves() {
        let _ = writeln!(text, "{:?}", shot.library);
    }
    hash.update(text.as_bytes());
    // What a frame uses of an animated USD layer is its model at that frame (`frame_model`):
    // the file's bytes would tie every frame to every sample.
    let deforming: Vec<std::path::PathBuf> = shot
        .deforming_files()
        .filter_map(|f| f.canonicalize().ok())
        .collect();
    for asset in shot.asset_inputs() {
        if asset.canonicalize().is_ok_and(|a| deforming.contains(&a)) {
            continue;
        }
        let bytes = std::fs::read(asset).ok()?;
        hash.update((bytes.len() as u64).to_le_bytes());
        hash.update(&bytes);
    }
    Some(hash)
}

/// Hashes the model a frame of a moving shot draws: per patch its name, trim, knots, weights
/// and every control point to the bit (`{:?}` of the library: an `f64` prints as the shortest
/// text that reads back to the same bits), and the parts. Two frames hash alike only when
/// every patch is posed alike.
fn frame_model(hash: &mut Sha256, library: &PatchLibrary) {
    let mut text = String::new();
    let _ = writeln!(text, "model {library:?}");
    hash.update(text.as_bytes());
}

/// A [`std::fmt::Write`] that feeds what is written into a hash, so that a `Debug` print of a
/// frame's whole input is hashed without being held as text.
struct HashWriter<'a>(&'a mut Sha256);

impl std::fmt::Write for HashWriter<'_> {
    fn write_str(&mut self, s: &str) -> std::fmt::Result {
        self.0.update(s.as_bytes());
        Ok(())
    }
}

impl RenderJob {
    /// The fingerprint of frame `frame`: what the whole job shares (glint's version, the
    /// settings but the thread count, the AOVs, the model as placed when nothing moves, the
    /// bytes of every patch file and texture) and the frame's [`Scene`] — what the renderer is
    /// handed: every patch's look (tone, prepared highlight, line style), the camera, the light,
    /// the outlines and the AOVs — with, when the shot moves, the model posed there. Each is
    /// hashed through its `Debug` print, which names every field (an `f64` prints as the
    /// shortest text that reads back to the same bits; a texture or a smoothed shape as its
    /// size and a digest of its values), so a field added to what a frame is rendered from is
    /// in the fingerprint without being listed here. `None` when an asset cannot be read or the
    /// frame has no scene (it would not render). Two frames share it only when they would be
    /// rendered from the same input, so an edit changes the fingerprints of exactly the frames
    /// whose input it changes.
    ///
    /// [`Scene`]: crate::render::Scene
    #[must_use]
    pub fn fingerprint(&self, frame: i64) -> Option<Fingerprint> {
        let mut hash = self.digest.get_or_init(|| job_digest(self)).clone()?;
        let state = self.shot().at(frame as f64);
        let scene = state.scene(self.shot()).ok()?;
        // Every field, so that a new one must be placed here: the model is the job's when
        // nothing moves, hashed once.
        let crate::render::Scene {
            library,
            looks,
            camera,
            light,
            outlines,
            aovs,
            materials,
        } = &scene;
        let _ = write!(
            HashWriter(&mut hash),
            "{:?}",
            (looks, camera, light, outlines, aovs)
        );
        // Filled only when some patch draws material borders, which read it.
        if !materials.is_empty() {
            let _ = write!(HashWriter(&mut hash), "{materials:?}");
        }
        if self.shot().moves() {
            frame_model(&mut hash, library);
        }
        let digest = hash.finalize();
        Some(Fingerprint(
            digest[..16].iter().map(|b| format!("{b:02x}")).collect(),
        ))
    }
}
