//! Clip edits in the viewer: each edit is one undoable step, undoing every edit
//! gives back the original clip bit for bit, redo makes them again, Ctrl+Z and
//! Ctrl+Shift+Z work, and Save as BVH writes the edited clip under a name that
//! says so.

mod support;

use mocap::ops::edit::Edit;
use mocap_viewer::Command;
use mocap_viewer::Viewer;

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");

fn clip(v: &Viewer) -> mocap::Clip {
    v.state().stage.actors[0].clip().unwrap().clone()
}

#[test]
fn every_edit_kind_undoes_to_the_original_bit_for_bit() {
    let mut v = Viewer::default();
    v.load("walk.bvh", WALK).unwrap();
    let original = clip(&v);
    let edits = [
        Edit::Trim { first: 3, last: 50 },
        Edit::Resample { fps: 60.0 },
        Edit::Reverse,
        Edit::PingPong,
        Edit::LoopKnit { frames: 5 },
        Edit::InPlace { remove_turning: true },
        Edit::UpAxis { from: 2, negative: false },
        Edit::Scale { factor: 0.01 },
        Edit::Rename { from: "Head".into(), to: "Kopf".into() },
        Edit::RemoveJoint { name: "LeftForeArm".into(), fold: true },
        Edit::RemoveJoint { name: "RightForeArm".into(), fold: false },
    ];
    let mut after = Vec::new();
    for (k, e) in edits.iter().enumerate() {
        v.try_apply(Command::Edit { character: 0, edit: e.clone(), label: format!("edit {k}") })
            .unwrap_or_else(|m| panic!("{e:?}: {m}"));
        after.push(clip(&v));
        v.pose();
        assert!(v.state().stage.actors[0].extra.pose.iter().all(|t| t.translation.is_finite()));
    }
    assert!(v.snapshot().clips[0].edited);
    assert_eq!(v.snapshot().undo.as_deref(), Some("edit 10"));
    for k in (0..edits.len()).rev() {
        assert_eq!(support::undo(&mut v).as_deref(), Some(format!("edit {k}").as_str()));
    }
    assert_eq!(clip(&v), original, "undoing everything gives back the original");
    assert!(support::undo(&mut v).is_none() && !v.snapshot().clips[0].edited);
    for expected in &after {
        support::redo(&mut v).unwrap();
        assert_eq!(&clip(&v), expected);
    }
    // A failed edit changes nothing and is not recorded.
    let before = clip(&v);
    assert!(
        v.try_apply(Command::Edit { character: 0, edit: Edit::Trim { first: 9, last: 2 }, label: "bad".into() })
            .is_err()
    );
    assert_eq!(clip(&v), before);
    assert_eq!(v.snapshot().undo.as_deref(), Some("edit 10"));
}

#[test]
fn save_as_bvh_writes_the_edited_clip_and_says_so() {
    let mut v = Viewer::default();
    v.load("clips/walk.bvh", WALK).unwrap();
    assert_eq!(v.save_bvh(0).unwrap().0, "walk.bvh");
    v.try_apply(Command::Edit { character: 0, edit: Edit::Reverse, label: "Reverse".into() }).unwrap();
    let (name, text) = v.save_bvh(0).unwrap();
    assert_eq!(name, "walk-edited.bvh");
    let again = mocap::formats::bvh::parse(text.as_bytes()).unwrap();
    assert_eq!(again.motion().data(), clip(&v).motion().data(), "parse(save(x)) is x");
    assert_eq!(again.skeleton(), clip(&v).skeleton());
    // A model has no BVH.
    assert!(v.save_bvh(5).is_none());
}

