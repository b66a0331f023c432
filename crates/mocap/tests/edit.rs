//! Clip edits on the generated walk: each edit's exact effect, and every result
//! saves as BVH and reads back the same.

use mocap::Clip;
use mocap::glam::Vec3;
use mocap::ops::edit::{Edit, apply, apply_all};

fn walk() -> Clip {
    mocap::formats::bvh::parse(include_bytes!("../../../data/walk.bvh")).unwrap()
}

fn positions(clip: &Clip, frame: usize) -> Vec<Vec3> {
    clip.world_positions(frame)
}

fn same_pose(a: &Clip, fa: usize, b: &Clip, fb: usize, tolerance: f32) -> bool {
    positions(a, fa).iter().zip(positions(b, fb)).all(|(p, q)| p.distance(q) <= tolerance)
}

/// Saving and reading back gives the same clip, value for value.
fn round_trips(clip: &Clip) {
    let again = mocap::formats::bvh::parse(mocap::formats::bvh::write(clip).as_bytes()).unwrap();
    assert_eq!(again.skeleton(), clip.skeleton());
    assert_eq!(again.motion().data(), clip.motion().data());
}

#[test]
fn trim_reverse_and_ping_pong_move_whole_rows() {
    let w = walk();
    let n = w.frame_count();
    let t = apply(&w, &Edit::Trim { first: 10, last: 29 }).unwrap();
    assert_eq!(t.frame_count(), 20);
    assert_eq!(t.motion().row(0), w.motion().row(10));
    assert_eq!(t.motion().row(19), w.motion().row(29));
    assert!(
        apply(&w, &Edit::Trim { first: 5, last: n }).is_err() && apply(&w, &Edit::Trim { first: 9, last: 3 }).is_err()
    );
    let r = apply(&w, &Edit::Reverse).unwrap();
    assert_eq!(r.motion().row(0), w.motion().row(n - 1));
    assert_eq!(apply(&r, &Edit::Reverse).unwrap(), w, "reverse twice is the identity");
    let p = apply(&w, &Edit::PingPong).unwrap();
    assert_eq!(p.frame_count(), 2 * n - 2);
    for k in 1..n - 1 {
        assert_eq!(p.motion().row(n - 1 + k), w.motion().row(n - 1 - k));
    }
    for c in [&t, &r, &p] {
        round_trips(c);
    }
}

#[test]
fn resampling_at_an_integer_factor_keeps_the_original_frames() {
    let w = walk();
    let fps = 1.0 / w.frame_time();
    let double = apply(&w, &Edit::Resample { fps: fps * 2.0 }).unwrap();
    assert_eq!(double.frame_count(), 2 * w.frame_count() - 1);
    for f in 0..w.frame_count() {
        assert!(same_pose(&w, f, &double, 2 * f, 1e-3), "frame {f}");
    }
    // In between: the clip's own interpolation.
    let mid = {
        let mut out = Vec::new();
        w.sample_world_positions_into(
            w.timeline().time_of(10) + w.frame_time() / 2.0,
            mocap::Interpolation::Linear,
            &mut out,
        );
        out
    };
    assert!(positions(&double, 21).iter().zip(&mid).all(|(a, b)| a.distance(*b) < 1e-3));
    let half = apply(&w, &Edit::Resample { fps: fps / 2.0 }).unwrap();
    assert_eq!(half.frame_count(), (w.frame_count() + 1) / 2);
    assert!(same_pose(&w, 20, &half, 10, 1e-3));
    assert!(apply(&w, &Edit::Resample { fps: 0.0 }).is_err() && apply(&w, &Edit::Resample { fps: f64::NAN }).is_err());
    round_trips(&double);
}

