//! A model: named patches, looked up by name or index, and its named parts (groups of patches).

use std::sync::Arc;

use thiserror::Error;

use super::{NurbsSurface, Trim};

/// One patch of a model.
#[derive(Clone, Debug, PartialEq)]
pub struct NamedPatch {
    pub name: String,
    pub surface: NurbsSurface,
    /// The part of the surface's domain that is drawn, when it is trimmed; shared between the
    /// copies of a patch (instances of a model).
    pub trim: Option<Arc<Trim>>,
}

impl NamedPatch {
    /// Whether `other` has this patch's trim: both none, or the same loops (the one shared
    /// copy, or an equal one).
    #[must_use]
    pub fn same_trim(&self, other: &Self) -> bool {
        match (&self.trim, &other.trim) {
            (None, None) => true,
            (Some(a), Some(b)) => Arc::ptr_eq(a, b) || a == b,
            _ => false,
        }
    }

    /// The untrimmed patch `surface` named `name`.
    #[must_use]
    pub fn new(name: impl Into<String>, surface: NurbsSurface) -> Self {
        Self {
            name: name.into(),
            surface,
            trim: None,
        }
    }

    /// Whether (u, v) is on the drawn part of the patch: anywhere when it is untrimmed.
    #[must_use]
    pub fn keeps(&self, u: f64, v: f64) -> bool {
        self.trim.as_ref().is_none_or(|t| t.contains(u, v))
    }
}

/// A named part of a model: a set of its patches (`lid`, `glass`). Selectors in a shot match
/// group names as they match patch names.
#[derive(Clone, Debug, PartialEq)]
pub struct PatchGroup {
    pub name: String,
    /// Indices into the library's patches, increasing, each once.
    pub patches: Vec<usize>,
}

/// The patches of one model file, in file order, and its named parts.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PatchLibrary {
    pub patches: Vec<NamedPatch>,
    /// Named groups of `patches`, each name distinct from every other group's and patch's.
    pub groups: Vec<PatchGroup>,
}

impl PatchLibrary {
    /// Which of this model's patches `pose` moves, when `pose` is this model posed otherwise:
    /// the same patches, names, parts and trims, each surface the same but (maybe) its control
    /// points ([`NurbsSurface::same_but_points`]); a patch is moved when some control point
    /// differs. None when `pose` is another model.
    #[must_use]
    pub fn try_moved_in(&self, pose: &PatchLibrary) -> Option<Vec<bool>> {
        if self.patches.len() != pose.patches.len() || self.groups != pose.groups {
            return None;
        }
        self.patches
            .iter()
            .zip(&pose.patches)
            .map(|(a, b)| {
                (a.name == b.name && a.same_trim(b) && a.surface.same_but_points(&b.surface))
                    .then(|| a.surface != b.surface)
            })
            .collect()
    }
}

/// A patch name or index that is not in the library.
#[derive(Clone, Debug, Error, PartialEq)]
#[error("no patch '{query}'; the patches are: {}", names.join(", "))]
pub struct PatchNotFound {
    pub query: String,
    pub names: Vec<String>,
}

impl PatchLibrary {
    /// A library of `patches` with no groups.
    #[must_use]
    pub fn new(patches: Vec<NamedPatch>) -> Self {
        Self {
            patches,
            groups: Vec::new(),
        }
    }

    /// The group named `name`, if there is one.
    #[must_use]
    pub fn group(&self, name: &str) -> Option<&PatchGroup> {
        self.groups.iter().find(|g| g.name == name)
    }

    /// Every name that names patches: the parts' names, then the patches'.
    #[must_use]
    pub fn names(&self) -> Vec<&str> {
        self.groups
            .iter()
            .map(|g| g.name.as_str())
            .chain(self.patches.iter().map(|p| p.name.as_str()))
            .collect()
    }

    /// The groups patch `patch` belongs to.
    pub fn groups_of(&self, patch: usize) -> impl Iterator<Item = &PatchGroup> {
        self.groups
            .iter()
            .filter(move |g| g.patches.binary_search(&patch).is_ok())
    }

    /// The patch named `query`, or else, when `query` is a whole number, the patch at that
    /// 0-based index.
    pub fn find(&self, query: &str) -> Result<&NamedPatch, PatchNotFound> {
        self.patches
            .iter()
            .find(|p| p.name == query)
            .or_else(|| {
                query
                    .parse::<usize>()
                    .ok()
                    .and_then(|i| self.patches.get(i))
            })
            .ok_or_else(|| PatchNotFound {
                query: query.to_owned(),
                names: self.patches.iter().map(|p| p.name.clone()).collect(),
            })
    }

    /// Every control point of every patch, patch by patch (the surfaces lie in their hull).
    pub fn control_points(&self) -> impl Iterator<Item = glam::DVec3> + '_ {
        self.patches.iter().flat_map(|p| p.surface.control_points())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::shapes;

    #[test]
    fn find_by_name_then_index_and_list_names_when_missing() {
        let patch = |name: &str| NamedPatch {
            name: name.into(),
            trim: None,
            surface: shapes::plane(1.0, 1.0).unwrap(),
        };
        let lib = PatchLibrary {
            patches: vec![patch("lid"), patch("1"), patch("body")],
            groups: Vec::new(),
        };
        assert_eq!(lib.find("body").unwrap().name, "body");
        assert_eq!(lib.find("1").unwrap().name, "1");
        assert_eq!(lib.find("2").unwrap().name, "body");
        let err = lib.find("spout").unwrap_err();
        assert_eq!(
            err.to_string(),
            "no patch 'spout'; the patches are: lid, 1, body"
        );
    }
}
