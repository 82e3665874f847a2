//! The undo history of a tuning session: each accepted change as the file's text before and
//! after it, so that undoing writes the text back exactly as it was.

/// One accepted change: the file's text before and after it.
#[derive(Clone, Debug, PartialEq, Eq)]
struct Step {
    before: String,
    after: String,
}

/// Changes that can be undone, and undone changes that can be made again.
#[derive(Clone, Debug, Default)]
pub struct History {
    done: Vec<Step>,
    undone: Vec<Step>,
}

/// The most changes kept to undo; older ones are forgotten.
pub const MAX_UNDO: usize = 500;

impl History {
    /// Records a change from `before` to `after`; what was undone can no longer be redone.
    pub fn record(&mut self, before: String, after: String) {
        self.undone.clear();
        self.done.push(Step { before, after });
        if self.done.len() > MAX_UNDO {
            self.done.remove(0);
        }
    }

    /// The text to go back to from `current`, when the last change made it; the change moves
    /// to the redo list. `None` when there is nothing to undo or the text is not what the last
    /// change left (edited elsewhere meanwhile).
    pub fn undo(&mut self, current: &str) -> Option<String> {
        let step = self.done.last().filter(|s| s.after == current)?.clone();
        self.done.pop();
        let before = step.before.clone();
        self.undone.push(step);
        Some(before)
    }

    /// The text to go forward to from `current`, when it is what the last undo left.
    pub fn redo(&mut self, current: &str) -> Option<String> {
        let step = self.undone.last().filter(|s| s.before == current)?.clone();
        self.undone.pop();
        let after = step.after.clone();
        self.done.push(step);
        Some(after)
    }

    /// Forgets everything: the file was changed by someone else.
    pub fn clear(&mut self) {
        self.done.clear();
        self.undone.clear();
    }

    /// How many changes can be undone and redone.
    #[must_use]
    pub fn depth(&self) -> (usize, usize) {
        (self.done.len(), self.undone.len())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn undo_and_redo_walk_the_texts_back_and_forth() {
        let mut h = History::default();
        h.record("a".into(), "b".into());
        h.record("b".into(), "c".into());
        assert_eq!(h.undo("c").as_deref(), Some("b"));
        assert_eq!(h.undo("b").as_deref(), Some("a"));
        assert_eq!(h.undo("a"), None);
        assert_eq!(h.redo("a").as_deref(), Some("b"));
        assert_eq!(h.depth(), (1, 1));
        h.record("b".into(), "d".into());
        assert_eq!(h.redo("d"), None, "a new change ends what could be redone");
    }

    #[test]
    fn a_text_changed_elsewhere_is_not_undone() {
        let mut h = History::default();
        h.record("a".into(), "b".into());
        assert_eq!(h.undo("b, edited elsewhere"), None);
        assert_eq!(h.depth(), (1, 0));
    }
}