#[test]
fn in_place_keeps_height_and_rotations() {
    let w = walk();
    let p = apply(&w, &Edit::InPlace { remove_turning: false }).unwrap();
    let root = 0;
    let start = positions(&w, 0)[root];
    let mut lw = mocap::LocalPose::default();
    let mut lp = mocap::LocalPose::default();
    for f in 0..w.frame_count() {
        let (a, b) = (positions(&w, f)[root], positions(&p, f)[root]);
        assert!(
            (a.y - b.y).abs() < 1e-4 && (b.x - start.x).abs() < 1e-4 && (b.z - start.z).abs() < 1e-4,
            "frame {f}: {a} → {b}"
        );
        w.local_pose_into(f, &mut lw);
        p.local_pose_into(f, &mut lp);
        for (q1, q2) in lw.rotation.iter().zip(&lp.rotation) {
            assert!(q1.dot(*q2).abs() > 0.99999, "frame {f}: rotations unchanged");
        }
    }
    round_trips(&p);
}

#[test]
fn loop_knit_brings_the_end_onto_the_start() {
    let w = walk();
    let n = w.frame_count();
    let k = apply(&w, &Edit::LoopKnit { frames: 8 }).unwrap();
    let gap = |c: &Clip| {
        let mut a = mocap::LocalPose::default();
        let mut b = mocap::LocalPose::default();
        c.local_pose_into(0, &mut a);
        c.local_pose_into(n - 1, &mut b);
        a.rotation.iter().zip(&b.rotation).map(|(x, y)| x.angle_between(*y)).fold(0.0f32, f32::max)
    };
    assert!(gap(&k) <= gap(&w) / 8.0 + 1e-4, "the last frame is close to the first: {} vs {}", gap(&k), gap(&w));
    assert!(same_pose(&w, n - 10, &k, n - 10, 1e-4), "frames before the knit are untouched");
    assert!(apply(&w, &Edit::LoopKnit { frames: n }).is_err());
}

#[test]
fn up_axis_scale_rename_keep_the_figure() {
    let w = walk();
    // Pretend the walk was Z-up: turning it keeps every distance between joints.
    let turned = apply(&w, &Edit::UpAxis { from: 2, negative: false }).unwrap();
    for f in [0, 30] {
        let (a, b) = (positions(&w, f), positions(&turned, f));
        for i in 0..a.len() {
            for j in 0..a.len() {
                assert!((a[i].distance(a[j]) - b[i].distance(b[j])).abs() < 1e-3);
            }
        }
        // What was +Z (up in the file) is +Y now.
        let head = w.skeleton().find("Head").unwrap();
        assert!(((b[head] - b[0]).y - (a[head] - a[0]).z).abs() < 1e-3);
    }
    let scaled = apply(&w, &Edit::Scale { factor: 0.01 }).unwrap();
    assert!(positions(&w, 12).iter().zip(positions(&scaled, 12)).all(|(a, b)| (*a * 0.01).distance(b) < 1e-5));
    let renamed = apply(&w, &Edit::Rename { from: "Head".into(), to: "Kopf".into() }).unwrap();
    assert!(renamed.skeleton().find("Kopf").is_some() && renamed.skeleton().find("Head").is_none());
    assert!(apply(&w, &Edit::Rename { from: "Nope".into(), to: "X".into() }).is_err());
    assert!(apply(&w, &Edit::Rename { from: "Head".into(), to: "two words".into() }).is_err());
    for c in [&turned, &scaled, &renamed] {
        round_trips(c);
    }
}

#[test]
fn removing_a_joint_folds_or_drops_its_motion() {
    let w = walk();
    let name = "LeftForeArm";
    let gone = w.skeleton().find(name).unwrap();
    let folded = apply(&w, &Edit::RemoveJoint { name: name.into(), fold: true }).unwrap();
    assert_eq!(folded.skeleton().len(), w.skeleton().len() - 1);
    assert!(folded.skeleton().find(name).is_none());
    for f in [0, 17, 40] {
        let (a, b) = (positions(&w, f), positions(&folded, f));
        let kept: Vec<Vec3> = a.iter().enumerate().filter(|(i, _)| *i != gone).map(|(_, p)| *p).collect();
        for (j, (p, q)) in kept.iter().zip(&b).enumerate() {
            let joint = &folded.skeleton().joints()[j];
            if !joint.is_end_site() {
                assert!(p.distance(*q) < 1e-3, "frame {f}: {} moved {p} → {q}", joint.name);
            }
        }
    }
    let dropped = apply(&w, &Edit::RemoveJoint { name: name.into(), fold: false }).unwrap();
    let hand = dropped.skeleton().find("LeftHand").unwrap();
    assert!(
        positions(&dropped, 17)[hand].distance(positions(&w, 17)[w.skeleton().find("LeftHand").unwrap()]) > 1e-3,
        "dropping loses the forearm's turn"
    );
    assert!(
        apply(&w, &Edit::RemoveJoint { name: "Hips".into(), fold: true }).is_err(),
        "a root with several children stays"
    );
    round_trips(&folded);
    // Edits chain in order.
    let chained = apply_all(&w, &[Edit::Trim { first: 0, last: 9 }, Edit::Reverse]).unwrap();
    assert_eq!(chained.motion().row(0), w.motion().row(9));
}

