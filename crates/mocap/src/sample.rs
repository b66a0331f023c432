//! Sampling a clip in time: frame/time conversions and pose interpolation.

use crate::fk::{local_to_world_in_place, local_transform, Transform};
use crate::skeleton::Skeleton;
use crate::motion::Motion;

/// How to get a pose between two frames.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Interpolation {
    /// The nearest frame.
    Nearest,
    /// Rotations by quaternion slerp (shortest arc), translations by lerp.
    #[default]
    Linear,
}

/// Where a time falls between two frames.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FramePosition {
    /// The frame at or before the time.
    pub frame0: usize,
    /// The frame after (equal to `frame0` at the ends or on an exact frame).
    pub frame1: usize,
    /// Blend weight of `frame1`, in `[0, 1)`.
    pub alpha: f32,
}

/// Time in seconds of a frame.
pub fn time_of_frame(frame: usize, frame_time: f64) -> f64 {
    frame as f64 * frame_time
}

/// Locates `time` (seconds) among `frame_count` frames `frame_time` apart, clamped
/// to the clip. A time within a millionth of a frame of an exact frame is that frame,
/// so `time_of_frame(n - 1)` always maps back to the last frame.
pub fn frame_position(time: f64, frame_time: f64, frame_count: usize) -> FramePosition {
    let last = frame_count.saturating_sub(1);
    let valid_frame_time = frame_time.is_finite() && frame_time > 0.0;
    if !valid_frame_time || !time.is_finite() || frame_count == 0 {
        return FramePosition { frame0: 0, frame1: 0, alpha: 0.0 };
    }
    let f = (time / frame_time).clamp(0.0, last as f64);
    let nearest = f.round();
    if (f - nearest).abs() < 1e-6 {
        let frame = nearest as usize;
        return FramePosition { frame0: frame, frame1: frame, alpha: 0.0 };
    }
    let frame0 = (f.floor() as usize).min(last);
    let frame1 = (frame0 + 1).min(last);
    FramePosition { frame0, frame1, alpha: (f - frame0 as f64) as f32 }
}

/// The frame shown at `time` without interpolation (nearest, clamped).
pub fn frame_at_time(time: f64, frame_time: f64, frame_count: usize) -> usize {
    let p = frame_position(time, frame_time, frame_count);
    if p.alpha >= 0.5 { p.frame1 } else { p.frame0 }
}

/// World transforms at `time`, written into `out` (reused, no allocation once sized).
pub fn sample_world_transforms(
    skeleton: &Skeleton,
    motion: &Motion,
    time: f64,
    interpolation: Interpolation,
    out: &mut Vec<Transform>,
) {
    let p = frame_position(time, motion.frame_time(), motion.frame_count());
    let (row0, row1) = (motion.row(p.frame0), motion.row(p.frame1));
    out.clear();
    out.reserve(skeleton.joints.len());
    let blend = interpolation == Interpolation::Linear && p.frame0 != p.frame1 && p.alpha > 0.0;
    let pick_second = interpolation == Interpolation::Nearest && p.alpha >= 0.5;
    for joint in &skeleton.joints {
        let local = if blend {
            let a = local_transform(joint, row0);
            let b = local_transform(joint, row1);
            Transform {
                rotation: a.rotation.slerp(b.rotation, p.alpha),
                translation: a.translation.lerp(b.translation, p.alpha),
            }
        } else if pick_second {
            local_transform(joint, row1)
        } else {
            local_transform(joint, row0)
        };
        out.push(local);
    }
    local_to_world_in_place(skeleton, out);
}
