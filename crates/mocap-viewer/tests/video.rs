//! Video frames (no GPU): the picture of a time is the view's picture at that
//! time, without selection overlays, and making it leaves the view as it was.

use mocap_viewer::{Command, Viewer};

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");

fn paused_at(frame: usize) -> Viewer {
    let mut v = Viewer::default();
    v.load("walk.bvh", WALK).unwrap();
    v.apply(Command::SetPlaying(false)).unwrap();
    v.apply(Command::Seek(frame)).unwrap();
    v.pose();
    v
}

fn capsule_ends(scene: &mocap_render::Scene) -> Vec<[f32; 3]> {
    scene.capsules.iter().map(|c| c.a.to_array()).collect()
}

fn close(a: &[[f32; 3]], b: &[[f32; 3]]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(p, q)| p.iter().zip(q).all(|(x, y)| (x - y).abs() < 1e-4))
}

#[test]
fn a_video_frame_is_the_view_at_that_time() {
    let mut at_30 = paused_at(30);
    let view_30 = capsule_ends(at_30.scene());
    let mut v = paused_at(5);
    let view_5 = capsule_ends(v.scene());
    let (scene, camera) = v.video_frame(1.0, 16.0 / 9.0, false);
    assert!(!scene.capsules.is_empty() && scene.grid.is_some(), "figure and floor");
    assert!(close(&capsule_ends(&scene), &view_30), "time 1.0 s is frame 30 at 30 fps (0.033333 s a frame)");
    assert!(!close(&capsule_ends(&scene), &view_5));
    // The view is untouched: its playhead, pose and camera.
    assert_eq!(v.state().frame(), 5);
    assert_eq!(capsule_ends(v.scene()), view_5);
    let (_, again) = at_30.video_frame(1.0, 16.0 / 9.0, false);
    assert_eq!(format!("{camera:?}"), format!("{again:?}"), "the view's camera at the export's aspect");
}

#[test]
fn follow_moves_the_camera_with_the_root_only_in_the_video() {
    let mut v = paused_at(0);
    let target = v.state().camera.target;
    let (_, still) = v.video_frame(2.0, 1.0, false);
    let (_, followed) = v.video_frame(2.0, 1.0, true);
    assert_ne!(format!("{still:?}"), format!("{followed:?}"), "the camera follows the walking root");
    assert_eq!(v.state().camera.target, target, "the view's camera stays");
    assert!(!v.state().settings.follow_root);
}

#[test]
fn the_defaults_are_the_clip_and_its_loop_range() {
    let mut v = paused_at(0);
    let d = v.video_defaults();
    assert!((d.fps - 30.0).abs() < 1e-3, "{d:?}");
    assert!((d.duration - 2.2).abs() < 1e-3, "{d:?}");
    assert_eq!(d.range, None);
    v.apply(Command::SetRange(Some((3, 9)))).unwrap();
    let d = v.video_defaults();
    let (a, b) = d.range.unwrap();
    assert!((a - 0.1).abs() < 1e-4 && (b - 0.3).abs() < 1e-4, "{d:?}");
}