#[test]
fn ctrl_z_and_ctrl_shift_z_undo_and_redo() {
    let ctx = egui::Context::default();
    let mut v = Viewer::default();
    v.load("walk.bvh", WALK).unwrap();
    let original = clip(&v);
    v.try_apply(Command::Edit { character: 0, edit: Edit::Reverse, label: "Reverse".into() }).unwrap();
    let reversed = clip(&v);
    let key = |key, shift| egui::Event::Key {
        key,
        physical_key: None,
        pressed: true,
        repeat: false,
        modifiers: egui::Modifiers { ctrl: true, command: true, shift, ..Default::default() },
    };
    let run = |v: &mut Viewer, t: f64, events: Vec<egui::Event>| {
        let input = egui::RawInput {
            time: Some(t),
            screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(1280.0, 800.0))),
            events,
            ..Default::default()
        };
        let mut out = ctx.run_ui(input, |ui| {
            v.ui(ui, None);
        });
        out.textures_delta.clear();
    };
    let camera = v.state().camera.clone();
    run(&mut v, 0.0, vec![key(egui::Key::Z, false)]);
    assert_eq!(clip(&v), original);
    run(&mut v, 0.1, vec![key(egui::Key::Z, true)]);
    assert_eq!(clip(&v), reversed);
    run(&mut v, 0.2, vec![key(egui::Key::Z, false)]);
    run(&mut v, 0.3, vec![key(egui::Key::Y, false)]);
    assert_eq!(clip(&v), reversed);
    assert_eq!(v.state().camera.distance, camera.distance, "Ctrl+Z does not zoom");
}

#[test]
fn closing_an_edited_character_asks_first() {
    let ctx = egui::Context::default();
    let mut v = Viewer::default();
    v.load("walk.bvh", WALK).unwrap();
    v.add("again.bvh", WALK).unwrap();
    v.try_apply(Command::Edit { character: 1, edit: Edit::Reverse, label: "Reverse".into() }).unwrap();
    let run = |v: &mut Viewer, t: f64| {
        let input = egui::RawInput {
            time: Some(t),
            screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(1280.0, 800.0))),
            ..Default::default()
        };
        let mut out = ctx.run_ui(input, |ui| {
            v.ui(ui, None);
        });
        out.textures_delta.clear();
    };
    // What the × button does for an edited character: ask, keep it open meanwhile.
    v.apply(Command::Close(1)).unwrap();
    run(&mut v, 0.0);
    run(&mut v, 0.1);
    assert_eq!(v.state().stage.actors.len(), 2, "still open while asking");
    assert_eq!(v.state().pending_close, Some(1));
    // Closing an unedited one needs no question.
    assert!(!v.state().history.edited(0));
}

#[test]
fn a_layer_from_another_open_clip_is_one_undoable_step() {
    let mut v = Viewer::default();
    v.load("walk.bvh", WALK).unwrap();
    v.add("wave.bvh", WALK).unwrap();
    v.try_apply(Command::Edit { character: 1, edit: Edit::Reverse, label: "Reverse".into() }).unwrap();
    let original = clip(&v);
    v.try_apply(Command::AddLayer { character: 0, source: 1, layer: mocap::ops::layer::Layer::on("RightShoulder") })
        .unwrap();
    assert_ne!(clip(&v), original);
    assert_eq!(v.snapshot().undo.as_deref(), Some("Layer wave.bvh on RightShoulder"));
    support::undo(&mut v);
    assert_eq!(clip(&v), original);
    assert!(
        v.try_apply(Command::AddLayer { character: 0, source: 1, layer: mocap::ops::layer::Layer::on("Wing") })
            .is_err()
    );
}

