//! Retargeting ([`mocap::ops::retarget`]): onto itself it is the identity; onto a
//! skeleton with other names, proportions, rest pose and up axis every mapped
//! bone points where its source bone points on every frame, and the hips' path is
//! the source's scaled by the legs; real files (CMU Acclaim onto a BVH skeleton).

mod common;

use mocap::Clip;
use mocap::glam::{Quat, Vec3};
use mocap::ops::edit::{Edit, apply};
use mocap::ops::retarget::{Options, Reference, map_joints, retarget};

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");

fn walk() -> Clip {
    mocap::formats::bvh::parse(WALK).unwrap()
}

/// World positions at a frame, stood Y up.
fn positions(clip: &Clip, frame: usize) -> Vec<Vec3> {
    let up = clip.up_axis().rotation();
    clip.world_positions(frame).into_iter().map(|p| up * p).collect()
}

/// The worst angle (degrees) over every frame between a mapped target limb bone
/// (a mapped joint to its only child, mapped) and its source bone. (Bones out of
/// a branching joint, the chest to each shoulder, are fixed offsets that one
/// rotation cannot point all at once where another skeleton's point.)
fn worst_bone_angle(source: &Clip, out: &Clip, pairs: &[(usize, usize)]) -> (f32, String) {
    let ts = out.skeleton();
    let source_of = |t: usize| pairs.iter().find(|p| p.0 == t).map(|p| p.1);
    let mut worst = (0.0f32, String::new());
    for f in 0..source.frame_count() {
        let (a, b) = (positions(out, f), positions(source, f));
        for (c, joint) in ts.joints().iter().enumerate() {
            let Some(p) = joint.parent else { continue };
            if ts.joints().iter().filter(|j| j.parent == Some(p)).count() != 1 {
                continue;
            }
            let (Some(sp), Some(sc)) = (source_of(p), source_of(c)) else { continue };
            // Only bones whose source joints are parent and child too.
            if source.skeleton().joints()[sc].parent != Some(sp) {
                continue;
            }
            // A bone of no length (CMU's root to lowerback) has no direction.
            let (bt, bs) = (a[c] - a[p], b[sc] - b[sp]);
            if bt.length() < 1e-3 * out.pose_extent() || bs.length() < 1e-3 * source.pose_extent() {
                continue;
            }
            let (dt, ds) = (bt.normalize(), bs.normalize());
            let angle = dt.dot(ds).clamp(-1.0, 1.0).acos().to_degrees();
            if angle > worst.0 {
                worst = (angle, format!("{} at frame {f}", joint.name));
            }
        }
    }
    worst
}

#[test]
fn onto_itself_it_is_the_identity() {
    let clip = walk();
    for reference in [Reference::FirstFrame, Reference::Rest] {
        let (out, pairs) = retarget(&clip, &clip, &Options { reference, ..Options::default() }).unwrap();
        assert_eq!(pairs.len(), clip.skeleton().joints().iter().filter(|j| !j.is_end_site()).count());
        assert_eq!(out.frame_count(), clip.frame_count());
        assert_eq!(out.frame_time(), clip.frame_time());
        let height = clip.pose_height();
        for f in [0, 17, clip.frame_count() - 1] {
            for (a, b) in positions(&out, f).iter().zip(positions(&clip, f)) {
                assert!(a.distance(b) < 1e-3 * height, "{reference:?} frame {f}: {a} vs {b}");
            }
        }
    }
}

/// The walk with Mixamo's names, half the size, its arms hanging down in the
/// rest pose (an A-pose of sorts) and Z up.
fn other_character() -> Clip {
    let mut clip = walk();
    let names: Vec<String> =
        clip.skeleton().joints().iter().filter(|j| !j.is_end_site()).map(|j| j.name.clone()).collect();
    for name in names {
        clip = apply(&clip, &Edit::Rename { from: name.clone(), to: format!("mixamorig:{name}") }).unwrap();
    }
    clip = apply(&clip, &Edit::Scale { factor: 0.5 }).unwrap();
    for side in ["Left", "Right"] {
        let joint = format!("mixamorig:{side}ForeArm");
        let length = clip.skeleton().joints()[clip.skeleton().find(&joint).unwrap()].offset.length();
        clip = apply(&clip, &Edit::SetOffset { name: joint, offset: Vec3::new(0.0, -length, 0.0) }).unwrap();
    }
    apply(&clip, &Edit::UpAxis { from: 1, negative: true }).unwrap()
}

