//! Setting up a capture rig on a model in the view ([`mocap::capture::Rig`]):
//! Fit skeleton places a humanoid (or the skeleton of an open clip) inside the
//! model's set-up frame; the user drags its joints to where they belong and the
//! spin handles (one per single-child bone, across it) to turn the bones' "up";
//! Bind binds every vertex to its nearest bone, and painting reassigns the
//! vertices under the pointer to the selected bone. The model stays on its set-up
//! frame meanwhile. Capture skeleton then uses this rig; Save rig downloads it.
//!
//! Everything is drawn as overlay lines (seen through the mesh): bones in yellow,
//! joints as small crosses (the selected one white), spins in cyan, and with
//! "Show binding" every vertex as a dot in its bone's colour.

use mocap::capture::Rig;
use mocap::glam::Vec3;

/// `character` of a rig joint's handle.
pub const RIG_JOINT: usize = usize::MAX - 1;
/// `character` of a spin handle (its `joint` is the bone's first joint).
pub const RIG_SPIN: usize = usize::MAX - 2;
/// `character` of a vertex handle while painting.
pub const RIG_PAINT: usize = usize::MAX - 3;

/// Screen radius (points) of the painting brush.
pub const BRUSH: f32 = 16.0;

/// A rig being set up on a model.
#[derive(Clone, Debug)]
pub struct RigEdit {
    /// The model's character index.
    pub model: usize,
    /// The rig.
    pub rig: Rig,
    /// The selected rig joint (its bone is the one painted).
    pub selected: Option<usize>,
    /// Painting the binding (vertex handles instead of joint handles).
    pub painting: bool,
    /// Drawing every vertex in its bone's colour.
    pub show_binding: bool,
    /// The set-up frame's vertex positions (file units).
    pub(crate) setup: Vec<Vec3>,
}

/// A bone's colour for the binding view.
pub(crate) fn bone_color(bone: usize) -> [u8; 4] {
    const PALETTE: [[u8; 3]; 8] = [
        [230, 80, 80],
        [80, 200, 90],
        [90, 140, 255],
        [240, 200, 60],
        [200, 100, 230],
        [60, 210, 210],
        [250, 140, 60],
        [170, 170, 170],
    ];
    let [r, g, b] = PALETTE[bone % PALETTE.len()];
    [r, g, b, 255]
}
