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

use crate::model::channel::{AngleUnit, Channel, ChannelKind};
use crate::model::clip::Clip;
use crate::model::motion::Motion;
use crate::model::skeleton::{EulerConvention, Joint, Skeleton};
use crate::model::time::Timeline;
use crate::ops::bake;
use crate::runtime::pose::{LocalPose, from_row};
use crate::runtime::sample::{Interpolation, SampleScratch, sample};
use glam::{EulerRot, Quat, Vec3};

mod spec;

pub use spec::{EditSpec, SpecError};

/// One clip edit.
#[derive(Clone, Debug, PartialEq)]
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
        Edit::Resample { fps } => resample(&clip, *fps),
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

/// The clip with the rows `order` (frame indices) in that order.
fn rows(clip: &Clip, order: Vec<usize>) -> Result<Clip, EditError> {
    let motion = clip.motion();
    let width = motion.channel_count();
    let mut data = Vec::with_capacity(width * order.len());
    for f in &order {
        data.extend_from_slice(motion.row(*f));
    }
    rebuild(clip, clip.skeleton().clone(), motion.frame_time(), order.len(), data)
}

fn rebuild(clip: &Clip, skeleton: Skeleton, frame_time: f64, frames: usize, data: Vec<f32>) -> Result<Clip, EditError> {
    let width = skeleton.channel_count();
    let motion = Motion::new(frame_time, width, frames, data)
        .ok_or_else(|| EditError("the edit made no valid motion".into()))?;
    let mut out = Clip::new(skeleton, motion.with_angle_unit(clip.motion().angle_unit()))
        .map_err(|e| EditError(e.to_string()))?;
    out.metadata = clip.metadata.clone();
    Ok(out)
}

/// Every frame's local pose.
fn locals(clip: &Clip) -> Vec<LocalPose> {
    (0..clip.frame_count())
        .map(|f| {
            let mut local = LocalPose::default();
            from_row(clip.skeleton(), clip.motion().row(f), clip.motion().angle_unit(), &mut local);
            local
        })
        .collect()
}

/// glam's intrinsic order for the product `R[a0] · R[a1] · R[a2]`.
fn euler_order(axes: [usize; 3]) -> EulerRot {
    match axes {
        [0, 1, 2] => EulerRot::XYZ,
        [0, 2, 1] => EulerRot::XZY,
        [1, 0, 2] => EulerRot::YXZ,
        [1, 2, 0] => EulerRot::YZX,
        [2, 0, 1] => EulerRot::ZXY,
        _ => EulerRot::ZYX,
    }
}

/// Appends joint `j`'s channel values for a local pose (a plain, intrinsic
/// skeleton): positions from the translation, rotations decomposed in the joint's
/// own channel order (axes it has no channel for are left out).
pub(crate) fn joint_values(joint: &Joint, translation: Vec3, rotation: Quat, unit: AngleUnit, out: &mut Vec<f32>) {
    let mut axes: Vec<usize> = joint.channels.iter().filter(|c| c.is_rotation()).map(|c| c.axis()).collect();
    axes.dedup();
    let mut full = axes.clone();
    for a in 0..3 {
        if !full.contains(&a) {
            full.push(a);
        }
    }
    let order = euler_order([full[0], full[1], full[2]]);
    let (a, b, c) = rotation.to_euler(order);
    let angles = [a, b, c];
    let per = unit.radians_per_unit();
    let mut rotation_index = 0;
    for channel in &joint.channels {
        match channel.kind() {
            ChannelKind::Translation => out.push(translation[channel.axis()]),
            ChannelKind::Rotation => {
                let k = full.iter().position(|&x| x == channel.axis()).unwrap_or(rotation_index);
                out.push(angles.get(k).copied().unwrap_or(0.0) / per);
                rotation_index += 1;
            }
            ChannelKind::Scale => out.push(1.0),
            ChannelKind::Length => out.push(0.0),
        }
    }
}

/// A motion row for a local pose of a plain skeleton.
fn row_of(skeleton: &Skeleton, local: &LocalPose, unit: AngleUnit, out: &mut Vec<f32>) {
    for (j, joint) in skeleton.joints().iter().enumerate() {
        let t = local.translation.get(j).copied().unwrap_or(joint.offset);
        let q = local.rotation.get(j).copied().unwrap_or(Quat::IDENTITY);
        joint_values(joint, t, q, unit, out);
    }
}

