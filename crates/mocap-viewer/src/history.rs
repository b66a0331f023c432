//! Clip edits in the viewer with undo and redo: each edit keeps the character's
//! asset from before and after it, so undoing every edit gives back the original
//! clip bit for bit.

use mocap::Asset;

/// One edit as the history keeps it.
#[derive(Clone, Debug, PartialEq)]
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
    /// A key this change took away (deleting or moving a key).
    pub unkey: Option<usize>,
    /// The edit itself, when it can be made again on another clip (for deleting or
    /// moving a key under later edits); `None` for layers.
    pub edit: Option<mocap::ops::edit::Edit>,
}

/// Done and undone edits, and which are saved.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct History {
    done: Vec<Change>,
    undone: Vec<Change>,
    /// A serial number per done and undone change, in the same order.
    done_ids: Vec<u64>,
    undone_ids: Vec<u64>,
    next_id: u64,
    /// Per character saved: the serial of its last done change then (`None`: none).
    saved: Vec<(usize, Option<u64>)>,
}

/// Most edits kept for undo (the oldest are forgotten past this).
pub const DEPTH: usize = 500;

impl History {
    /// Records an edit (clearing what could be redone).
    pub fn push(&mut self, change: Change) {
        self.undone.clear();
        self.undone_ids.clear();
        self.done.push(change);
        self.done_ids.push(self.next_id);
        self.next_id += 1;
        if self.done.len() > DEPTH {
            self.done.remove(0);
            self.done_ids.remove(0);
        }
    }

    /// The last edit, moved to the redo list.
    pub fn undo(&mut self) -> Option<&Change> {
        let change = self.done.pop()?;
        self.undone.push(change);
        self.undone_ids.extend(self.done_ids.pop());
        self.undone.last()
    }

    /// The last undone edit, moved back to the done list.
    pub fn redo(&mut self) -> Option<&Change> {
        let change = self.undone.pop()?;
        self.done.push(change);
        self.done_ids.extend(self.undone_ids.pop());
        self.done.last()
    }

    /// The done and the undone changes, oldest first (undone: the next to redo last).
    pub fn changes(&self) -> (&[Change], &[Change]) {
        (&self.done, &self.undone)
    }

    /// A history holding these done and undone changes (as [`History::changes`] gives them), none saved.
    pub fn from_changes(done: Vec<Change>, undone: Vec<Change>) -> History {
        let n = (done.len() + undone.len()) as u64;
        History {
            done_ids: (0..done.len() as u64).collect(),
            undone_ids: (done.len() as u64..n).collect(),
            next_id: n,
            done,
            undone,
            saved: Vec::new(),
        }
    }

    /// The serial of character `c`'s last done change.
    fn last_id(&self, c: usize) -> Option<u64> {
        self.done.iter().zip(&self.done_ids).rev().find(|(x, _)| x.character == c).map(|(_, id)| *id)
    }

    /// Changes whenever the history does (an edit, undo, redo, save or clear).
    pub fn stamp(&self) -> String {
        format!("{}:{:?}:{:?}:{:?}", self.next_id, self.done_ids, self.undone_ids, self.saved)
    }

    /// Character `c` is saved as it is now (Save as BVH or glTF).
    pub fn mark_saved(&mut self, c: usize) {
        let last = self.last_id(c);
        self.saved.retain(|(x, _)| *x != c);
        self.saved.push((c, last));
    }

    /// Whether character `c` has edits made or undone since it was last saved (or
    /// opened).
    pub fn unsaved(&self, c: usize) -> bool {
        let mark = self.saved.iter().find(|(x, _)| *x == c).and_then(|(_, id)| *id);
        self.last_id(c) != mark
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
            if let Some(k) = change.unkey {
                keys.retain(|x| *x != k);
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

    /// Character `c`'s edits as a list that can be made again: the asset they
    /// start from (the original, or what the last layer made) and the edits in
    /// order, with deleted keys taken out and moved ones in their new place.
    /// `None` when `c` has no edits.
    pub fn effective(&self, c: usize) -> Option<(Asset, Vec<mocap::ops::edit::Edit>)> {
        let mine: Vec<&Change> = self.done.iter().filter(|x| x.character == c).collect();
        let first = mine.first()?;
        let mut base = first.before.clone();
        let mut edits: Vec<mocap::ops::edit::Edit> = Vec::new();
        for change in mine {
            if let Some(k) = change.unkey {
                // A key deleted or moved: take the latest key at that frame out.
                let at = edits.iter().rposition(|e| e.key_frame() == Some(k));
                if let Some(i) = at {
                    edits.remove(i);
                }
                let to = change.edit.as_ref().and_then(|e| e.key_frame());
                for e in &mut edits {
                    e.follow_key(k, to);
                }
                if let Some(e) = &change.edit {
                    edits.insert(at.unwrap_or(edits.len()), e.clone());
                }
                continue;
            }
            match &change.edit {
                Some(e) => edits.push(e.clone()),
                None => {
                    // A layer: what it made is the new starting point.
                    base = change.after.clone();
                    edits.clear();
                }
            }
        }
        Some((base, edits))
    }

    /// Forgets everything (files opened, characters closed).
    pub fn clear(&mut self) {
        *self = History { next_id: self.next_id, ..History::default() };
    }
}
