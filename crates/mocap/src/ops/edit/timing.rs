//! Edits of time: [`Edit::Resample`](super::Edit::Resample) and
//! [`Edit::LoopKnit`](super::Edit::LoopKnit) (trimming, reversing and ping-pong
//! only reorder rows, [`super::apply`]).

use super::poses::{from_locals, locals, roots};
use super::{EditError, err};
use crate::model::clip::Clip;
use crate::model::time::Timeline;
use crate::runtime::pose::LocalPose;
use crate::runtime::sample::{Interpolation, SampleScratch, sample};
use glam::Quat;

pub(super) fn resample(clip: &Clip, fps: f64, interpolation: Interpolation) -> Result<Clip, EditError> {
    if !(fps.is_finite() && fps > 0.0 && fps <= 100_000.0) {
        return err(format!("fps {fps}: expected a positive frame rate"));
    }
    let duration = clip.duration();
    let timeline = Timeline::new(1.0 / fps, 1);
    let frames = if duration > 0.0 { timeline.frames_to_reach(duration) } else { clip.frame_count().min(1) };
    if frames > crate::model::time::MAX_FRAMES / 4 || frames.saturating_mul(clip.skeleton().channel_count()) > 1 << 30 {
        return err(format!("fps {fps}: {frames} frames would be too many"));
    }
    let mut scratch = SampleScratch::default();
    let poses: Vec<LocalPose> = (0..frames)
        .map(|f| {
            let mut local = LocalPose::default();
            sample(clip.skeleton(), clip.motion(), f as f64 / fps, interpolation, &mut scratch, &mut local);
            local
        })
        .collect();
    from_locals(clip, clip.skeleton().clone(), 1.0 / fps, &poses)
}

pub(super) fn loop_knit(clip: &Clip, k: usize) -> Result<Clip, EditError> {
    let n = clip.frame_count();
    if k == 0 || k >= n {
        return err(format!("loop knit over {k} frames: the clip has {n} frames (use 1 to {})", n.saturating_sub(1)));
    }
    let mut poses = locals(clip);
    let first = poses[0].clone();
    let last = poses[n - 1].clone();
    let roots = roots(clip.skeleton());
    for i in 0..k {
        // Weight of the correction that takes the last frame onto the first: the
        // frame after the last is (virtually) the first.
        let w = (i + 1) as f32 / (k + 1) as f32;
        let pose = &mut poses[n - k + i];
        for j in 0..pose.rotation.len() {
            let delta = first.rotation[j] * last.rotation[j].inverse();
            pose.rotation[j] = (Quat::IDENTITY.slerp(delta, w) * pose.rotation[j]).normalize();
        }
        for &r in &roots {
            let dy = first.translation[r].y - last.translation[r].y;
            pose.translation[r].y += dy * w;
        }
    }
    from_locals(clip, clip.skeleton().clone(), clip.frame_time(), &poses)
}
