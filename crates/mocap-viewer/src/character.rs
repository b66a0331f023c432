//! One character on the stage: a clip placed in the shared world by the core's
//! [`mocap::stage`], with what only the viewer keeps ([`Look`]): its colour, the
//! figure the renderer draws, children lists for the joint tree, and its current
//! pose.

use mocap::stage::{Actor, PoseScratch};
use mocap::{Clip, Interpolation, Transform};
use mocap_render::FigureJoint;

/// Bone colours given to characters in turn (the renderer's palette).
pub use mocap_render::PALETTE;

/// What the viewer keeps per character.
#[derive(Clone, Debug, Default)]
pub struct Look {
    /// Bone colour (sRGB, 0-255).
    pub color: [u8; 4],
    /// Parents and joint markers, as the renderer draws them.
    pub figure: Vec<FigureJoint>,
    /// Children of each joint, in joint order (for the joint tree).
    pub children: Vec<Vec<usize>>,
    /// World transforms of the last [`pose_at`] (metres, placed), in joint order.
    pub pose: Vec<Transform>,
}

/// A clip on the viewer's stage.
pub type Character = Actor<Look>;

/// A visible character named `name`, in the first palette colour no character in
/// `open` uses.
pub fn new_character(name: &str, clip: Clip, open: &[Character]) -> Character {
    let figure = mocap_render::figure(clip.skeleton().joints().iter().map(|j| (j.parent, !j.is_end_site())));
    let look = Look { color: next_color(open), figure, children: clip.skeleton().children(), pose: Vec::new() };
    Actor::new(name, clip, look)
}

/// Poses the character at `time`: interpolated when `smooth`, else the frame shown
/// at that time in its own frame time (the one rule of [`mocap::time`]). Past its
/// end a clip holds its last pose. The transforms are in metres and placed.
pub fn pose_at(c: &mut Character, time: f64, smooth: bool, scratch: &mut PoseScratch) {
    let interpolation = if smooth { Interpolation::Linear } else { Interpolation::Step };
    let mut pose = std::mem::take(&mut c.extra.pose);
    c.pose_at(time, interpolation, scratch, &mut pose);
    c.extra.pose = pose;
}

/// The first palette colour no open character uses, or the palette cycled by count.
pub fn next_color(open: &[Character]) -> [u8; 4] {
    let unused = PALETTE.iter().find(|c| !open.iter().any(|o| o.extra.color == **c));
    unused.copied().unwrap_or(PALETTE[open.len() % PALETTE.len()])
}
