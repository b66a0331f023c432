//! IK solvers on local poses: reachable targets are reached, unreachable ones give
//! a straight chain toward them, the two-bone solver bends toward its pole, limits
//! hold, degenerate input gives no NaN, and the default chains of real skeletons
//! are their arms and legs.

mod common;

use mocap::glam::Vec3;
use mocap::runtime::ik::{self, Chain, Options};
use mocap::{LocalPose, Skeleton};

/// A chain of `n` joints along +Y, bones of `length`, each with three rotation
/// channels, ending in an End Site; the first frame bends every joint a little.
fn chain_clip(n: usize, length: f32) -> mocap::Clip {
    let mut text = String::from(
        "HIERARCHY\nROOT j0\n{\nOFFSET 0 0 0\nCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n",
    );
    for i in 1..n {
        text.push_str(&format!("JOINT j{i}\n{{\nOFFSET 0 {length} 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n"));
    }
    text.push_str(&format!("End Site\n{{\nOFFSET 0 {length} 0\n}}\n"));
    text.push_str(&"}\n".repeat(n));
    text.push_str("MOTION\nFrames: 1\nFrame Time: 0.1\n0 0 0 0 0 0");
    for i in 1..n {
        text.push_str(&format!(" {} {} 0", 10.0 + i as f32, 5.0));
    }
    text.push('\n');
    mocap::formats::bvh::parse(text.as_bytes()).unwrap()
}

fn pose_of(clip: &mocap::Clip) -> LocalPose {
    let mut pose = LocalPose::default();
    clip.local_pose_into(0, &mut pose);
    pose
}

fn positions(skeleton: &Skeleton, pose: &LocalPose) -> Vec<Vec3> {
    let mut model = Vec::new();
    mocap::local_to_model(skeleton, pose, &mut model);
    model.iter().map(|t| t.translation).collect()
}

fn all_finite(pose: &LocalPose) -> bool {
    pose.rotation.iter().all(|q| q.is_finite() && (q.length() - 1.0).abs() < 1e-3)
}

#[test]
fn every_solver_reaches_a_reachable_target() {
    for (n, bones) in [(3usize, 2usize), (11, 10)] {
        let clip = chain_clip(n, 1.0);
        let skeleton = clip.skeleton();
        // The End Site is the effector: the chain is the bones from j(n-1-bones+1)… to it.
        let effector = skeleton.len() - 1;
        let chain = Chain::up_from(skeleton, effector, bones).unwrap();
        assert_eq!(chain.joints().len(), bones + 1);
        let root = positions(skeleton, &pose_of(&clip))[chain.root()];
        for target in [Vec3::new(0.8, 0.6, 0.3), Vec3::new(-1.2, 0.2, 0.5), Vec3::new(0.1, -0.9, 0.2)] {
            let target = root + target * (bones as f32 * 0.8) / target.length();
            // CCD converges slowly on long chains folding back: give it passes.
            let options = Options { limits: false, iterations: 20_000, ..Options::default() };
            let tolerance = 1e-4 * bones as f32;
            type Solver = fn(&Skeleton, &mut LocalPose, &Chain, Vec3, &Options) -> ik::Solve;
            let mut solvers: Vec<(&str, Solver)> = vec![("ccd", ik::ccd), ("fabrik", ik::fabrik)];
            if bones == 2 {
                solvers.push(("two_bone", |s, p, c, t, o| ik::two_bone(s, p, c, t, t + Vec3::Z, o)));
            }
            for (name, solve) in solvers {
                let mut pose = pose_of(&clip);
                let result = solve(skeleton, &mut pose, &chain, target, &Options { tolerance, ..options });
                let got = positions(skeleton, &pose)[effector];
                assert!(got.distance(target) <= tolerance, "{name}, {bones} bones: {got} vs {target} ({result:?})");
                assert!(result.reached && all_finite(&pose), "{name}: {result:?}");
                // Joints above the chain did not move.
                let before = positions(skeleton, &pose_of(&clip));
                let after = positions(skeleton, &pose);
                for j in 0..=chain.root() {
                    assert!(before[j].distance(after[j]) < 1e-5, "{name}: joint {j} moved");
                }
            }
        }
    }
}

