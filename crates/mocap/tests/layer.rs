//! Motion layers: a layer on a subtree leaves every joint outside it bit-identical,
//! puts every joint inside it on the layer, matches joints named by other
//! conventions, blends by weight and fades, and saves as BVH.

use mocap::ops::edit::{Edit, apply as edit};
use mocap::ops::layer::{self, Blend, Layer};
use mocap::{Clip, LocalPose};

fn walk() -> Clip {
    mocap::formats::bvh::parse(include_bytes!("../../../data/walk.bvh")).unwrap()
}

fn subtree(clip: &Clip, root: usize) -> Vec<bool> {
    let joints = clip.skeleton().joints();
    let mut inside = vec![false; joints.len()];
    for (i, j) in joints.iter().enumerate() {
        inside[i] = i == root || j.parent.is_some_and(|p| inside[p]);
    }
    inside
}

fn local(clip: &Clip, frame: usize) -> LocalPose {
    let mut p = LocalPose::default();
    clip.local_pose_into(frame, &mut p);
    p
}

#[test]
fn a_layer_drives_its_subtree_and_nothing_else() {
    let base = walk();
    let wave = edit(&base, &Edit::Reverse).unwrap();
    let out = layer::apply(&base, &wave, &Layer::on("RightShoulder")).unwrap();
    let root = base.skeleton().find("RightShoulder").unwrap();
    let inside = subtree(&base, root);
    assert_eq!(out.skeleton(), base.skeleton(), "the base's skeleton and bone lengths");
    for f in [0, 13, 40, 66] {
        for (j, joint) in base.skeleton().joints().iter().enumerate() {
            let cols = joint.columns();
            if !inside[j] {
                assert_eq!(
                    &out.motion().row(f)[cols.clone()],
                    &base.motion().row(f)[cols],
                    "frame {f}: {} untouched",
                    joint.name
                );
            }
        }
        let (o, w) = (local(&out, f), local(&wave, f));
        for j in (0..inside.len()).filter(|&j| inside[j] && !base.skeleton().is_end_site(j)) {
            assert!(o.rotation[j].dot(w.rotation[j]).abs() > 0.9999, "frame {f}: joint {j} is the layer's");
        }
    }
    mocap::formats::bvh::parse(mocap::formats::bvh::write(&out).as_bytes()).unwrap();
}

#[test]
fn joints_named_by_another_convention_match() {
    let base = walk();
    let mut wave = edit(&base, &Edit::Reverse).unwrap();
    for (from, to) in
        [("RightShoulder", "rCollar"), ("RightArm", "rShldr"), ("RightForeArm", "rForeArm"), ("RightHand", "rHand")]
    {
        wave = edit(&wave, &Edit::Rename { from: from.into(), to: to.into() }).unwrap();
    }
    let root = base.skeleton().find("RightShoulder").unwrap();
    let pairs = layer::match_joints(base.skeleton(), wave.skeleton(), root, &[]);
    assert_eq!(pairs.len(), 4, "{pairs:?}");
    let out = layer::apply(&base, &wave, &Layer::on("RightShoulder")).unwrap();
    let hand = base.skeleton().find("RightForeArm").unwrap();
    let (o, w) = (local(&out, 20), local(&wave, 20));
    assert!(o.rotation[hand].dot(w.rotation[wave.skeleton().find("rForeArm").unwrap()]).abs() > 0.9999);
    // Nothing to match: a clear error.
    let other = mocap::formats::bvh::parse(b"HIERARCHY\nROOT Tail\n{\nOFFSET 0 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{\nOFFSET 0 1 0\n}\n}\nMOTION\nFrames: 1\nFrame Time: 0.1\n0 0 0\n").unwrap();
    assert!(
        layer::apply(&base, &other, &Layer::on("RightShoulder"))
            .unwrap_err()
            .to_string()
            .contains("no joint of the layer matches")
    );
    assert!(layer::apply(&base, &wave, &Layer::on("Wing")).is_err());
}

#[test]
fn an_explicit_map_wins_and_can_leave_a_joint_out() {
    let base = walk();
    let wave = edit(&base, &Edit::Reverse).unwrap();
    let root = base.skeleton().find("RightShoulder").unwrap();
    let (arm, fore, hand) = ["RightArm", "RightForeArm", "RightHand"].map(|n| base.skeleton().find(n).unwrap()).into();
    // RightArm played by the layer's LeftArm; RightHand left out.
    let map = vec![("RightArm".to_owned(), "LeftArm".to_owned()), ("RightHand".to_owned(), String::new())];
    let pairs = layer::match_joints(base.skeleton(), wave.skeleton(), root, &map);
    let left_arm = wave.skeleton().find("LeftArm").unwrap();
    assert!(pairs.contains(&(arm, left_arm)), "{pairs:?}");
    assert!(pairs.iter().any(|&(b, l)| b == fore && l == fore));
    assert!(!pairs.iter().any(|&(b, _)| b == hand), "the hand is left out: {pairs:?}");
    let out = layer::apply(&base, &wave, &Layer { map, ..Layer::on("RightShoulder") }).unwrap();
    let (o, w, b) = (local(&out, 20), local(&wave, 20), local(&base, 20));
    assert!(o.rotation[arm].dot(w.rotation[left_arm]).abs() > 0.9999, "the arm plays the layer's left arm");
    let cols = base.skeleton().joints()[hand].columns();
    assert_eq!(&out.motion().row(20)[cols.clone()], &base.motion().row(20)[cols], "the hand keeps the base");
    assert!(o.rotation[hand].dot(b.rotation[hand]).abs() > 0.9999);
}

#[test]
fn weight_fades_and_additive() {
    let base = walk();
    let wave = edit(&base, &Edit::Reverse).unwrap();
    let none = layer::apply(&base, &wave, &Layer { weight: 0.0, ..Layer::on("RightShoulder") }).unwrap();
    assert_eq!(none.motion().data(), base.motion().data(), "weight 0 is the base");
    let faded = layer::apply(&base, &wave, &Layer { fade_in: 1.0, ..Layer::on("RightShoulder") }).unwrap();
    assert_eq!(faded.motion().row(0), base.motion().row(0), "fully faded out at the start");
    let arm = base.skeleton().find("RightArm").unwrap();
    let (f, w) = (local(&faded, 60), local(&wave, 60));
    assert!(f.rotation[arm].dot(w.rotation[arm]).abs() > 0.9999, "fully in after the fade");
    // Additive with the base itself as the layer adds its change since frame 0.
    let add = layer::apply(&base, &base, &Layer { blend: Blend::Additive, ..Layer::on("RightShoulder") }).unwrap();
    let (a, b0, bf) = (local(&add, 30), local(&base, 0), local(&base, 30));
    let expected = bf.rotation[arm] * b0.rotation[arm].inverse() * bf.rotation[arm];
    assert!(a.rotation[arm].dot(expected).abs() > 0.9999);
    assert!(layer::apply(&base, &wave, &Layer { weight: 2.0, ..Layer::on("RightShoulder") }).is_err());
}