/// A clip of `skeleton` from one local pose per frame (translations for joints
/// with position channels, rotations decomposed in each joint's channel order,
/// degrees), `frame_time` seconds apart.
pub fn clip_from_poses(skeleton: Skeleton, frame_time: f64, poses: &[LocalPose]) -> Result<Clip, EditError> {
    let mut data = Vec::with_capacity(skeleton.channel_count() * poses.len());
    for p in poses {
        row_of(&skeleton, p, AngleUnit::Degrees, &mut data);
    }
    let width = skeleton.channel_count();
    let motion = Motion::new(frame_time, width, poses.len(), data)
        .ok_or_else(|| EditError("no valid motion from these poses".into()))?;
    Clip::new(skeleton, motion).map_err(|e| EditError(e.to_string()))
}

/// The clip from local poses (same skeleton).
fn from_locals(clip: &Clip, skeleton: Skeleton, frame_time: f64, poses: &[LocalPose]) -> Result<Clip, EditError> {
    let unit = clip.motion().angle_unit();
    let mut data = Vec::with_capacity(skeleton.channel_count() * poses.len());
    for p in poses {
        row_of(&skeleton, p, unit, &mut data);
    }
    rebuild(clip, skeleton, frame_time, poses.len(), data)
}

fn resample(clip: &Clip, fps: f64) -> Result<Clip, EditError> {
    if !(fps.is_finite() && fps > 0.0 && fps <= 100_000.0) {
        return err(format!("fps {fps}: expected a positive frame rate"));
    }
    let duration = clip.duration();
    let timeline = Timeline::new(1.0 / fps, 1);
    let frames = if duration > 0.0 { timeline.frames_to_reach(duration) } else { clip.frame_count().min(1) };
    if frames > crate::model::time::MAX_FRAMES / 4 || frames.saturating_mul(clip.skeleton().channel_count()) > 1 << 30 {
        return err(format!("fps {fps}: {frames} frames would be too many"));
    }
    let mut scratch = SampleScratch::default();
    let poses: Vec<LocalPose> = (0..frames)
        .map(|f| {
            let mut local = LocalPose::default();
            sample(clip.skeleton(), clip.motion(), f as f64 / fps, Interpolation::Linear, &mut scratch, &mut local);
            local
        })
        .collect();
    from_locals(clip, clip.skeleton().clone(), 1.0 / fps, &poses)
}

fn roots(skeleton: &Skeleton) -> Vec<usize> {
    skeleton.roots().collect()
}

fn loop_knit(clip: &Clip, k: usize) -> Result<Clip, EditError> {
    let n = clip.frame_count();
    if k == 0 || k >= n {
        return err(format!("loop knit over {k} frames: the clip has {n} frames (use 1 to {})", n.saturating_sub(1)));
    }
    let mut poses = locals(clip);
    let first = poses[0].clone();
    let last = poses[n - 1].clone();
    let roots = roots(clip.skeleton());
    for i in 0..k {
        // Weight of the correction that takes the last frame onto the first: the
        // frame after the last is (virtually) the first.
        let w = (i + 1) as f32 / (k + 1) as f32;
        let pose = &mut poses[n - k + i];
        for j in 0..pose.rotation.len() {
            let delta = first.rotation[j] * last.rotation[j].inverse();
            pose.rotation[j] = (Quat::IDENTITY.slerp(delta, w) * pose.rotation[j]).normalize();
        }
        for &r in &roots {
            let dy = first.translation[r].y - last.translation[r].y;
            pose.translation[r].y += dy * w;
        }
    }
    from_locals(clip, clip.skeleton().clone(), clip.frame_time(), &poses)
}

fn in_place(clip: &Clip, remove_turning: bool) -> Result<Clip, EditError> {
    let mut poses = locals(clip);
    let Some(first) = poses.first().cloned() else { return Ok(clip.clone()) };
    for &r in &roots(clip.skeleton()) {
        let start = first.translation[r];
        let heading0 = heading(first.rotation[r]);
        for pose in &mut poses {
            pose.translation[r].x = start.x;
            pose.translation[r].z = start.z;
            if remove_turning {
                let turn = heading(pose.rotation[r]) - heading0;
                pose.rotation[r] = (Quat::from_rotation_y(-turn) * pose.rotation[r]).normalize();
            }
        }
    }
    from_locals(clip, clip.skeleton().clone(), clip.frame_time(), &poses)
}