#[test]
fn unreachable_targets_give_a_straight_chain_toward_them() {
    let clip = chain_clip(5, 1.0);
    let skeleton = clip.skeleton();
    let effector = skeleton.len() - 1;
    for bones in [2usize, 4] {
        let chain = Chain::up_from(skeleton, effector, bones).unwrap();
        let root = positions(skeleton, &pose_of(&clip))[chain.root()];
        let target = root + Vec3::new(3.0, -4.0, 12.0);
        let dir = (target - root).normalize();
        let mut solvers: Vec<(&str, Box<dyn Fn(&mut LocalPose) -> ik::Solve>)> = vec![
            ("ccd", Box::new(|p: &mut LocalPose| ik::ccd(skeleton, p, &chain, target, &Options::default()))),
            ("fabrik", Box::new(|p: &mut LocalPose| ik::fabrik(skeleton, p, &chain, target, &Options::default()))),
        ];
        if bones == 2 {
            solvers.push((
                "two_bone",
                Box::new(|p: &mut LocalPose| {
                    ik::two_bone(skeleton, p, &chain, target, Vec3::Z * 5.0, &Options::default())
                }),
            ));
        }
        for (name, solve) in solvers {
            let mut pose = pose_of(&clip);
            let result = solve(&mut pose);
            assert!(!result.reached && all_finite(&pose), "{name}: {result:?}");
            let p = positions(skeleton, &pose);
            for &j in chain.joints() {
                let along = p[j] - root;
                let off_line = (along - dir * along.dot(dir)).length();
                assert!(
                    off_line < 2e-3 && along.dot(dir) >= -1e-4,
                    "{name}: joint {j} is {off_line} off the line to the target"
                );
            }
            let reach = p[effector].distance(root);
            assert!((reach - bones as f32).abs() < 1e-3, "{name}: the chain keeps its length ({reach})");
        }
    }
}

#[test]
fn the_two_bone_solver_bends_toward_the_pole() {
    let clip = chain_clip(3, 1.0);
    let skeleton = clip.skeleton();
    let effector = skeleton.len() - 1;
    let chain = Chain::up_from(skeleton, effector, 2).unwrap();
    let root = positions(skeleton, &pose_of(&clip))[chain.root()];
    let target = root + Vec3::new(0.0, 1.2, 0.0);
    for pole in [Vec3::X, -Vec3::X, Vec3::Z, Vec3::new(-1.0, 0.0, -1.0)] {
        let mut pose = pose_of(&clip);
        let result = ik::two_bone(skeleton, &mut pose, &chain, target, root + pole * 3.0, &Options::default());
        assert!(result.reached, "{result:?}");
        let mid = positions(skeleton, &pose)[chain.joints()[1]];
        let axis = (target - root).normalize();
        let side = (mid - root) - axis * (mid - root).dot(axis);
        assert!(side.normalize().dot(pole.normalize()) > 0.999, "pole {pole}: the middle joint is at {mid}");
    }
}

