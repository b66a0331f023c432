//! Viewer behaviour without a GPU: loading, errors, playback, selection, primitives.

use mocap_viewer::Command;
use mocap_viewer::{Viewer, pose_scene};

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");

fn loaded() -> Viewer {
    let mut v = Viewer::default();
    v.load("walk.bvh", WALK).expect("walk.bvh loads");
    v
}

#[test]
fn default_clip_loads_and_plays_from_frame_zero() {
    let v = loaded();
    let s = v.snapshot();
    assert_eq!(s.clips.len(), 1);
    assert_eq!(s.clips[0].name, "walk.bvh");
    assert_eq!(s.clips[0].frames, 67);
    assert_eq!(s.clips[0].joints, 21);
    assert_eq!(s.frame, 0);
    assert!(s.playing);
    assert_eq!(s.error, None);
}

#[test]
fn bad_file_keeps_the_open_clip_and_reports_position() {
    let mut v = loaded();
    let err = v.load("bad.bvh", b"HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0\n").unwrap_err();
    assert!(err.starts_with("bad.bvh:"), "{err}");
    let s = v.snapshot();
    assert_eq!(s.clips[0].name, "walk.bvh");
    assert_eq!(s.error.as_deref(), Some(err.as_str()));
}

#[test]
fn new_clip_starts_at_zero_and_keeps_play_state() {
    let mut v = loaded();
    v.apply(Command::SetPlaying(false)).unwrap();
    v.apply(Command::Seek(30)).unwrap();
    assert_eq!(v.state().frame(), 30);
    v.load("again.bvh", WALK).unwrap();
    assert_eq!(v.state().frame(), 0);
    assert!(!v.snapshot().playing);
}

#[test]
fn seek_is_clamped_and_frame_exact() {
    let mut v = loaded();
    v.apply(Command::SetPlaying(false)).unwrap();
    v.apply(Command::Seek(1000)).unwrap();
    assert_eq!(v.state().frame(), 66);
    v.apply(Command::Seek(7)).unwrap();
    assert_eq!(v.state().frame(), 7);
}

#[test]
fn selection_by_index_is_validated() {
    let mut v = loaded();
    v.apply(Command::Select { character: v.state().current(), joint: Some(3) }).unwrap();
    assert_eq!(v.snapshot().selected_joint.as_deref(), Some("Neck"));
    v.apply(Command::Select { character: v.state().current(), joint: Some(10_000) }).unwrap();
    assert_eq!(v.snapshot().selected_joint, None);
}

#[test]
fn pose_becomes_bones_joints_and_a_floor_in_metres() {
    let mut v = loaded();
    v.apply(Command::SetPlaying(false)).unwrap();
    v.apply(Command::Select { character: v.state().current(), joint: Some(0) }).unwrap();
    v.pose();
    let doc = v.state().current_character().unwrap();
    let joints = doc.clip().unwrap().skeleton().joints().len();
    let scene = v.scene();
    // Capsules (the default): one per bone, a ball at the root, and the
    // selected joint's highlight ball.
    assert_eq!(scene.capsules.len(), joints - 1 + 1 + 1, "one capsule per non-root joint");
    assert!(scene.lines.is_empty() && scene.spheres.is_empty());
    assert!(scene.shadows);
    let grid = scene.grid.unwrap();
    assert!((grid.cell - 0.5).abs() < 1e-6, "0.5 m cells: {}", grid.cell);
    // Y up: the head is above the hips; the centimetre clip is about 1.7 m tall.
    let pose = &v.state().stage.actors[0].extra.pose;
    assert!(pose[4].translation.y > pose[0].translation.y);
    assert!(grid.center.y <= pose[0].translation.y);
    let height = v.state().stage.actors[0].world_extent();
    assert!((1.0..2.5).contains(&height), "height in metres: {height}");

    // Sticks: one line per bone, a sphere per joint (not End Sites), casters for shadows.
    v.apply(mocap_viewer::Command::ToggleDrawMode).unwrap();
    let mut edited = v.state().settings.clone();
    edited.shadows = false;
    v.apply(Command::SetSettings(edited)).unwrap();
    v.pose();
    let scene = v.scene();
    assert_eq!(scene.lines.len(), joints - 1, "one bone per non-root joint");
    assert_eq!(scene.spheres.len(), 21);
    assert_eq!(scene.shadow_casters.len(), joints - 1);
    assert!(scene.capsules.is_empty() && !scene.shadows);
    // Bone axes: three overlay lines per joint (not End Sites), over the figure.
    let mut edited = v.state().settings.clone();
    edited.show_axes = true;
    v.apply(Command::SetSettings(edited)).unwrap();
    v.pose();
    assert_eq!(v.scene().overlay_lines.len(), 3 * 21);
    assert!(v.state().view_fragment().contains("mode=sticks&shadows=0"), "{}", v.state().view_fragment());
}

#[test]
fn clip_without_frames_is_shown_without_panicking() {
    let mut v = Viewer::default();
    let bvh = b"HIERARCHY\nROOT Hips\n{\n OFFSET 0 0 0\n CHANNELS 3 Xrotation Yrotation Zrotation\n End Site\n {\n  OFFSET 0 1 0\n }\n}\nMOTION\nFrames: 0\nFrame Time: 0.0333\n";
    if v.load("empty.bvh", bvh).is_err() {
        return; // the reader may reject it; then there is nothing to show
    }
    v.apply(Command::SetPlaying(true)).unwrap();
    v.apply(Command::Seek(3)).unwrap();
    v.pose();
    let mut scene = mocap_render::Scene::default();
    pose_scene::build_scene(&v.state().stage, &v.state().settings, None, &mut scene);
    assert_eq!(v.state().frame(), 0);
}