/// Rotation about the vertical axis of where `q` takes +Z (radians).
fn heading(q: Quat) -> f32 {
    let f = q * Vec3::Z;
    f.x.atan2(f.z)
}

fn up_axis(clip: &Clip, from: usize, negative: bool) -> Result<Clip, EditError> {
    // The rotation taking the file's up onto +Y.
    let up = match from {
        0 => Vec3::X,
        1 => Vec3::Y,
        2 => Vec3::Z,
        _ => return err(format!("up axis {from}: expected x, y or z")),
    } * if negative { -1.0 } else { 1.0 };
    let fix = Quat::from_rotation_arc(up, Vec3::Y);
    let mut poses = locals(clip);
    let roots = roots(clip.skeleton());
    for pose in &mut poses {
        for &r in &roots {
            pose.translation[r] = fix * pose.translation[r];
            pose.rotation[r] = (fix * pose.rotation[r]).normalize();
        }
    }
    // Roots need all three rotation channels (and position channels when they move).
    let joints: Vec<Joint> = clip
        .skeleton()
        .joints()
        .iter()
        .map(|j| {
            if j.parent.is_some() {
                return j.clone();
            }
            let mut channels: Vec<Channel> =
                j.channels.iter().filter(|c| c.kind() == ChannelKind::Translation).copied().collect();
            if channels.is_empty() && j.offset != Vec3::ZERO {
                channels.extend([Channel::Xposition, Channel::Yposition, Channel::Zposition]);
            } else if !channels.is_empty() {
                channels = vec![Channel::Xposition, Channel::Yposition, Channel::Zposition];
            }
            if !j.is_end_site() {
                channels.extend([Channel::Zrotation, Channel::Xrotation, Channel::Yrotation]);
            }
            let mut joint = Joint::new(j.name.clone(), j.parent, fix * j.offset, channels);
            if j.is_end_site() {
                joint = Joint::end_site(j.name.clone(), j.parent, fix * j.offset);
            }
            joint
        })
        .collect();
    let skeleton = Skeleton::new(joints, EulerConvention::Intrinsic).map_err(|e| EditError(e.to_string()))?;
    from_locals(clip, skeleton, clip.frame_time(), &poses)
}

fn scale(clip: &Clip, factor: f32) -> Result<Clip, EditError> {
    if !(factor.is_finite() && factor > 0.0) {
        return err(format!("scale {factor}: expected a positive factor"));
    }
    let joints: Vec<Joint> = clip
        .skeleton()
        .joints()
        .iter()
        .map(|j| {
            let mut joint = j.clone();
            joint.offset *= factor;
            joint
        })
        .collect();
    let skeleton = Skeleton::new(joints, EulerConvention::Intrinsic).map_err(|e| EditError(e.to_string()))?;
    let mut data = clip.motion().data().to_vec();
    let width = clip.skeleton().channel_count().max(1);
    let translation_columns: Vec<usize> = clip
        .skeleton()
        .joints()
        .iter()
        .flat_map(|j| {
            j.channels
                .iter()
                .enumerate()
                .filter(|(_, c)| c.kind() == ChannelKind::Translation)
                .map(move |(k, _)| j.first_channel() + k)
        })
        .collect();
    for row in data.chunks_mut(width) {
        for &c in &translation_columns {
            if let Some(v) = row.get_mut(c) {
                *v *= factor;
            }
        }
    }
    rebuild(clip, skeleton, clip.frame_time(), clip.frame_count(), data)
}