#[test]
fn degenerate_input_gives_no_nan() {
    let clip = chain_clip(4, 1.0);
    let skeleton = clip.skeleton();
    let effector = skeleton.len() - 1;
    let chain = Chain::up_from(skeleton, effector, 3).unwrap();
    let root = positions(skeleton, &pose_of(&clip))[chain.root()];
    let short = Chain::up_from(skeleton, effector, 2).unwrap();
    let short_root = positions(skeleton, &pose_of(&clip))[short.root()];
    for target in [Vec3::NAN, Vec3::INFINITY, root, Vec3::splat(1e30), short_root] {
        for solver in 0..3 {
            let mut pose = pose_of(&clip);
            let before = pose.clone();
            let result = match solver {
                0 => ik::ccd(skeleton, &mut pose, &chain, target, &Options::default()),
                1 => ik::fabrik(skeleton, &mut pose, &chain, target, &Options::default()),
                _ => ik::two_bone(skeleton, &mut pose, &short, target, Vec3::NAN, &Options::default()),
            };
            assert!(all_finite(&pose), "solver {solver}, target {target}: {result:?}");
            if !target.is_finite() {
                assert_eq!(pose, before, "a non-finite target changes nothing");
            }
        }
    }
    // Zero-length bones.
    let flat = chain_clip(4, 0.0);
    let s = flat.skeleton();
    let c = Chain::up_from(s, s.len() - 1, 3).unwrap();
    for solver in 0..2 {
        let mut pose = pose_of(&flat);
        let _ = if solver == 0 {
            ik::ccd(s, &mut pose, &c, Vec3::ONE, &Options::default())
        } else {
            ik::fabrik(s, &mut pose, &c, Vec3::ONE, &Options::default())
        };
        assert!(all_finite(&pose));
    }
    let c2 = Chain::up_from(s, s.len() - 1, 2).unwrap();
    let mut pose = pose_of(&flat);
    ik::two_bone(s, &mut pose, &c2, Vec3::ONE, Vec3::Z, &Options::default());
    assert!(all_finite(&pose));
    // A NaN in the pose stays out of the chain's other joints.
    let mut pose = pose_of(&clip);
    pose.translation[1] = Vec3::NAN;
    ik::ccd(skeleton, &mut pose, &chain, Vec3::ONE, &Options::default());
    ik::fabrik(skeleton, &mut pose, &chain, Vec3::ONE, &Options::default());
    assert!(all_finite(&pose));
    // Chains must run down the tree.
    assert!(Chain::new(skeleton, effector, 0).is_err());
    assert!(Chain::new(skeleton, 0, 99).is_err());
}

/// A knee with one dof limited to [0, 120] degrees and a hip with all three.
const LEG_ASF: &str = ":version 1.10\n:name leg\n:units\n  mass 1.0\n  length 1.0\n  angle deg\n:root\n  order TX TY TZ RX RY RZ\n  axis XYZ\n  position 0 0 0\n  orientation 0 0 0\n:bonedata\n  begin\n    id 1\n    name thigh\n    direction 0 -1 0\n    length 1\n    axis 0 0 0 XYZ\n    dof rx ry rz\n    limits (-90 45)\n           (-30 30)\n           (-40 40)\n  end\n  begin\n    id 2\n    name shin\n    direction 0 -1 0\n    length 1\n    axis 0 0 0 XYZ\n    dof rx\n    limits (0 120)\n  end\n  begin\n    id 3\n    name foot\n    direction 0 0 1\n    length 0.2\n    axis 0 0 0 XYZ\n  end\n:hierarchy\n  begin\n    root thigh\n    thigh shin\n    shin foot\n  end\n";

