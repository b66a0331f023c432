//! What the Retarget window (Edit ▸ Retarget onto…) is set to, as plain data.

use mocap::ops::retarget::Reference;

/// What the Retarget window is set to.
#[derive(Clone, Debug, PartialEq)]
pub struct RetargetDialog {
    /// The character whose motion is put on another.
    pub source: usize,
    /// The character that receives it (None until one is chosen).
    pub target: Option<usize>,
    /// Explicit pairs (target joint, source joint; empty: left out).
    pub map: Vec<(String, String)>,
    /// The pose the two skeletons are matched in.
    pub reference: Reference,
}

impl RetargetDialog {
    /// `source`'s motion, no target yet, names matched, first frames as reference.
    pub fn new(source: usize) -> RetargetDialog {
        RetargetDialog { source, target: None, map: Vec::new(), reference: Reference::default() }
    }

    /// The core options these settings make.
    pub fn options(&self) -> mocap::ops::retarget::Options {
        mocap::ops::retarget::Options { map: self.map.clone(), reference: self.reference }
    }
}