fn rename(clip: &Clip, from: &str, to: &str) -> Result<Clip, EditError> {
    let to = to.trim();
    if to.is_empty() || to.chars().any(|c| c.is_whitespace() || c == '{' || c == '}') {
        return err(format!("rename to `{to}`: a joint name needs no spaces or braces"));
    }
    let Some(index) = clip.skeleton().find(from) else { return err(format!("rename: no joint named `{from}`")) };
    let joints: Vec<Joint> = clip
        .skeleton()
        .joints()
        .iter()
        .enumerate()
        .map(|(i, j)| {
            let mut joint = j.clone();
            if i == index {
                joint.name = to.to_owned();
            }
            // An End Site named after its joint (`Head_End`, as readers name them) follows.
            if j.is_end_site() && j.parent == Some(index) && j.name == format!("{from}_End") {
                joint.name = format!("{to}_End");
            }
            joint
        })
        .collect();
    let skeleton = Skeleton::new(joints, EulerConvention::Intrinsic).map_err(|e| EditError(e.to_string()))?;
    rebuild(clip, skeleton, clip.frame_time(), clip.frame_count(), clip.motion().data().to_vec())
}

fn remove_joint(clip: &Clip, name: &str, fold: bool) -> Result<Clip, EditError> {
    let skeleton = clip.skeleton();
    let Some(gone) = skeleton.find(name) else { return err(format!("remove: no joint named `{name}`")) };
    let old = skeleton.joints();
    let parent = old[gone].parent;
    if parent.is_none() && old.iter().filter(|j| j.parent == Some(gone)).count() != 1 {
        return err(format!("remove `{name}`: a root can be removed only when it has exactly one child"));
    }
    let poses = locals(clip);
    // New indices: every joint but the removed one, in order.
    let map: Vec<Option<usize>> = (0..old.len())
        .scan(0usize, |next, i| {
            Some(if i == gone {
                None
            } else {
                *next += 1;
                Some(*next - 1)
            })
        })
        .collect();
    let children: Vec<usize> = (0..old.len()).filter(|&i| old[i].parent == Some(gone)).collect();
    // Children of the removed joint hang from its parent, at its offset plus
    // theirs. Folding gives a joint child position channels and all three
    // rotations (the removed joint's turning moves it); an End Site child keeps
    // its rest place.
    let joints: Vec<Joint> = old
        .iter()
        .enumerate()
        .filter(|(i, _)| *i != gone)
        .map(|(i, j)| {
            let new_parent = if j.parent == Some(gone) { parent } else { j.parent }.and_then(|p| map[p]);
            let child = children.contains(&i);
            let offset = if child { old[gone].offset + j.offset } else { j.offset };
            if j.is_end_site() {
                Joint::end_site(j.name.clone(), new_parent, offset)
            } else if child && fold {
                let mut channels = vec![Channel::Xposition, Channel::Yposition, Channel::Zposition];
                channels.extend([Channel::Zrotation, Channel::Xrotation, Channel::Yrotation]);
                Joint::new(j.name.clone(), new_parent, offset, channels)
            } else {
                Joint::new(j.name.clone(), new_parent, offset, j.channels.clone())
            }
        })
        .collect();
    let new_skeleton = Skeleton::new(joints, EulerConvention::Intrinsic).map_err(|e| EditError(e.to_string()))?;
    let new_poses: Vec<LocalPose> = poses
        .iter()
        .map(|p| {
            let mut out = LocalPose::rest(&new_skeleton);
            for (i, m) in map.iter().enumerate() {
                let Some(n) = *m else { continue };
                out.translation[n] = p.translation[i];
                out.rotation[n] = p.rotation[i];
                if children.contains(&i) && !old[i].is_end_site() {
                    if fold {
                        out.translation[n] = p.translation[gone] + p.rotation[gone] * p.translation[i];
                        out.rotation[n] = (p.rotation[gone] * p.rotation[i]).normalize();
                    } else {
                        out.translation[n] = old[gone].offset + p.translation[i];
                    }
                } else if old[i].is_end_site() {
                    out.translation[n] = new_skeleton.joints()[n].offset;
                }
            }
            out
        })
        .collect();
    from_locals(clip, new_skeleton, clip.frame_time(), &new_poses)
}

/// Weight of a correction keyed at `key` at frame `f`: 1 there, easing (smoothstep)
/// to 0 at `window + 1` frames away.
fn key_weight(f: usize, key: usize, window: usize) -> f32 {
    let d = f.abs_diff(key) as f32 / (window + 1) as f32;
    if d >= 1.0 {
        return 0.0;
    }
    let t = 1.0 - d;
    t * t * (3.0 - 2.0 * t)
}