#[test]
fn joint_limits_are_never_exceeded() {
    let loaded = mocap::load(&[mocap::Input { name: "leg.asf", bytes: LEG_ASF.as_bytes() }]);
    let clip = loaded.into_iter().next().unwrap().unwrap().into_clip().unwrap();
    let skeleton = clip.skeleton();
    let names: Vec<&str> = skeleton.joints().iter().map(|j| j.name.as_str()).collect();
    let find = |n: &str| names.iter().position(|x| *x == n).unwrap();
    let (thigh, shin, foot) = (find("thigh"), find("shin"), find("foot"));
    let chain = Chain::new(skeleton, thigh, foot).unwrap();
    let rest = LocalPose::rest(skeleton);
    // Targets all around, many out of the limits' reach.
    for k in 0..40 {
        let a = k as f32 * 0.7;
        let target = Vec3::new(a.sin() * 1.2, -0.5 - (a * 1.3).cos(), (a * 0.5).cos() * 1.1);
        for solver in 0..3 {
            let mut pose = rest.clone();
            match solver {
                0 => ik::ccd(skeleton, &mut pose, &chain, target, &Options::default()),
                1 => ik::fabrik(skeleton, &mut pose, &chain, target, &Options::default()),
                _ => ik::two_bone(skeleton, &mut pose, &chain, target, Vec3::new(0.0, -1.0, 1.0), &Options::default()),
            };
            assert!(all_finite(&pose));
            // The knee only bends about its own X, by 0–120°.
            let knee = skeleton.joints()[shin].rest_rotation.inverse() * pose.rotation[shin];
            let (x, y, z) = knee.to_euler(mocap::glam::EulerRot::XYZ);
            let (x, y, z) = (x.to_degrees(), y.to_degrees(), z.to_degrees());
            assert!(
                (-0.01..=120.01).contains(&x) && y.abs() < 0.01 && z.abs() < 0.01,
                "solver {solver}, target {target}: knee {x} {y} {z}"
            );
            // The hip: extrinsic rx ry rz = Rz·Ry·Rx, limits on each.
            let hip = skeleton.joints()[thigh].rest_rotation.inverse() * pose.rotation[thigh];
            let (rz, ry, rx) = hip.to_euler(mocap::glam::EulerRot::ZYX);
            let (rx, ry, rz) = (rx.to_degrees(), ry.to_degrees(), rz.to_degrees());
            assert!(
                (-90.01..=45.01).contains(&rx) && ry.abs() <= 30.01 && rz.abs() <= 40.01,
                "solver {solver}: hip {rx} {ry} {rz}"
            );
        }
    }
    // Without limits the knee bends backward freely when asked.
    let mut pose = rest.clone();
    let target = Vec3::new(0.0, -1.0, -1.0);
    ik::two_bone(
        skeleton,
        &mut pose,
        &chain,
        target,
        Vec3::new(0.0, -1.0, -5.0),
        &Options { limits: false, ..Options::default() },
    );
    assert!(positions(skeleton, &pose)[foot].distance(target) < 1e-3);
}

#[test]
fn default_chains_are_the_arms_and_legs_of_real_skeletons() {
    let Some(dir) = common::corpus_dir() else { return };
    for (file, feet, hands) in [
        ("bvh/assimp_cmu/01_01.bvh", ["LeftFoot", "RightFoot"], ["LeftHand", "RightHand"]),
        ("bvh/animated_drawings/jesse_dance.bvh", ["", ""], ["", ""]),
    ] {
        let clip = mocap::load_one(file, &std::fs::read(dir.join(file)).unwrap()).unwrap().clip().cloned().unwrap();
        let chains = ik::default_chains(clip.skeleton());
        let names: Vec<&str> = chains.iter().map(|(n, _)| n.as_str()).collect();
        assert_eq!(chains.len(), 4, "{file}: {names:?}");
        if !feet[0].is_empty() {
            let mut lower = names[..2].to_vec();
            lower.sort_unstable();
            let mut upper = names[2..].to_vec();
            upper.sort_unstable();
            assert_eq!((lower, upper), (feet.to_vec(), hands.to_vec()), "{file}");
        }
        // Each is a two-bone chain; the feet are the lowest effectors.
        assert!(chains.iter().all(|(_, c)| c.joints().len() == 3));
        let rest = mocap::runtime::fk::rest_positions(clip.skeleton());
        assert!(rest[chains[1].1.effector()].y < rest[chains[2].1.effector()].y, "{file}: {names:?}");
    }
}

