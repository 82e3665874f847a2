//! A USD layer as glint reads it, whichever file it came from: its prims, their properties and
//! values (a default and time samples), each with where it is written (a byte offset in a text
//! layer; [`NOWHERE`] in a binary one, whose errors name the prim instead).

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

/// One time sample of an attribute: its value at a time code.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Sample {
    pub time: f64,
    pub value: Value,
    /// Where its time code is written.
    pub at: usize,
}

/// An attribute or relationship.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Property {
    /// `xformOp:translate`, `points`.
    pub name: String,
    /// The type as written (`double3`, `point3f`), with `[]` for arrays; `rel` for a
    /// relationship.
    pub type_name: String,
    /// The value written without a time (`points = [...]`).
    pub default: Option<Value>,
    /// The time samples (`points.timeSamples = { 1: [...] }`), sorted by time, each time once;
    /// empty when none are written.
    pub samples: Vec<Sample>,
    /// Where its name is written.
    pub at: usize,
}

/// Time samples that differ where glint reads one value, and where; the message leaves the
/// attribute's name to be put before it.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct VaryingError {
    pub at: usize,
    pub message: String,
}

impl Property {
    /// The property's value at every time: its one sample value when it has time samples (they
    /// win over a default, as USD reads them at a time code), else its default. Samples that
    /// all hold the same value are that value; samples that differ are an error at the first
    /// that differs.
    pub fn held_value(&self) -> Result<Option<&Value>, VaryingError> {
        let Some(first) = self.samples.first() else {
            return Ok(self.default.as_ref());
        };
        match self.samples.iter().find(|s| s.value != first.value) {
            None => Ok(Some(&first.value)),
            Some(other) => Err(VaryingError {
                at: other.at,
                message: format!(
                    "changes over time (its samples at time codes {} and {} differ); glint animates only `points` and xformOps",
                    first.time, other.time
                ),
            }),
        }
    }

    /// The value the property has first: its earliest time sample, or its default when it
    /// has none.
    #[must_use]
    pub fn first_value(&self) -> Option<&Value> {
        self.samples
            .first()
            .map(|s| &s.value)
            .or(self.default.as_ref())
    }

    /// Whether its time samples hold more than one value.
    #[must_use]
    pub fn varies(&self) -> bool {
        self.samples
            .first()
            .is_some_and(|first| self.samples.iter().any(|s| s.value != first.value))
    }
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

/// The layer metadata that says how time codes run, each number with where it is written.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct LayerTimes {
    pub time_codes_per_second: Option<(f64, usize)>,
    pub frames_per_second: Option<(f64, usize)>,
    pub start_time_code: Option<(f64, usize)>,
    pub end_time_code: Option<(f64, usize)>,
}

/// A layer: its metadata's `upAxis` and time codes, and its root prims.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Layer {
    pub up_axis: Option<(String, usize)>,
    pub times: LayerTimes,
    pub prims: Vec<Prim>,
}
