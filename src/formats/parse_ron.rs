//! RON text parsed into a value, its errors placed where they are written.

use super::ron_location;
use super::FormatError;

/// Parses `text` (shown as `shown`) as `T`, with errors placed where they are written: a value
/// that failed its own checks, which serde reports at its closing bracket, at its start.
pub(super) fn parse_ron<T: serde::de::DeserializeOwned>(
    text: &str,
    shown: &str,
) -> Result<T, FormatError> {
    ron::Options::default().from_str(text).map_err(|e| {
        let (at, message) =
            ron_location::explain_at(text, &e.code, (e.span.start.line, e.span.start.col));
        FormatError::Ron {
            path: shown.into(),
            line: at.0,
            col: at.1,
            message,
        }
    })
}