fn correct(
    clip: &Clip,
    frame: usize,
    rotations: &[(String, Quat)],
    translations: &[(String, Vec3)],
    window: usize,
) -> Result<Clip, EditError> {
    let n = clip.frame_count();
    if frame >= n {
        return err(format!("key at frame {frame}: the clip has frames 0 to {}", n.saturating_sub(1)));
    }
    let skeleton = clip.skeleton();
    let find = |name: &str| skeleton.find(name).ok_or_else(|| EditError(format!("key: no joint named `{name}`")));
    let rotations: Vec<(usize, Quat)> =
        rotations.iter().map(|(name, q)| Ok((find(name)?, *q))).collect::<Result<_, EditError>>()?;
    let translations: Vec<(usize, Vec3)> =
        translations.iter().map(|(name, t)| Ok((find(name)?, *t))).collect::<Result<_, EditError>>()?;
    if rotations.iter().any(|(_, q)| !q.is_finite()) || translations.iter().any(|(_, t)| !t.is_finite()) {
        return err("key: a value is not finite");
    }
    let mut poses = locals(clip);
    let at_key = poses[frame].clone();
    // The change at the key, in each joint's own frame, spread over the window.
    let deltas: Vec<(usize, Quat)> =
        rotations.iter().map(|&(j, q)| (j, (at_key.rotation[j].inverse() * q).normalize())).collect();
    let moves: Vec<(usize, Vec3)> = translations.iter().map(|&(j, t)| (j, t - at_key.translation[j])).collect();
    for (f, pose) in poses.iter_mut().enumerate() {
        let w = key_weight(f, frame, window);
        if w <= 0.0 {
            continue;
        }
        for &(j, d) in &deltas {
            pose.rotation[j] = (pose.rotation[j] * Quat::IDENTITY.slerp(d, w)).normalize();
        }
        for &(j, m) in &moves {
            pose.translation[j] += m * w;
        }
    }
    // Joints whose translation is keyed need position channels.
    let joints: Vec<Joint> = skeleton
        .joints()
        .iter()
        .enumerate()
        .map(|(i, j)| {
            let moved = translations.iter().any(|(k, _)| *k == i);
            if moved && !j.channels.iter().any(|c| c.kind() == ChannelKind::Translation) {
                let mut channels = vec![Channel::Xposition, Channel::Yposition, Channel::Zposition];
                channels.extend(j.channels.iter().copied());
                Joint::new(j.name.clone(), j.parent, j.offset, channels)
            } else if j.is_end_site() {
                Joint::end_site(j.name.clone(), j.parent, j.offset)
            } else {
                Joint::new(j.name.clone(), j.parent, j.offset, j.channels.clone())
            }
        })
        .collect();
    let skeleton = Skeleton::new(joints, EulerConvention::Intrinsic).map_err(|e| EditError(e.to_string()))?;
    from_locals(clip, skeleton, clip.frame_time(), &poses)
}

/// Interpolates every frame from the poses at the frames `keys` (see
/// [`Edit::Key`]): slerp of rotations and lerp of positions between consecutive
/// keys, the first key's pose before it and the last key's after it.
fn tween(clip: &Clip, mut keys: Vec<usize>) -> Result<Clip, EditError> {
    let n = clip.frame_count();
    if let Some(k) = keys.iter().find(|&&k| k >= n) {
        return err(format!("key at frame {k}: the clip has frames 0 to {}", n.saturating_sub(1)));
    }
    keys.sort_unstable();
    keys.dedup();
    let (Some(&first), Some(&last)) = (keys.first(), keys.last()) else { return Ok(clip.clone()) };
    let source = locals(clip);
    let mut poses = source.clone();
    for (f, pose) in poses.iter_mut().enumerate() {
        let (a, b) = match keys.binary_search(&f) {
            Ok(_) => continue,
            Err(0) => (first, first),
            Err(i) if i >= keys.len() => (last, last),
            Err(i) => (keys[i - 1], keys[i]),
        };
        let t = if b > a { (f - a) as f32 / (b - a) as f32 } else { 0.0 };
        let (pa, pb) = (&source[a], &source[b]);
        for j in 0..pose.rotation.len().min(pa.rotation.len()).min(pb.rotation.len()) {
            pose.rotation[j] = pa.rotation[j].slerp(pb.rotation[j], t).normalize();
            pose.translation[j] = pa.translation[j].lerp(pb.translation[j], t);
        }
    }
    from_locals(clip, clip.skeleton().clone(), clip.frame_time(), &poses)
}

