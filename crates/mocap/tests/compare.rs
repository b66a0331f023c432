//! Comparing two takes: zero against itself, the error a geometric reference
//! gives for one joint turned by a known angle (and zero for joints it cannot
//! move), Procrustes alignment blind to a rigid move, and the speed of a long take.

use mocap::glam::{Quat, Vec3};
use mocap::ops::compare::{Align, compare};
use mocap::{Clip, Joint, Motion, Skeleton};

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");

fn walk() -> Clip {
    mocap::formats::bvh::parse(WALK).unwrap()
}

#[test]
fn a_clip_against_itself_is_zero() {
    let a = walk();
    let r = compare(&a, &a, Align::None, &[]).unwrap();
    assert_eq!(r.mpjpe, 0.0);
    assert!(r.joints.iter().all(|j| j.max == 0.0 && j.angle == Some(0.0)));
    assert_eq!(r.frames.len(), a.frame_count());
    assert_eq!(r.joints.len(), a.skeleton().joint_count(), "End Sites left out");
}

#[test]
fn one_joint_turned_by_a_known_angle() {
    let a = walk();
    let s = a.skeleton();
    let arm = s.find("LeftArm").unwrap();
    // The arm's first rotation channel (Z in BVH's Z X Y order) plus 20 degrees:
    // a turn about the parent's Z axis through the arm's joint, every frame.
    let column = s.joints()[arm].columns().start + s.joints()[arm].channels.iter().position(|c| c.to_string() == "Zrotation").unwrap();
    assert_eq!(s.joints()[arm].channels.iter().position(|c| c.to_string() == "Zrotation"), Some(s.joints()[arm].channels.iter().position(|c| c.to_string().ends_with("rotation")).unwrap()));
    let theta = 20f32;
    let c = s.channel_count();
    let mut data = a.motion().data().to_vec();
    for row in data.chunks_mut(c) {
        row[column] += theta;
    }
    let b = Clip::new(s.clone(), Motion::new(a.frame_time(), c, a.frame_count(), data).unwrap()).unwrap();
    let r = compare(&a, &b, Align::None, &[]).unwrap();
    // The reference: a point p turned by theta about axis n through centre o moves
    // 2 sin(theta/2) times its distance from the axis.
    let parent = s.joints()[arm].parent.unwrap();
    let subtree: Vec<usize> = (0..s.len()).filter(|&j| {
        let mut k = Some(j);
        while let Some(x) = k {
            if x == arm {
                return true;
            }
            k = s.joints()[x].parent;
        }
        false
    }).collect();
    let mut expected = vec![0.0f64; s.len()];
    let mut world = Vec::new();
    for f in 0..a.frame_count() {
        a.world_transforms_into(f, &mut world);
        let o = world[arm].translation;
        let n = (world[parent].rotation * Quat::IDENTITY) * Vec3::Z;
        for &j in &subtree {
            let v = world[j].translation - o;
            let radius = (v - n * v.dot(n)).length();
            expected[j] += f64::from(2.0 * (theta.to_radians() / 2.0).sin() * radius);
        }
    }
    for e in &mut expected {
        *e /= a.frame_count() as f64;
    }
    for je in &r.joints {
        let j = s.find(&je.name).unwrap();
        if subtree.contains(&j) && expected[j] > 1e-3 {
            let rel = (f64::from(je.mean) - expected[j]).abs() / expected[j];
            assert!(rel < 0.01, "{}: {} against the reference {}", je.name, je.mean, expected[j]);
        } else if !subtree.contains(&j) {
            assert!(je.max < 1e-4, "{} cannot move: {}", je.name, je.max);
        }
    }
    let turned = r.joints.iter().find(|j| j.name == "LeftForeArm").unwrap();
    assert!((turned.angle.unwrap() - 0.0).abs() < 1e-3, "the forearm's own rotation is unchanged");
    let arm_angle = r.joints.iter().find(|j| j.name == "LeftArm").unwrap().angle.unwrap();
    assert!((arm_angle - theta).abs() < 0.05, "the arm turned by {arm_angle} degrees");
    assert!(r.mpjpe > 0.0 && (r.mpjpe_m - r.mpjpe * 0.01).abs() < 1e-6, "cm to metres");
}

