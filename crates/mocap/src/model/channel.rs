//! The animated degrees of freedom a joint can have, in one general set shared by
//! every format, and the angle unit their rotation values are written in.

use serde::{Deserialize, Serialize};
use std::fmt;

/// One animated degree of freedom of a joint.
///
/// What each kind does to the joint's local transform (see [`crate::runtime::pose`]):
/// - a translation channel *sets* that component of the local translation (its rest
///   value is replaced, as Blender and BVHView read BVH position channels; readers
///   of formats that add to the rest translation add it when they read the value);
/// - rotation channels are angles in the clip's [`AngleUnit`], composed in file order
///   by the skeleton's [`crate::model::skeleton::EulerConvention`];
/// - scale channels set that component of the local scale (1 at rest);
/// - the bone-length channel (Acclaim `l`) moves the joint's children along their
///   rest direction by the value (a change of bone length, 0 at rest).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Channel {
    /// Sets the X component of the local translation.
    Xposition,
    /// Sets the Y component of the local translation.
    Yposition,
    /// Sets the Z component of the local translation.
    Zposition,
    /// Rotation about the local X axis.
    Xrotation,
    /// Rotation about the local Y axis.
    Yrotation,
    /// Rotation about the local Z axis.
    Zrotation,
    /// Sets the X component of the local scale.
    Xscale,
    /// Sets the Y component of the local scale.
    Yscale,
    /// Sets the Z component of the local scale.
    Zscale,
    /// Changes the bone's length: the children move along their rest direction.
    Length,
}

/// What a [`Channel`] animates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ChannelKind {
    /// A component of the translation.
    Translation,
    /// A rotation about an axis.
    Rotation,
    /// A component of the scale.
    Scale,
    /// The bone length.
    Length,
}

/// The unit rotation values are written in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum AngleUnit {
    /// Degrees (BVH, most Acclaim files).
    #[default]
    Degrees,
    /// Radians (`:RADIANS` AMC files, `angle rad` ASF files).
    Radians,
}

impl AngleUnit {
    /// Radians per unit.
    pub fn radians_per_unit(self) -> f32 {
        match self {
            AngleUnit::Degrees => core::f32::consts::PI / 180.0,
            AngleUnit::Radians => 1.0,
        }
    }

    /// `"deg"` or `"rad"`.
    pub fn name(self) -> &'static str {
        match self {
            AngleUnit::Degrees => "deg",
            AngleUnit::Radians => "rad",
        }
    }
}

impl Channel {
    /// Every channel: translations, rotations, scales, length.
    pub const ALL: [Channel; 10] = [
        Channel::Xposition,
        Channel::Yposition,
        Channel::Zposition,
        Channel::Xrotation,
        Channel::Yrotation,
        Channel::Zrotation,
        Channel::Xscale,
        Channel::Yscale,
        Channel::Zscale,
        Channel::Length,
    ];

    /// The six channels BVH can write, positions first.
    pub const BVH: [Channel; 6] = [
        Channel::Xposition,
        Channel::Yposition,
        Channel::Zposition,
        Channel::Xrotation,
        Channel::Yrotation,
        Channel::Zrotation,
    ];

    /// The BVH-style spelling, e.g. `"Xrotation"`, `"Yscale"`, `"length"`.
    pub fn name(self) -> &'static str {
        match self {
            Channel::Xposition => "Xposition",
            Channel::Yposition => "Yposition",
            Channel::Zposition => "Zposition",
            Channel::Xrotation => "Xrotation",
            Channel::Yrotation => "Yrotation",
            Channel::Zrotation => "Zrotation",
            Channel::Xscale => "Xscale",
            Channel::Yscale => "Yscale",
            Channel::Zscale => "Zscale",
            Channel::Length => "length",
        }
    }

    /// Parses a BVH channel name, ignoring ASCII case (`xRotation` is accepted);
    /// only the six channels BVH has.
    pub fn from_name(name: &[u8]) -> Option<Channel> {
        Channel::BVH.into_iter().find(|c| c.name().as_bytes().eq_ignore_ascii_case(name))
    }

    /// What the channel animates.
    pub fn kind(self) -> ChannelKind {
        match self {
            Channel::Xposition | Channel::Yposition | Channel::Zposition => ChannelKind::Translation,
            Channel::Xrotation | Channel::Yrotation | Channel::Zrotation => ChannelKind::Rotation,
            Channel::Xscale | Channel::Yscale | Channel::Zscale => ChannelKind::Scale,
            Channel::Length => ChannelKind::Length,
        }
    }

    /// The axis, 0 = X, 1 = Y, 2 = Z (the length channel says 1: bones run along their direction).
    pub fn axis(self) -> usize {
        match self {
            Channel::Xposition | Channel::Xrotation | Channel::Xscale => 0,
            Channel::Yposition | Channel::Yrotation | Channel::Yscale | Channel::Length => 1,
            Channel::Zposition | Channel::Zrotation | Channel::Zscale => 2,
        }
    }

    /// True for the three rotation channels.
    pub fn is_rotation(self) -> bool {
        self.kind() == ChannelKind::Rotation
    }

    /// True for the channels BVH can write.
    pub fn is_bvh(self) -> bool {
        matches!(self.kind(), ChannelKind::Translation | ChannelKind::Rotation)
    }
}

impl fmt::Display for Channel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
