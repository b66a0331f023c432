//! Which file axis points up. BVH is Y-up by convention, but some tools write
//! Z-up files (MakeHuman's skeletons, Blender scenes exported without the axis
//! conversion); drawn as Y-up such a character lies on its back. The world the
//! viewer and `mocap render` draw is Y-up: [`UpAxis::rotation`] takes a file's
//! axes there.
//!
//! The guess ([`UpAxis::guess`]) reads the motion, not the rest pose (rest
//! poses are often bones along X that the motion's rotations stand up): a clip
//! is Z-up when its posed frames are much deeper along Z than along Y (in the
//! median of frames spread over the clip) and its root does not travel along Z
//! as far as the figure is tall (a crawl along Z in a Y-up file travels), unless
//! its rest pose stands clearly along Y (a Y-up figure lying down in place: push-ups).
//! Files the guess gets wrong can be set by hand.

use crate::model::clip::{Aabb, Clip};
use glam::{Quat, Vec3};
use serde::{Deserialize, Serialize};
use std::f32::consts::FRAC_PI_2;

/// Frames of a clip the guess poses, spread evenly over it.
const GUESS_FRAMES: usize = 16;

/// How much deeper along Z than along Y (median over frames) a Z-up clip is.
/// On the corpus, Y-up clips measure at most 1.02 (VR trackers) and 0.73 for a
/// body, Z-up ones at least 2.18 (a walk: its stride is deep along Y).
const Z_OVER_Y: f32 = 1.5;

/// A rest pose this much taller along Y than deep along Z stands along Y.
const REST_Y_OVER_Z: f32 = 2.0;

/// Fewer joints than this give no evidence (a lone bone lies any way).
const MIN_JOINTS: usize = 4;

/// The file axis that points up.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum UpAxis {
    /// +Y up (BVH's convention, Acclaim, MD2 once decoded).
    #[default]
    Y,
    /// +Z up.
    Z,
}

impl UpAxis {
    /// Its name in URLs and on command lines: `y` or `z`.
    pub fn name(self) -> &'static str {
        match self {
            UpAxis::Y => "y",
            UpAxis::Z => "z",
        }
    }

    /// The axis called `name` (`y` or `z`, any case).
    pub fn from_name(name: &str) -> Option<UpAxis> {
        match name.trim() {
            n if n.eq_ignore_ascii_case("y") => Some(UpAxis::Y),
            n if n.eq_ignore_ascii_case("z") => Some(UpAxis::Z),
            _ => None,
        }
    }

    /// The rotation from the file's axes to the Y-up world: none for Y; for Z a
    /// quarter turn about X taking +Z to +Y (and +Y to −Z).
    pub fn rotation(self) -> Quat {
        match self {
            UpAxis::Y => Quat::IDENTITY,
            UpAxis::Z => Quat::from_rotation_x(-FRAC_PI_2),
        }
    }

    /// A point in the file's axes, in the Y-up world's (exact: no rounding).
    pub fn to_y_up(self, p: Vec3) -> Vec3 {
        match self {
            UpAxis::Y => p,
            UpAxis::Z => Vec3::new(p.x, p.z, -p.y),
        }
    }

    /// A point in the Y-up world's axes, in the file's ([`UpAxis::to_y_up`] undone).
    pub fn from_y_up(self, p: Vec3) -> Vec3 {
        match self {
            UpAxis::Y => p,
            UpAxis::Z => Vec3::new(p.x, -p.z, p.y),
        }
    }

    /// A box in the file's axes, as a box in the Y-up world's.
    pub fn box_to_y_up(self, b: Aabb) -> Aabb {
        if b.is_empty() {
            return b;
        }
        let (p, q) = (self.to_y_up(b.min), self.to_y_up(b.max));
        Aabb { min: p.min(q), max: p.max(q) }
    }

    /// The size of `size` (a box's edges in the file's axes) along this axis.
    pub fn height(self, size: Vec3) -> f32 {
        match self {
            UpAxis::Y => size.y,
            UpAxis::Z => size.z,
        }
    }

    /// Guesses which way is up in `clip` (see the module's documentation): Y
    /// unless the evidence for Z is strong.
    pub fn guess(clip: &Clip) -> UpAxis {
        let frames = clip.frame_count();
        if frames == 0 || clip.skeleton().len() < MIN_JOINTS {
            return UpAxis::Y;
        }
        let skip_roots = clip.skeleton().joints().iter().any(|j| j.parent.is_some());
        let mut ratios = Vec::with_capacity(GUESS_FRAMES);
        let mut root_z = (f32::INFINITY, f32::NEG_INFINITY);
        let mut tallest = 0.0f32;
        let mut positions = Vec::new();
        let step = frames.div_ceil(GUESS_FRAMES).max(1);
        for frame in (0..frames).step_by(step) {
            clip.world_positions_into(frame, &mut positions);
            let mut b = Aabb::EMPTY;
            for (joint, p) in clip.skeleton().joints().iter().zip(&positions) {
                if joint.parent.is_none() {
                    if p.z.is_finite() {
                        root_z = (root_z.0.min(p.z), root_z.1.max(p.z));
                    }
                    if skip_roots {
                        continue;
                    }
                }
                if p.is_finite() {
                    b.include(*p);
                }
            }
            if b.is_empty() {
                continue;
            }
            let size = b.size();
            tallest = tallest.max(size.z);
            ratios.push(size.z / size.y.max(f32::MIN_POSITIVE));
        }
        if ratios.is_empty() || rest_stands_along_y(clip) {
            return UpAxis::Y;
        }
        ratios.sort_by(f32::total_cmp);
        let median = ratios.get(ratios.len() / 2).copied().unwrap_or(0.0);
        let root_travel = if root_z.0 <= root_z.1 { root_z.1 - root_z.0 } else { 0.0 };
        if median > Z_OVER_Y && root_travel < 0.5 * tallest { UpAxis::Z } else { UpAxis::Y }
    }
}

