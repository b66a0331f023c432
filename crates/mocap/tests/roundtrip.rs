//! Property test: random skeletons and motions survive write → parse exactly.

use mocap::glam::{Quat, Vec3};
use mocap::{AngleUnit, Channel, Clip, EulerConvention, Joint, Motion, Skeleton};
use proptest::prelude::*;

/// A random tree built in pre-order (as files are), with random channel layouts.
fn skeleton_strategy() -> impl Strategy<Value = Skeleton> {
    let joint = (
        any::<u8>(),
        prop::array::uniform3(-1000.0f32..1000.0),
        prop::collection::vec(0usize..6, 0..7),
        any::<bool>(),
        "[A-Za-z_][A-Za-z0-9_:. -]{0,12}[A-Za-z0-9]",
    );
    prop::collection::vec(joint, 1..25).prop_map(|specs| {
        let mut joints: Vec<Joint> = Vec::new();
        for (i, (pick, offset, channels, end, name)) in specs.into_iter().enumerate() {
            // Parent: any earlier non-End-Site joint, or a new root.
            let candidates: Vec<usize> = (0..i).filter(|&p| !joints[p].is_end_site()).collect();
            let parent = if candidates.is_empty() || pick % 9 == 0 {
                None
            } else {
                Some(candidates[pick as usize % candidates.len()])
            };
            let end_site = end && parent.is_some() && pick % 3 == 0;
            let channels: Vec<Channel> =
                if end_site { vec![] } else { channels.into_iter().map(|c| Channel::BVH[c]).collect() };
            let name = format!("{name}{i}");
            joints.push(if end_site {
                Joint::end_site(name, parent, Vec3::from(offset))
            } else {
                Joint::new(name, parent, Vec3::from(offset), channels)
            });
        }
        // Reorder into pre-order so that the writer and the reader agree on columns.
        let mut order = Vec::new();
        let mut stack: Vec<usize> = (0..joints.len()).rev().filter(|&j| joints[j].parent.is_none()).collect();
        while let Some(j) = stack.pop() {
            order.push(j);
            stack.extend((0..joints.len()).rev().filter(|&c| joints[c].parent == Some(j)));
        }
        let mut new_index = vec![0; joints.len()];
        for (n, &old) in order.iter().enumerate() {
            new_index[old] = n;
        }
        let mut out: Vec<Joint> = order.iter().map(|&old| joints[old].clone()).collect();
        for j in &mut out {
            j.parent = j.parent.map(|p| new_index[p]);
        }
        Skeleton::new(out, EulerConvention::Intrinsic).unwrap()
    })
}

/// The same random trees, with random rest rotations, extrinsic or intrinsic
/// rotations, bone-length channels and radians: what BVH cannot hold as it is.
fn general_clip_strategy() -> impl Strategy<Value = Clip> {
    (
        skeleton_strategy(),
        prop::collection::vec(prop::array::uniform4(-1.0f32..1.0), 25),
        any::<bool>(),
        any::<bool>(),
        1usize..4,
    )
        .prop_flat_map(|(skeleton, rests, extrinsic, radians, frames)| {
            let joints: Vec<Joint> = skeleton
                .joints()
                .iter()
                .zip(rests.iter().cycle())
                .map(|(j, r)| {
                    let q = Quat::from_array(*r);
                    let q = if q.length() > 0.1 { q.normalize() } else { Quat::IDENTITY };
                    let mut j = j.clone().with_rest_rotation(q);
                    if !j.is_end_site() && j.channels.len() % 3 == 1 {
                        j.channels.push(Channel::Length);
                    }
                    j
                })
                .collect();
            let euler = if extrinsic { EulerConvention::Extrinsic } else { EulerConvention::Intrinsic };
            let skeleton = Skeleton::new(joints, euler).unwrap();
            let width = skeleton.channel_count();
            prop::collection::vec(-3.0f32..3.0, frames * width).prop_map(move |data| {
                let frames = if width == 0 { 1 } else { frames };
                let unit = if radians { AngleUnit::Radians } else { AngleUnit::Degrees };
                let motion = Motion::new(0.05, width, frames, data).unwrap().with_angle_unit(unit);
                Clip::new(skeleton.clone(), motion).unwrap()
            })
        })
}

