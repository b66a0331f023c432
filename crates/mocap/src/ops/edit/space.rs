//! Edits of where the clip stands: [`Edit::InPlace`](super::Edit::InPlace) (no
//! travel), [`Edit::UpAxis`](super::Edit::UpAxis) (stood Y-up) and
//! [`Edit::Scale`](super::Edit::Scale) (lengths).

use super::poses::{from_locals, locals, rebuild, roots};
use super::{EditError, err};
use crate::model::channel::{Channel, ChannelKind};
use crate::model::clip::Clip;
use crate::model::skeleton::{EulerConvention, Joint, Skeleton};
use glam::{Quat, Vec3};

pub(super) fn in_place(clip: &Clip, remove_turning: bool) -> Result<Clip, EditError> {
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

pub(super) fn up_axis(clip: &Clip, from: usize, negative: bool) -> Result<Clip, EditError> {
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

pub(super) fn scale(clip: &Clip, factor: f32) -> Result<Clip, EditError> {
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
