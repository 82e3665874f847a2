//! The files `glint render --watch` follows: a shot's inputs by their absolute paths, the
//! folders that hold them, and which file-system events change one of them.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use notify::event::{AccessKind, AccessMode};
use notify::{Event, EventKind};

/// The files a watch follows, and the folders they are in.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(super) struct WatchedFiles {
    /// Each file by its absolute path with its folder's symbolic links resolved (the form the
    /// watcher reports events in), to the path it was given as.
    files: BTreeMap<PathBuf, PathBuf>,
    folders: BTreeSet<PathBuf>,
}

impl WatchedFiles {
    /// The files at `paths`, relative to the working folder unless absolute.
    #[must_use]
    pub fn new<'p>(paths: impl IntoIterator<Item = &'p Path>) -> Self {
        let files: BTreeMap<PathBuf, PathBuf> = paths
            .into_iter()
            .map(|path| (resolved(path), path.to_path_buf()))
            .collect();
        let folders = files
            .keys()
            .filter_map(|f| f.parent().map(Path::to_path_buf))
            .collect();
        Self { files, folders }
    }

    /// The folders to watch: editors save by writing a new file and renaming it over the old
    /// one, which a watch on the file itself would lose.
    pub fn folders(&self) -> impl Iterator<Item = &Path> {
        self.folders.iter().map(PathBuf::as_path)
    }

    /// How many files are followed.
    #[must_use]
    pub fn len(&self) -> usize {
        self.files.len()
    }

    /// The followed files `event` changes, as they were given: none for a file opened, read
    /// or closed without writing (reading the inputs must not trigger a render), nor for a
    /// file not followed.
    #[must_use]
    pub fn changed_by(&self, event: &Event) -> Vec<&Path> {
        if !changes_content(event.kind) {
            return Vec::new();
        }
        event
            .paths
            .iter()
            .filter_map(|path| self.files.get(&resolved(path)))
            .map(PathBuf::as_path)
            .collect()
    }
}

/// Whether an event of `kind` can change a file's content: creation, modification (content,
/// name or metadata), removal, and closing a file that was open for writing; not opening,
/// reading or closing after reading.
#[must_use]
fn changes_content(kind: EventKind) -> bool {
    match kind {
        EventKind::Access(AccessKind::Close(AccessMode::Write)) => true,
        EventKind::Access(_) => false,
        EventKind::Any
        | EventKind::Create(_)
        | EventKind::Modify(_)
        | EventKind::Remove(_)
        | EventKind::Other => true,
    }
}

/// `path` made absolute, its folder's symbolic links resolved (the file itself may be missing
/// for a moment while an editor replaces it); `path` made absolute alone when its folder
/// cannot be resolved.
#[must_use]
fn resolved(path: &Path) -> PathBuf {
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    match (absolute.parent(), absolute.file_name()) {
        (Some(folder), Some(name)) => folder
            .canonicalize()
            .map_or_else(|_| absolute.clone(), |folder| folder.join(name)),
        _ => absolute,
    }
}

#[cfg(test)]
mod tests {
    use notify::event::{CreateKind, ModifyKind, RenameMode};

    use super::*;

    fn event(kind: EventKind, paths: &[&Path]) -> Event {
        Event {
            kind,
            paths: paths.iter().map(|p| p.to_path_buf()).collect(),
            attrs: Default::default(),
        }
    }

    #[test]
    fn only_writes_to_followed_files_count_whatever_the_path_spelling() {
        let dir = tempfile::tempdir().unwrap();
        let sub = dir.path().join("looks");
        std::fs::create_dir(&sub).unwrap();
        let shot = dir.path().join("shot.ron");
        let include = sub.join("studio.ron");
        // The include as a shot names it: through a folder and back.
        let roundabout = sub.join("..").join("looks").join("studio.ron");
        let watched = WatchedFiles::new([shot.as_path(), roundabout.as_path()]);
        assert_eq!(watched.len(), 2);
        assert_eq!(watched.folders().count(), 2);

        let saved = event(
            EventKind::Modify(ModifyKind::Name(RenameMode::To)),
            &[&include],
        );
        assert_eq!(watched.changed_by(&saved), [roundabout.as_path()]);
        let both = event(
            EventKind::Modify(ModifyKind::Name(RenameMode::Both)),
            &[&dir.path().join(".shot.ron.swp"), &shot],
        );
        assert_eq!(watched.changed_by(&both), [shot.as_path()]);
        let closed = event(
            EventKind::Access(AccessKind::Close(AccessMode::Write)),
            &[&shot],
        );
        assert_eq!(watched.changed_by(&closed).len(), 1);

        let read = event(
            EventKind::Access(AccessKind::Open(AccessMode::Any)),
            &[&shot],
        );
        assert!(watched.changed_by(&read).is_empty());
        let other_file = event(
            EventKind::Create(CreateKind::File),
            &[&dir.path().join("out.0001.png")],
        );
        assert!(watched.changed_by(&other_file).is_empty());
    }
}
