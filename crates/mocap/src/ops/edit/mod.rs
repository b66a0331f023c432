//! Clip edits: each takes a clip and gives a new one that BVH can hold (the input
//! is baked first, [`crate::ops::bake::to_bvh`]), so every result can be saved and read
//! back exactly.
//!
//! Edits that only reorder or drop frames ([`Edit::Trim`], [`Edit::Reverse`],
//! [`Edit::PingPong`]) copy motion rows, bit for bit. The others work on local
//! poses (sampled with the clip's own rule, changed, written back as channel
//! values in each joint's own rotation order): [`Edit::Resample`],
//! [`Edit::LoopKnit`], [`Edit::InPlace`], [`Edit::UpAxis`], [`Edit::Scale`],
//! [`Edit::RemoveJoint`]; [`Edit::Rename`] changes names only.
//!
//! Every edit is also written as text, a spec (`trim:0:9`, `knit:4`, `up:z`):
//! [`EditSpec`] reads and writes the grammar, and `"…".parse::<Edit>()` reads the
//! specs that need no clip.
//!
//! One file per concept: the [`Edit`] type and [`apply`] here; poses to and from
//! channel rows (`poses`); edits of time (`timing`), of where the clip stands
//! (`space`), of the rig (`rig`, with [`new_character`]) and keys (`keys`); and
//! the text form of every edit (`spec`).

use crate::model::clip::Clip;
use crate::ops::bake;
use glam::{Quat, Vec3};
use keys::{correct, tween};
use poses::rows;
use rig::{add_joint, remove_joint, rename, set_channels, set_offset};
use serde::{Deserialize, Serialize};
use space::{in_place, scale, up_axis};
use timing::{loop_knit, resample};

mod keys;
mod poses;
mod rig;
mod space;
mod spec;
mod timing;

pub use poses::clip_from_poses;
pub(crate) use poses::joint_values;
pub use rig::new_character;
pub use spec::{EditSpec, SpecError};

/// One clip edit (serde: kept in the viewer's saved session; quaternions and
/// vectors as arrays `[x, y, z, w]`, `[x, y, z]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub enum Edit {
    /// Keep frames `first..=last`.
    Trim {
        /// First frame kept.
        first: usize,
        /// Last frame kept (inclusive).
        last: usize,
    },
    /// Resample to `fps` frames per second over the same duration, with the
    /// clip's own sampling (rotations by slerp, translations by lerp).
    Resample {
        /// The new frame rate.
        fps: f64,
    },
    /// Play backward.
    Reverse,
    /// Forward, then backward without repeating the ends (a seamless loop).
    PingPong,
    /// Blend the last `frames` frames toward the first so the loop is seamless
    /// (rotations and the root's height; the root's travel is kept).
    LoopKnit {
        /// Frames blended.
        frames: usize,
    },
    /// Remove the root's horizontal travel (its height stays); with
    /// `remove_turning`, also its turning about the vertical axis.
    InPlace {
        /// Also keep the root facing as on the first frame.
        remove_turning: bool,
    },
    /// The file's up axis is `from` (`Z` for Z-up files): turn the whole clip so
    /// that it is Y-up (distances kept).
    UpAxis {
        /// 0 = X, 1 = Y (no change), 2 = Z; `negative` for -X/-Y/-Z.
        from: usize,
        /// The file's up points along the negative axis.
        negative: bool,
    },
    /// Multiply every length (offsets and positions) by `factor` (a unit change).
    Scale {
        /// Length factor, positive and finite.
        factor: f32,
    },
    /// Rename a joint.
    Rename {
        /// Current name.
        from: String,
        /// New name.
        to: String,
    },
    /// A pose correction keyed at `frame`: the named joints take these local
    /// rotations (and roots these local positions) there, and the change fades out
    /// over `window` frames on each side, so a glitch is fixed without a pop.
    Correct {
        /// The frame keyed.
        frame: usize,
        /// Joint names and their local rotations at the frame.
        rotations: Vec<(String, Quat)>,
        /// Joint names and their local translations at the frame (moved roots).
        translations: Vec<(String, Vec3)>,
        /// Frames on each side over which the correction fades.
        window: usize,
    },
    /// A key of key-frame animation: the named joints take these local rotations
    /// (and roots these positions) at `frame` exactly, and every frame between two
    /// keys of `keys` (with `frame` among them) is interpolated from the poses at
    /// those keys: rotations by slerp, positions linearly, so the motion goes
    /// smoothly from key to key; frames before the first key and after the last
    /// hold its pose.
    Key {
        /// The frame keyed.
        frame: usize,
        /// Joint names and their local rotations at the frame.
        rotations: Vec<(String, Quat)>,
        /// Joint names and their local translations at the frame (moved roots).
        translations: Vec<(String, Vec3)>,
        /// The other keyed frames (any order; repeats and `frame` itself are fine).
        keys: Vec<usize>,
    },
    /// Add a joint under `parent` at `offset` (three rotation channels, rest pose on
    /// every frame); the parent's End Site, if it had one, gives way, and the new
    /// joint gets its own.
    AddJoint {
        /// The parent joint's name.
        parent: String,
        /// The new joint's name (unique).
        name: String,
        /// Its offset from the parent, in the parent's frame.
        offset: Vec3,
    },
    /// Move a joint (or End Site) relative to its parent.
    SetOffset {
        /// The joint's name.
        name: String,
        /// The new offset.
        offset: Vec3,
    },
    /// Give a joint position channels or not, and its rotation order (`"ZXY"`,
    /// any order of X, Y and Z); its motion is kept.
    SetChannels {
        /// The joint's name.
        name: String,
        /// Xposition Yposition Zposition first.
        position: bool,
        /// The rotation axes in order, e.g. `"ZXY"`.
        order: String,
    },
    /// Remove a joint; its children move to its parent. With `fold`, its motion
    /// is folded into them so that no position changes; without, it is dropped.
    RemoveJoint {
        /// The joint's name.
        name: String,
        /// Keep positions (fold) or drop the joint's motion.
        fold: bool,
    },
    /// [`Edit::Resample`] with cubic in-betweens
    /// ([`crate::runtime::sample::Interpolation::Cubic`]): through every frame,
    /// smooth across them. (Last in the list: stored sessions keep their indices.)
    ResampleCubic {
        /// The new frame rate.
        fps: f64,
    },
}

