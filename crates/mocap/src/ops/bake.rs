//! Baking a clip of the general model into one BVH can hold: intrinsic
//! `Zrotation Xrotation Yrotation` rotations in degrees, no rest rotations, no scale
//! or length channels. Every joint's model position is kept on every frame; rest
//! rotations, extrinsic orders, radians and bone-length changes are folded into
//! the written values. Used by [`crate::formats::bvh::write`] and the converters.

use crate::error::Warning;
use crate::model::channel::{AngleUnit, Channel, ChannelKind};
use crate::model::clip::Clip;
use crate::model::motion::Motion;
use crate::model::skeleton::{EulerConvention, Joint, Skeleton};
use crate::runtime::pose::{LocalPose, from_row};
use glam::{EulerRot, Quat, Vec3};

/// True when BVH can hold the clip as it is.
pub fn is_bvh_ready(clip: &Clip) -> bool {
    clip.skeleton().is_plain() && clip.motion().angle_unit() == AngleUnit::Degrees
}

/// What each joint gets in the baked clip.
#[derive(Clone, Copy)]
struct Plan {
    translate: bool,
    rotate: bool,
}

const ROTATIONS: [Channel; 3] = [Channel::Zrotation, Channel::Xrotation, Channel::Yrotation];
const POSITIONS: [Channel; 3] = [Channel::Xposition, Channel::Yposition, Channel::Zposition];

fn plan(skeleton: &Skeleton) -> Vec<Plan> {
    let joints = skeleton.joints();
    joints
        .iter()
        .map(|j| {
            let parent_stretches =
                j.parent.and_then(|p| joints.get(p)).is_some_and(|p| p.channels.contains(&Channel::Length));
            let has = |kind| j.channels.iter().any(|c| c.kind() == kind);
            // An End Site under a stretching bone becomes a joint with position
            // channels (BVH cannot animate an End Site's offset).
            Plan {
                translate: has(ChannelKind::Translation) || parent_stretches,
                rotate: !j.is_end_site() && (has(ChannelKind::Rotation) || j.rest_rotation != Quat::IDENTITY),
            }
        })
        .collect()
}

/// A BVH-ready copy of `clip` and the warnings about what BVH cannot keep (scale).
/// A clip that is already BVH-ready comes back unchanged.
pub fn to_bvh(clip: &Clip) -> (Clip, Vec<Warning>) {
    if is_bvh_ready(clip) {
        return (clip.clone(), Vec::new());
    }
    let skeleton = clip.skeleton();
    let motion = clip.motion();
    let plans = plan(skeleton);
    let mut warnings = Vec::new();
    let mut first = LocalPose::default();
    from_row(skeleton, motion.row(0), motion.angle_unit(), &mut first);
    let scaled = skeleton.joints().iter().any(|j| j.channels.iter().any(|c| c.kind() == ChannelKind::Scale));
    if scaled {
        warnings.push(Warning {
            line: None,
            message: "BVH has no scale channels: scale was dropped (End Sites keep the first frame's scaled length)"
                .into(),
        });
    }
    let joints: Vec<Joint> = skeleton
        .joints()
        .iter()
        .zip(&plans)
        .map(|(j, plan)| {
            if j.is_end_site() && !plan.translate {
                let parent_scale = j.parent.and_then(|p| first.scale.get(p)).copied().unwrap_or(Vec3::ONE);
                // A non-finite scale in the first frame keeps the unscaled offset.
                let scaled = j.offset * parent_scale;
                return Joint::end_site(j.name.clone(), j.parent, if scaled.is_finite() { scaled } else { j.offset });
            }
            let mut channels = Vec::new();
            if plan.translate {
                channels.extend(POSITIONS);
            }
            if plan.rotate {
                channels.extend(ROTATIONS);
            }
            Joint::new(j.name.clone(), j.parent, j.offset, channels)
        })
        .collect();
    let Ok(baked) = Skeleton::new(joints, EulerConvention::Intrinsic) else { return (clip.clone(), warnings) };
    let width = baked.channel_count();
    let frames = motion.frame_count();
    let mut data = Vec::with_capacity(width.saturating_mul(frames));
    let mut local = LocalPose::default();
    for frame in 0..frames {
        from_row(skeleton, motion.row(frame), motion.angle_unit(), &mut local);
        for (i, plan) in plans.iter().enumerate() {
            if plan.translate {
                data.extend(local.translation.get(i).copied().unwrap_or(Vec3::ZERO).to_array());
            }
            if plan.rotate {
                let q = local.rotation.get(i).copied().unwrap_or(Quat::IDENTITY);
                let (z, x, y) = q.to_euler(EulerRot::ZXY);
                data.extend([z.to_degrees(), x.to_degrees(), y.to_degrees()]);
            }
        }
    }
    let motion = Motion::new(motion.frame_time(), width, frames, data).unwrap_or_default();
    let mut out = match Clip::new(baked, motion) {
        Ok(c) => c,
        Err(_) => return (clip.clone(), warnings),
    };
    out.warnings = clip.warnings.iter().cloned().chain(warnings.iter().cloned()).collect();
    out.metadata = clip.metadata.clone();
    (out, warnings)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::runtime::pose::axis_rotation;

    #[test]
    fn glam_zxy_is_intrinsic_z_then_x_then_y() {
        let (a, b, c) = (0.3f32, -1.1, 2.0);
        let q = Quat::from_euler(EulerRot::ZXY, a, b, c);
        let r = Quat::from_rotation_z(a) * Quat::from_rotation_x(b) * Quat::from_rotation_y(c);
        assert!(q.dot(r).abs() > 0.99999);
        let (z, x, y) = r.to_euler(EulerRot::ZXY);
        let back = Quat::from_rotation_z(z) * Quat::from_rotation_x(x) * Quat::from_rotation_y(y);
        assert!(back.dot(r).abs() > 0.99999);
    }

    #[test]
    fn baking_keeps_model_positions() {
        // A root with a rest rotation and extrinsic radians, a child that stretches its bone.
        let root = Joint::new(
            "r",
            None,
            Vec3::new(1.0, 2.0, 3.0),
            vec![Channel::Xposition, Channel::Xrotation, Channel::Yrotation, Channel::Zrotation],
        )
        .with_rest_rotation(axis_rotation(2, 30.0, AngleUnit::Degrees));
        let child = Joint::new("c", Some(0), Vec3::new(0.0, 2.0, 0.0), vec![Channel::Zrotation, Channel::Length])
            .with_rest_rotation(axis_rotation(0, -45.0, AngleUnit::Degrees));
        let end = Joint::end_site("e", Some(1), Vec3::new(0.5, 1.0, 0.0));
        let skeleton = Skeleton::new(vec![root, child, end], EulerConvention::Extrinsic).unwrap();
        let data = vec![0.5, 0.4, -0.2, 1.3, 0.7, 0.25, -1.0, 1.0, 2.0, 3.0, -0.6, 0.0];
        let motion = Motion::new(0.1, 6, 2, data).unwrap().with_angle_unit(AngleUnit::Radians);
        let clip = Clip::new(skeleton, motion).unwrap();
        let (baked, warnings) = to_bvh(&clip);
        assert!(warnings.is_empty());
        assert!(is_bvh_ready(&baked));
        let text = crate::formats::bvh::write(&clip);
        let reread = crate::formats::bvh::parse(text.as_bytes()).unwrap();
        for frame in 0..2 {
            for (a, b) in clip.world_positions(frame).iter().zip(reread.world_positions(frame)) {
                assert!((*a - b).length() < 1e-4, "frame {frame}: {a} vs {b}");
            }
        }
    }
}
