//! Retargeting: a source clip's motion on a target skeleton.
//!
//! Inputs: the source clip, the target (a clip whose skeleton, and whose
//! reference pose, receive the motion) and a joint map ([`map_joints`]: by name
//! across the common conventions, [`crate::ops::layer::canonical_name`], then
//! explicit pairs; where names fail, the shape of the tree, [`chains`]). Output: a clip on exactly the target's skeleton (its names,
//! hierarchy and offsets; channels: the root's position and every joint's
//! rotation) at the source's frame times.
//!
//! The pose is carried in world space, not by copying local rotations, so two
//! skeletons with different rest poses (an A-pose onto a T-pose, or a rest pose
//! that lies on its side) still agree. Both skeletons are first stood Y up. In
//! the reference pose ([`Reference`]) each mapped target bone is turned onto the
//! direction of its source bone (the shortest arc from the target bone to the
//! source's); on every frame it is then turned by what turned the source joint
//! from its reference (its world rotation change), twist included. So every
//! mapped bone points where its source bone points, frame by frame. Unmapped
//! joints keep their reference rotation relative to their parent. The root's
//! path is the source's, scaled by the ratio of the legs (hip to knee to ankle;
//! of the heights when no leg is mapped), so feet keep their stride.
//!
//! One pass over the frames, each a pass over the joints in parent-before-child
//! order; no recursion.

use crate::model::channel::Channel;
use crate::model::clip::Clip;
use crate::model::motion::Motion;
use crate::model::skeleton::{EulerConvention, Joint, Skeleton};
use crate::ops::layer::canonical_name;
use crate::runtime::fk::{Transform, local_to_model};
use crate::runtime::pose::LocalPose;
use glam::{EulerRot, Quat, Vec3};

pub mod chains;

/// Which pose the two skeletons are matched in.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Reference {
    /// Each file's rest pose (every channel zero).
    Rest,
    /// Each clip's first frame (for files whose rest pose is not a pose at all).
    #[default]
    FirstFrame,
}

/// How to retarget.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Options {
    /// Explicit (target joint, source joint) pairs, before matching by name; an
    /// empty source name leaves that target joint unmapped.
    pub map: Vec<(String, String)>,
    /// The pose the skeletons are matched in.
    pub reference: Reference,
}

/// Why a retarget could not be made.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum RetargetError {
    /// No target joint matched a source joint.
    #[error("no joint of the target matches one of the source (give a map: TARGET=SOURCE pairs)")]
    NothingMapped,
    /// An explicit pair names a joint that does not exist.
    #[error("the map names `{0}`, which is not a joint of the {1}")]
    NoSuchJoint(String, &'static str),
    /// The result is not a valid clip (should not happen).
    #[error("{0}")]
    Clip(String),
}

