//! A USD layer as glint reads it, whichever file it came from: its prims, their properties and
//! values, each with where it is written (a byte offset in a text layer; [`NOWHERE`] in a
//! binary one, whose errors name the prim instead).

/// The place of what a binary layer holds: no line and column to name.
#[cfg_attr(not(feature = "usd-binary"), allow(dead_code))]
pub(super) const NOWHERE: usize = usize::MAX;

/// A value as written.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Value {
    Number(f64),
    /// A string or token.
    Str(String),
    /// `(a, b, …)`
    Tuple(Vec<Value>),
    /// `[a, b, …]`
    List(Vec<Value>),
    /// A word (`None`, `true`, an identifier), a path, an asset or a dictionary: nothing glint
    /// reads a number from.
    Other,
}

/// An attribute or relationship.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Property {
    /// `xformOp:translate`, `points`.
    pub name: String,
    /// The type as written (`double3`, `point3f`), with `[]` for arrays; `rel` for a
    /// relationship.
    pub type_name: String,
    pub value: Option<Value>,
    /// Where its name is written.
    pub at: usize,
}

/// A prim: `def TYPE "name" (metadata) { … }`.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Prim {
    pub type_name: Option<String>,
    pub name: String,
    /// Where `def` is written.
    pub at: usize,
    /// `active = false` in its metadata.
    pub inactive: bool,
    pub properties: Vec<Property>,
    pub children: Vec<Prim>,
}

impl Prim {
    /// The property named `name`, if written.
    #[must_use]
    pub fn property(&self, name: &str) -> Option<&Property> {
        self.properties.iter().find(|p| p.name == name)
    }
}

/// A layer: its metadata's `upAxis` and its root prims.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Layer {
    pub up_axis: Option<(String, usize)>,
    pub prims: Vec<Prim>,
}
