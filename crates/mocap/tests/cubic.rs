//! Cubic interpolation: through every frame, C¹ across frames (checked
//! numerically), unit quaternions, and resampling 30 → 120 → 30 fps gives the
//! original frames back.

use mocap::glam::{Quat, Vec3};
use mocap::ops::edit::{Edit, apply};
use mocap::runtime::sample::{Interpolation, SampleScratch, sample};
use mocap::{Clip, LocalPose};

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");

fn walk() -> Clip {
    mocap::formats::bvh::parse(WALK).unwrap()
}

fn at(clip: &Clip, time: f64) -> LocalPose {
    let mut scratch = SampleScratch::default();
    let mut out = LocalPose::default();
    sample(clip.skeleton(), clip.motion(), time, Interpolation::Cubic, &mut scratch, &mut out);
    out
}

#[test]
fn it_passes_through_every_frame() {
    let clip = walk();
    let mut frame = LocalPose::default();
    for f in 0..clip.frame_count() {
        clip.local_pose_into(f, &mut frame);
        let cubic = at(&clip, f as f64 * clip.frame_time());
        // At the frame's time (to the float rounding of f x frame time).
        for j in 0..frame.rotation.len() {
            assert!(cubic.rotation[j].dot(frame.rotation[j]).abs() > 1.0 - 1e-6, "frame {f} joint {j}");
            assert!(cubic.translation[j].distance(frame.translation[j]) < 1e-4, "frame {f} joint {j}");
        }
    }
}

/// Angular velocity (rad/s) from `a` to `b` over `dt`.
fn spin(a: Quat, b: Quat, dt: f64) -> Vec3 {
    let d = b * a.conjugate();
    let d = if d.w < 0.0 { -d } else { d };
    let v = Vec3::new(d.x, d.y, d.z);
    let s = v.length();
    if s < 1e-9 { v * (2.0 / dt as f32) } else { v * (2.0 * s.atan2(d.w) / s / dt as f32) }
}

#[test]
fn it_is_smooth_across_frames_and_keeps_unit_quaternions() {
    let clip = walk();
    let dt = clip.frame_time();
    let h = dt * 0.02;
    let (mut worst_t, mut worst_r) = (0.0f32, 0.0f32);
    for f in 2..clip.frame_count() - 2 {
        let t = f as f64 * dt;
        let (before, now, after) = (at(&clip, t - h), at(&clip, t), at(&clip, t + h));
        for j in 0..now.rotation.len() {
            assert!((now.rotation[j].length() - 1.0).abs() < 1e-5 && (before.rotation[j].length() - 1.0).abs() < 1e-5);
            // Left and right derivatives agree at the frame (C¹): their gap is
            // small next to the change either side.
            let (vl, vr) = ((now.translation[j] - before.translation[j]) / h as f32, (after.translation[j] - now.translation[j]) / h as f32);
            let scale = vl.length().max(vr.length()).max(1.0);
            worst_t = worst_t.max((vl - vr).length() / scale);
            let (wl, wr) = (spin(before.rotation[j], now.rotation[j], h), spin(now.rotation[j], after.rotation[j], h));
            let scale = wl.length().max(wr.length()).max(0.5);
            worst_r = worst_r.max((wl - wr).length() / scale);
        }
    }
    // A corner (C⁰ only: linear) shows as a gap of the order of the change itself.
    assert!(worst_t < 0.1, "translations: the derivatives jump by {worst_t}");
    assert!(worst_r < 0.1, "rotations: the angular velocities jump by {worst_r}");
}

#[test]
fn linear_sampling_has_corners_that_cubic_does_not() {
    // The same measure on linear sampling finds the corners (the test can fail).
    let clip = walk();
    let dt = clip.frame_time();
    let h = dt * 0.02;
    let lin = |t: f64| {
        let mut out = LocalPose::default();
        sample(clip.skeleton(), clip.motion(), t, Interpolation::Linear, &mut SampleScratch::default(), &mut out);
        out
    };
    let mut worst = 0.0f32;
    for f in 2..clip.frame_count() - 2 {
        let t = f as f64 * dt;
        let (b, n, a) = (lin(t - h), lin(t), lin(t + h));
        for j in 0..n.rotation.len() {
            let (wl, wr) = (spin(b.rotation[j], n.rotation[j], h), spin(n.rotation[j], a.rotation[j], h));
            worst = worst.max((wl - wr).length() / wl.length().max(wr.length()).max(0.5));
        }
    }
    assert!(worst > 0.3, "linear sampling should show corners ({worst})");
}

#[test]
fn upsampling_then_back_gives_the_frames_again() {
    let clip = walk();
    let fps = 1.0 / clip.frame_time();
    let up = apply(&clip, &Edit::ResampleCubic { fps: fps * 4.0 }).unwrap();
    assert!(up.frame_count() >= clip.frame_count() * 4 - 4);
    let down = apply(&up, &Edit::ResampleCubic { fps }).unwrap();
    assert_eq!(down.frame_count(), clip.frame_count());
    let (a, b) = (clip.motion().data(), down.motion().data());
    let worst = a.iter().zip(b).map(|(x, y)| (x - y).abs()).fold(0.0f32, f32::max);
    assert!(worst < 2e-3, "values differ by up to {worst}");
    let spec: mocap::ops::edit::EditSpec = "fps:120:cubic".parse().unwrap();
    assert_eq!(spec.to_string(), "fps:120:cubic");
}
