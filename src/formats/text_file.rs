//! A text file read whole, with the place of the first byte that is not UTF-8 when it is not
//! text.

use std::path::Path;

use thiserror::Error;

/// Why a text file could not be read.
#[derive(Debug, Error)]
pub enum TextError {
    /// It could not be read at all.
    #[error("cannot read the file: {0}")]
    Io(#[from] std::io::Error),
    /// It is not a regular file (a folder, a device such as `/dev/zero`).
    #[error("it is not a regular file")]
    NotAFile,
    /// It is larger than [`MAX_TEXT_BYTES`].
    #[error("it is larger than {} MiB, the most a shot, look or patch file may hold", MAX_TEXT_BYTES >> 20)]
    TooLarge,
    /// It is not UTF-8 text: the bytes from `line`:`col` (1-based, counted in characters of the
    /// valid text before) do not read.
    #[error("the file is not UTF-8 text: the bytes at {line}:{col} do not read as UTF-8")]
    NotUtf8 { line: usize, col: usize },
}

/// The largest text file glint reads: 256 MiB, far beyond any shot or model written by hand
/// or exported, and checked before reading so that no file makes it read without end.
pub const MAX_TEXT_BYTES: u64 = 256 << 20;

/// The file at `path` as text: a regular file of at most [`MAX_TEXT_BYTES`].
pub fn read_text(path: &Path) -> Result<String, TextError> {
    use std::io::Read as _;
    let file = std::fs::File::open(path)?;
    let meta = file.metadata()?;
    if !meta.is_file() {
        return Err(TextError::NotAFile);
    }
    if meta.len() > MAX_TEXT_BYTES {
        return Err(TextError::TooLarge);
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    // A file that grows while it is read still stops at the limit.
    file.take(MAX_TEXT_BYTES + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > MAX_TEXT_BYTES {
        return Err(TextError::TooLarge);
    }
    String::from_utf8(bytes).map_err(|e| {
        let valid = &e.as_bytes()[..e.utf8_error().valid_up_to()];
        // Up to `valid_up_to` the bytes are UTF-8.
        let before = std::str::from_utf8(valid).unwrap_or_default();
        let line = before.matches('\n').count() + 1;
        let col = before
            .rsplit('\n')
            .next()
            .unwrap_or_default()
            .chars()
            .count()
            + 1;
        TextError::NotUtf8 { line, col }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_byte_that_is_not_text_is_placed() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("a.ron");
        std::fs::write(&path, b"Shot(\n  name: \"\xc3\xa9t\xe9\"\n)").unwrap();
        match read_text(&path) {
            Err(TextError::NotUtf8 { line, col }) => assert_eq!((line, col), (2, 12)),
            other => panic!("{other:?}"),
        }
        std::fs::write(&path, "Shot()").unwrap();
        assert_eq!(read_text(&path).unwrap(), "Shot()");
        assert!(matches!(
            read_text(&dir.path().join("none")),
            Err(TextError::Io(_))
        ));
    }
}
