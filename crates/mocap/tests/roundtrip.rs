//! Property test: random skeletons and motions survive write → parse exactly.

use mocap::glam::Vec3;
use mocap::{Channel, Clip, Joint, Motion, Skeleton};
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
        let mut next = 0;
        for (i, (pick, offset, channels, end, name)) in specs.into_iter().enumerate() {
            // Parent: any earlier non-End-Site joint, or a new root.
            let candidates: Vec<usize> = (0..i).filter(|&p| !joints[p].end_site).collect();
            let parent = if candidates.is_empty() || pick % 9 == 0 { None } else { Some(candidates[pick as usize % candidates.len()]) };
            let end_site = end && parent.is_some() && pick % 3 == 0;
            let channels: Vec<Channel> = if end_site { vec![] } else { channels.into_iter().map(|c| Channel::ALL[c]).collect() };
            joints.push(Joint { name: format!("{name}{i}"), parent, offset: Vec3::from(offset), first_channel: 0, channels, end_site });
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
            j.first_channel = next;
            next += j.channels.len();
        }
        Skeleton { joints: out }
    })
}

fn clip_strategy() -> impl Strategy<Value = Clip> {
    (skeleton_strategy(), 0usize..6, 1e-4f64..1.0).prop_flat_map(|(skeleton, frames, dt)| {
        let width = skeleton.channel_count();
        let value = prop_oneof![any::<f32>().prop_filter("finite", |v| v.is_finite()), -360.0f32..360.0, Just(-0.0f32)];
        prop::collection::vec(value, frames * width).prop_map(move |data| {
            let frames = if width == 0 { frames.min(1) } else { frames };
            let data = if width == 0 { vec![] } else { data };
            Clip { skeleton: skeleton.clone(), motion: Motion::new(dt, width, frames, data).unwrap(), warnings: vec![] }
        })
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

    #[test]
    fn write_then_parse_is_exact(clip in clip_strategy()) {
        let text = mocap::bvh::write(&clip);
        prop_assert!(!text.contains('\r'));
        let back = mocap::bvh::parse(text.as_bytes()).map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
        prop_assert_eq!(clip.skeleton.len(), back.skeleton.len());
        for (a, b) in clip.skeleton.joints.iter().zip(&back.skeleton.joints) {
            if !a.end_site { prop_assert_eq!(&a.name, &b.name); }
            prop_assert_eq!((a.parent, a.end_site, &a.channels, a.first_channel), (b.parent, b.end_site, &b.channels, b.first_channel));
            prop_assert_eq!(a.offset.to_array().map(f32::to_bits), b.offset.to_array().map(f32::to_bits));
        }
        prop_assert_eq!(clip.frame_count(), back.frame_count());
        prop_assert_eq!(clip.frame_time(), back.frame_time());
        let bits = |c: &Clip| c.motion.data().iter().map(|v| v.to_bits()).collect::<Vec<_>>();
        prop_assert_eq!(bits(&clip), bits(&back));
    }

    #[test]
    fn parse_never_panics_on_mutated_input(bytes in prop::collection::vec(any::<u8>(), 0..400), cut in 0usize..400) {
        let base = b"HIERARCHY\nROOT A\n{\nOFFSET 0 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{\nOFFSET 0 1 0\n}\n}\nMOTION\nFrames: 2\nFrame Time: 0.1\n1 2 3\n4 5 6\n";
        let mut input = base[..cut.min(base.len())].to_vec();
        input.extend_from_slice(&bytes);
        if let Ok(clip) = mocap::bvh::parse(&input) {
            let _ = clip.bounds();
            let _ = mocap::bvh::write(&clip);
        }
    }
}
