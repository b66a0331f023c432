//! Clip edits in the viewer with undo and redo: each edit keeps the character's
//! asset from before and after it, so undoing every edit gives back the original
//! clip bit for bit.

use mocap::Asset;

/// One edit as the history keeps it.
#[derive(Clone, Debug)]
pub struct Change {
    /// The character edited (0-based).
    pub character: usize,
    /// What the edit was, for menus ("Reverse", "Trim 10–40", …).
    pub label: String,
    /// The asset before the edit.
    pub before: Asset,
    /// The asset after it.
    pub after: Asset,
    /// For a key (a keyed pose correction), its frame.
    pub key: Option<usize>,
    /// Whether the edit moves frames (trim, resample, reverse…): earlier keys no
    /// longer sit where they were.
    pub retimes: bool,
}

/// Done and undone edits.
#[derive(Clone, Debug, Default)]
pub struct History {
    done: Vec<Change>,
    undone: Vec<Change>,
}

/// Most edits kept for undo (the oldest are forgotten past this).
pub const DEPTH: usize = 500;

impl History {
    /// Records an edit (clearing what could be redone).
    pub fn push(&mut self, change: Change) {
        self.undone.clear();
        self.done.push(change);
        if self.done.len() > DEPTH {
            self.done.remove(0);
        }
    }

    /// The last edit, moved to the redo list.
    pub fn undo(&mut self) -> Option<&Change> {
        let change = self.done.pop()?;
        self.undone.push(change);
        self.undone.last()
    }

    /// The last undone edit, moved back to the done list.
    pub fn redo(&mut self) -> Option<&Change> {
        let change = self.undone.pop()?;
        self.done.push(change);
        self.done.last()
    }

    /// Label of the edit Undo would undo.
    pub fn next_undo(&self) -> Option<&str> {
        self.done.last().map(|c| c.label.as_str())
    }

    /// Label of the edit Redo would redo.
    pub fn next_redo(&self) -> Option<&str> {
        self.undone.last().map(|c| c.label.as_str())
    }

    /// Whether character `c` has edits that are done.
    pub fn edited(&self, c: usize) -> bool {
        self.done.iter().any(|x| x.character == c)
    }

    /// The frames keyed on character `c` since its frames last moved, in order.
    pub fn keys(&self, c: usize) -> Vec<usize> {
        let mut keys = Vec::new();
        for change in self.done.iter().filter(|x| x.character == c) {
            if change.retimes {
                keys.clear();
            }
            if let Some(k) = change.key {
                if !keys.contains(&k) {
                    keys.push(k);
                }
            }
        }
        keys.sort_unstable();
        keys
    }

    /// Forgets everything (files opened, characters closed).
    pub fn clear(&mut self) {
        self.done.clear();
        self.undone.clear();
    }
}
