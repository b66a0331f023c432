//! Steps the tests take through the viewer's commands, where a test wants what
//! the step gave back (the label undone, the key reached).

#![allow(dead_code)]

use mocap_viewer::{Command, Viewer};

/// Undoes the last edit; its label, or `None` when there was none.
pub fn undo(v: &mut Viewer) -> Option<String> {
    let label = v.state().history.next_undo().map(str::to_owned);
    v.try_apply(Command::Undo).ok().and(label)
}

/// Redoes the last undone edit; its label, or `None` when there was none.
pub fn redo(v: &mut Viewer) -> Option<String> {
    let label = v.state().history.next_redo().map(str::to_owned);
    v.try_apply(Command::Redo).ok().and(label)
}

/// Goes to the next (`forward`) or previous key; the frame reached, or `None`
/// when there is no key that way.
pub fn step_key(v: &mut Viewer, forward: bool) -> Option<usize> {
    let before = v.state().frame();
    v.try_apply(Command::StepKey(forward)).ok()?;
    let after = v.state().frame();
    (after != before).then_some(after)
}
