//! A loaded clip with what the UI derives from it once.

use mocap::{Aabb, Clip, Units};
use mocap_render::FigureJoint;

/// A clip, its file name and derived facts (children lists, units, scale).
pub struct Document {
    /// File name as given when loading.
    pub name: String,
    /// The clip.
    pub clip: Clip,
    /// Children of each joint, in file order.
    pub children: Vec<Vec<usize>>,
    /// Guessed length unit.
    pub units: Units,
    /// Bounds of all joints over all frames (computed once).
    pub bounds: Aabb,
    /// Size of the first pose in file units (a humanoid's height), for sizing markers.
    pub extent: f32,
    /// Parents and end points of the joints, as the renderer draws them.
    pub figure: Vec<FigureJoint>,
}

impl Document {
    /// Wraps a clip.
    pub fn new(name: &str, clip: Clip) -> Document {
        let n = clip.skeleton().joints().len();
        let mut children = vec![Vec::new(); n];
        for (i, joint) in clip.skeleton().joints().iter().enumerate() {
            if let Some(list) = joint.parent.and_then(|p| children.get_mut(p)) {
                list.push(i);
            }
        }
        let extent = clip.pose_extent();
        let extent = if extent.is_finite() && extent > 0.0 { extent } else { 1.0 };
        let figure = clip.skeleton().joints().iter().map(|j| FigureJoint { parent: j.parent, end_site: j.is_end_site() }).collect();
        Document { name: name.to_owned(), units: clip.units(), bounds: clip.bounds(), clip, children, extent, figure }
    }

    /// Timing facts for playback.
    pub fn timing(&self) -> crate::playback::Timing {
        crate::playback::Timing { frames: self.clip.frame_count(), frame_time: self.clip.frame_time() }
    }

    /// Joints that are not End Sites.
    pub fn joint_count(&self) -> usize {
        self.clip.skeleton().joints().iter().filter(|j| !j.is_end_site()).count()
    }

    /// Metres per file unit (the scale that puts this clip in the shared metre world).
    pub fn meters_per_unit(&self) -> f32 {
        self.units.meters_per_unit()
    }
}
