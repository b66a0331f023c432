//! The bendy tentacle: a chain of bones with one smooth skin, the classic
//! demonstration of skeletal animation with soft skinning (a rigid skin creases at
//! every joint; a soft one bends) and of IK (its tip follows a target).
//!
//! [`tentacle`] makes the skeleton as a one-frame clip (a chain along +Y, each
//! joint with three rotation channels, ending in an End Site at the tip);
//! [`tentacle_skin`] wraps one closed, tapering tube around the whole chain,
//! weighted rigidly (each vertex to the bone it lies along) or softly (blended
//! across each joint).

use crate::model::channel::Channel;
use crate::model::clip::Clip;
use crate::model::motion::Motion;
use crate::model::skeleton::{EulerConvention, Joint, Skeleton};
use crate::runtime::skin::{Skin, SkinError};
use glam::Vec3;
use std::f32::consts::TAU;

/// Fewest and most bones the demo offers.
pub const BONES: std::ops::RangeInclusive<usize> = 2..=10;
/// Length of each bone (metres: the clip reads as metres).
pub const BONE_LENGTH: f32 = 0.5;
/// Radius at the base.
pub const RADIUS: f32 = 0.12;
/// Name of the End Site at the tip.
pub const TIP: &str = "tip";

/// The tentacle's skeleton with `bones` bones (clamped to [`BONES`]), at rest.
pub fn tentacle(bones: usize) -> Clip {
    let bones = bones.clamp(*BONES.start(), *BONES.end());
    let bone = Vec3::new(0.0, BONE_LENGTH, 0.0);
    let rotations = || vec![Channel::Zrotation, Channel::Xrotation, Channel::Yrotation];
    let mut joints: Vec<Joint> = (0..bones)
        .map(|b| Joint::new(format!("bone{b}"), b.checked_sub(1), if b == 0 { Vec3::ZERO } else { bone }, rotations()))
        .collect();
    joints.push(Joint::end_site(TIP, Some(bones - 1), bone));
    let width = 3 * bones;
    // One frame of the rest pose, at the 30 Hz the clip has always had (written
    // to 6 digits, as in a BVH file).
    let clip = Skeleton::new(joints, EulerConvention::Intrinsic).ok().and_then(|skeleton| {
        let motion = Motion::new(FRAME_TIME, width, 1, vec![0.0; width])?;
        Clip::new(skeleton, motion).ok()
    });
    // A chain of unique names with one channel set per joint: always valid.
    clip.unwrap_or_default()
}

/// Seconds per frame of [`tentacle`]'s clip.
const FRAME_TIME: f64 = 0.0333333;