/// The (target joint, source joint) pairs, in target joint order: explicit ones
/// first, then equal names, then equal [`canonical_name`]s, then, for target
/// joints still unmapped (and not left out by the map), the pairs the shape of
/// the two trees gives ([`shape_pairs`]). End Sites are matched only through
/// explicit pairs. Each source joint drives at most one target joint.
pub fn map_joints(
    target: &Skeleton,
    source: &Skeleton,
    explicit: &[(String, String)],
) -> Result<Vec<(usize, usize)>, RetargetError> {
    for (t, s) in explicit {
        if target.find(t).is_none() {
            return Err(RetargetError::NoSuchJoint(t.clone(), "target"));
        }
        if !s.is_empty() && source.find(s).is_none() {
            return Err(RetargetError::NoSuchJoint(s.clone(), "source"));
        }
    }
    let canonical: Vec<String> = source.joints().iter().map(|j| canonical_name(&j.name)).collect();
    let mut used = vec![false; source.len()];
    let mut pairs = Vec::new();
    for (i, joint) in target.joints().iter().enumerate() {
        let explicit = explicit.iter().find(|(t, _)| *t == joint.name);
        let found = match explicit {
            Some((_, s)) if s.is_empty() => None,
            Some((_, s)) => source.find(s),
            None if joint.is_end_site() => None,
            None => source.find(&joint.name).filter(|&s| !source.is_end_site(s)).or_else(|| {
                let c = canonical_name(&joint.name);
                (0..source.len()).find(|&k| !used[k] && canonical[k] == c && !source.is_end_site(k))
            }),
        };
        if let Some(s) = found.filter(|&s| !used[s]) {
            used[s] = true;
            pairs.push((i, s));
        }
    }
    let mut mapped = vec![false; target.len()];
    for &(t, _) in &pairs {
        mapped[t] = true;
    }
    for (t, s) in shape_pairs(target, source) {
        let named = target.joints().get(t).is_some_and(|j| explicit.iter().any(|(x, _)| *x == j.name));
        if !mapped[t] && !named && !used[s] && !target.is_end_site(t) && !source.is_end_site(s) {
            (mapped[t], used[s]) = (true, true);
            pairs.push((t, s));
        }
    }
    pairs.sort_unstable();
    if pairs.is_empty() {
        return Err(RetargetError::NothingMapped);
    }
    Ok(pairs)
}

/// The pairs the shapes of two skeletons' trees give, in their rest poses
/// ([`chains::find_body`], [`chains::match_bodies`]); none unless both are humanoid.
pub fn shape_pairs(target: &Skeleton, source: &Skeleton) -> Vec<(usize, usize)> {
    let (t_at, s_at) = (chains::rest_positions(target), chains::rest_positions(source));
    match (chains::find_body(target, &t_at), chains::find_body(source, &s_at)) {
        (Some(t), Some(s)) => chains::match_bodies(&t, &t_at, &s, &s_at),
        _ => Vec::new(),
    }
}

