//! BVA segments ↔ the animation model.
//!
//! Reading: each segment becomes a root joint whose channels are the segment's nine
//! columns in file order (translations set the position, rotations compose
//! intrinsically in column order, scales set the scale), with an End Site one unit
//! up its local Y axis: scaled by the segment's `YSCALE`, the drawn bone runs from
//! the segment's position along its local Y for `YSCALE` units.
//!
//! Writing ([`from_clip`]): every joint that is not an End Site becomes a segment
//! holding its model-space position each frame, its rotation turned so that local
//! Y points at its first child, and a uniform scale equal to the distance to that
//! child, so the segment draws the joint's bone and its position is exact.

use super::{Bva, BvaChannel, CHANNEL_COUNT, Segment};
use crate::error::{ParseError, Warning};
use crate::model::channel::{AngleUnit, Channel};
use crate::model::clip::{Clip, Units};
use crate::model::motion::Motion;
use crate::model::skeleton::{EulerConvention, Joint, Skeleton};
use glam::{EulerRot, Quat, Vec3};

fn channel(c: BvaChannel) -> Channel {
    match c {
        BvaChannel::XTran => Channel::Xposition,
        BvaChannel::YTran => Channel::Yposition,
        BvaChannel::ZTran => Channel::Zposition,
        BvaChannel::XRot => Channel::Xrotation,
        BvaChannel::YRot => Channel::Yrotation,
        BvaChannel::ZRot => Channel::Zrotation,
        BvaChannel::XScale => Channel::Xscale,
        BvaChannel::YScale => Channel::Yscale,
        BvaChannel::ZScale => Channel::Zscale,
    }
}

/// Turns parsed segments into a clip. Segments with fewer frames than the longest
/// hold their last row; the first segment's frame time is used; rotations in
/// radians are converted to degrees unless every segment uses radians.
pub fn to_clip(bva: &Bva) -> Result<Clip, ParseError> {
    let mut joints = Vec::with_capacity(bva.segments.len() * 2);
    for segment in &bva.segments {
        let root = joints.len();
        joints.push(Joint::new(
            segment.name.clone(),
            None,
            Vec3::ZERO,
            segment.channels.iter().map(|&c| channel(c)).collect(),
        ));
        joints.push(Joint::end_site(format!("{}_End", segment.name), Some(root), Vec3::Y));
    }
    let skeleton =
        Skeleton::new(joints, EulerConvention::Intrinsic).map_err(|e| ParseError::new(1, 1, e.to_string()))?;
    let frames = bva.segments.iter().map(|s| s.frame_count).max().unwrap_or(0);
    let all_radians = !bva.segments.is_empty() && bva.segments.iter().all(Segment::angle_in_radians);
    let width = bva.segments.len() * CHANNEL_COUNT;
    let mut data = Vec::with_capacity(width.saturating_mul(frames));
    for frame in 0..frames {
        for segment in &bva.segments {
            let row = segment.row(frame.min(segment.frame_count.saturating_sub(1)));
            let to_degrees = segment.angle_in_radians() && !all_radians;
            for (k, c) in segment.channels.iter().enumerate() {
                let v = row.get(k).copied().unwrap_or(0.0);
                data.push(if to_degrees && c.is_rotation() { v.to_degrees() } else { v });
            }
        }
    }
    let frame_time = bva.segments.first().map_or(super::DEFAULT_FRAME_TIME, |s| s.frame_time);
    let unit = if all_radians { AngleUnit::Radians } else { AngleUnit::Degrees };
    let motion = Motion::new(frame_time, width, frames, data)
        .or_else(|| Motion::new(super::DEFAULT_FRAME_TIME, width, frames, Vec::new()).filter(|_| frames == 0))
        .ok_or_else(|| ParseError::new(1, 1, "segments hold an unusable frame time"))?
        .with_angle_unit(unit);
    let mut clip = Clip::new(skeleton, motion).map_err(|e| ParseError::new(1, 1, e.to_string()))?;
    clip.warnings = bva.warnings.clone();
    if let Some(first) = bva.segments.first() {
        let mut words: Vec<&str> = Vec::new();
        for unit in &first.units {
            if !words.contains(&unit.as_str()) {
                words.push(unit);
            }
        }
        clip.metadata.push(("units".into(), words.join(", ")));
    }
    Ok(clip)
}

/// The BVA word for a length unit.
fn unit_word(units: Units) -> &'static str {
    match units {
        Units::Meters => "METERS",
        Units::Decimeters => "DECIMETERS",
        Units::Centimeters => "CENTIMETERS",
        Units::Millimeters => "MILLIMETERS",
        Units::Inches => "INCHES",
        Units::CmuInches | Units::Unknown => "UNITS",
    }
}