impl Edit {
    /// The frame of a key ([`Edit::Correct`] or [`Edit::Key`]); `None` for other edits.
    pub fn key_frame(&self) -> Option<usize> {
        match self {
            Edit::Correct { frame, .. } | Edit::Key { frame, .. } => Some(*frame),
            _ => None,
        }
    }

    /// The same key at frame `to` (`None` when this is not a key).
    pub fn at_frame(&self, to: usize) -> Option<Edit> {
        let mut e = self.clone();
        match &mut e {
            Edit::Correct { frame, .. } | Edit::Key { frame, .. } => *frame = to,
            _ => return None,
        }
        Some(e)
    }

    /// After the key at `from` was deleted (`to` = `None`) or moved to `to`: a
    /// [`Edit::Key`]'s list of other keys follows. Other edits are unchanged.
    pub fn follow_key(&mut self, from: usize, to: Option<usize>) {
        if let Edit::Key { keys, .. } = self {
            if keys.contains(&from) {
                keys.retain(|k| *k != from);
                keys.extend(to);
            }
        }
    }
}

/// Why an edit cannot be made.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct EditError(pub String);

fn err<T>(message: impl Into<String>) -> Result<T, EditError> {
    Err(EditError(message.into()))
}

/// Applies `edit` to `clip`.
pub fn apply(clip: &Clip, edit: &Edit) -> Result<Clip, EditError> {
    let (clip, _) = bake::to_bvh(clip);
    let frames = clip.frame_count();
    match edit {
        Edit::Trim { first, last } => {
            if first > last || *last >= frames {
                return err(format!("trim {first}:{last}: the clip has frames 0 to {}", frames.saturating_sub(1)));
            }
            rows(&clip, (*first..=*last).collect())
        }
        Edit::Reverse => rows(&clip, (0..frames).rev().collect()),
        Edit::PingPong => {
            let back = (1..frames.saturating_sub(1)).rev();
            rows(&clip, (0..frames).chain(back).collect())
        }
        Edit::Resample { fps } => resample(&clip, *fps, crate::runtime::sample::Interpolation::Linear),
        Edit::ResampleCubic { fps } => resample(&clip, *fps, crate::runtime::sample::Interpolation::Cubic),
        Edit::LoopKnit { frames: k } => loop_knit(&clip, *k),
        Edit::InPlace { remove_turning } => in_place(&clip, *remove_turning),
        Edit::UpAxis { from, negative } => up_axis(&clip, *from, *negative),
        Edit::Scale { factor } => scale(&clip, *factor),
        Edit::Rename { from, to } => rename(&clip, from, to),
        Edit::RemoveJoint { name, fold } => remove_joint(&clip, name, *fold),
        Edit::Correct { frame, rotations, translations, window } => {
            correct(&clip, *frame, rotations, translations, *window)
        }
        Edit::Key { frame, rotations, translations, keys } => {
            let keyed = correct(&clip, *frame, rotations, translations, 0)?;
            tween(&keyed, keys.iter().copied().chain([*frame]).collect())
        }
        Edit::AddJoint { parent, name, offset } => add_joint(&clip, parent, name, *offset),
        Edit::SetOffset { name, offset } => set_offset(&clip, name, *offset),
        Edit::SetChannels { name, position, order } => set_channels(&clip, name, *position, order),
    }
}

/// Applies edits in order.
pub fn apply_all(clip: &Clip, edits: &[Edit]) -> Result<Clip, EditError> {
    edits.iter().try_fold(clip.clone(), |c, e| apply(&c, e))
}
