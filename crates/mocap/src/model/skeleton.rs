//! Skeletons: flat arrays of joints in parent-before-child order.
//!
//! A [`Skeleton`] can only be built by [`Skeleton::new`], which checks the
//! invariants every consumer relies on (parents before children, End Sites without
//! channels, limits matching channels) and assigns each joint's motion columns, so
//! a skeleton that breaks them cannot exist.

use crate::model::channel::Channel;
use glam::{Quat, Vec3};
use serde::{Deserialize, Serialize};

/// The range a degree of freedom may take (Acclaim `limits`), in the channel's unit.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Limit {
    /// Smallest value (may be `-inf`).
    pub min: f32,
    /// Largest value (may be `inf`).
    pub max: f32,
}

/// How a joint's rotation channels compose.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum EulerConvention {
    /// Intrinsic, in file order: `Zrotation Xrotation Yrotation` is `Rz · Rx · Ry`
    /// (BVH, BVA).
    #[default]
    Intrinsic,
    /// Extrinsic, in file order: `rx ry rz` rotates about X first, then the fixed Y,
    /// then the fixed Z, i.e. `Rz · Ry · Rx` (Acclaim `dof` and `axis` orders).
    Extrinsic,
}

/// One joint (or End Site) of a skeleton.
#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    /// The joint's name as written in the file (End Sites get `"<parent>_End"`
    /// unless the file names them).
    pub name: String,
    /// Index of the parent joint; always smaller than this joint's index in a
    /// [`Skeleton`]. `None` for a root.
    pub parent: Option<usize>,
    /// Rest translation from the parent joint, in the parent's frame, file units.
    pub offset: Vec3,
    /// Rest rotation relative to the parent's frame (identity for BVH; Acclaim's
    /// `axis` relative to its parent's): a joint's local rotation is this times its
    /// channel rotations.
    pub rest_rotation: Quat,
    /// Animated channels in file order (empty for End Sites).
    pub channels: Vec<Channel>,
    /// Per-channel limits (Acclaim `limits`): empty, or one per channel.
    pub limits: Vec<Limit>,
    first_channel: usize,
    end_site: bool,
}

impl Joint {
    /// A joint with these channels, no rest rotation and no limits.
    pub fn new(name: impl Into<String>, parent: Option<usize>, offset: Vec3, channels: Vec<Channel>) -> Joint {
        Joint {
            name: name.into(),
            parent,
            offset,
            rest_rotation: Quat::IDENTITY,
            channels,
            limits: Vec::new(),
            first_channel: 0,
            end_site: false,
        }
    }

    /// An End Site: a point that only marks where its parent's bone ends.
    pub fn end_site(name: impl Into<String>, parent: Option<usize>, offset: Vec3) -> Joint {
        Joint { end_site: true, ..Joint::new(name, parent, offset, Vec::new()) }
    }

    /// The same joint with a rest rotation.
    pub fn with_rest_rotation(mut self, rotation: Quat) -> Joint {
        self.rest_rotation = rotation;
        self
    }

    /// The same joint with per-channel limits.
    pub fn with_limits(mut self, limits: Vec<Limit>) -> Joint {
        self.limits = limits;
        self
    }

    /// Column of the first channel in a motion row (channels are consecutive).
    pub fn first_channel(&self) -> usize {
        self.first_channel
    }

    /// The motion columns of this joint's channels.
    pub fn columns(&self) -> std::ops::Range<usize> {
        self.first_channel..self.first_channel + self.channels.len()
    }

    /// True for an End Site (no channels; it marks where the last bone ends).
    pub fn is_end_site(&self) -> bool {
        self.end_site
    }
}

/// Why joints do not make a skeleton.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("joint {index} (`{name}`): {message}")]
pub struct SkeletonError {
    /// Index of the offending joint.
    pub index: usize,
    /// Its name.
    pub name: String,
    /// What is wrong.
    pub message: String,
}