/// One tube around the whole chain of `clip` (as [`tentacle`] makes it), tapering to
/// 40% at the tip: each vertex weighted to the bone it lies along (`soft` false),
/// or blended across each joint over ±35% of a bone (`soft` true).
pub fn tentacle_skin(clip: &Clip, soft: bool) -> Result<Skin, SkinError> {
    let skeleton = clip.skeleton();
    let bind = clip.bind_pose();
    let bones = skeleton.len().saturating_sub(1).max(1);
    let length = bones as f32 * BONE_LENGTH;
    let rings_per_bone = 8;
    let rings = bones * rings_per_bone + 1;
    let segments = 16u32;
    let (mut positions, mut normals, mut joints, mut weights) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let radius_at = |y: f32| RADIUS * (1.0 - 0.6 * (y / length).clamp(0.0, 1.0));
    let influence = |y: f32| -> ([u32; 4], [f32; 4]) {
        let b = ((y / BONE_LENGTH) as usize).min(bones - 1);
        if !soft {
            return ([b as u32; 4], [1.0, 0.0, 0.0, 0.0]);
        }
        // Blend toward the neighbour across the nearest joint.
        let local = y / BONE_LENGTH - b as f32;
        let h = 0.35;
        let smooth = |t: f32| {
            let t = t.clamp(0.0, 1.0);
            t * t * (3.0 - 2.0 * t)
        };
        if local > 1.0 - h && b + 1 < bones {
            let w = 0.5 * smooth((local - (1.0 - h)) / h);
            ([b as u32, (b + 1) as u32, 0, 0], [1.0 - w, w, 0.0, 0.0])
        } else if local < h && b > 0 {
            let w = 0.5 * smooth((h - local) / h);
            ([b as u32, (b - 1) as u32, 0, 0], [1.0 - w, w, 0.0, 0.0])
        } else {
            ([b as u32; 4], [1.0, 0.0, 0.0, 0.0])
        }
    };
    // The base pole, the rings, the tip pole.
    let mut push = |p: Vec3, n: Vec3| {
        let (j, w) = influence(p.y);
        positions.push(p);
        normals.push(n);
        joints.push(j);
        weights.push(w);
    };
    push(Vec3::ZERO, -Vec3::Y);
    for r in 0..rings {
        let y = length * r as f32 / (rings - 1) as f32;
        let radius = radius_at(y);
        for s in 0..segments {
            let a = s as f32 * TAU / segments as f32;
            let dir = Vec3::new(a.cos(), 0.0, -a.sin());
            push(Vec3::new(0.0, y, 0.0) + dir * radius, (dir + Vec3::Y * 0.6 * RADIUS / length).normalize());
        }
    }
    push(Vec3::new(0.0, length, 0.0), Vec3::Y);
    let ring = |r: u32| 1 + r * segments;
    let next = |s: u32| (s + 1) % segments;
    let tip = 1 + rings as u32 * segments;
    let mut indices = Vec::new();
    for s in 0..segments {
        indices.extend([0, ring(0) + next(s), ring(0) + s]);
    }
    for r in 0..rings as u32 - 1 {
        for s in 0..segments {
            let (lo, hi) = (ring(r), ring(r + 1));
            indices.extend([lo + s, lo + next(s), hi + next(s), lo + s, hi + next(s), hi + s]);
        }
    }
    let last = ring(rings as u32 - 1);
    for s in 0..segments {
        indices.extend([tip, last + s, last + next(s)]);
    }
    Skin::new(positions, normals, indices, joints, weights, &bind)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The tentacle as it was made before it was built in code: BVH text, parsed.
    fn tentacle_from_text(bones: usize) -> Clip {
        let bones = bones.clamp(*BONES.start(), *BONES.end());
        let mut text =
            String::from("HIERARCHY\nROOT bone0\n{\n  OFFSET 0 0 0\n  CHANNELS 3 Zrotation Xrotation Yrotation\n");
        for b in 1..bones {
            text.push_str(&format!(
                "JOINT bone{b}\n{{\n  OFFSET 0 {BONE_LENGTH} 0\n  CHANNELS 3 Zrotation Xrotation Yrotation\n"
            ));
        }
        text.push_str(&format!("End Site {TIP}\n{{\n  OFFSET 0 {BONE_LENGTH} 0\n}}\n"));
        text.push_str(&"}\n".repeat(bones));
        text.push_str("MOTION\nFrames: 1\nFrame Time: 0.0333333\n");
        text.push_str(&"0 0 0 ".repeat(bones));
        text.push('\n');
        // Generated text in the format's own grammar: it always parses.
        crate::formats::bvh::parse(text.as_bytes()).unwrap_or_default()
    }

    #[test]
    fn the_tentacle_built_in_code_is_the_one_its_bvh_text_gave() {
        for bones in [0, 1, 2, 3, 7, 10, 11, 50] {
            let (code, text) = (tentacle(bones), tentacle_from_text(bones));
            assert_eq!(code, text, "{bones} bones");
            assert_eq!(crate::formats::bvh::write(&code), crate::formats::bvh::write(&text), "{bones} bones");
        }
    }

    #[test]
    fn the_tentacle_is_a_chain_with_a_closed_skin() {
        let clip = tentacle(3);
        assert_eq!(clip.skeleton().len(), 4);
        assert_eq!(clip.skeleton().find(TIP), Some(3));
        assert!((clip.world_positions(0)[3].y - 3.0 * BONE_LENGTH).abs() < 1e-6);
        for soft in [false, true] {
            let skin = tentacle_skin(&clip, soft).unwrap();
            let mut edges = std::collections::HashMap::new();
            for t in skin.indices().chunks(3) {
                for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                    *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
                }
            }
            assert!(edges.values().all(|&n| n == 2), "closed");
            // Its flat ends lie at 0 and the tip's height: seen from outside
            // beyond them too.
            let top = 3.0 * BONE_LENGTH;
            crate::build::body::tests::assert_wound_outward(
                skin.positions(),
                skin.indices(),
                1e-3 * top,
                top * (1.0 - 1e-3),
            );
            let blended = skin.weights().iter().filter(|w| w[1] > 0.0).count();
            assert_eq!(blended > 0, soft, "soft skins blend across joints, rigid ones do not");
        }
        assert_eq!(tentacle(50).skeleton().len(), *BONES.end() + 1, "clamped");
    }
}