/// The source's motion on the target's skeleton (see the module documentation),
/// with the joint pairs used.
pub fn retarget(source: &Clip, target: &Clip, options: &Options) -> Result<(Clip, Vec<(usize, usize)>), RetargetError> {
    let pairs = map_joints(target.skeleton(), source.skeleton(), &options.map)?;
    let ts = target.skeleton();
    let n = ts.len();
    let mut source_of = vec![None; n];
    for &(t, s) in &pairs {
        source_of[t] = Some(s);
    }
    let (up_s, up_t) = (source.up_axis().rotation(), target.up_axis().rotation());
    let stand = |up: Quat, w: &[Transform]| -> Vec<Transform> {
        w.iter()
            .map(|t| Transform {
                rotation: (up * t.rotation).normalize(),
                translation: up * t.translation,
                scale: t.scale,
            })
            .collect()
    };
    let reference = |clip: &Clip| -> Vec<Transform> {
        let mut w = Vec::new();
        match options.reference {
            Reference::FirstFrame if clip.frame_count() > 0 => clip.world_transforms_into(0, &mut w),
            _ => local_to_model(clip.skeleton(), &LocalPose::rest(clip.skeleton()), &mut w),
        }
        w
    };
    let ref_s = stand(up_s, &reference(source));
    let ref_t = stand(up_t, &reference(target));
    let parent = |i: usize| ts.joints().get(i).and_then(|j| j.parent).filter(|&p| p < i);

    // Each mapped target joint's correction: its bones turned onto the source
    // bones' directions (the largest subtree's exactly, a second one as near as
    // the first allows, which fixes the turn about the first).
    let (size_t, size_s) = (target.pose_extent(), source.pose_extent());
    let mut correction = vec![Quat::IDENTITY; n];
    for i in 0..n {
        let inherited = parent(i).map_or(Quat::IDENTITY, |p| correction[p]);
        correction[i] = source_of[i]
            .and_then(|s| {
                let bones = bone_pairs(ts, source.skeleton(), &source_of, i, s);
                // A bone shorter than a thousandth of its skeleton (CMU's root to
                // lowerback) has no direction to match.
                let dir = |w: &[Transform], a: usize, b: usize, size: f32| {
                    let d = w.get(b)?.translation - w.get(a)?.translation;
                    (d.length() > size * 1e-3).then(|| d.normalize())
                };
                let mut dirs = bones
                    .iter()
                    .filter_map(|&(tc, sc)| Some((dir(&ref_t, i, tc, size_t)?, dir(&ref_s, s, sc, size_s)?)));
                let (a1, b1) = dirs.next()?;
                let second = dirs.find(|(a2, b2)| a1.cross(*a2).length() > 0.1 && b1.cross(*b2).length() > 0.1);
                Some(match second {
                    Some((a2, b2)) => basis(b1, b2) * basis(a1, a2).inverse(),
                    None => Quat::from_rotation_arc(a1, b1),
                })
            })
            .unwrap_or(inherited);
    }
    let scale = leg_ratio(ts, &ref_t, &ref_s, &source_of).unwrap_or_else(|| {
        let (hs, ht) = (source.pose_height(), target.pose_height());
        if hs > 0.0 && ht.is_finite() { ht / hs } else { 1.0 }
    });

    // The output skeleton: the target's joints, the root's position and every rotation.
    let roots: Vec<bool> = (0..n).map(|i| parent(i).is_none()).collect();
    let joints: Vec<Joint> = ts
        .joints()
        .iter()
        .enumerate()
        .map(|(i, j)| {
            if j.is_end_site() {
                return Joint::end_site(j.name.clone(), j.parent, j.offset);
            }
            let mut channels = Vec::new();
            if roots[i] {
                channels.extend([Channel::Xposition, Channel::Yposition, Channel::Zposition]);
            }
            channels.extend([Channel::Zrotation, Channel::Xrotation, Channel::Yrotation]);
            Joint::new(j.name.clone(), j.parent, j.offset, channels)
        })
        .collect();
    let skeleton = Skeleton::new(joints, EulerConvention::Intrinsic).map_err(|e| RetargetError::Clip(e.to_string()))?;
    let width = skeleton.channel_count();
    let frames = source.frame_count();
    let mut data = Vec::with_capacity(width.saturating_mul(frames));
    let (mut ws, mut world) = (Vec::new(), vec![Transform::IDENTITY; n]);
    let unstand = up_t.inverse();
    let ref_local: Vec<Quat> = (0..n)
        .map(|i| parent(i).map_or(ref_t[i].rotation, |p| ref_t[p].rotation.inverse() * ref_t[i].rotation))
        .collect();
    for f in 0..frames {
        source.world_transforms_into(f, &mut ws);
        let ws = stand(up_s, &ws);
        for i in 0..n {
            let parent_rotation = parent(i).map_or(Quat::IDENTITY, |p| world[p].rotation);
            let rotation = match source_of[i] {
                Some(s) => {
                    let change = ws[s].rotation * ref_s[s].rotation.inverse();
                    (change * correction[i] * ref_t[i].rotation).normalize()
                }
                None => (parent_rotation * ref_local[i]).normalize(),
            };
            world[i].rotation = rotation;
        }
        for (i, j) in skeleton.joints().iter().enumerate() {
            if j.is_end_site() {
                continue;
            }
            let local = match parent(i) {
                Some(p) => world[p].rotation.inverse() * world[i].rotation,
                None => unstand * world[i].rotation,
            };
            if roots[i] {
                // The root follows the source's root (or the first mapped joint's) path, scaled.
                let driver = source_of[i].or_else(|| pairs.first().map(|&(_, s)| s)).unwrap_or(0);
                let path = ws.get(driver).map_or(Vec3::ZERO, |t| t.translation) * scale;
                // A position channel replaces the offset (see `runtime::pose`).
                data.extend((unstand * path).to_array());
            }
            let (z, x, y) = local.to_euler(EulerRot::ZXY);
            data.extend([z.to_degrees(), x.to_degrees(), y.to_degrees()]);
        }
    }
    let motion = Motion::new(source.frame_time(), width, frames, data)
        .ok_or_else(|| RetargetError::Clip("the retargeted motion does not fit its channels".into()))?;
    let mut clip = Clip::new(skeleton, motion).map_err(|e| RetargetError::Clip(e.to_string()))?;
    // Onto a character (glTF), the result wears its look: same joints, same binds.
    if let Some(look) = target.character.as_ref().and_then(|c| c.look.clone()) {
        let character = crate::model::character::Character { look: Some(look), ..Default::default() };
        clip = clip.with_character(std::sync::Arc::new(character));
    }
    Ok((clip, pairs))
}