/// A set of joint trees (one file may hold several roots), flattened so that every
/// parent comes before its children.
#[derive(Clone, Debug, PartialEq)]
pub struct Skeleton {
    joints: Vec<Joint>,
    euler: EulerConvention,
    channel_count: usize,
    has_length: bool,
    has_scale: bool,
    plain: bool,
}

impl Default for Skeleton {
    /// No joints: what [`Skeleton::new`] makes of none (plain, no channels).
    fn default() -> Skeleton {
        Skeleton {
            joints: Vec::new(),
            euler: EulerConvention::Intrinsic,
            channel_count: 0,
            has_length: false,
            has_scale: false,
            plain: true,
        }
    }
}

impl Skeleton {
    /// Checks the joints and builds a skeleton: every parent must come before its
    /// child, End Sites have no channels and no children, and `limits` are empty
    /// or one per channel.
    /// Motion columns are assigned in joint order, channels in their order.
    pub fn new(joints: Vec<Joint>, euler: EulerConvention) -> Result<Skeleton, SkeletonError> {
        Skeleton::build(joints, euler, true)
    }

    /// [`Skeleton::new`] for joints whose rest rotations are already unit
    /// quaternions (a stored skeleton, [`crate::formats::store`]): they are kept
    /// bit for bit rather than normalised again, and one that is not a unit
    /// quaternion (within glam's tolerance) is an error.
    pub(crate) fn with_unit_rotations(joints: Vec<Joint>, euler: EulerConvention) -> Result<Skeleton, SkeletonError> {
        Skeleton::build(joints, euler, false)
    }

    /// The checks of [`Skeleton::new`]; `normalise` normalises rest rotations,
    /// otherwise they must be unit already.
    fn build(joints: Vec<Joint>, euler: EulerConvention, normalise: bool) -> Result<Skeleton, SkeletonError> {
        let mut joints = joints;
        let mut next = 0usize;
        let end_sites: Vec<bool> = joints.iter().map(|j| j.end_site).collect();
        for (index, joint) in joints.iter_mut().enumerate() {
            let fail = |message: &str| SkeletonError { index, name: joint.name.clone(), message: message.to_owned() };
            if joint.parent.is_some_and(|p| p >= index) {
                return Err(fail("its parent does not come before it"));
            }
            if joint.parent.is_some_and(|p| end_sites[p]) {
                return Err(fail("its parent is an End Site, which has no children"));
            }
            if joint.end_site && !joint.channels.is_empty() {
                return Err(fail("an End Site has no channels"));
            }
            if !joint.limits.is_empty() && joint.limits.len() != joint.channels.len() {
                return Err(fail("limits must be given for every channel or none"));
            }
            if !joint.offset.is_finite() || !joint.rest_rotation.is_finite() {
                return Err(fail("its rest transform is not finite"));
            }
            if normalise {
                joint.rest_rotation = joint.rest_rotation.normalize();
            } else if !joint.rest_rotation.is_normalized() {
                return Err(fail("its rest rotation is not a unit quaternion"));
            }
            joint.first_channel = next;
            next += joint.channels.len();
        }
        let has_length = joints.iter().any(|j| j.channels.contains(&Channel::Length));
        let has_scale =
            joints.iter().any(|j| j.channels.iter().any(|c| c.kind() == crate::model::channel::ChannelKind::Scale));
        let plain = euler == EulerConvention::Intrinsic
            && joints.iter().all(|j| j.rest_rotation == Quat::IDENTITY && j.channels.iter().all(|c| c.is_bvh()));
        Ok(Skeleton { joints, euler, channel_count: next, has_length, has_scale, plain })
    }

