//! Named parts of a model: groups of its patches, written in a patch library's `groups` or in
//! a `NAME.parts.ron` file beside the model (the only way for `.bpt` files, whose patches have
//! no names), and resolved against the model's patches.

use std::collections::BTreeMap;
use std::fmt;
use std::path::{Path, PathBuf};

use serde::de::{self, Deserializer, Visitor};
use serde::Deserialize;

use super::parse_ron::parse_ron;
use super::ron_location::closest_name;
use super::ron_paths::Step;
use super::FormatError;
use crate::geom::{NamedPatch, PatchGroup};

/// Groups as written: each name with its members.
pub type GroupsSpec = BTreeMap<String, Vec<Member>>;

/// A member of a group as written: a patch's name, or its 0-based index in the file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Member {
    Name(String),
    Index(u64),
}

impl fmt::Display for Member {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Member::Name(name) => write!(f, "\"{name}\""),
            Member::Index(index) => write!(f, "{index}"),
        }
    }
}

impl<'de> Deserialize<'de> for Member {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct MemberVisitor;
        impl Visitor<'_> for MemberVisitor {
            type Value = Member;
            fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
                f.write_str("a patch name (\"lid\") or a 0-based patch index (20)")
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Member, E> {
                Ok(Member::Name(v.to_string()))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Member, E> {
                Ok(Member::Index(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Member, E> {
                u64::try_from(v).map(Member::Index).map_err(|_| {
                    E::custom(format!("patch index {v} is negative; indices count from 0"))
                })
            }
        }
        deserializer.deserialize_any(MemberVisitor)
    }
}

/// A `NAME.parts.ron` file: `Parts(groups: {"lid": [24, 25, 26, 27], …})`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields, rename = "Parts")]
struct PartsFile {
    groups: GroupsSpec,
}

/// The parts file of the model at `model`: `teapot.bpt` → `teapot.parts.ron`.
#[must_use]
pub fn parts_file(model: &Path) -> PathBuf {
    model.with_extension("parts.ron")
}

/// For a parts file (`NAME.parts.ron`), the model it is beside: `NAME.bpt` where that exists,
/// else `NAME.ron`.
#[must_use]
pub fn model_of_parts_file(path: &Path) -> Option<PathBuf> {
    let name = path.file_name()?.to_str()?;
    let stem = name.strip_suffix(".parts.ron")?;
    let bpt = path.with_file_name(format!("{stem}.bpt"));
    Some(if bpt.exists() {
        bpt
    } else {
        path.with_file_name(format!("{stem}.ron"))
    })
}

/// A group that cannot be made: which group, which member (if one), and why.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GroupError {
    pub group: String,
    /// The member's place in the group's list, when one member is at fault.
    pub member: Option<usize>,
    pub message: String,
}

impl GroupError {
    /// Where the fault is written, below `groups` (a path of [`Step`]s ending in the group's
    /// entry or the member's item).
    #[must_use]
    pub fn path<'a>(&'a self, to_groups: &[Step<'a>]) -> Vec<Step<'a>> {
        let mut path = to_groups.to_vec();
        path.push(Step::Entry(&self.group));
        path.extend(self.member.map(Step::Index));
        path
    }
}

/// The groups `spec` of a model whose patches are `patches`, with names not among `taken`
/// (groups already defined). Group names must be non-empty, without `/` and differ from every
/// patch name; each member must name a patch; a group must have at least one.
pub fn resolve_groups(
    spec: &GroupsSpec,
    patches: &[NamedPatch],
    taken: &[PatchGroup],
) -> Result<Vec<PatchGroup>, GroupError> {
    let mut groups = Vec::with_capacity(spec.len());
    for (name, members) in spec {
        let fault = |member: Option<usize>, message: String| GroupError {
            group: name.clone(),
            member,
            message,
        };
        if name.is_empty() || name.contains('/') {
            return Err(fault(
                None,
                format!("the group name \"{name}\" must be non-empty and without `/`"),
            ));
        }
        if patches.iter().any(|p| p.name == *name) {
            return Err(fault(
                None,
                format!("the group name \"{name}\" is also a patch's name; a selector could not tell them apart"),
            ));
        }
        if taken.iter().any(|g| g.name == *name) {
            return Err(fault(
                None,
                format!("the group \"{name}\" is already defined for this model"),
            ));
        }
        if members.is_empty() {
            return Err(fault(
                None,
                format!("the group \"{name}\" names no patch; list at least one"),
            ));
        }
        let mut indices = Vec::with_capacity(members.len());
        for (k, member) in members.iter().enumerate() {
            let index = match member {
                Member::Name(wanted) => patches.iter().position(|p| p.name == *wanted),
                Member::Index(i) => usize::try_from(*i).ok().filter(|&i| i < patches.len()),
            };
            let Some(index) = index else {
                let names: Vec<&str> = patches.iter().map(|p| p.name.as_str()).collect();
                let close = match member {
                    Member::Name(wanted) => closest_name(wanted, &names),
                    Member::Index(_) => None,
                };
                let hint = match close {
                    Some(close) => format!("; did you mean \"{close}\"?"),
                    None => format!(
                        "; the model has {} patches, named {}",
                        patches.len(),
                        name_range(&names)
                    ),
                };
                return Err(fault(
                    Some(k),
                    format!("group \"{name}\": no patch {member}{hint}"),
                ));
            };
            indices.push(index);
        }
        indices.sort_unstable();
        indices.dedup();
        groups.push(PatchGroup {
            name: name.clone(),
            patches: indices,
        });
    }
    Ok(groups)
}

/// "\"a\", \"b\", …" for a few names, "\"0\" … \"31\"" for many.
fn name_range(names: &[&str]) -> String {
    match names {
        [] => "nothing".into(),
        [first, .., last] if names.len() > 6 => format!("\"{first}\" … \"{last}\""),
        _ => names
            .iter()
            .map(|n| format!("\"{n}\""))
            .collect::<Vec<_>>()
            .join(", "),
    }
}

/// Reads the parts file at `path` for a model whose patches are `patches` and that already has
/// the groups `taken`; errors name the file, line and column.
pub fn read_parts_file(
    path: &Path,
    patches: &[NamedPatch],
    taken: &[PatchGroup],
) -> Result<Vec<PatchGroup>, FormatError> {
    let shown = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|source| FormatError::Io {
        path: shown.clone(),
        source,
    })?;
    let file: PartsFile = parse_ron(&text, &shown)?;
    resolve_groups(&file.groups, patches, taken).map_err(|e| {
        FormatError::ron_at(
            &text,
            &shown,
            &e.path(&[Step::Field("groups")]),
            e.message.clone(),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::shapes;

    fn patches(names: &[&str]) -> Vec<NamedPatch> {
        names
            .iter()
            .map(|name| NamedPatch {
                name: (*name).into(),
                trim: None,
                surface: shapes::plane(1.0, 1.0).unwrap(),
            })
            .collect()
    }

    fn spec(groups: &[(&str, Vec<Member>)]) -> GroupsSpec {
        groups
            .iter()
            .map(|(name, members)| ((*name).to_string(), members.clone()))
            .collect()
    }

    #[test]
    fn members_by_name_or_index_become_sorted_unique_indices() {
        let model = patches(&["hood", "roof", "trunk"]);
        let groups = resolve_groups(
            &spec(&[(
                "body",
                vec![
                    Member::Name("trunk".into()),
                    Member::Index(0),
                    Member::Name("hood".into()),
                ],
            )]),
            &model,
            &[],
        )
        .unwrap();
        assert_eq!(
            groups,
            vec![PatchGroup {
                name: "body".into(),
                patches: vec![0, 2]
            }]
        );
    }

    #[test]
    fn every_fault_names_its_group_and_member() {
        let model = patches(&["hood", "roof"]);
        let fails = |groups: GroupsSpec, taken: &[PatchGroup]| {
            resolve_groups(&groups, &model, taken).unwrap_err()
        };
        let e = fails(spec(&[("g", vec![Member::Name("rof".into())])]), &[]);
        assert_eq!(
            (e.member, e.message.contains("did you mean \"roof\"")),
            (Some(0), true)
        );
        let e = fails(
            spec(&[("g", vec![Member::Index(0), Member::Index(2)])]),
            &[],
        );
        assert_eq!(e.member, Some(1));
        assert!(e.message.contains("2 patches"), "{}", e.message);
        for (name, says) in [
            ("roof", "also a patch's name"),
            ("a/b", "without `/`"),
            ("", "non-empty"),
        ] {
            let e = fails(spec(&[(name, vec![Member::Index(0)])]), &[]);
            assert!(e.message.contains(says), "{}", e.message);
            assert_eq!(e.member, None);
        }
        assert!(fails(spec(&[("g", vec![])]), &[])
            .message
            .contains("no patch"));
        let taken = [PatchGroup {
            name: "g".into(),
            patches: vec![0],
        }];
        assert!(fails(spec(&[("g", vec![Member::Index(1)])]), &taken)
            .message
            .contains("already defined"));
    }

    #[test]
    fn a_fault_is_located_at_its_member() {
        let text = "Parts(groups: {\n  \"lid\": [24, 25, 99],\n})";
        let error = resolve_groups(
            &ron::from_str::<PartsFile>(text).unwrap().groups,
            &patches(&["p"; 30]),
            &[],
        );
        let error = error.unwrap_err();
        let FormatError::Ron { line, col, .. } = FormatError::ron_at(
            text,
            "t.parts.ron",
            &error.path(&[Step::Field("groups")]),
            error.message.clone(),
        ) else {
            panic!("not a RON error");
        };
        assert_eq!((line, col), (2, 19));
    }
}