/// A figure whose hips drift along X while its left foot stays on the floor for
/// frames 0–14 (skating with it), then lifts for 15–29.
fn skating_clip() -> mocap::Clip {
    let mut text = String::from(
        "HIERARCHY\nROOT Hips\n{\nOFFSET 0 90 0\nCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n",
    );
    for (side, x) in [("Left", 10.0), ("Right", -10.0)] {
        text.push_str(&format!("JOINT {side}UpLeg\n{{\nOFFSET {x} 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nJOINT {side}Leg\n{{\nOFFSET 0 -42 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nJOINT {side}Foot\n{{\nOFFSET 0 -42 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{{\nOFFSET 0 -4 12\n}}\n}}\n}}\n}}\n"));
    }
    text.push_str("JOINT Spine\n{\nOFFSET 0 20 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nJOINT Head\n{\nOFFSET 0 60 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{\nOFFSET 0 20 0\n}\n}\n}\n");
    for (side, x) in [("Left", 25.0), ("Right", -25.0)] {
        text.push_str(&format!("JOINT {side}Arm\n{{\nOFFSET {x} 70 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nJOINT {side}ForeArm\n{{\nOFFSET 0 -28 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nJOINT {side}Hand\n{{\nOFFSET 0 -25 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{{\nOFFSET 0 -8 0\n}}\n}}\n}}\n}}\n"));
    }
    text.push_str("}\nMOTION\nFrames: 30\nFrame Time: 0.0333333\n");
    for f in 0..30 {
        let x = f as f32 * 0.5;
        // The left knee bends slightly throughout; from frame 15 the left hip lifts the leg.
        let lift = if f >= 15 { -40.0 } else { 0.0 };
        let left = format!("0 {lift} 0 0 10 0 0 0 0");
        let right = "0 -20 0 0 30 0 0 0 0";
        let rest = "0 0 0 ".repeat(8);
        text.push_str(&format!("{x} 0 0 0 0 0 {left} {right} {rest}\n"));
    }
    mocap::formats::bvh::parse(text.as_bytes()).unwrap()
}

#[test]
fn foot_locking_pins_a_skating_foot_and_lets_it_go() {
    use mocap::ops::contact::FootLock;
    let clip = skating_clip();
    let lock = FootLock::new(&clip);
    assert_eq!(lock.legs.len(), 2, "two legs found");
    let skeleton = clip.skeleton();
    let left =
        lock.legs.iter().find(|l| skeleton.joints()[l.chain.effector()].name == "LeftFoot").expect("the left leg");
    assert!(left.contact[..14].iter().all(|c| *c), "stance frames are contacts: {:?}", left.contact);
    assert!(left.contact[16..].iter().all(|c| !*c), "the lifted foot is not: {:?}", left.contact);
    let foot = left.chain.effector();
    let mut pinned = Vec::new();
    for f in 0..14 {
        let mut local = LocalPose::default();
        clip.local_pose_into(f, &mut local);
        lock.apply(&clip, &mut local, clip.timeline().time_of(f));
        pinned.push(positions(skeleton, &local)[foot]);
        assert!(all_finite(&local));
    }
    let unlocked: Vec<Vec3> = (0..14).map(|f| clip.world_positions(f)[foot]).collect();
    assert!(unlocked[0].distance(unlocked[13]) > 5.0, "without locking the foot skates");
    for p in &pinned {
        assert!(p.distance(pinned[0]) < 1e-2, "locked, the foot stays put: {p} vs {}", pinned[0]);
    }
    // Well after the run the left foot's lock is off: its leg is the clip's own
    // (the right foot skates on the floor the whole time, so it stays locked).
    let mut local = LocalPose::default();
    clip.local_pose_into(25, &mut local);
    let before = local.clone();
    lock.apply(&clip, &mut local, clip.timeline().time_of(25));
    for &j in left.chain.joints() {
        assert_eq!(local.rotation[j], before.rotation[j]);
    }
}

#[test]
fn the_generated_walk_has_alternating_foot_contacts() {
    let walk = mocap::formats::bvh::parse(include_bytes!("../../../data/walk.bvh")).unwrap();
    let lock = mocap::ops::contact::FootLock::new(&walk);
    assert_eq!(lock.legs.len(), 2);
    for leg in &lock.legs {
        let n = leg.contact.iter().filter(|c| **c).count();
        assert!(n > 5 && n < leg.contact.len() - 5, "{} of {} frames in contact", n, leg.contact.len());
    }
}