fn clip_strategy() -> impl Strategy<Value = Clip> {
    (skeleton_strategy(), 0usize..6, 1e-4f64..1.0).prop_flat_map(|(skeleton, frames, dt)| {
        let width = skeleton.channel_count();
        let value = prop_oneof![any::<f32>().prop_filter("finite", |v| v.is_finite()), -360.0f32..360.0, Just(-0.0f32)];
        prop::collection::vec(value, frames * width).prop_map(move |data| {
            let frames = if width == 0 { frames.min(1) } else { frames };
            let data = if width == 0 { vec![] } else { data };
            Clip::new(skeleton.clone(), Motion::new(dt, width, frames, data).unwrap()).unwrap()
        })
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn write_then_parse_is_exact(clip in clip_strategy()) {
        let text = mocap::formats::bvh::write(&clip);
        prop_assert!(!text.contains('\r'));
        let back = mocap::formats::bvh::parse(text.as_bytes()).map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
        prop_assert_eq!(clip.skeleton().len(), back.skeleton().len());
        for (a, b) in clip.skeleton().joints().iter().zip(back.skeleton().joints()) {
            if !a.is_end_site() { prop_assert_eq!(&a.name, &b.name); }
            prop_assert_eq!((a.parent, a.is_end_site(), &a.channels, a.first_channel()), (b.parent, b.is_end_site(), &b.channels, b.first_channel()));
            prop_assert_eq!(a.offset.to_array().map(f32::to_bits), b.offset.to_array().map(f32::to_bits));
        }
        prop_assert_eq!(clip.frame_count(), back.frame_count());
        prop_assert_eq!(clip.frame_time(), back.frame_time());
        let bits = |c: &Clip| c.motion().data().iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        prop_assert_eq!(bits(&clip), bits(&back));
    }

    #[test]
    fn rest_rotations_and_general_channels_survive_write_then_parse(clip in general_clip_strategy()) {
        let text = mocap::formats::bvh::write(&clip);
        let back = mocap::formats::bvh::parse(text.as_bytes()).map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
        prop_assert_eq!(clip.skeleton().len(), back.skeleton().len());
        prop_assert_eq!(clip.frame_count(), back.frame_count());
        let size = clip.bounds().size().length().max(1.0);
        for frame in 0..clip.frame_count() {
            // Joints are written depth-first, as the random trees already are.
            for (n, (a, b)) in clip.world_positions(frame).iter().zip(back.world_positions(frame)).enumerate() {
                prop_assert!((*a - b).length() <= 1e-4 * size, "frame {} joint {}: {} vs {}", frame, n, a, b);
            }
        }
    }

    #[test]
    fn loading_never_panics_on_mutated_bva_asf_or_amc(bytes in prop::collection::vec(any::<u8>(), 0..200), cut in 0usize..700, which in 0usize..3) {
        let bva = b"Segment: Hips\nFrames: 2\nFrame Time: 0.1\nXTRAN YTRAN ZTRAN XROT YROT ZROT XSCALE YSCALE ZSCALE\nINCHES INCHES INCHES DEGREES DEGREES DEGREES INCHES INCHES INCHES\n1 2 3 4 5 6 7 8 9\n1 2 3 4 5 6 7 8 9\n".to_vec();
        let asf = b":version 1.10\n:name T\n:units\n mass 1\n length 1\n angle deg\n:root\n order TX TY TZ RX RY RZ\n axis XYZ\n position 0 0 0\n orientation 0 0 0\n:bonedata\n begin\n id 1\n name b\n direction 1 0 0\n length 2\n axis 0 0 30 XYZ\n dof rx ry rz l\n limits (-1 1) (-inf inf) (0 2) (0 1)\n end\n:hierarchy\n begin\n root b\n end\n".to_vec();
        let amc = b":FULLY-SPECIFIED\n:DEGREES\n1\nroot 0 1 2 3 4 5\nb 1 2 3 0.5\n2\nroot 0 1 2 3 4 5\nb 1 2 3 0.5\n".to_vec();
        let mut files = [bva, asf, amc];
        let target = &mut files[which];
        target.truncate(cut.min(target.len()));
        target.extend_from_slice(&bytes);
        let inputs = [
            mocap::Input { name: "a.bva", bytes: &files[0] },
            mocap::Input { name: "t.asf", bytes: &files[1] },
            mocap::Input { name: "t.amc", bytes: &files[2] },
        ];
        for loaded in mocap::load(&inputs).into_iter().flatten() {
            let _ = loaded.asset.bounds();
            let _ = mocap::formats::bvh::write(loaded.clip().unwrap());
            let _ = mocap::formats::bva::write(&mocap::formats::bva::from_clip(loaded.clip().unwrap()).0);
        }
    }

    #[test]
    fn parse_never_panics_on_mutated_input(bytes in prop::collection::vec(any::<u8>(), 0..400), cut in 0usize..400) {
        let base = b"HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{\nOFFSET 0 1 0\n}\n}\nMOTION\nFrames: 2\nFrame Time: 0.1\n1 2 3\n4 5 6\n";
        let mut input = base[..cut.min(base.len())].to_vec();
        input.extend_from_slice(&bytes);
        if let Ok(clip) = mocap::formats::bvh::parse(&input) {
            let _ = clip.bounds();
            let _ = mocap::formats::bvh::write(&clip);
        }
    }
}

/// Found by the mutation test (`tests/mutations.rs`): a BVA segment whose first
/// frame's scale is infinite made baking fail and `bvh::write` call itself for
/// ever (a stack overflow in `mocap convert`). It writes, once baked, and reads back.
#[test]
fn a_bva_with_an_infinite_first_scale_writes_as_bvh() {
    let header = "Segment: Hips\nFrames: 2\nFrame Time: 0.033333\nXTRAN\tYTRAN\tZTRAN\tXROT\tYROT\tZROT\tXSCALE\tYSCALE\tZSCALE\nCENTIMETERS\tCENTIMETERS\tCENTIMETERS\tDEGREES\tDEGREES\tDEGREES\tCENTIMETERS\tCENTIMETERS\tCENTIMETERS\n";
    let text = format!("{header}0\t92\t0\t0\t0\t0\t10\t-1e39\t10\n1\t92\t0\t0\t0\t0\t10\t10\t10\n");
    let bva = mocap::formats::bva::parse(text.as_bytes()).expect("reads, with a warning");
    let clip = mocap::formats::bva::to_clip(&bva).expect("a clip");
    let written = mocap::formats::bvh::write(&clip);
    let again = mocap::formats::bvh::parse(written.as_bytes()).expect("the written BVH reads");
    assert_eq!(again.frame_count(), 2);
    assert!(again.skeleton().joints().iter().all(|j| j.offset.is_finite()));
}
