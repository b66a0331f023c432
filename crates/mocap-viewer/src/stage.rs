//! The open characters and their layout: the core's shared [`mocap::stage::Stage`]
//! (the one `mocap render` uses too), holding the viewer's [`Look`] per character.

use crate::character::Look;

/// Every open character, in order, and how they are placed.
pub type Stage = mocap::stage::Stage<Look>;
