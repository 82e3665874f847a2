//! The memory ceiling a job's frames must stay under.

use super::memory::default_memory_ceiling;

/// The most memory a frame of a job may need, in bytes, with which ceiling it is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct MemoryCeiling {
    pub bytes: u64,
    /// Which ceiling it is, as a refusal names it.
    pub whose: &'static str,
}

impl MemoryCeiling {
    /// The ceiling `max_memory` sets (`--max-memory`), or else the default,
    /// [`default_memory_ceiling`], which reads the machine's memory: a job makes its ceiling
    /// once, so that a reload does not read the machine again.
    #[must_use]
    pub(super) fn set_or_default(max_memory: Option<u64>) -> Self {
        match max_memory {
            Some(bytes) => Self {
                bytes,
                whose: "the ceiling --max-memory sets",
            },
            None => Self {
                bytes: default_memory_ceiling(),
                whose: "the default ceiling, three quarters of this machine's memory",
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_ceiling_given_is_kept_and_named() {
        let ceiling = MemoryCeiling::set_or_default(Some(3 << 30));
        assert_eq!(ceiling.bytes, 3 << 30);
        assert!(ceiling.whose.contains("--max-memory"));
    }

    #[test]
    fn without_one_the_default_is_the_machines() {
        let ceiling = MemoryCeiling::set_or_default(None);
        assert_eq!(ceiling.bytes, default_memory_ceiling());
        assert!(ceiling.whose.contains("default"));
    }
}
