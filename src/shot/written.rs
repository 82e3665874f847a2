//! Where an entry of a shot's list is written.

/// Where an entry of a list is written: the file (index into the sources) and its place in
/// that file's list.
#[derive(Clone, Copy, Debug)]
pub(super) struct Written {
    pub source: usize,
    pub index: usize,
}
