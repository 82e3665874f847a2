//! What is said of a selector's pattern that picks no patch: the closest name, or how names
//! are made.

use crate::formats::ron_location::closest_name;
use crate::geom::PatchLibrary;

/// What is said of a selector's `pattern` that picks nothing in `library`: the closest name,
/// or how names are made.
#[must_use]
pub(super) fn no_match_message(pattern: &str, library: &PatchLibrary) -> String {
    let names = library.names();
    let mut message = format!("the selector \"{pattern}\" matches no patch or part");
    match closest_name(pattern, &names) {
        Some(close) => message.push_str(&format!("; did you mean \"{close}\"?")),
        None => message.push_str(&format!(
            "; patches are named INSTANCE/PATCH and parts INSTANCE/PART, e.g. \"{}\"",
            names.first().copied().unwrap_or("ball/0")
        )),
    }
    message
}
