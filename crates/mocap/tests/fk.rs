//! Forward kinematics and sampling semantics.

use mocap::Timeline;
use mocap::formats::bvh::parse;
use mocap::glam::{EulerRot, Mat3, Quat, Vec3};
use mocap::{Channel, Interpolation};

fn approx(a: Vec3, b: Vec3) -> bool {
    (a - b).abs().max_element() < 1e-4
}

/// Root with `channels`, one child at (0,1,0) with its own 3 rotations, and an End
/// Site at (1,0,0) under the child.
fn chain(channels: &str, row: &str) -> mocap::Clip {
    let src = format!(
        "HIERARCHY\nROOT R\n{{\nOFFSET 0 0 0\n{channels}\nJOINT C\n{{\nOFFSET 0 1 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{{\nOFFSET 1 0 0\n}}\n}}\n}}\nMOTION\nFrames: 1\nFrame Time: 0.1\n{row}\n"
    );
    parse(src.as_bytes()).unwrap()
}

fn axis_matrix(c: Channel, deg: f32) -> Mat3 {
    let r = deg.to_radians();
    match c.axis() {
        0 => Mat3::from_rotation_x(r),
        1 => Mat3::from_rotation_y(r),
        _ => Mat3::from_rotation_z(r),
    }
}

#[test]
fn every_rotation_order_is_intrinsic_file_order() {
    use Channel::*;
    let orders = [
        [Xrotation, Yrotation, Zrotation],
        [Xrotation, Zrotation, Yrotation],
        [Yrotation, Xrotation, Zrotation],
        [Yrotation, Zrotation, Xrotation],
        [Zrotation, Xrotation, Yrotation],
        [Zrotation, Yrotation, Xrotation],
    ];
    let angles = [30.0f32, -50.0, 75.0];
    for order in orders {
        let names: Vec<&str> = order.iter().map(|c| c.name()).collect();
        let clip = chain(&format!("CHANNELS 3 {}", names.join(" ")), "30 -50 75 0 0 0");
        // Reference: matrices multiplied in file order, applied to the child offset.
        let m = axis_matrix(order[0], angles[0]) * axis_matrix(order[1], angles[1]) * axis_matrix(order[2], angles[2]);
        let expected_child = m * Vec3::new(0.0, 1.0, 0.0);
        let expected_end = expected_child + m * Vec3::new(1.0, 0.0, 0.0);
        let p = clip.world_positions(0);
        assert!(approx(p[1], expected_child), "{names:?}: {} vs {expected_child}", p[1]);
        assert!(approx(p[2], expected_end), "{names:?}: {} vs {expected_end}", p[2]);
    }
}

#[test]
fn known_rotations_by_hand() {
    // Zrotation 90 turns the child's +Y offset to -X.
    let clip = chain("CHANNELS 3 Zrotation Xrotation Yrotation", "90 0 0 0 0 0");
    assert!(approx(clip.world_positions(0)[1], Vec3::new(-1.0, 0.0, 0.0)));
    // Z then X (intrinsic): Rz(90)·Rx(90)·(0,1,0) = (0,0,1); X then Z would give (-1,0,0).
    let clip = chain("CHANNELS 3 Zrotation Xrotation Yrotation", "90 90 0 0 0 0");
    assert!(approx(clip.world_positions(0)[1], Vec3::new(0.0, 0.0, 1.0)), "{}", clip.world_positions(0)[1]);
    let q = clip.skeleton().joints().len();
    assert_eq!(q, 3);
    let glam_ref = Quat::from_euler(EulerRot::ZXY, 90f32.to_radians(), 90f32.to_radians(), 0.0);
    assert!(approx(glam_ref * Vec3::Y, Vec3::Z));
}

#[test]
fn position_channels_replace_offset_components_on_any_joint() {
    let src = "HIERARCHY\nROOT R\n{\nOFFSET 10 20 30\nCHANNELS 3 Xposition Yposition Zposition\nJOINT C\n{\nOFFSET 5 5 5\nCHANNELS 4 Yposition Xrotation Yrotation Zrotation\nEnd Site\n{\nOFFSET 0 0 1\n}\n}\n}\nMOTION\nFrames: 1\nFrame Time: 0.1\n1 2 3 -7 0 0 0\n";
    let clip = parse(src.as_bytes()).unwrap();
    let p = clip.world_positions(0);
    assert_eq!(p[0], Vec3::new(1.0, 2.0, 3.0));
    assert_eq!(p[1], Vec3::new(6.0, -5.0, 8.0));
    assert_eq!(p[2], Vec3::new(6.0, -5.0, 9.0));
}

