//! A glTF take baked a key per frame is read by taking key `f` for frame `f`
//! (`Track::on_grid`, `Track::key`) instead of searching and interpolating:
//! the values are those `Track::sample` gives at the frame's time, and a track
//! whose keys stray from the frames, are too few, or are not `LINEAR`, is
//! sampled as before.

use gltf::animation::Interpolation;
use mocap::formats::gltf::animation::{Path, Track};
use mocap::glam::Quat;
use proptest::prelude::*;

/// A rotation track with a key at every given time, turning about a tilted axis.
fn track(times: Vec<f32>, interpolation: Interpolation, speed: f32) -> Track {
    let axis = mocap::glam::Vec3::new(0.3, 1.0, -0.2).normalize();
    let values = times.iter().flat_map(|&t| Quat::from_axis_angle(axis, t * speed).to_array()).collect();
    Track { node: 0, path: Path::Rotation, interpolation, times, values }
}

fn grid(frames: usize, frame_time: f64) -> Vec<f32> {
    (0..frames).map(|f| (f as f64 * frame_time) as f32).collect()
}

proptest! {
    #[test]
    fn a_key_per_frame_reads_as_sampling_at_the_frames(
        frames in 2usize..6000,
        fps in prop::sample::select(vec![24.0f64, 30.0, 60.0, 120.0, 240.0]),
        speed in -20.0f32..20.0,
    ) {
        let frame_time = 1.0 / fps;
        let t = track(grid(frames, frame_time), Interpolation::Linear, speed);
        prop_assert!(t.on_grid(frame_time, frames));
        let mut cursor = 0;
        for f in (0..frames).step_by(frames / 50 + 1) {
            let (mut keyed, mut sampled) = ([0.0f32; 4], [0.0f32; 4]);
            t.key(f, &mut keyed);
            t.sample((f as f64 * frame_time) as f32, &mut cursor, &mut sampled);
            let angle = Quat::from_array(keyed).angle_between(Quat::from_array(sampled));
            prop_assert!(angle < 1e-3, "frame {f}: {angle} rad apart");
        }
    }

    #[test]
    fn keys_off_the_frames_are_sampled(
        frames in 3usize..500,
        shift in 0.01f64..0.99,
        which in 0usize..1000,
    ) {
        let frame_time = 1.0 / 30.0;
        let mut times = grid(frames, frame_time);
        let k = 1 + which % (frames - 1);
        times[k] += (shift * frame_time * 0.5) as f32;
        prop_assert!(!track(times, Interpolation::Linear, 1.0).on_grid(frame_time, frames));
    }
}

#[test]
fn too_few_keys_step_and_cubic_tracks_are_sampled() {
    let frame_time = 1.0 / 30.0;
    let keys = grid(100, frame_time);
    assert!(track(keys.clone(), Interpolation::Linear, 1.0).on_grid(frame_time, 100));
    assert!(!track(keys.clone(), Interpolation::Linear, 1.0).on_grid(frame_time, 101));
    assert!(!track(keys.clone(), Interpolation::Step, 1.0).on_grid(frame_time, 100));
    assert!(!track(keys, Interpolation::CubicSpline, 1.0).on_grid(frame_time, 100));
}

#[test]
fn a_zero_key_reads_as_no_turn() {
    let t = Track {
        node: 0,
        path: Path::Rotation,
        interpolation: Interpolation::Linear,
        times: vec![0.0, 0.5],
        values: vec![0.0; 8],
    };
    let mut out = [9.0f32; 4];
    t.key(1, &mut out);
    assert_eq!(out, [0.0, 0.0, 0.0, 1.0]);
    out = [9.0; 4];
    t.key(2, &mut out);
    assert_eq!(out, [9.0; 4], "no key 2: left as it was");
    t.key(usize::MAX, &mut out);
    assert_eq!(out, [9.0; 4], "nor a key past any length");
}
