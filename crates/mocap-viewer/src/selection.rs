//! What is selected: a joint of one character.

/// A selected joint: indices into the stage's characters and that clip's joints.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Selection {
    /// Index of the character (0-based).
    pub character: usize,
    /// Index of the joint in that character's skeleton.
    pub joint: usize,
}
