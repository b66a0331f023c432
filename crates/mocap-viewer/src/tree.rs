//! The joint tree the hierarchy panel lists, as plain data: what is folded
//! ([`Folds`], part of [`crate::AppState`]) and the rows shown ([`rows`]), built
//! by one iterative depth-first pass (no recursion: a file can hold a
//! 200,000-level-deep skeleton).

use crate::character::Character;
use crate::selection::Selection;
use std::collections::HashSet;

/// At most this many joint names are listed in [`crate::Snapshot::tree_labels`].
pub const MAX_LABELS: usize = 10_000;

/// What is folded: characters, and joints (per character) whose children are hidden.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Folds {
    characters: HashSet<usize>,
    joints: HashSet<(usize, usize)>,
}

impl Folds {
    /// Whether character `character` (with `None`) or its joint `joint` is folded.
    pub fn is_folded(&self, character: usize, joint: Option<usize>) -> bool {
        match joint {
            None => self.characters.contains(&character),
            Some(j) => self.joints.contains(&(character, j)),
        }
    }

    /// Folds (`folded`) or unfolds character `character` (with `None`) or its joint `joint`.
    pub fn set(&mut self, character: usize, joint: Option<usize>, folded: bool) {
        match (joint, folded) {
            (None, true) => self.characters.insert(character),
            (None, false) => self.characters.remove(&character),
            (Some(j), true) => self.joints.insert((character, j)),
            (Some(j), false) => self.joints.remove(&(character, j)),
        };
    }

    /// Unfolds the character of `s` and every ancestor of its joint, so the row shows.
    pub fn unfold_to(&mut self, characters: &[Character], s: Selection) {
        self.characters.remove(&s.character);
        let Some(clip) = characters.get(s.character).and_then(|c| c.clip()) else { return };
        let joints = clip.skeleton().joints();
        let mut at = joints.get(s.joint).and_then(|j| j.parent);
        while let Some(p) = at {
            self.joints.remove(&(s.character, p));
            at = joints.get(p).and_then(|j| j.parent).filter(|&q| q < p);
        }
    }

    /// Character `index` was closed: forget its folds and renumber the ones after it.
    pub fn remove_character(&mut self, index: usize) {
        let shift = |c: usize| {
            if c > index {
                Some(c - 1)
            } else if c < index {
                Some(c)
            } else {
                None
            }
        };
        self.characters = self.characters.iter().filter_map(|&c| shift(c)).collect();
        self.joints = self.joints.iter().filter_map(|&(c, j)| Some((shift(c)?, j))).collect();
    }
}

/// One row of the hierarchy panel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Row {
    /// A character's header: colour, visibility, name, remove.
    Header(usize),
    /// A character's hand-set offset.
    Offset(usize),
    /// A model's animation chooser.
    Animation(usize),
    /// A joint of a character at a depth (roots are 0).
    Joint {
        /// Character index.
        character: usize,
        /// Joint index.
        joint: usize,
        /// Depth in the tree (roots are 0).
        depth: usize,
    },
}

/// Every row shown, in order: per character its header, then (unless folded) its
/// offset and its joints depth-first, skipping the children of folded joints.
pub fn rows(characters: &[Character], folds: &Folds) -> Vec<Row> {
    let mut rows = Vec::new();
    let mut stack: Vec<(usize, usize)> = Vec::new();
    for (c, character) in characters.iter().enumerate() {
        rows.push(Row::Header(c));
        if folds.is_folded(c, None) {
            continue;
        }
        rows.push(Row::Offset(c));
        let Some(clip) = character.clip() else {
            rows.push(Row::Animation(c));
            continue;
        };
        if clip.takes().len() > 1 {
            rows.push(Row::Animation(c));
        }
        let children = &character.extra.children;
        stack.clear();
        stack.extend(clip.skeleton().roots().collect::<Vec<_>>().into_iter().rev().map(|r| (r, 0)));
        while let Some((joint, depth)) = stack.pop() {
            rows.push(Row::Joint { character: c, joint, depth });
            if folds.is_folded(c, Some(joint)) {
                continue;
            }
            if let Some(kids) = children.get(joint) {
                stack.extend(kids.iter().rev().map(|&k| (k, depth + 1)));
            }
        }
    }
    rows
}

/// The names of the joints listed, in row order (at most [`MAX_LABELS`]).
pub fn listed_joints(characters: &[Character], folds: &Folds) -> Vec<String> {
    let names = rows(characters, folds).into_iter().filter_map(|r| match r {
        Row::Joint { character, joint, .. } => {
            characters.get(character)?.clip()?.skeleton().joints().get(joint).map(|j| j.name.clone())
        }
        _ => None,
    });
    names.take(MAX_LABELS).collect()
}
