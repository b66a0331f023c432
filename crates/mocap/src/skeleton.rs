//! Skeletons: flat arrays of joints in parent-before-child order.

use crate::channel::Channel;
use glam::Vec3;

/// One joint (or End Site) of a skeleton.
#[derive(Clone, Debug, PartialEq)]
pub struct Joint {
    /// The joint's name as written in the file (End Sites get `"<parent>_End"`
    /// unless the file names them).
    pub name: String,
    /// Index of the parent joint; always smaller than this joint's index.
    /// `None` for a root.
    pub parent: Option<usize>,
    /// Rest offset from the parent, in file units.
    pub offset: Vec3,
    /// Animated channels in file order (empty for End Sites).
    pub channels: Vec<Channel>,
    /// Column of the first channel in a motion row.
    pub first_channel: usize,
    /// True for an `End Site`: no channels, it only marks where the last bone ends.
    pub end_site: bool,
}

/// A set of joint trees (one file may hold several ROOTs), flattened so that every
/// parent comes before its children.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Skeleton {
    /// All joints, parent-before-child; End Sites included.
    pub joints: Vec<Joint>,
}

impl Skeleton {
    /// Number of joints including End Sites.
    pub fn len(&self) -> usize {
        self.joints.len()
    }

    /// True when there are no joints at all.
    pub fn is_empty(&self) -> bool {
        self.joints.is_empty()
    }

    /// Total number of channels, i.e. the width of a motion row.
    pub fn channel_count(&self) -> usize {
        self.joints.iter().map(|j| j.channels.len()).sum()
    }

    /// Indices of the root joints, one per skeleton in the file.
    pub fn roots(&self) -> impl Iterator<Item = usize> + '_ {
        self.joints
            .iter()
            .enumerate()
            .filter(|(_, j)| j.parent.is_none())
            .map(|(i, _)| i)
    }

    /// Index of the first joint with this name.
    pub fn find(&self, name: &str) -> Option<usize> {
        self.joints.iter().position(|j| j.name == name)
    }

    /// Depth of each joint (roots are 0), in one pass.
    pub fn depths(&self) -> Vec<usize> {
        let mut depths = Vec::with_capacity(self.joints.len());
        for joint in &self.joints {
            let d = joint
                .parent
                .and_then(|p| depths.get(p).copied())
                .map_or(0, |d: usize| d + 1);
            depths.push(d);
        }
        depths
    }

    /// Checks the invariants every consumer relies on: parents come before their
    /// children and every channel column lies inside a motion row.
    pub fn validate(&self) -> Result<(), String> {
        let width = self.channel_count();
        for (i, j) in self.joints.iter().enumerate() {
            if let Some(p) = j.parent.filter(|&p| p >= i) {
                return Err(format!("joint {i} ({}) has parent {p} after it", j.name));
            }
            if j.first_channel + j.channels.len() > width {
                return Err(format!("joint {i} ({}) has channels out of range", j.name));
            }
        }
        Ok(())
    }
}