/// A new character for the creator: a root joint `Hips` one metre up with all six
/// channels and an End Site above it, `frames` frames of its rest pose at `fps`.
pub fn new_character(frames: usize, fps: f64) -> Clip {
    let root = Joint::new(
        "Hips",
        None,
        Vec3::new(0.0, 1.0, 0.0),
        vec![
            Channel::Xposition,
            Channel::Yposition,
            Channel::Zposition,
            Channel::Zrotation,
            Channel::Xrotation,
            Channel::Yrotation,
        ],
    );
    let end = Joint::end_site("Hips_End", Some(0), Vec3::new(0.0, 0.1, 0.0));
    let skeleton = Skeleton::new(vec![root, end], EulerConvention::Intrinsic).unwrap_or_default();
    let frames = frames.max(1);
    let row = [0.0, 1.0, 0.0, 0.0, 0.0, 0.0];
    let data: Vec<f32> = (0..frames).flat_map(|_| row).collect();
    let fps = if fps.is_finite() && fps > 0.0 { fps } else { 30.0 };
    Motion::new(1.0 / fps, 6, frames, data).and_then(|m| Clip::new(skeleton, m).ok()).unwrap_or_default()
}

/// Joints (each with the index of its source joint, if any) put in depth-first
/// order, parents remapped; returns the new joints and, per new joint, its source.
fn depth_first(joints: Vec<(Joint, Option<usize>)>) -> (Vec<Joint>, Vec<Option<usize>>) {
    let mut children: Vec<Vec<usize>> = vec![Vec::new(); joints.len()];
    let mut roots = Vec::new();
    for (i, (j, _)) in joints.iter().enumerate() {
        match j.parent.filter(|&p| p < joints.len() && p != i) {
            Some(p) => children[p].push(i),
            None => roots.push(i),
        }
    }
    let mut order = Vec::with_capacity(joints.len());
    let mut stack: Vec<usize> = roots.into_iter().rev().collect();
    while let Some(i) = stack.pop() {
        order.push(i);
        stack.extend(children[i].iter().rev());
    }
    let mut position = vec![0usize; joints.len()];
    for (k, &i) in order.iter().enumerate() {
        position[i] = k;
    }
    let mut out = Vec::with_capacity(order.len());
    let mut sources = Vec::with_capacity(order.len());
    for &i in &order {
        let (joint, source) = &joints[i];
        let mut joint = joint.clone();
        joint.parent = joint.parent.map(|p| position[p]);
        out.push(joint);
        sources.push(*source);
    }
    (out, sources)
}

/// A clip over `joints` (from [`depth_first`]): each frame's local pose taken from
/// the source joints, rest values for new ones.
fn restructured(clip: &Clip, joints: Vec<Joint>, sources: &[Option<usize>]) -> Result<Clip, EditError> {
    // Plain joints again (columns are assigned by the skeleton).
    let joints: Vec<Joint> = joints
        .into_iter()
        .map(|j| {
            if j.is_end_site() {
                Joint::end_site(j.name.clone(), j.parent, j.offset)
            } else {
                Joint::new(j.name.clone(), j.parent, j.offset, j.channels.clone())
            }
        })
        .collect();
    let skeleton = Skeleton::new(joints, EulerConvention::Intrinsic).map_err(|e| EditError(e.to_string()))?;
    let rest = LocalPose::rest(&skeleton);
    let poses: Vec<LocalPose> = locals(clip)
        .iter()
        .map(|p| {
            let mut out = rest.clone();
            for (n, source) in sources.iter().enumerate() {
                if let Some(i) = source {
                    if !skeleton.is_end_site(n) {
                        out.translation[n] = p.translation[*i];
                        out.rotation[n] = p.rotation[*i];
                    }
                }
            }
            out
        })
        .collect();
    from_locals(clip, skeleton, clip.frame_time(), &poses)
}

