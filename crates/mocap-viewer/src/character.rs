//! One character on the stage: a document with its colour, visibility, placement
//! and current pose (world transforms in metres, placed).

use crate::document::Document;
use crate::playback::Playback;
use mocap::glam::Vec3;
use mocap::{Aabb, Interpolation, Transform};

/// Bone colours given to characters in turn (the renderer's palette).
pub use mocap_render::PALETTE;

/// Share of a frame within which a playhead before a frame's time counts as on it.
const NEAR_FRAME: f64 = 0.01;

/// A clip placed in the shared world (metres, Y up).
pub struct Character {
    /// The clip and what is derived from it.
    pub document: Document,
    /// Bone colour (sRGB, 0-255).
    pub color: [u8; 4],
    /// Whether it is drawn (hidden characters keep their lane and their time).
    pub visible: bool,
    /// Offset set by hand in metres, added to the layout's.
    pub offset: Vec3,
    /// Offset the layout gave it in metres (see [`crate::stage::Stage::arrange`]).
    pub layout_offset: Vec3,
    pose: Vec<Transform>,
}

impl Character {
    /// A visible character at the origin.
    pub fn new(document: Document, color: [u8; 4]) -> Character {
        Character { document, color, visible: true, offset: Vec3::ZERO, layout_offset: Vec3::ZERO, pose: Vec::new() }
    }

    /// Metres per file unit (from the guessed unit).
    pub fn scale(&self) -> f32 {
        self.document.meters_per_unit()
    }

    /// Where the clip's origin stands in the world: layout offset plus the hand-set one (metres).
    pub fn placement(&self) -> Vec3 {
        self.layout_offset + self.offset
    }

    /// Bounds of the whole motion in metres, before placement.
    pub fn local_bounds(&self) -> Aabb {
        self.document.bounds.scaled(self.scale())
    }

    /// Bounds of the whole motion in metres, where it stands.
    pub fn bounds(&self) -> Aabb {
        self.local_bounds().translated(self.placement())
    }

    /// Size of the first pose in metres (a humanoid's height).
    pub fn extent(&self) -> f32 {
        self.document.extent * self.scale()
    }

    /// Poses the character at the playhead: interpolated at its time when `smooth`,
    /// else on the frame [`Playback::frame`] gives in this clip's own frame time. Past
    /// its end a clip holds its last pose. The transforms are scaled to metres and placed.
    pub fn pose_at(&mut self, playback: &Playback, smooth: bool) {
        let clip = &self.document.clip;
        if smooth {
            clip.sample_world_transforms_into(playback.time.min(clip.duration()), Interpolation::Linear, &mut self.pose);
        } else {
            clip.world_transforms_into(self.frame(playback), &mut self.pose);
        }
        let (scale, at) = (self.scale(), self.placement());
        for t in &mut self.pose {
            t.translation = t.translation * scale + at;
        }
    }

    /// World transforms of the last [`Character::pose_at`] (metres, placed), in joint order.
    pub fn pose(&self) -> &[Transform] {
        &self.pose
    }

    /// The frame of this clip shown at the playhead: the last one not after it, in
    /// its own frame time (clamped, so past its end the last). Files write frame times
    /// with 6-7 digits (0.0333333), so two clips' frames drift apart by a little: a
    /// playhead within 1% of a frame before that frame's time counts as on it.
    pub fn frame(&self, playback: &Playback) -> usize {
        let timing = self.document.timing();
        let frame = playback.frame(timing);
        let next = (frame + 1).min(timing.last());
        if timing.time_of(next) - playback.time < NEAR_FRAME * timing.frame_time { next } else { frame }
    }
}

/// The first palette colour no open character uses, or the palette cycled by count.
pub fn next_color(open: &[Character]) -> [u8; 4] {
    let unused = PALETTE.iter().find(|c| !open.iter().any(|o| o.color == **c));
    unused.copied().unwrap_or(PALETTE[open.len() % PALETTE.len()])
}