/// Every joint's model transform as a segment (see the module docs), with the
/// clip's frame time; rotations in degrees, intrinsic X then Y then Z. Warnings say
/// what a BVA cannot keep (the hierarchy).
pub fn from_clip(clip: &Clip) -> (Bva, Vec<Warning>) {
    let skeleton = clip.skeleton();
    let children = skeleton.children();
    let length = unit_word(clip.units());
    let units: [String; CHANNEL_COUNT] = std::array::from_fn(|k| {
        if BvaChannel::ALL.get(k).is_some_and(|c| c.is_rotation()) { "DEGREES".to_owned() } else { length.to_owned() }
    });
    let frames = clip.frame_count().max(1);
    let mut segments: Vec<Segment> = skeleton
        .joints()
        .iter()
        .filter(|j| !j.is_end_site())
        .map(|j| Segment {
            name: j.name.clone(),
            frame_time: clip.frame_time(),
            channels: BvaChannel::ALL,
            units: units.clone(),
            frame_count: frames,
            data: Vec::with_capacity(frames * CHANNEL_COUNT),
            line: 0,
        })
        .collect();
    let mut model = Vec::new();
    for frame in 0..frames {
        clip.world_transforms_into(frame, &mut model);
        let mut segment = segments.iter_mut();
        for (j, joint) in skeleton.joints().iter().enumerate() {
            if joint.is_end_site() {
                continue;
            }
            let Some((t, segment)) = model.get(j).zip(segment.next()) else { break };
            let child = children.get(j).and_then(|c| c.first()).and_then(|&c| model.get(c));
            let (rotation, scale) = match child {
                Some(c) if (c.translation - t.translation).length() > 0.0 => {
                    let d = c.translation - t.translation;
                    let local = (t.rotation.inverse() * d).normalize_or_zero();
                    (t.rotation * Quat::from_rotation_arc(Vec3::Y, local), d.length())
                }
                _ => (t.rotation, 0.0),
            };
            let (x, y, z) = rotation.normalize().to_euler(EulerRot::XYZ);
            let p = t.translation;
            segment.data.extend([p.x, p.y, p.z, x.to_degrees(), y.to_degrees(), z.to_degrees(), scale, scale, scale]);
        }
    }
    let warnings = vec![Warning {
        line: None,
        message: "BVA has no hierarchy: each joint was written as a segment in world space".into(),
    }];
    (Bva { segments, warnings: Vec::new() }, warnings)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bvh_to_bva_keeps_every_joint_and_bone_end() {
        let src = "HIERARCHY\nROOT Hips\n{\nOFFSET 0 90 0\nCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\nJOINT Leg\n{\nOFFSET 10 -5 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{\nOFFSET 0 -40 3\n}\n}\nJOINT Arm\n{\nOFFSET -20 30 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{\nOFFSET -25 0 0\n}\n}\n}\nMOTION\nFrames: 3\nFrame Time: 0.04\n1 90 2 10 20 30 40 -50 60 0 0 90\n3 91 0 -170 5 0 80 10 -20 45 45 45\n0 0 0 0 0 0 0 0 0 0 0 0\n";
        let clip = crate::formats::bvh::parse(src.as_bytes()).unwrap();
        let (bva, _) = from_clip(&clip);
        assert_eq!(bva.segments.len(), 3);
        let back = to_clip(&crate::formats::bva::parse(crate::formats::bva::write(&bva).as_bytes()).unwrap()).unwrap();
        assert_eq!(back.frame_count(), 3);
        assert_eq!(back.frame_time(), 0.04);
        for frame in 0..3 {
            let a = clip.world_positions(frame);
            let b = back.world_positions(frame);
            // Segment roots at the joints; Hips' segment ends at its first child, Leg's and Arm's at their End Sites.
            for (seg, joint) in [(0, 0), (2, 1), (4, 3)] {
                assert!((a[joint] - b[seg]).length() < 1e-3, "frame {frame} joint {joint}: {} vs {}", a[joint], b[seg]);
            }
            for (seg_end, joint) in [(1, 1), (3, 2), (5, 4)] {
                assert!(
                    (a[joint] - b[seg_end]).length() < 1e-3,
                    "frame {frame} end of {joint}: {} vs {}",
                    a[joint],
                    b[seg_end]
                );
            }
        }
        // BVA → BVH: each segment a root with six channels, the scale dropped with a warning.
        let (bvh, warnings) = crate::ops::bake::to_bvh(&back);
        assert!(warnings.iter().any(|w| w.message.contains("scale")));
        assert_eq!(bvh.skeleton().roots().count(), 3);
        assert!(bvh.skeleton().joints().iter().filter(|j| j.parent.is_none()).all(|j| j.channels.len() == 6));
        let reread = crate::formats::bvh::parse(crate::formats::bvh::write(&bvh).as_bytes()).unwrap();
        let first = back.world_positions(0);
        for (a, b) in first.iter().zip(reread.world_positions(0)) {
            assert!((*a - b).length() < 1e-3, "{a} vs {b}");
        }
    }
}
