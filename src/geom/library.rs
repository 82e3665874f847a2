//! A model: named patches, looked up by name or index.

use thiserror::Error;

use super::NurbsSurface;

/// One patch of a model.
#[derive(Clone, Debug, PartialEq)]
pub struct NamedPatch {
    pub name: String,
    pub surface: NurbsSurface,
}

/// The patches of one model file, in file order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PatchLibrary {
    pub patches: Vec<NamedPatch>,
}

/// A patch name or index that is not in the library.
#[derive(Clone, Debug, Error, PartialEq)]
#[error("no patch '{query}'; the patches are: {}", names.join(", "))]
pub struct PatchNotFound {
    pub query: String,
    pub names: Vec<String>,
}

impl PatchLibrary {
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
            surface: shapes::plane(1.0, 1.0).unwrap(),
        };
        let lib = PatchLibrary {
            patches: vec![patch("lid"), patch("1"), patch("body")],
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