fn add_joint(clip: &Clip, parent: &str, name: &str, offset: Vec3) -> Result<Clip, EditError> {
    let skeleton = clip.skeleton();
    let name = name.trim();
    if name.is_empty() || name.chars().any(|c| c.is_whitespace() || c == '{' || c == '}') {
        return err(format!("add `{name}`: a joint name needs no spaces or braces"));
    }
    if skeleton.find(name).is_some() {
        return err(format!("add `{name}`: there is already a joint of that name"));
    }
    if !offset.is_finite() {
        return err(format!("add `{name}`: the offset is not finite"));
    }
    let p = skeleton.find(parent).ok_or_else(|| EditError(format!("add: no joint named `{parent}`")))?;
    if skeleton.is_end_site(p) {
        return err(format!("add under `{parent}`: an End Site has no children"));
    }
    let mut joints: Vec<(Joint, Option<usize>)> = skeleton
        .joints()
        .iter()
        .enumerate()
        // The parent's End Site gives way to the new joint.
        .filter(|(_, j)| !(j.is_end_site() && j.parent == Some(p)))
        .map(|(i, j)| (j.clone(), Some(i)))
        .collect();
    // Parents as positions in this list.
    let position: Vec<Option<usize>> = {
        let mut map = vec![None; skeleton.len()];
        for (k, (_, source)) in joints.iter().enumerate() {
            if let Some(i) = source {
                map[*i] = Some(k);
            }
        }
        map
    };
    for (joint, _) in &mut joints {
        joint.parent = joint.parent.and_then(|q| position[q]);
    }
    let parent_position = position[p].ok_or_else(|| EditError("the parent vanished".into()))?;
    let new_index = joints.len();
    joints.push((
        Joint::new(
            name,
            Some(parent_position),
            offset,
            vec![Channel::Zrotation, Channel::Xrotation, Channel::Yrotation],
        ),
        None,
    ));
    let tip = if offset.length() > 0.0 { offset * 0.25 } else { Vec3::new(0.0, 0.05, 0.0) };
    joints.push((Joint::end_site(format!("{name}_End"), Some(new_index), tip), None));
    let (joints, sources) = depth_first(joints);
    restructured(clip, joints, &sources)
}

fn set_offset(clip: &Clip, name: &str, offset: Vec3) -> Result<Clip, EditError> {
    let skeleton = clip.skeleton();
    let j = skeleton.find(name).ok_or_else(|| EditError(format!("offset: no joint named `{name}`")))?;
    if !offset.is_finite() {
        return err(format!("offset of `{name}`: not finite"));
    }
    // A joint with position channels keeps its animated position; for it the rest
    // offset changes only the file's OFFSET line.
    with_joint_changed(clip, j, |joint| joint.offset = offset)
}

/// The clip with joint `j` changed by `change` (same joints and order; each
/// frame's pose kept, written back for the changed joint's channels).
fn with_joint_changed(clip: &Clip, j: usize, change: impl FnOnce(&mut Joint)) -> Result<Clip, EditError> {
    let mut joints: Vec<Joint> = clip.skeleton().joints().to_vec();
    if let Some(joint) = joints.get_mut(j) {
        change(joint);
    }
    let sources: Vec<Option<usize>> = (0..joints.len()).map(Some).collect();
    restructured(clip, joints, &sources)
}

fn set_channels(clip: &Clip, name: &str, position: bool, order: &str) -> Result<Clip, EditError> {
    let skeleton = clip.skeleton();
    let j = skeleton.find(name).ok_or_else(|| EditError(format!("channels: no joint named `{name}`")))?;
    if skeleton.is_end_site(j) {
        return err(format!("channels of `{name}`: an End Site has none"));
    }
    let axes: Vec<Channel> = order
        .trim()
        .chars()
        .map(|c| match c.to_ascii_uppercase() {
            'X' => Ok(Channel::Xrotation),
            'Y' => Ok(Channel::Yrotation),
            'Z' => Ok(Channel::Zrotation),
            _ => Err(EditError(format!("rotation order `{order}`: use X, Y and Z, e.g. ZXY"))),
        })
        .collect::<Result<_, _>>()?;
    let mut seen = axes.clone();
    seen.sort_by_key(|c| c.axis());
    seen.dedup();
    if seen.len() != axes.len() || axes.len() != 3 {
        return err(format!("rotation order `{order}`: name each of X, Y and Z once"));
    }
    let mut channels =
        if position { vec![Channel::Xposition, Channel::Yposition, Channel::Zposition] } else { Vec::new() };
    channels.extend(axes);
    with_joint_changed(clip, j, |joint| joint.channels = channels)
}
