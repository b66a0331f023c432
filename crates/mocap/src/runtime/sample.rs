//! Sampling a motion in time: the first stage of the pipeline,
//! `time → local pose` (see [`crate::runtime::pose`]); frames are located by the one rule in
//! [`crate::model::time`].

use crate::model::motion::Motion;
use crate::model::skeleton::Skeleton;
use crate::runtime::pose::{LocalPose, blend, cubic, from_row};

/// How to get a pose between two frames.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Interpolation {
    /// The nearest frame (rounding the time's position between two frames).
    Nearest,
    /// The frame shown at the time: the last frame not after it
    /// ([`crate::model::time::Timeline::frame_at`]); what a paused or stepped view shows.
    Step,
    /// Rotations by quaternion slerp (shortest arc), translations and scales by lerp.
    #[default]
    Linear,
    /// Through every frame and smooth across them (C¹): translations and scales
    /// by Catmull-Rom, rotations by squad on the shortest arc, each from the two
    /// frames around the time and one on either side (the ends repeated).
    Cubic,
}

impl Interpolation {
    /// `nearest`, `step`, `linear` or `cubic`.
    pub fn from_name(name: &str) -> Option<Interpolation> {
        match name {
            "nearest" => Some(Interpolation::Nearest),
            "step" => Some(Interpolation::Step),
            "linear" => Some(Interpolation::Linear),
            "cubic" => Some(Interpolation::Cubic),
            _ => None,
        }
    }

    /// The name [`Interpolation::from_name`] reads.
    pub fn name(self) -> &'static str {
        match self {
            Interpolation::Nearest => "nearest",
            Interpolation::Step => "step",
            Interpolation::Linear => "linear",
            Interpolation::Cubic => "cubic",
        }
    }
}

/// Scratch poses for [`sample`] (the two frames it blends).
#[derive(Clone, Debug, Default)]
pub struct SampleScratch {
    a: LocalPose,
    b: LocalPose,
    /// The frames either side of `a` and `b` (cubic only).
    before: LocalPose,
    after: LocalPose,
}

/// The local pose at `time` seconds (clamped to the clip).
///
/// Inputs: the skeleton, its motion, a time, the interpolation, and reusable
/// scratch. Output: `out`, one entry per joint. A motion with no frames gives the
/// rest pose.
pub fn sample(
    skeleton: &Skeleton,
    motion: &Motion,
    time: f64,
    interpolation: Interpolation,
    scratch: &mut SampleScratch,
    out: &mut LocalPose,
) {
    let timeline = motion.timeline();
    let p = timeline.position(time);
    let unit = motion.angle_unit();
    match interpolation {
        Interpolation::Linear if p.frame1 != p.frame0 && p.alpha > 0.0 => {
            from_row(skeleton, motion.row(p.frame0), unit, &mut scratch.a);
            from_row(skeleton, motion.row(p.frame1), unit, &mut scratch.b);
            blend(&scratch.a, &scratch.b, p.alpha, out);
        }
        Interpolation::Cubic if p.frame1 != p.frame0 && p.alpha > 0.0 => {
            let before = p.frame0.saturating_sub(1);
            let after = (p.frame1 + 1).min(timeline.last());
            from_row(skeleton, motion.row(before), unit, &mut scratch.before);
            from_row(skeleton, motion.row(p.frame0), unit, &mut scratch.a);
            from_row(skeleton, motion.row(p.frame1), unit, &mut scratch.b);
            from_row(skeleton, motion.row(after), unit, &mut scratch.after);
            cubic(&scratch.before, &scratch.a, &scratch.b, &scratch.after, p.alpha, out);
        }
        Interpolation::Nearest => from_row(skeleton, motion.row(timeline.nearest(time)), unit, out),
        Interpolation::Step => from_row(skeleton, motion.row(p.frame0), unit, out),
        Interpolation::Linear | Interpolation::Cubic => from_row(skeleton, motion.row(p.frame0), unit, out),
    }
}