#[test]
fn the_creator_makes_a_character_that_poses_keys_and_saves() {
    use mocap::glam::Vec3;
    let mut v = Viewer::default();
    v.apply(Command::NewCharacter).unwrap();
    assert!(v.state().settings.pose_mode && v.state().selected_name() == Some("Hips"));
    v.try_apply(Command::Edit {
        character: 0,
        edit: Edit::AddJoint { parent: "Hips".into(), name: "Arm".into(), offset: Vec3::new(0.0, 0.4, 0.0) },
        label: "Add Arm".into(),
    })
    .unwrap();
    v.try_apply(Command::Edit {
        character: 0,
        edit: Edit::AddJoint { parent: "Arm".into(), name: "Hand".into(), offset: Vec3::new(0.0, 0.4, 0.0) },
        label: "Add Hand".into(),
    })
    .unwrap();
    let names: Vec<String> = v.snapshot().clips[0].joint_names.clone();
    assert_eq!(names, ["Hips", "Arm", "Hand", "Hand_End"]);
    // Pose the hand at frame 30 by dragging, key it, play it back.
    v.apply(Command::Seek(30)).unwrap();
    v.pose();
    let hand = 2;
    let start = v.state().stage.actors[0].extra.pose[hand].translation;
    let target = start + Vec3::new(0.3, -0.2, 0.0);
    assert!(v.drag_joint(0, hand, target).unwrap().reached);
    v.try_apply(Command::SetKey).unwrap();
    v.pose();
    assert!(v.state().stage.actors[0].extra.pose[hand].translation.distance(target) < 2e-3);
    v.apply(Command::Seek(0)).unwrap();
    v.pose();
    assert!(v.state().settings.key_between, "the creator keys between keys");
    assert!(
        v.state().stage.actors[0].extra.pose[hand].translation.distance(target) < 2e-3,
        "one key holds on every frame"
    );
    // Keys show on the timeline and the playhead steps between them.
    assert_eq!(v.snapshot().clips[0].keys, [30]);
    assert_eq!(support::step_key(&mut v, true), Some(30));
    assert_eq!(support::step_key(&mut v, true), None);
    assert_eq!(support::step_key(&mut v, false), None);
    v.try_apply(Command::Edit { character: 0, edit: Edit::Reverse, label: "Reverse".into() }).unwrap();
    assert!(v.snapshot().clips[0].keys.is_empty(), "frames moved: the key is no longer where it was");
    support::undo(&mut v);
    assert_eq!(v.snapshot().clips[0].keys, [30]);
    // Saved and read back: the same skeleton and motion.
    let (name, text) = v.save_bvh(0).unwrap();
    assert_eq!(name, "character-edited.bvh");
    let again = mocap::formats::bvh::parse(text.as_bytes()).unwrap();
    assert_eq!(again.skeleton(), clip(&v).skeleton());
    assert_eq!(again.motion().data(), clip(&v).motion().data());
    let mut dropped = Viewer::default();
    dropped.load(&name, text.as_bytes()).unwrap();
    assert_eq!(dropped.snapshot().clips[0].joint_names, names);
    // A second key at frame 50: the motion goes from one key to the other.
    v.apply(Command::Seek(50)).unwrap();
    v.pose();
    let second = target + Vec3::new(-0.5, 0.1, 0.0);
    assert!(v.drag_joint(0, hand, second).unwrap().reached);
    v.try_apply(Command::SetKey).unwrap();
    assert_eq!(v.snapshot().clips[0].keys, [30, 50]);
    let hand_at = |v: &mut Viewer, f: usize| {
        v.apply(Command::Seek(f)).unwrap();
        v.pose();
        v.state().stage.actors[0].extra.pose[hand].translation
    };
    assert!(
        hand_at(&mut v, 30).distance(target) < 2e-3 && hand_at(&mut v, 50).distance(second) < 2e-3,
        "each key holds its pose"
    );
    let mid = hand_at(&mut v, 40);
    assert!(
        mid.x < target.x - 0.1 && mid.x > second.x + 0.1,
        "halfway, the hand is between the keys: {mid} ({target} → {second})"
    );
    assert!(
        hand_at(&mut v, 10).distance(target) < 2e-3 && hand_at(&mut v, 59).distance(second) < 2e-3,
        "held before the first key and after the last"
    );
    // Deleting the first key: the second one, alone, holds everywhere.
    v.try_apply(Command::DeleteKey(30)).unwrap();
    assert_eq!(v.snapshot().clips[0].keys, [50]);
    assert!(hand_at(&mut v, 30).distance(second) < 2e-3, "the key list of the remaining key followed");
}

