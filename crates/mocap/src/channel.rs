//! The six BVH channel kinds and what each does to a joint's local transform.

use std::fmt;

/// One animated degree of freedom of a joint, as named in a BVH `CHANNELS` line.
///
/// Semantics (what [`crate::fk`] implements):
/// - a position channel *replaces* that component of the joint's rest `OFFSET`
///   (as Blender and BVHView do);
/// - rotation channels are in degrees and are applied in file order as intrinsic
///   rotations: `Zrotation Xrotation Yrotation` means `R = Rz · Rx · Ry`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Channel {
    /// Replaces the X component of the offset.
    Xposition,
    /// Replaces the Y component of the offset.
    Yposition,
    /// Replaces the Z component of the offset.
    Zposition,
    /// Rotation about the local X axis, degrees.
    Xrotation,
    /// Rotation about the local Y axis, degrees.
    Yrotation,
    /// Rotation about the local Z axis, degrees.
    Zrotation,
}

impl Channel {
    /// All channels, positions first.
    pub const ALL: [Channel; 6] = [
        Channel::Xposition,
        Channel::Yposition,
        Channel::Zposition,
        Channel::Xrotation,
        Channel::Yrotation,
        Channel::Zrotation,
    ];

    /// The BVH spelling, e.g. `"Xrotation"`.
    pub fn name(self) -> &'static str {
        match self {
            Channel::Xposition => "Xposition",
            Channel::Yposition => "Yposition",
            Channel::Zposition => "Zposition",
            Channel::Xrotation => "Xrotation",
            Channel::Yrotation => "Yrotation",
            Channel::Zrotation => "Zrotation",
        }
    }

    /// Parses a channel name, ignoring ASCII case (`xRotation` is accepted).
    pub fn from_name(name: &[u8]) -> Option<Channel> {
        Channel::ALL
            .into_iter()
            .find(|c| c.name().as_bytes().eq_ignore_ascii_case(name))
    }

    /// The axis, 0 = X, 1 = Y, 2 = Z.
    pub fn axis(self) -> usize {
        match self {
            Channel::Xposition | Channel::Xrotation => 0,
            Channel::Yposition | Channel::Yrotation => 1,
            Channel::Zposition | Channel::Zrotation => 2,
        }
    }

    /// True for the three rotation channels.
    pub fn is_rotation(self) -> bool {
        matches!(
            self,
            Channel::Xrotation | Channel::Yrotation | Channel::Zrotation
        )
    }
}

impl fmt::Display for Channel {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}