/// Whether the skeleton's rest pose (its offsets alone) stands clearly along Y:
/// then a motion lying along Z is a Y-up figure lying down (push-ups, a nap),
/// not a Z-up file. Rest poses of Z-up files point along Z, or along X.
fn rest_stands_along_y(clip: &Clip) -> bool {
    let skip_roots = clip.skeleton().joints().iter().any(|j| j.parent.is_some());
    let mut b = Aabb::EMPTY;
    for (joint, p) in clip.skeleton().joints().iter().zip(crate::runtime::fk::rest_positions(clip.skeleton())) {
        if !(skip_roots && joint.parent.is_none()) && p.is_finite() {
            b.include(p);
        }
    }
    !b.is_empty() && b.size().y > REST_Y_OVER_Z * b.size().z
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_rotation_and_boxes_agree() {
        assert_eq!(UpAxis::from_name("Z"), Some(UpAxis::Z));
        assert_eq!(UpAxis::from_name(" y "), Some(UpAxis::Y));
        assert_eq!(UpAxis::from_name("x"), None);
        for up in [UpAxis::Y, UpAxis::Z] {
            assert_eq!(UpAxis::from_name(up.name()), Some(up));
            let p = Vec3::new(1.0, 2.0, 3.0);
            assert!((up.rotation() * p - up.to_y_up(p)).abs().max_element() < 1e-6, "{up:?}");
            assert_eq!(up.from_y_up(up.to_y_up(p)), p);
        }
        assert_eq!(UpAxis::Z.to_y_up(Vec3::Z), Vec3::Y, "Z-up's up is the world's up");
        let b = UpAxis::Z.box_to_y_up(Aabb { min: Vec3::new(-1.0, -2.0, 0.0), max: Vec3::new(1.0, 3.0, 17.0) });
        assert_eq!((b.min, b.max), (Vec3::new(-1.0, 0.0, -3.0), Vec3::new(1.0, 17.0, 2.0)));
        assert!(UpAxis::Z.box_to_y_up(Aabb::EMPTY).is_empty());
    }

    /// A figure whose rest pose stands along `up` (Y or Z): hips, spine, head,
    /// two arms and two legs, over 8 frames in place; `lying` turns the root a
    /// quarter about X in every frame.
    fn figure(up: UpAxis, lying: bool) -> Clip {
        let at = |x: f32, h: f32| {
            let p = if up == UpAxis::Y { Vec3::new(x, h, 0.0) } else { Vec3::new(x, 0.0, h) };
            format!("OFFSET {} {} {}\n", p.x, p.y, p.z)
        };
        let mut s = format!(
            "HIERARCHY\nROOT Hips\n{{\n{}CHANNELS 6 Xposition Yposition Zposition Xrotation Yrotation Zrotation\n",
            at(0.0, 1.0)
        );
        s.push_str(&format!("JOINT Spine\n{{\n{}CHANNELS 3 Xrotation Yrotation Zrotation\nJOINT Head\n{{\n{}CHANNELS 3 Xrotation Yrotation Zrotation\nEnd Site\n{{\n{}}}\n}}\n", at(0.0, 0.5), at(0.0, 0.3), at(0.0, 0.2)));
        for x in [0.3f32, -0.3] {
            s.push_str(&format!(
                "JOINT Arm{x}\n{{\n{}CHANNELS 3 Xrotation Yrotation Zrotation\nEnd Site\n{{\n{}}}\n}}\n",
                at(x, 0.3),
                at(0.0, -0.6)
            ));
        }
        s.push_str("}\n");
        for x in [0.1f32, -0.1] {
            s.push_str(&format!(
                "JOINT Leg{x}\n{{\n{}CHANNELS 3 Xrotation Yrotation Zrotation\nEnd Site\n{{\n{}}}\n}}\n",
                at(x, 0.0),
                at(0.0, -1.0)
            ));
        }
        s.push_str("}\nMOTION\nFrames: 8\nFrame Time: 0.1\n");
        let turn = if lying { if up == UpAxis::Y { -90.0 } else { 90.0 } } else { 0.0 };
        for _ in 0..8 {
            s.push_str(&format!("0 0 0 {turn} 0 0{}\n", " 0".repeat(3 * 6)));
        }
        crate::formats::bvh::parse(s.as_bytes()).unwrap()
    }

    #[test]
    fn guesses_from_the_motion_and_the_rest_pose() {
        assert_eq!(UpAxis::guess(&figure(UpAxis::Y, false)), UpAxis::Y);
        assert_eq!(UpAxis::guess(&figure(UpAxis::Z, false)), UpAxis::Z, "stands along Z");
        // A Y-up figure lying along Z in place (push-ups) is no Z-up file.
        assert_eq!(UpAxis::guess(&figure(UpAxis::Y, true)), UpAxis::Y);
        // A Z-up file whose motion lays it along Y is read as it moves: Y.
        assert_eq!(UpAxis::guess(&figure(UpAxis::Z, true)), UpAxis::Y);
    }
}
