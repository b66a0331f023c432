//! View ▸ Between frames (Nearest, Linear, Cubic): while playing, a time
//! between frames is posed by the core's sampling of that kind, the URL
//! fragment keeps the choice, and Edit ▸ Resample then makes a cubic resample.

use mocap::Interpolation;
use mocap_viewer::{Command, Viewer};

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");

fn posed(between: Interpolation, time: f64) -> Vec<mocap::glam::Quat> {
    let mut v = Viewer::default();
    v.load("walk.bvh", WALK).unwrap();
    let mut settings = v.state().settings.clone();
    assert!(settings.set_between(between.name()));
    v.apply(Command::SetSettings(settings)).unwrap();
    v.apply(Command::SetTime(time)).unwrap();
    v.apply(Command::SetPlaying(true)).unwrap();
    v.pose();
    // The fragment keeps the choice, and a link opened with it restores it.
    let fragment = v.state().view_fragment();
    assert_eq!(fragment.contains("cubic"), between == Interpolation::Cubic);
    let mut opened = Viewer::default();
    opened.load("walk.bvh", WALK).unwrap();
    opened.apply_fragment(&fragment);
    assert_eq!(opened.state().settings.between, between, "{fragment}");
    v.state().stage.actors[0].extra.pose.iter().map(|t| t.rotation).collect()
}

fn sampled(between: Interpolation, time: f64) -> Vec<mocap::glam::Quat> {
    let clip = mocap::formats::bvh::parse(WALK).unwrap();
    let mut expected = Vec::new();
    clip.sample_world_transforms_into(time, between, &mut expected);
    expected.iter().map(|t| t.rotation).collect()
}

fn close(a: &[mocap::glam::Quat], b: &[mocap::glam::Quat]) -> bool {
    a.iter().zip(b).all(|(x, y)| x.dot(*y).abs() > 1.0 - 1e-6)
}

#[test]
fn each_choice_poses_by_its_own_sampling() {
    let time = 10.4 / 30.0;
    let poses = [Interpolation::Nearest, Interpolation::Linear, Interpolation::Cubic].map(|i| (i, posed(i, time)));
    for (i, pose) in &poses {
        assert!(close(pose, &sampled(*i, time)), "the view samples by {i:?}");
    }
    for (k, (i, a)) in poses.iter().enumerate() {
        for (j, b) in &poses[k + 1..] {
            assert!(!close(a, b), "{i:?} and {j:?} differ between frames");
        }
    }
}

#[test]
fn unknown_names_change_nothing() {
    let mut settings = mocap_viewer::ViewSettings::default();
    assert!(!settings.set_between("step"));
    assert!(!settings.set_between("smooth"));
    assert_eq!(settings.between, Interpolation::Linear);
    assert!(settings.set_between("nearest"));
    assert_eq!(settings.between, Interpolation::Nearest);
}
