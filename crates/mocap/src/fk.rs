//! Forward kinematics: channel values to local transforms, local to world in one
//! linear pass over parent indices (parents always come first).

use crate::channel::Channel;
use crate::fastmath::sin_cos;
use crate::skeleton::{Joint, Skeleton};
use glam::{Quat, Vec3};

/// A rigid transform: rotate, then translate.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    /// Orientation.
    pub rotation: Quat,
    /// Position.
    pub translation: Vec3,
}

impl Transform {
    /// No rotation, no translation.
    pub const IDENTITY: Transform = Transform { rotation: Quat::IDENTITY, translation: Vec3::ZERO };

    /// `self ∘ child`: the child's transform expressed in `self`'s parent space.
    #[inline]
    pub fn compose(&self, child: &Transform) -> Transform {
        Transform {
            rotation: self.rotation * child.rotation,
            translation: self.translation + self.rotation * child.translation,
        }
    }
}

/// Half-angle in radians per degree.
const HALF_RAD_PER_DEG: f32 = core::f32::consts::PI / 360.0;

/// Quaternion for a rotation of `degrees` about one axis (0 = X, 1 = Y, 2 = Z).
#[inline]
pub fn axis_rotation(axis: usize, degrees: f32) -> Quat {
    let (s, c) = sin_cos(degrees * HALF_RAD_PER_DEG);
    match axis {
        0 => Quat::from_xyzw(s, 0.0, 0.0, c),
        1 => Quat::from_xyzw(0.0, s, 0.0, c),
        _ => Quat::from_xyzw(0.0, 0.0, s, c),
    }
}

/// A joint's local transform for one motion row.
///
/// Position channels replace that component of the offset; rotation channels are
/// multiplied in file order (intrinsic). Values missing from a short row count as 0.
#[inline]
pub fn local_transform(joint: &Joint, row: &[f32]) -> Transform {
    let mut translation = joint.offset;
    let mut rotation = Quat::IDENTITY;
    for (k, channel) in joint.channels.iter().enumerate() {
        let value = row.get(joint.first_channel + k).copied().unwrap_or(0.0);
        match channel {
            Channel::Xposition => translation.x = value,
            Channel::Yposition => translation.y = value,
            Channel::Zposition => translation.z = value,
            Channel::Xrotation | Channel::Yrotation | Channel::Zrotation => {
                rotation *= axis_rotation(channel.axis(), value);
            }
        }
    }
    Transform { rotation, translation }
}

/// Fills `out` with every joint's local transform for one motion row.
pub fn local_transforms(skeleton: &Skeleton, row: &[f32], out: &mut Vec<Transform>) {
    out.clear();
    out.extend(skeleton.joints.iter().map(|j| local_transform(j, row)));
}

/// Turns local transforms into world transforms in place, in one pass.
///
/// `transforms` holds one local transform per joint on entry and one world transform
/// per joint on return. Works because each parent precedes its children.
pub fn local_to_world_in_place(skeleton: &Skeleton, transforms: &mut [Transform]) {
    for (i, joint) in skeleton.joints.iter().enumerate().take(transforms.len()) {
        if let Some(p) = joint.parent.filter(|&p| p < i) {
            transforms[i] = transforms[p].compose(&transforms[i]);
        }
    }
}

/// World transforms of all joints for one motion row: local and world in a single
/// fused pass. `out` is resized to the joint count and reused without allocating.
pub fn world_transforms(skeleton: &Skeleton, row: &[f32], out: &mut Vec<Transform>) {
    out.clear();
    out.reserve(skeleton.joints.len());
    for (i, joint) in skeleton.joints.iter().enumerate() {
        let local = local_transform(joint, row);
        let world = match joint.parent.filter(|&p| p < i).and_then(|p| out.get(p)) {
            Some(parent) => parent.compose(&local),
            None => local,
        };
        out.push(world);
    }
}

/// World positions of the rest pose: offsets only, channels ignored.
pub fn rest_positions(skeleton: &Skeleton) -> Vec<Vec3> {
    let mut out: Vec<Vec3> = Vec::with_capacity(skeleton.joints.len());
    for (i, joint) in skeleton.joints.iter().enumerate() {
        let base = joint.parent.filter(|&p| p < i).and_then(|p| out.get(p)).copied().unwrap_or(Vec3::ZERO);
        out.push(base + joint.offset);
    }
    out
}