    /// All joints, parent-before-child; End Sites included.
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }

    /// How rotation channels compose.
    pub fn euler(&self) -> EulerConvention {
        self.euler
    }

    /// Number of joints including End Sites.
    pub fn len(&self) -> usize {
        self.joints.len()
    }

    /// True when there are no joints at all.
    pub fn is_empty(&self) -> bool {
        self.joints.is_empty()
    }

    /// True when joint `index` is an End Site.
    pub fn is_end_site(&self, index: usize) -> bool {
        self.joints.get(index).is_some_and(|j| j.end_site)
    }

    /// Number of joints that are not End Sites.
    pub fn joint_count(&self) -> usize {
        self.joints.iter().filter(|j| !j.end_site).count()
    }

    /// Total number of channels, i.e. the width of a motion row.
    pub fn channel_count(&self) -> usize {
        self.channel_count
    }

    /// True when some joint has a bone-length channel.
    pub fn has_length_channels(&self) -> bool {
        self.has_length
    }

    /// True for skeletons BVH can hold as they are: intrinsic rotations, only
    /// translation and rotation channels, no rest rotations.
    pub fn is_plain(&self) -> bool {
        self.plain
    }

    /// True when some joint has a scale channel.
    pub fn has_scale_channels(&self) -> bool {
        self.has_scale
    }

    /// Indices of the root joints, one per skeleton in the file.
    pub fn roots(&self) -> impl Iterator<Item = usize> + '_ {
        self.joints.iter().enumerate().filter(|(_, j)| j.parent.is_none()).map(|(i, _)| i)
    }

    /// Index of the first joint with this name.
    pub fn find(&self, name: &str) -> Option<usize> {
        self.joints.iter().position(|j| j.name == name)
    }

    /// Children of each joint, in joint order (one linear pass).
    pub fn children(&self) -> Vec<Vec<usize>> {
        let mut kids = vec![Vec::new(); self.joints.len()];
        for (i, j) in self.joints.iter().enumerate() {
            if let Some(list) = j.parent.and_then(|p| kids.get_mut(p)) {
                list.push(i);
            }
        }
        kids
    }

    /// Depth of each joint (roots are 0), in one pass.
    pub fn depths(&self) -> Vec<usize> {
        let mut depths = Vec::with_capacity(self.joints.len());
        for joint in &self.joints {
            let d = joint.parent.and_then(|p| depths.get(p).copied()).map_or(0, |d: usize| d + 1);
            depths.push(d);
        }
        depths
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn invariants_are_checked_and_columns_assigned() {
        let ok = Skeleton::new(
            vec![
                Joint::new("a", None, Vec3::ZERO, vec![Channel::Xposition, Channel::Zrotation]),
                Joint::new("b", Some(0), Vec3::Y, vec![Channel::Length]),
                Joint::end_site("b_End", Some(1), Vec3::Y),
            ],
            EulerConvention::Intrinsic,
        )
        .unwrap();
        assert_eq!(ok.channel_count(), 3);
        assert_eq!(ok.joints()[1].columns(), 2..3);
        assert!(ok.is_end_site(2) && !ok.is_end_site(1) && !ok.is_end_site(9));
        assert_eq!(ok.joint_count(), 2);
        let bad_parent = Skeleton::new(vec![Joint::new("a", Some(0), Vec3::ZERO, vec![])], EulerConvention::Intrinsic);
        assert_eq!(bad_parent.unwrap_err().index, 0);
        let mut end = Joint::end_site("e", None, Vec3::ZERO);
        end.channels.push(Channel::Xrotation);
        assert!(Skeleton::new(vec![end], EulerConvention::Intrinsic).is_err());
        let under_end = vec![Joint::end_site("e", None, Vec3::Y), Joint::new("a", Some(0), Vec3::Y, vec![])];
        assert_eq!(Skeleton::new(under_end, EulerConvention::Intrinsic).unwrap_err().index, 1);
        let limits = Joint::new("a", None, Vec3::ZERO, vec![Channel::Xrotation]).with_limits(vec![]);
        assert!(Skeleton::new(vec![limits.clone()], EulerConvention::Intrinsic).is_ok());
        let two = limits.with_limits(vec![Limit { min: 0.0, max: 1.0 }; 2]);
        assert!(Skeleton::new(vec![two], EulerConvention::Intrinsic).is_err());
        let nan = Joint::new("a", None, Vec3::NAN, vec![]);
        assert!(Skeleton::new(vec![nan], EulerConvention::Intrinsic).is_err());
    }
}