#[test]
fn onto_another_character_every_bone_points_where_the_source_bone_points() {
    let source = walk();
    let target = other_character();
    for reference in [Reference::FirstFrame, Reference::Rest] {
        let (out, pairs) = retarget(&source, &target, &Options { reference, ..Options::default() }).unwrap();
        assert_eq!(out.skeleton().len(), target.skeleton().len());
        for (a, b) in out.skeleton().joints().iter().zip(target.skeleton().joints()) {
            assert_eq!(
                (&a.name, a.parent, a.offset),
                (&b.name, b.parent, b.offset),
                "the target's skeleton, unchanged"
            );
        }
        assert_eq!(pairs.len(), 21, "matched by name across conventions");
        let (worst, at) = worst_bone_angle(&source, &out, &pairs);
        assert!(worst < 0.5, "{reference:?}: a bone is {worst}° off its source ({at})");
        // The hips follow the source's path at half the size (the legs' ratio), Z up again.
        let hips = out.skeleton().find("mixamorig:Hips").unwrap();
        for f in [0, 30, 60] {
            let (a, b) = (positions(&out, f)[hips], positions(&source, f)[0] * 0.5);
            assert!(a.distance(b) < 1e-3, "frame {f}: hips at {a}, expected {b}");
        }
        assert_eq!(out.up_axis(), target.up_axis());
    }
}

#[test]
fn a_map_overrides_names_and_a_bad_one_is_named() {
    let source = walk();
    let target = walk();
    let map = vec![("LeftArm".to_owned(), String::new())];
    let pairs = map_joints(target.skeleton(), source.skeleton(), &map).unwrap();
    assert!(!pairs.iter().any(|&(t, _)| target.skeleton().joints()[t].name == "LeftArm"), "left out by the map");
    let bad = vec![("LeftArm".to_owned(), "Wing".to_owned())];
    let e = map_joints(target.skeleton(), source.skeleton(), &bad).unwrap_err();
    assert_eq!(e.to_string(), "the map names `Wing`, which is not a joint of the source");
    // Nothing in common: a clear error.
    let stranger = mocap::formats::bvh::parse(b"HIERARCHY\nROOT Blob\n{\n OFFSET 0 0 0\n CHANNELS 3 Zrotation Xrotation Yrotation\n End Site\n {\n  OFFSET 0 1 0\n }\n}\nMOTION\nFrames: 1\nFrame Time: 0.1\n0 0 0\n").unwrap();
    assert!(retarget(&source, &stranger, &Options::default()).is_err());
}

/// `clip` with every joint renamed `name(i)`: only the tree's shape is left.
fn renamed(mut clip: Clip, name: impl Fn(usize) -> String) -> Clip {
    let names: Vec<String> =
        clip.skeleton().joints().iter().filter(|j| !j.is_end_site()).map(|j| j.name.clone()).collect();
    for (i, from) in names.into_iter().enumerate() {
        clip = apply(&clip, &Edit::Rename { from, to: name(i) }).unwrap();
    }
    clip
}

/// The walk with names that say nothing (`j1`, `j2`, …).
fn anonymous() -> Clip {
    renamed(walk(), |i| format!("j{i}"))
}

#[test]
fn where_names_fail_the_shape_of_the_tree_maps_every_joint() {
    let source = walk();
    let target = anonymous();
    let pairs = map_joints(target.skeleton(), source.skeleton(), &[]).unwrap();
    let joints = source.skeleton().joints().iter().filter(|j| !j.is_end_site()).count();
    assert_eq!(pairs.len(), joints, "every joint found by shape: {pairs:?}");
    assert!(pairs.iter().all(|&(t, s)| t == s), "each joint onto itself: {pairs:?}");
    let (out, _) = retarget(&source, &target, &Options::default()).unwrap();
    let height = source.pose_height();
    for f in [0, 33, source.frame_count() - 1] {
        for (a, b) in positions(&out, f).iter().zip(positions(&source, f)) {
            assert!(a.distance(b) < 1e-3 * height, "frame {f}: {a} vs {b}");
        }
    }
    // The same from the other side, and an explicit pair still wins.
    assert_eq!(map_joints(source.skeleton(), target.skeleton(), &[]).unwrap(), pairs);
    let map = vec![("j7".to_owned(), String::new())];
    let pairs = map_joints(target.skeleton(), source.skeleton(), &map).unwrap();
    let j7 = target.skeleton().find("j7").unwrap();
    assert!(pairs.iter().all(|&(t, _)| t != j7), "left out by the map");
}

/// The walk without its collar bones (arms straight from the chest), anonymous.
fn anonymous_without_collars() -> Clip {
    let mut clip = walk();
    for side in ["Left", "Right"] {
        clip = apply(&clip, &Edit::RemoveJoint { name: format!("{side}Shoulder"), fold: true }).unwrap();
    }
    renamed(clip, |i| format!("bone{i:03}"))
}