#[test]
fn a_keyed_correction_fades_over_its_window() {
    let w = walk();
    let arm = w.skeleton().find("LeftArm").unwrap();
    let mut at = mocap::LocalPose::default();
    w.local_pose_into(20, &mut at);
    let turned = at.rotation[arm] * mocap::glam::Quat::from_rotation_z(0.8);
    let key = |window| {
        apply(
            &w,
            &Edit::Correct { frame: 20, rotations: vec![("LeftArm".into(), turned)], translations: vec![], window },
        )
        .unwrap()
    };
    let k = key(3);
    let rotation = |c: &Clip, f: usize| {
        let mut p = mocap::LocalPose::default();
        c.local_pose_into(f, &mut p);
        p.rotation[arm]
    };
    assert!(rotation(&k, 20).dot(turned).abs() > 0.99999, "the key holds at its frame");
    let change = |f: usize| rotation(&k, f).angle_between(rotation(&w, f));
    assert!(
        change(21) > change(22) && change(22) > change(23) && change(23) > 0.0 && change(24) < 1e-5,
        "it fades: {} {} {} {}",
        change(21),
        change(22),
        change(23),
        change(24)
    );
    assert!((change(19) - change(21)).abs() < 0.05, "both sides alike");
    let sharp = key(0);
    assert!(rotation(&sharp, 21).angle_between(rotation(&w, 21)) < 1e-5, "window 0 keys one frame");
    assert!(apply(&w, &Edit::Correct { frame: 99, rotations: vec![], translations: vec![], window: 1 }).is_err());
    assert!(
        apply(
            &w,
            &Edit::Correct { frame: 1, rotations: vec![("Tail".into(), turned)], translations: vec![], window: 1 }
        )
        .is_err()
    );
    round_trips(&k);
}