/// The mapped bones of target joint `t` (driven by source joint `s`): for each
/// child subtree of `t`, its nearest mapped joint and that joint's source, which
/// must be a descendant of `s`; the largest subtree first.
fn bone_pairs(
    target: &Skeleton,
    source: &Skeleton,
    source_of: &[Option<usize>],
    t: usize,
    s: usize,
) -> Vec<(usize, usize)> {
    let below = |sk: &Skeleton, a: usize, mut b: usize| {
        while let Some(p) = sk.joints().get(b).and_then(|j| j.parent).filter(|&p| p < b) {
            if p == a {
                return true;
            }
            b = p;
        }
        false
    };
    let mut found: Vec<(usize, usize, usize)> = Vec::new();
    for c in (t + 1)..target.len() {
        if target.joints().get(c).and_then(|j| j.parent) != Some(t) {
            continue;
        }
        let under = |k: usize| k == c || below(target, c, k);
        // The nearest mapped joint at or under this child (the first in joint order).
        let Some((tc, sc)) = (c..target.len()).find_map(|k| source_of[k].filter(|_| under(k)).map(|sc| (k, sc))) else {
            continue;
        };
        if below(source, s, sc) {
            found.push((tc, sc, (c..target.len()).filter(|&k| under(k)).count()));
        }
    }
    found.sort_by_key(|&(_, _, size)| std::cmp::Reverse(size));
    found.into_iter().map(|(tc, sc, _)| (tc, sc)).collect()
}

/// The rotation taking +X to `a` and the XY plane to the plane of `a` and `b`.
fn basis(a: Vec3, b: Vec3) -> Quat {
    let x = a.normalize();
    let z = x.cross(b).normalize();
    let y = z.cross(x);
    Quat::from_mat3(&glam::Mat3::from_cols(x, y, z))
}

/// Target leg length over source leg length (upper leg joint to its foot, both
/// mapped, averaged over the legs found).
fn leg_ratio(target: &Skeleton, ref_t: &[Transform], ref_s: &[Transform], source_of: &[Option<usize>]) -> Option<f32> {
    let mut ratios = Vec::new();
    for side in ["left", "right"] {
        let find = |part: &str| {
            let wanted = format!("{side}{part}");
            target.joints().iter().position(|j| canonical_name(&j.name) == wanted)
        };
        let (Some(hip), Some(knee), Some(foot)) = (find("upleg"), find("leg"), find("foot")) else { continue };
        let (Some(sh), Some(sk), Some(sf)) = (source_of[hip], source_of[knee], source_of[foot]) else { continue };
        let at = |w: &[Transform], k: usize| w.get(k).map_or(Vec3::ZERO, |t| t.translation);
        let length =
            |w: &[Transform], a: usize, b: usize, c: usize| at(w, a).distance(at(w, b)) + at(w, b).distance(at(w, c));
        let (lt, ls) = (length(ref_t, hip, knee, foot), length(ref_s, sh, sk, sf));
        if ls > 0.0 && lt.is_finite() {
            ratios.push(lt / ls);
        }
    }
    (!ratios.is_empty()).then(|| ratios.iter().sum::<f32>() / ratios.len() as f32)
}