#[test]
fn frame_time_conversions_are_exact_at_the_last_frame() {
    for (n, dt) in [(2752usize, 0.0083333f64), (339, 0.0333333), (100, 0.013889), (7, 1.0 / 3.0)] {
        let last = n - 1;
        let t = Timeline::new(dt, n);
        assert_eq!(t.frame_at(t.time_of(last)), last);
        let p = t.position(t.time_of(last));
        assert_eq!((p.frame0, p.frame1, p.alpha), (last, last, 0.0));
        for f in [0, 1, n / 2, last] {
            assert_eq!(t.frame_at(t.time_of(f)), f, "n={n} f={f}");
        }
        assert_eq!(t.frame_at(1e9), last);
        assert_eq!(t.frame_at(-5.0), 0);
        assert_eq!(t.frame_at(f64::NAN), 0);
    }
}

#[test]
fn interpolated_sampling_blends_rotations_and_translations() {
    let src = "HIERARCHY\nROOT R\n{\nOFFSET 0 0 0\nCHANNELS 4 Xposition Yposition Zposition Zrotation\nEnd Site\n{\nOFFSET 0 1 0\n}\n}\nMOTION\nFrames: 2\nFrame Time: 1\n0 0 0 0\n2 4 6 90\n";
    let clip = parse(src.as_bytes()).unwrap();
    let mut out = Vec::new();
    clip.sample_world_transforms_into(0.5, Interpolation::Linear, &mut out);
    assert!(approx(out[0].translation, Vec3::new(1.0, 2.0, 3.0)));
    let s = 45f32.to_radians();
    assert!(approx(out[1].translation, Vec3::new(1.0 - s.sin(), 2.0 + s.cos(), 3.0)), "{}", out[1].translation);
    clip.sample_world_transforms_into(0.4, Interpolation::Nearest, &mut out);
    assert_eq!(out[0].translation, Vec3::ZERO);
    clip.sample_world_transforms_into(0.6, Interpolation::Nearest, &mut out);
    assert_eq!(out[0].translation, Vec3::new(2.0, 4.0, 6.0));
    // On an exact frame, sampling equals the frame's FK.
    clip.sample_world_transforms_into(1.0, Interpolation::Linear, &mut out);
    assert_eq!(out.iter().map(|t| t.translation).collect::<Vec<_>>(), clip.world_positions(1));
}

#[test]
fn slerp_takes_the_short_way() {
    // 170° and -170° about Z are 20° apart; the midpoint is 180°, not 0°.
    let src = "HIERARCHY\nROOT R\n{\nOFFSET 0 0 0\nCHANNELS 1 Zrotation\nEnd Site\n{\nOFFSET 0 1 0\n}\n}\nMOTION\nFrames: 2\nFrame Time: 1\n170\n-170\n";
    let clip = parse(src.as_bytes()).unwrap();
    let mut out = Vec::new();
    clip.sample_world_transforms_into(0.5, Interpolation::Linear, &mut out);
    assert!(approx(out[1].translation, Vec3::new(0.0, -1.0, 0.0)), "{}", out[1].translation);
}

#[test]
fn buffer_api_reuses_capacity() {
    let clip = chain("CHANNELS 3 Zrotation Xrotation Yrotation", "1 2 3 4 5 6");
    let mut out = Vec::with_capacity(3);
    let ptr = out.as_ptr();
    for _ in 0..10 {
        clip.world_positions_into(0, &mut out);
    }
    assert_eq!(out.as_ptr(), ptr);
    assert_eq!(out, clip.world_positions(0));
}

#[test]
fn bounds_cover_all_frames() {
    let src = "HIERARCHY\nROOT R\n{\nOFFSET 0 0 0\nCHANNELS 3 Xposition Yposition Zposition\n}\nMOTION\nFrames: 3\nFrame Time: 1\n0 0 0\n5 -1 2\n-3 4 0\n";
    let b = parse(src.as_bytes()).unwrap().bounds();
    assert_eq!((b.min, b.max), (Vec3::new(-3.0, -1.0, 0.0), Vec3::new(5.0, 4.0, 2.0)));
}