/// `a` moved rigidly: a new root above it, turned 40 degrees about Y and shifted.
fn moved(a: &Clip) -> Clip {
    let mut joints = vec![Joint::new("World", None, Vec3::new(120.0, 0.0, -75.0), Vec::new())
        .with_rest_rotation(Quat::from_rotation_y(40f32.to_radians()))];
    joints.extend(a.skeleton().joints().iter().map(|j| {
        let mut j = j.clone();
        j.parent = Some(j.parent.map_or(0, |p| p + 1));
        j
    }));
    let skeleton = Skeleton::new(joints, a.skeleton().euler()).unwrap();
    Clip::new(skeleton, a.motion().clone()).unwrap()
}

#[test]
fn procrustes_is_blind_to_a_rigid_move() {
    let a = walk();
    let b = moved(&a);
    let far = compare(&a, &b, Align::None, &[]).unwrap();
    assert!(far.mpjpe > 50.0, "{}", far.mpjpe);
    let fitted = compare(&a, &b, Align::Procrustes, &[]).unwrap();
    assert!(fitted.mpjpe < 1e-3, "{}", fitted.mpjpe);
    let root = compare(&a, &b, Align::Root, &[]).unwrap();
    assert!(root.mpjpe < 1e-3, "{}", root.mpjpe);
    // Once for the whole take: a rigid move is undone just as well.
    let once = compare(&a, &b, Align::ProcrustesOnce, &[]).unwrap();
    assert!(once.mpjpe < 1e-3, "{}", once.mpjpe);
    let root_once = compare(&a, &b, Align::RootOnce, &[]).unwrap();
    assert!(root_once.mpjpe < 1e-3, "{}", root_once.mpjpe);
}

#[test]
fn once_keeps_what_per_frame_alignment_removes() {
    // A copy whose root drifts sideways frame by frame: per-frame Procrustes
    // removes the drift, a single fit for the whole take cannot.
    let a = walk();
    let s = a.skeleton();
    let c = s.channel_count();
    let mut data = a.motion().data().to_vec();
    for (f, row) in data.chunks_mut(c).enumerate() {
        row[0] += f as f32 * 0.3;
    }
    let b = Clip::new(s.clone(), Motion::new(a.frame_time(), c, a.frame_count(), data).unwrap()).unwrap();
    let each = compare(&a, &b, Align::Procrustes, &[]).unwrap();
    let once = compare(&a, &b, Align::ProcrustesOnce, &[]).unwrap();
    assert_eq!(a.units(), b.units());
    // (A turn of the whole path absorbs much of a steady drift; not all of it.)
    assert!(each.mpjpe < 1e-3 && once.mpjpe > 0.5, "per frame {} once {}", each.mpjpe, once.mpjpe);
    assert_eq!(Align::from_name("procrustes-once"), Some(Align::ProcrustesOnce));
    assert_eq!(Align::from_name("root-once"), Some(Align::RootOnce));
}

#[test]
fn two_long_takes_compare_quickly() {
    // 36,000 frames: the walk's rows repeated.
    let a = walk();
    let c = a.skeleton().channel_count();
    let rows = a.motion().data();
    let data: Vec<f32> = (0..36_000).flat_map(|k| rows[(k % a.frame_count()) * c..][..c].to_vec()).collect();
    let long = Clip::new(a.skeleton().clone(), Motion::new(a.frame_time(), c, 36_000, data).unwrap()).unwrap();
    let t0 = std::time::Instant::now();
    let r = compare(&long, &long, Align::Procrustes, &[]).unwrap();
    eprintln!("two 36,000-frame takes compared in {:?} (debug build)", t0.elapsed());
    assert_eq!(r.frames.len(), 36_000);
}