#[test]
fn the_edit_menu_draws_for_clips_models_and_nothing() {
    // The menu's contents, drawn in a plain panel (no clicks): no panic for any state.
    let ctx = egui::Context::default();
    let mut v = Viewer::default();
    let draw = |v: &Viewer| {
        let input = egui::RawInput {
            screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(800.0, 1400.0))),
            ..Default::default()
        };
        let mut commands = Vec::new();
        let mut out = ctx.run_ui(input, |ui| {
            egui::CentralPanel::default()
                .show(ui, |ui| mocap_viewer::ui::edit_menu::show(ui, &v.edit_menu_view(), &mut commands));
        });
        out.textures_delta.clear();
        assert!(commands.is_empty(), "drawing the menu sends nothing: {commands:?}");
    };
    draw(&v);
    v.load("walk.bvh", WALK).unwrap();
    draw(&v);
    v.apply(Command::Select { character: v.state().current(), joint: Some(7) }).unwrap();
    v.apply(Command::SetRange(Some((5, 20)))).unwrap();
    v.add("wave.bvh", WALK).unwrap();
    v.try_apply(Command::Edit { character: 0, edit: Edit::Reverse, label: "Reverse".into() }).unwrap();
    draw(&v);
    v.apply(Command::Select { character: v.state().current(), joint: Some(5) }).unwrap();
    draw(&v);
    assert!(v.state().notice.is_none());
}

#[test]
fn keys_can_be_deleted_and_moved_under_later_edits() {
    use mocap::glam::Quat;
    let mut v = Viewer::default();
    v.load("walk.bvh", WALK).unwrap();
    let original = clip(&v);
    let arm = original.skeleton().find("LeftArm").unwrap();
    let at = |f: usize| {
        let mut p = mocap::LocalPose::default();
        original.local_pose_into(f, &mut p);
        p.rotation[arm]
    };
    let key = |frame: usize, q: Quat| Edit::Correct {
        frame,
        rotations: vec![("LeftArm".into(), q)],
        translations: vec![],
        window: 2,
    };
    let (q10, q40) = (at(10) * Quat::from_rotation_z(0.7), at(40) * Quat::from_rotation_x(0.5));
    v.try_apply(Command::Edit { character: 0, edit: key(10, q10), label: "Key at frame 10".into() }).unwrap();
    v.try_apply(Command::Edit { character: 0, edit: key(40, q40), label: "Key at frame 40".into() }).unwrap();
    v.try_apply(Command::Edit {
        character: 0,
        edit: Edit::Rename { from: "Head".into(), to: "Kopf".into() },
        label: "Rename".into(),
    })
    .unwrap();
    assert_eq!(v.snapshot().clips[0].keys, [10, 40]);
    let rotation = |v: &Viewer, f: usize| {
        let mut p = mocap::LocalPose::default();
        clip(v).local_pose_into(f, &mut p);
        p.rotation[arm]
    };
    // Delete the first key: frame 10 is the clip's again, the second key and the rename stay.
    v.try_apply(Command::DeleteKey(10)).unwrap();
    assert_eq!(v.snapshot().clips[0].keys, [40]);
    assert!(rotation(&v, 10).dot(at(10)).abs() > 0.99999);
    assert!(rotation(&v, 40).dot(q40).abs() > 0.99999);
    assert!(clip(&v).skeleton().find("Kopf").is_some());
    // Move the second key to frame 45.
    v.try_apply(Command::MoveKey { from: 40, to: 45 }).unwrap();
    assert_eq!(v.snapshot().clips[0].keys, [45]);
    assert!(rotation(&v, 45).dot(q40).abs() > 0.99999 && rotation(&v, 40).dot(at(40)).abs() > 0.999);
    // Both are undoable.
    support::undo(&mut v);
    assert_eq!(v.snapshot().clips[0].keys, [40]);
    support::undo(&mut v);
    assert_eq!(v.snapshot().clips[0].keys, [10, 40]);
    assert!(v.try_apply(Command::DeleteKey(33)).is_err());
}