#[test]
fn view_fragment_round_trips_exactly() {
    let mut v = loaded();
    v.apply(Command::SetPlaying(false)).unwrap();
    v.apply(Command::Seek(17)).unwrap();
    v.apply(Command::SetSpeed(0.37)).unwrap();
    v.apply(Command::SetLooping(false)).unwrap();
    v.apply(Command::SetRange(Some((5, 40)))).unwrap();
    let mut edited = v.state().camera.clone();
    edited.yaw = 1.234_567_9;
    v.apply(Command::SetCamera(edited)).unwrap();
    let mut edited = v.state().camera.clone();
    edited.pitch = -0.3;
    v.apply(Command::SetCamera(edited)).unwrap();
    let mut edited = v.state().camera.clone();
    edited.distance = 3.251_877_4;
    v.apply(Command::SetCamera(edited)).unwrap();
    let mut edited = v.state().camera.clone();
    edited.target = mocap::glam::Vec3::new(0.1, 0.2, -0.3);
    v.apply(Command::SetCamera(edited)).unwrap();
    let mut edited = v.state().settings.clone();
    edited.show_axes = true;
    v.apply(Command::SetSettings(edited)).unwrap();
    let mut edited = v.state().settings.clone();
    edited.show_joints = false;
    v.apply(Command::SetSettings(edited)).unwrap();
    let mut edited = v.state().panels.clone();
    edited.inspector = false;
    v.apply(Command::SetPanels(edited)).unwrap();
    let joint = v
        .state()
        .current_character()
        .and_then(|d| d.clip()?.skeleton().joints().iter().position(|j| j.name == "LeftHand"))
        .or(Some(3));
    v.apply(Command::Select { character: v.state().current(), joint: joint }).unwrap();
    let fragment = v.state().view_fragment();

    let mut w = loaded();
    w.apply_fragment(&format!("#{fragment}"));
    assert_eq!(w.state().view_fragment(), fragment);
    assert_eq!(w.state().playback, v.state().playback);
    assert_eq!(w.state().camera, v.state().camera);
    assert_eq!(w.state().settings, v.state().settings);
    assert_eq!(w.state().panels, v.state().panels);
    assert_eq!(w.state().selected, v.state().selected);
    assert_eq!(w.state().frame(), 17);
}

#[test]
fn view_fragment_accepts_frames_names_and_junk() {
    let mut v = loaded();
    let name = v
        .state()
        .current_character()
        .and_then(|d| d.clip()?.skeleton().joints().get(2))
        .map(|j| j.name.clone())
        .unwrap_or_default();
    v.apply_fragment(&format!(
        "f=9999&play=0&sel={}&speed=abc&cam=nan,1,1,1,1,1&panels=none",
        mocap_viewer::view_state::percent_encode(&name)
    ));
    let last = v.state().current_character().map_or(0, |d| d.asset.frame_count() - 1);
    assert_eq!(v.state().frame(), last);
    assert!(!v.state().playback.playing);
    assert_eq!(v.snapshot().selected_joint.as_deref(), Some(name.as_str()));
    assert_eq!(v.state().playback.speed, 1.0);
    assert!(!v.state().panels.hierarchy && !v.state().panels.inspector);
    v.apply_fragment("sel=NoSuchJoint");
    assert_eq!(v.state().selected, None);
}

#[test]
fn banner_says_what_became_of_what_was_open() {
    const BAD: &[u8] = b"HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0\n";
    // Nothing in the drop opens: the open clip stays, and the banner says so.
    let mut v = loaded();
    let errors = v.open_files(&[("bad.bvh", BAD)], mocap_viewer::OpenMode::Replace);
    assert_eq!(errors.len(), 1);
    let s = v.snapshot();
    assert_eq!((s.clips[0].name.as_str(), s.error.as_deref()), ("walk.bvh", Some(errors[0].as_str())));
    assert_eq!(s.error_note, Some("What was open is still open."));
    // Part of the drop opens and replaces what was open: the banner must not claim
    // that what was open is still open.
    let errors = v.open_files(&[("second.bvh", WALK), ("bad.bvh", BAD)], mocap_viewer::OpenMode::Replace);
    let s = v.snapshot();
    assert_eq!(s.clips.iter().map(|c| c.name.as_str()).collect::<Vec<_>>(), ["second.bvh"]);
    assert_eq!(s.error.as_deref(), Some(errors[0].as_str()));
    assert_eq!(s.error_note, Some("The other files opened."));
    // Nothing open and nothing opened: no second line.
    let mut empty = Viewer::default();
    empty.open_files(&[("bad.bvh", BAD)], mocap_viewer::OpenMode::Replace);
    assert!(empty.snapshot().error.is_some_and(|e| e.starts_with("bad.bvh:")));
    assert_eq!(empty.snapshot().error_note, None);
    // A refused action (the timeline's "× key" where there is no key) is not a
    // file that failed to open.
    v.apply(Command::DismissNotice).unwrap();
    v.apply(Command::DeleteKey(5)).expect_err("no key at frame 5");
    let notice = v.state().notice.clone().expect("the refusal is shown");
    assert_eq!(notice.outcome, mocap_viewer::Outcome::Refused);
    assert!(notice.headline().starts_with("Could not do that: "), "{}", notice.headline());
    assert_eq!(v.snapshot().error_note, Some("Nothing was changed."));
}
