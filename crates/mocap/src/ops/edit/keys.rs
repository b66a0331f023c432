//! Keys: a pose correction faded in and out around its frame
//! ([`Edit::Correct`](super::Edit::Correct)), and key-frame animation, every frame
//! between keys interpolated ([`Edit::Key`](super::Edit::Key)).

use super::poses::{from_locals, locals};
use super::{EditError, err};
use crate::model::channel::{Channel, ChannelKind};
use crate::model::clip::Clip;
use crate::model::skeleton::{EulerConvention, Joint, Skeleton};
use glam::{Quat, Vec3};

/// Weight of a correction keyed at `key` at frame `f`: 1 there, easing (smoothstep)
/// to 0 at `window + 1` frames away.
fn key_weight(f: usize, key: usize, window: usize) -> f32 {
    let d = f.abs_diff(key) as f32 / (window + 1) as f32;
    if d >= 1.0 {
        return 0.0;
    }
    let t = 1.0 - d;
    t * t * (3.0 - 2.0 * t)
}

pub(super) fn correct(
    clip: &Clip,
    frame: usize,
    rotations: &[(String, Quat)],
    translations: &[(String, Vec3)],
    window: usize,
) -> Result<Clip, EditError> {
    let n = clip.frame_count();
    if frame >= n {
        return err(format!("key at frame {frame}: the clip has frames 0 to {}", n.saturating_sub(1)));
    }
    let skeleton = clip.skeleton();
    let find = |name: &str| skeleton.find(name).ok_or_else(|| EditError(format!("key: no joint named `{name}`")));
    let rotations: Vec<(usize, Quat)> =
        rotations.iter().map(|(name, q)| Ok((find(name)?, *q))).collect::<Result<_, EditError>>()?;
    let translations: Vec<(usize, Vec3)> =
        translations.iter().map(|(name, t)| Ok((find(name)?, *t))).collect::<Result<_, EditError>>()?;
    if rotations.iter().any(|(_, q)| !q.is_finite()) || translations.iter().any(|(_, t)| !t.is_finite()) {
        return err("key: a value is not finite");
    }
    let mut poses = locals(clip);
    let at_key = poses[frame].clone();
    // The change at the key, in each joint's own frame, spread over the window.
    let deltas: Vec<(usize, Quat)> =
        rotations.iter().map(|&(j, q)| (j, (at_key.rotation[j].inverse() * q).normalize())).collect();
    let moves: Vec<(usize, Vec3)> = translations.iter().map(|&(j, t)| (j, t - at_key.translation[j])).collect();
    for (f, pose) in poses.iter_mut().enumerate() {
        let w = key_weight(f, frame, window);
        if w <= 0.0 {
            continue;
        }
        for &(j, d) in &deltas {
            pose.rotation[j] = (pose.rotation[j] * Quat::IDENTITY.slerp(d, w)).normalize();
        }
        for &(j, m) in &moves {
            pose.translation[j] += m * w;
        }
    }
    // Joints whose translation is keyed need position channels.
    let joints: Vec<Joint> = skeleton
        .joints()
        .iter()
        .enumerate()
        .map(|(i, j)| {
            let moved = translations.iter().any(|(k, _)| *k == i);
            if moved && !j.channels.iter().any(|c| c.kind() == ChannelKind::Translation) {
                let mut channels = vec![Channel::Xposition, Channel::Yposition, Channel::Zposition];
                channels.extend(j.channels.iter().copied());
                Joint::new(j.name.clone(), j.parent, j.offset, channels)
            } else if j.is_end_site() {
                Joint::end_site(j.name.clone(), j.parent, j.offset)
            } else {
                Joint::new(j.name.clone(), j.parent, j.offset, j.channels.clone())
            }
        })
        .collect();
    let skeleton = Skeleton::new(joints, EulerConvention::Intrinsic).map_err(|e| EditError(e.to_string()))?;
    from_locals(clip, skeleton, clip.frame_time(), &poses)
}

/// Interpolates every frame from the poses at the frames `keys` (see
/// [`Edit::Key`]): slerp of rotations and lerp of positions between consecutive
/// keys, the first key's pose before it and the last key's after it.
pub(super) fn tween(clip: &Clip, mut keys: Vec<usize>) -> Result<Clip, EditError> {
    let n = clip.frame_count();
    if let Some(k) = keys.iter().find(|&&k| k >= n) {
        return err(format!("key at frame {k}: the clip has frames 0 to {}", n.saturating_sub(1)));
    }
    keys.sort_unstable();
    keys.dedup();
    let (Some(&first), Some(&last)) = (keys.first(), keys.last()) else { return Ok(clip.clone()) };
    let source = locals(clip);
    let mut poses = source.clone();
    for (f, pose) in poses.iter_mut().enumerate() {
        let (a, b) = match keys.binary_search(&f) {
            Ok(_) => continue,
            Err(0) => (first, first),
            Err(i) if i >= keys.len() => (last, last),
            Err(i) => (keys[i - 1], keys[i]),
        };
        let t = if b > a { (f - a) as f32 / (b - a) as f32 } else { 0.0 };
        let (pa, pb) = (&source[a], &source[b]);
        for j in 0..pose.rotation.len().min(pa.rotation.len()).min(pb.rotation.len()) {
            pose.rotation[j] = pa.rotation[j].slerp(pb.rotation[j], t).normalize();
            pose.translation[j] = pa.translation[j].lerp(pb.translation[j], t);
        }
    }
    from_locals(clip, clip.skeleton().clone(), clip.frame_time(), &poses)
}
