//! Edits of the rig: joints renamed, removed, added, moved and given other
//! channels, each frame's pose kept; and the creator's [`new_character`].

use super::poses::{from_locals, locals, rebuild};
use super::{EditError, err};
use crate::model::channel::Channel;
use crate::model::clip::Clip;
use crate::model::motion::Motion;
use crate::model::skeleton::{EulerConvention, Joint, Skeleton};
use crate::runtime::pose::LocalPose;
use glam::Vec3;

pub(super) fn rename(clip: &Clip, from: &str, to: &str) -> Result<Clip, EditError> {
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

pub(super) fn remove_joint(clip: &Clip, name: &str, fold: bool) -> Result<Clip, EditError> {
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

pub(super) fn add_joint(clip: &Clip, parent: &str, name: &str, offset: Vec3) -> Result<Clip, EditError> {
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

pub(super) fn set_offset(clip: &Clip, name: &str, offset: Vec3) -> Result<Clip, EditError> {
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

pub(super) fn set_channels(clip: &Clip, name: &str, position: bool, order: &str) -> Result<Clip, EditError> {
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