#[test]
fn cmu_acclaim_onto_skeletons_with_names_that_say_nothing() {
    let Some(source) = cmu_02_01() else { return };
    let named = walk();
    let (_, by_name) = retarget(&source, &named, &Options::default()).unwrap();
    let limbs = [
        "LeftUpLeg",
        "LeftLeg",
        "LeftFoot",
        "RightUpLeg",
        "RightLeg",
        "RightFoot",
        "LeftArm",
        "LeftForeArm",
        "LeftHand",
        "RightArm",
        "RightForeArm",
        "RightHand",
        "Head",
    ];
    let driver = |pairs: &[(usize, usize)], t: usize| {
        pairs.iter().find(|p| p.0 == t).map(|p| source.skeleton().joints()[p.1].name.clone())
    };
    // Anonymous, same tree: the limbs get the drivers names gave them.
    let target = anonymous();
    let (out, pairs) = retarget(&source, &target, &Options::default()).unwrap();
    for limb in limbs {
        let t = named.skeleton().find(limb).unwrap();
        assert_eq!(driver(&pairs, t), driver(&by_name, t), "{limb}");
    }
    let (worst, at) = worst_bone_angle(&source, &out, &pairs);
    assert!(worst < 3.0, "a limb is {worst}° off its source ({at})");
    // No collar bones: the upper arm still takes CMU's humerus, not its clavicle.
    let target = anonymous_without_collars();
    let (out, pairs) = retarget(&source, &target, &Options::default()).unwrap();
    let arm = |side: &str| {
        let before = named.skeleton().find(&format!("{side}Arm")).unwrap();
        // Removing the shoulder before it moves the arm one index down, per side removed.
        before - if side == "Left" { 1 } else { 2 }
    };
    assert_eq!(driver(&pairs, arm("Left")).as_deref(), Some("lhumerus"), "{pairs:?}");
    assert_eq!(driver(&pairs, arm("Right")).as_deref(), Some("rhumerus"), "{pairs:?}");
    let (worst, at) = worst_bone_angle(&source, &out, &pairs);
    assert!(worst < 3.0, "a limb is {worst}° off its source ({at})");
}

/// CMU's subject 2, take 1 (Acclaim), from the corpus.
fn cmu_02_01() -> Option<Clip> {
    let dir = common::corpus_dir()?;
    let asf = std::fs::read(dir.join("asf_amc/cmu/02.asf")).unwrap();
    let amc = std::fs::read(dir.join("asf_amc/cmu/02_01.amc")).unwrap();
    let inputs = [mocap::Input { name: "02.asf", bytes: &asf }, mocap::Input { name: "02_01.amc", bytes: &amc }];
    mocap::load(&inputs).into_iter().find_map(|r| match r.map(|l| l.asset) {
        Ok(mocap::Asset::Clip(c)) => Some(c),
        _ => None,
    })
}

#[test]
fn cmu_acclaim_onto_a_bvh_skeleton_keeps_every_limb_direction() {
    let Some(dir) = common::corpus_dir() else { return };
    let asf = std::fs::read(dir.join("asf_amc/cmu/02.asf")).unwrap();
    let amc = std::fs::read(dir.join("asf_amc/cmu/02_01.amc")).unwrap();
    let inputs = [mocap::Input { name: "02.asf", bytes: &asf }, mocap::Input { name: "02_01.amc", bytes: &amc }];
    let source = mocap::load(&inputs)
        .into_iter()
        .find_map(|r| match r.map(|l| l.asset) {
            Ok(mocap::Asset::Clip(c)) => Some(c),
            _ => None,
        })
        .unwrap();
    let target = walk();
    let (out, pairs) = retarget(&source, &target, &Options::default()).unwrap();
    let names =
        |t: usize, s: usize| (target.skeleton().joints()[t].name.clone(), source.skeleton().joints()[s].name.clone());
    let named: Vec<(String, String)> = pairs.iter().map(|&(t, s)| names(t, s)).collect();
    for (t, s) in [
        ("Hips", "root"),
        ("LeftUpLeg", "lfemur"),
        ("RightLeg", "rtibia"),
        ("LeftArm", "lhumerus"),
        ("RightForeArm", "rradius"),
        ("Head", "head"),
    ] {
        assert!(named.contains(&(t.to_owned(), s.to_owned())), "{t} from {s}: {named:?}");
    }
    let (worst, at) = worst_bone_angle(&source, &out, &pairs);
    assert!(worst < 3.0, "a limb is {worst}° off its source ({at})");
    assert_eq!(out.frame_count(), source.frame_count());
    let _ = Quat::IDENTITY;
}
