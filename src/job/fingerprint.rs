//! What made a frame: a hash of everything its pixels depend on, written into its files so that
//! a later run can tell a frame made from the current inputs from one made from older ones.

/// The name a frame's fingerprint is stored under: a PNG text chunk's keyword, an EXR header
/// attribute's name.
pub const FINGERPRINT_KEY: &str = "glint:fingerprint";

/// The fingerprint of a frame: 32 hex digits (128 bits of SHA-256).
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Fingerprint(pub String);

impl std::fmt::Display for Fingerprint {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}
