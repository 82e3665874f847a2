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
    /// It is not UTF-8 text: the bytes from `line`:`col` (1-based, counted in characters of the
    /// valid text before) do not read.
    #[error("the file is not UTF-8 text: the bytes at {line}:{col} do not read as UTF-8")]
    NotUtf8 { line: usize, col: usize },
}

/// The file at `path` as text.
pub fn read_text(path: &Path) -> Result<String, TextError> {
    let bytes = std::fs::read(path)?;
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
