//! Between clips and poses, for the edits: motion rows copied in a new order, every
//! frame's local pose, and local poses written back as channel values in each
//! joint's own rotation order.

use super::EditError;
use crate::model::channel::{AngleUnit, ChannelKind};
use crate::model::clip::Clip;
use crate::model::motion::Motion;
use crate::model::skeleton::{Joint, Skeleton};
use crate::runtime::pose::{LocalPose, from_row};
use glam::{EulerRot, Quat, Vec3};

/// The clip with the rows `order` (frame indices) in that order.
pub(super) fn rows(clip: &Clip, order: Vec<usize>) -> Result<Clip, EditError> {
    let motion = clip.motion();
    let width = motion.channel_count();
    let mut data = Vec::with_capacity(width * order.len());
    for f in &order {
        data.extend_from_slice(motion.row(*f));
    }
    rebuild(clip, clip.skeleton().clone(), motion.frame_time(), order.len(), data)
}

pub(super) fn rebuild(
    clip: &Clip,
    skeleton: Skeleton,
    frame_time: f64,
    frames: usize,
    data: Vec<f32>,
) -> Result<Clip, EditError> {
    let width = skeleton.channel_count();
    let motion = Motion::new(frame_time, width, frames, data)
        .ok_or_else(|| EditError("the edit made no valid motion".into()))?;
    let mut out = Clip::new(skeleton, motion.with_angle_unit(clip.motion().angle_unit()))
        .map_err(|e| EditError(e.to_string()))?;
    out.metadata = clip.metadata.clone();
    out.keep_character_of(clip);
    Ok(out)
}

/// Every frame's local pose.
pub(super) fn locals(clip: &Clip) -> Vec<LocalPose> {
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
pub(super) fn from_locals(
    clip: &Clip,
    skeleton: Skeleton,
    frame_time: f64,
    poses: &[LocalPose],
) -> Result<Clip, EditError> {
    let unit = clip.motion().angle_unit();
    let mut data = Vec::with_capacity(skeleton.channel_count() * poses.len());
    for p in poses {
        row_of(&skeleton, p, unit, &mut data);
    }
    rebuild(clip, skeleton, frame_time, poses.len(), data)
}

pub(super) fn roots(skeleton: &Skeleton) -> Vec<usize> {
    skeleton.roots().collect()
}