#[test]
fn the_creator_builds_a_character_that_saves_and_reads_back() {
    let mut c = mocap::ops::edit::new_character(20, 30.0);
    assert_eq!(c.skeleton().len(), 2);
    assert_eq!(c.frame_count(), 20);
    let steps = [
        Edit::AddJoint { parent: "Hips".into(), name: "Spine".into(), offset: Vec3::new(0.0, 0.3, 0.0) },
        Edit::AddJoint { parent: "Spine".into(), name: "Head".into(), offset: Vec3::new(0.0, 0.4, 0.0) },
        Edit::AddJoint { parent: "Spine".into(), name: "LeftArm".into(), offset: Vec3::new(0.2, 0.3, 0.0) },
        Edit::AddJoint { parent: "LeftArm".into(), name: "LeftHand".into(), offset: Vec3::new(0.5, 0.0, 0.0) },
        Edit::SetOffset { name: "LeftHand".into(), offset: Vec3::new(0.45, 0.0, 0.0) },
        Edit::SetChannels { name: "Spine".into(), position: false, order: "XYZ".into() },
        Edit::Rename { from: "LeftHand".into(), to: "LeftWrist".into() },
    ];
    for e in &steps {
        c = apply(&c, e).unwrap_or_else(|m| panic!("{e:?}: {m}"));
    }
    let names: Vec<&str> = c.skeleton().joints().iter().map(|j| j.name.as_str()).collect();
    assert_eq!(
        names,
        ["Hips", "Spine", "Head", "Head_End", "LeftArm", "LeftWrist", "LeftWrist_End"],
        "depth-first, End Sites only at the leaves"
    );
    let wrist = c.skeleton().find("LeftWrist").unwrap();
    assert!((c.world_positions(0)[wrist] - Vec3::new(0.65, 1.6, 0.0)).length() < 1e-5);
    // Animate it: a key on the arm at frame 10.
    let turned = mocap::glam::Quat::from_rotation_z(-1.2);
    c = apply(
        &c,
        &Edit::Correct { frame: 10, rotations: vec![("LeftArm".into(), turned)], translations: vec![], window: 5 },
    )
    .unwrap();
    assert!(c.world_positions(10)[wrist].y < 1.6 - 0.3, "the arm swings down at the key");
    // Save, read back: the same skeleton and motion.
    round_trips(&c);
    // Bad requests say why.
    for bad in [
        Edit::AddJoint { parent: "Nope".into(), name: "X".into(), offset: Vec3::ONE },
        Edit::AddJoint { parent: "Hips".into(), name: "Spine".into(), offset: Vec3::ONE },
        Edit::AddJoint { parent: "Head_End".into(), name: "X".into(), offset: Vec3::ONE },
        Edit::SetChannels { name: "Spine".into(), position: false, order: "XXZ".into() },
        Edit::SetOffset { name: "Spine".into(), offset: Vec3::NAN },
    ] {
        assert!(apply(&c, &bad).is_err(), "{bad:?}");
    }
    // Removing a joint moves its children to its parent.
    let without = apply(&c, &Edit::RemoveJoint { name: "Spine".into(), fold: false }).unwrap();
    let head = without.skeleton().find("Head").unwrap();
    assert_eq!(without.skeleton().joints()[head].parent, Some(0));
}

#[test]
fn keys_interpolate_from_key_to_key_and_hold_outside() {
    use mocap::glam::Quat;
    let mut c = mocap::ops::edit::new_character(60, 30.0);
    c = apply(&c, &Edit::AddJoint { parent: "Hips".into(), name: "Arm".into(), offset: Vec3::new(0.0, 0.5, 0.0) })
        .unwrap();
    let turn = |deg: f32| vec![("Arm".to_owned(), Quat::from_rotation_z(deg.to_radians()))];
    let a = apply(
        &c,
        &Edit::Key {
            frame: 10,
            rotations: turn(80.0),
            translations: vec![("Hips".into(), Vec3::new(0.0, 1.0, 0.0))],
            keys: vec![],
        },
    )
    .unwrap();
    let arm = a.skeleton().find("Arm").unwrap();
    let angle = |clip: &Clip, f: usize| {
        let mut p = mocap::LocalPose::default();
        clip.local_pose_into(f, &mut p);
        let (axis, angle) = p.rotation[arm].to_axis_angle();
        angle.to_degrees() * axis.z.signum()
    };
    for f in [0, 10, 35, 59] {
        assert!((angle(&a, f) - 80.0).abs() < 1e-3, "one key holds everywhere: frame {f} at {}", angle(&a, f));
    }
    let b = apply(
        &a,
        &Edit::Key {
            frame: 40,
            rotations: turn(-40.0),
            translations: vec![("Hips".into(), Vec3::new(3.0, 1.0, 0.0))],
            keys: vec![10],
        },
    )
    .unwrap();
    for (f, want) in [(0, 80.0), (10, 80.0), (20, 40.0), (25, 20.0), (30, 0.0), (40, -40.0), (59, -40.0)] {
        assert!((angle(&b, f) - want).abs() < 1e-2, "frame {f}: {} not {want}", angle(&b, f));
    }
    let hips_x = |f: usize| positions(&b, f)[0].x;
    assert!(
        (hips_x(25) - hips_x(10) - (hips_x(40) - hips_x(10)) * 0.5).abs() < 1e-4,
        "the root moves linearly between keys"
    );
    round_trips(&b);
    assert!(
        apply(&a, &Edit::Key { frame: 40, rotations: turn(0.0), translations: vec![], keys: vec![99] }).is_err(),
        "a key past the end is refused"
    );
}
