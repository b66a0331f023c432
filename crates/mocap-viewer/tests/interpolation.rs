//! View ▸ Cubic in-betweens: while playing, a time between frames is posed by
//! the core's cubic sampling (not the linear blend), the URL fragment keeps it,
//! and Edit ▸ Resample then makes a cubic resample.

use mocap::Interpolation;
use mocap_viewer::{Command, Viewer};

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");

fn posed(cubic: bool, time: f64) -> Vec<mocap::glam::Quat> {
    let mut v = Viewer::default();
    v.load("walk.bvh", WALK).unwrap();
    let mut settings = v.state().settings.clone();
    settings.cubic = cubic;
    v.apply(Command::SetSettings(settings)).unwrap();
    v.apply(Command::SetTime(time)).unwrap();
    v.apply(Command::SetPlaying(true)).unwrap();
    v.pose();
    assert!(v.state().view_fragment().contains("cubic") == cubic);
    v.state().stage.actors[0].extra.pose.iter().map(|t| t.rotation).collect()
}

#[test]
fn cubic_in_betweens_pose_by_the_cubic_sampling() {
    let time = 10.4 / 30.0;
    let (linear, cubic) = (posed(false, time), posed(true, time));
    let clip = mocap::formats::bvh::parse(WALK).unwrap();
    let mut expected = Vec::new();
    clip.sample_world_transforms_into(time, Interpolation::Cubic, &mut expected);
    let expected: Vec<mocap::glam::Quat> = expected.iter().map(|t| t.rotation).collect();
    let close = |a: &[mocap::glam::Quat], b: &[mocap::glam::Quat]| a.iter().zip(b).all(|(x, y)| x.dot(*y).abs() > 1.0 - 1e-6);
    assert!(close(&cubic, &expected), "the view samples cubically");
    assert!(!close(&cubic, &linear), "and that differs from the linear blend");
}
