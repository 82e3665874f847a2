//! A shot or look file's text read for editing, before an edit and back after it, its problems as
//! edit errors at their place.

use super::error::EditError;
use super::param_sites::ParsedFile;
use crate::shot::ShotError;

/// The text read as a shot or look file.
pub(super) fn read_file(text: &str) -> Result<ParsedFile, EditError> {
    ParsedFile::parse(text).map_err(|e| match e {
        ShotError::At {
            line, col, message, ..
        } => EditError::Parse { line, col, message },
        ShotError::File { message, .. } => EditError::Parse {
            line: 1,
            col: 1,
            message,
        },
    })
}

/// `edited` when it reads back as `expected` (the file as first read, with the one `what` it
/// edits changed); otherwise why not.
pub(super) fn read_back(
    edited: String,
    expected: &ParsedFile,
    what: &str,
) -> Result<String, String> {
    match read_file(&edited) {
        Ok(reread) if reread == *expected => Ok(edited),
        Ok(_) => Err(format!(
            "the edited file reads back with more changed than this {what}"
        )),
        Err(e) => Err(format!("the edited file does not read back (at {e})")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shot::fixtures::STYLED_SHOT;

    #[test]
    fn an_edit_is_kept_only_when_it_reads_back_as_the_file_with_its_one_track_changed() {
        let expected = read_file(STYLED_SHOT).unwrap();
        assert_eq!(
            read_back(STYLED_SHOT.to_string(), &expected, "track").as_deref(),
            Ok(STYLED_SHOT)
        );
        // A splice gone wrong: a number the edit did not ask for changed as well.
        let changed = STYLED_SHOT.replace("fps: 24", "fps: 25");
        let reason = read_back(changed, &expected, "track").unwrap_err();
        assert!(reason.contains("more changed than this track"), "{reason}");
        // Or a file that no longer parses.
        let reason = read_back(format!("{STYLED_SHOT})"), &expected, "track").unwrap_err();
        assert!(reason.contains("does not read back"), "{reason}");
    }
}
