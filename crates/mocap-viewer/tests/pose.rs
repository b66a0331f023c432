//! Pose mode (no GPU): dragging a joint moves it by IK at the frame shown, the
//! clip's own pose becomes a ghost, other frames and Reset show the clip; and a real
//! pointer drag in the headless UI grabs the joint under it instead of orbiting.

mod support;

use mocap::glam::Vec3;
use mocap_viewer::Command;
use mocap_viewer::Viewer;

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");

fn paused() -> Viewer {
    let mut v = Viewer::default();
    v.load("walk.bvh", WALK).unwrap();
    v.apply(Command::SetPlaying(false)).unwrap();
    v.apply(Command::Seek(12)).unwrap();
    v.pose();
    v
}

fn joint(v: &Viewer, name: &str) -> usize {
    v.state().stage.actors[0].clip().unwrap().skeleton().find(name).unwrap()
}

fn at(v: &Viewer, j: usize) -> Vec3 {
    v.state().stage.actors[0].extra.pose[j].translation
}

#[test]
fn dragging_a_hand_moves_it_and_its_arm_follows() {
    let mut v = paused();
    let (hand, other, elbow) = (joint(&v, "LeftHand"), joint(&v, "RightHand"), joint(&v, "LeftForeArm"));
    let (before, other_before, elbow_before) = (at(&v, hand), at(&v, other), at(&v, elbow));
    let target = before + Vec3::new(0.08, 0.12, -0.05);
    let solve = v.drag_joint(0, hand, target).unwrap();
    assert!(solve.reached, "{solve:?}");
    assert!(at(&v, hand).distance(target) < 1e-3, "the hand is at the target: {}", at(&v, hand));
    assert!(at(&v, elbow).distance(elbow_before) > 1e-3, "the elbow follows");
    assert_eq!(at(&v, other), other_before, "the other hand stays");
    assert!(!v.state().stage.actors[0].extra.ghost.is_empty(), "the clip's own pose is ghosted");
    assert!(v.scene().overlay_lines.len() > 10, "the ghost is drawn");
    assert!(v.snapshot().clips[0].corrected);
    // Another frame shows the clip; coming back shows the correction again.
    v.apply(Command::Seek(20)).unwrap();
    v.pose();
    assert!(v.state().stage.actors[0].extra.ghost.is_empty());
    v.apply(Command::Seek(12)).unwrap();
    v.pose();
    assert!(at(&v, hand).distance(target) < 1e-3);
    v.apply(Command::ResetPose).unwrap();
    v.pose();
    assert!(at(&v, hand).distance(before) < 1e-5, "Reset restores the clip");
    assert!(!v.state().has_corrections());
}

#[test]
fn dragging_the_root_moves_the_whole_figure_and_nonsense_is_refused() {
    let mut v = paused();
    let head = joint(&v, "Head");
    let (root, head_before) = (at(&v, 0), at(&v, head));
    v.drag_joint(0, 0, root + Vec3::new(0.3, 0.0, 0.0)).unwrap();
    assert!(at(&v, 0).distance(root + Vec3::new(0.3, 0.0, 0.0)) < 1e-4);
    assert!(at(&v, head).distance(head_before + Vec3::new(0.3, 0.0, 0.0)) < 1e-3);
    assert!(v.drag_joint(0, 999, Vec3::ZERO).is_none());
    assert!(v.drag_joint(5, 0, Vec3::ZERO).is_none());
    assert!(v.drag_joint(0, head, Vec3::NAN).is_none());
    assert!(v.state().stage.actors[0].extra.pose.iter().all(|t| t.translation.is_finite()));
}

fn run(ctx: &egui::Context, v: &mut Viewer, time: f64, events: Vec<egui::Event>) {
    let input = egui::RawInput {
        time: Some(time),
        screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(1280.0, 800.0))),
        events,
        ..Default::default()
    };
    let mut output = ctx.run_ui(input, |ui| {
        v.ui(ui, None);
    });
    output.textures_delta.clear();
}

fn button(pos: egui::Pos2, pressed: bool) -> egui::Event {
    egui::Event::PointerButton { pos, button: egui::PointerButton::Primary, pressed, modifiers: egui::Modifiers::NONE }
}

#[test]
fn a_pointer_drag_in_the_view_grabs_the_joint_in_pose_mode() {
    let ctx = egui::Context::default();
    let mut v = paused();
    v.apply_fragment("draw=joints,interp,pose");
    assert!(v.state().settings.pose_mode);
    run(&ctx, &mut v, 0.0, vec![]);
    run(&ctx, &mut v, 0.05, vec![]);
    let hand = joint(&v, "LeftHand");
    let start = v.joint_on_screen(0, hand).expect("the hand is on screen");
    let camera_before = v.state().camera.clone();
    let end = start + egui::vec2(30.0, -25.0);
    let mut t = 0.1;
    run(&ctx, &mut v, t, vec![egui::Event::PointerMoved(start), button(start, true)]);
    for k in 1..=6 {
        t += 0.05;
        let p = start + (end - start) * (k as f32 / 6.0);
        run(&ctx, &mut v, t, vec![egui::Event::PointerMoved(p)]);
    }
    run(&ctx, &mut v, t + 0.05, vec![button(end, false)]);
    run(&ctx, &mut v, t + 0.1, vec![]);
    assert_eq!(v.state().camera, camera_before, "the drag moved the joint, not the camera");
    let now = v.joint_on_screen(0, hand).unwrap();
    assert!(now.distance(end) < 2.0, "the hand follows the pointer: {now:?} vs {end:?}");
    assert_eq!(v.state().selected_name(), Some("LeftHand"));
    // Outside Pose mode the same drag orbits.
    v.apply(Command::ResetPose).unwrap();
    let mut edited = v.state().settings.clone();
    edited.pose_mode = false;
    v.apply(Command::SetSettings(edited)).unwrap();
    run(&ctx, &mut v, t + 0.2, vec![]);
    let s = v.joint_on_screen(0, hand).unwrap();
    run(&ctx, &mut v, t + 0.25, vec![egui::Event::PointerMoved(s), button(s, true)]);
    run(&ctx, &mut v, t + 0.3, vec![egui::Event::PointerMoved(s + egui::vec2(40.0, 0.0))]);
    run(&ctx, &mut v, t + 0.35, vec![button(s + egui::vec2(40.0, 0.0), false)]);
    assert_ne!(v.state().camera, camera_before, "it orbits");
    assert!(!v.state().has_corrections());
}

#[test]
fn foot_locking_finds_contacts_and_keeps_a_planted_foot_still() {
    let mut v = paused();
    v.apply_fragment("draw=joints,interp,footlock");
    assert!(v.state().settings.foot_lock);
    v.pose();
    let s = v.snapshot();
    assert_eq!(s.clips[0].foot_contacts.len(), 2, "two feet");
    assert!(s.clips[0].foot_contacts.iter().all(|&n| n > 5), "{:?}", s.clips[0].foot_contacts);
    assert!(v.state().view_fragment().contains("footlock"));
    // Inside a contact run of a foot, the locked foot does not move between frames.
    let lock = v.state().stage.actors[0].extra.foot_lock.clone().unwrap();
    let leg = &lock.legs[0];
    let run =
        (1..leg.contact.len()).find(|&f| leg.contact[f] && leg.contact[f - 1]).expect("a run of two contact frames");
    let foot = leg.chain.effector();
    let mut at_frame = |f: usize| {
        v.apply(Command::Seek(f)).unwrap();
        v.pose();
        v.state().stage.actors[0].extra.pose[foot].translation
    };
    let (a, b) = (at_frame(run - 1), at_frame(run));
    assert!(a.distance(b) < 1e-3, "the planted foot stays: {a} → {b}");
    assert!(v.state().stage.actors[0].extra.pose.iter().all(|t| t.translation.is_finite()));
}

#[test]
fn a_dragged_pose_becomes_a_key_that_fades_and_saves() {
    let mut v = paused();
    let hand = joint(&v, "LeftHand");
    let target = at(&v, hand) + Vec3::new(0.08, 0.12, -0.05);
    assert!(v.drag_joint(0, hand, target).unwrap().reached);
    let mut edited = v.state().settings.clone();
    edited.key_window = 2;
    v.apply(Command::SetSettings(edited)).unwrap();
    assert_eq!(v.try_apply(Command::SetKey), Ok(()));
    assert!(!v.state().has_corrections(), "the correction is now part of the clip");
    assert_eq!(v.snapshot().undo.as_deref(), Some("Key at frame 12"));
    v.pose();
    assert!(
        at(&v, hand).distance(target) < 2e-3,
        "keyed: the hand is at the target at frame 12 ({})",
        at(&v, hand).distance(target)
    );
    // It fades: frame 14 moved less than frame 13, frame 15 (past the window) not at all.
    let clip = v.state().stage.actors[0].clip().unwrap().clone();
    let original = mocap::formats::bvh::parse(WALK).unwrap();
    let moved = |f: usize| clip.world_positions(f)[hand].distance(original.world_positions(f)[hand]);
    assert!(moved(13) > moved(14) && moved(14) > 0.0 && moved(15) < 1e-4, "{} {} {}", moved(13), moved(14), moved(15));
    // Saved, it reads back with the key.
    let (_, text) = v.save_bvh(0).unwrap();
    let saved = mocap::formats::bvh::parse(text.as_bytes()).unwrap();
    assert!(saved.world_positions(12)[hand].distance(clip.world_positions(12)[hand]) < 1e-3);
    // Undo restores the clip bit for bit.
    support::undo(&mut v);
    assert_eq!(v.state().stage.actors[0].clip().unwrap(), &original);
}

#[test]
fn a_typed_rotation_is_a_correction_that_keys() {
    use mocap::glam::{EulerRot, Quat};
    let mut v = paused();
    let arm = joint(&v, "LeftArm");
    let q = Quat::from_euler(EulerRot::ZXY, 0.4, -0.3, 0.2);
    assert!(v.try_apply(Command::RotateJoint { character: 0, joint: arm, rotation: q }).is_ok());
    let drawn = mocap_viewer::character::drawn_local_rotation(&v.state().stage.actors[0], arm).unwrap();
    assert!(drawn.dot(q).abs() > 0.99999, "drawn as typed");
    assert!(v.state().has_corrections());
    v.try_apply(Command::SetKey).unwrap();
    let mut local = mocap::LocalPose::default();
    v.state().stage.actors[0].clip().unwrap().local_pose_into(12, &mut local);
    assert!(local.rotation[arm].dot(q).abs() > 0.99999, "keyed into the clip");
    assert!(
        !v.try_apply(Command::RotateJoint { character: 0, joint: 999, rotation: q }).is_ok()
            && !v
                .try_apply(Command::RotateJoint {
                    character: 0,
                    joint: arm,
                    rotation: Quat::from_xyzw(f32::NAN, 0.0, 0.0, 1.0)
                })
                .is_ok()
    );
}

#[test]
fn dragging_a_ring_turns_the_selected_joint_about_its_axis() {
    let ctx = egui::Context::default();
    let mut v = paused();
    let elbow = joint(&v, "LeftForeArm");
    v.apply(Command::Select { character: v.state().current(), joint: Some(elbow) }).unwrap();
    v.apply_fragment("draw=joints,interp,pose");
    run(&ctx, &mut v, 0.0, vec![]);
    run(&ctx, &mut v, 0.05, vec![]);
    let start = v.state().stage.actors[0].extra.pose[elbow];
    // A point on the ring about the joint's local Z axis, and one a quarter turn on.
    let axis = start.rotation * Vec3::Z;
    let radius = v.state().stage.actors[0].world_extent() * 0.12;
    let u = axis.any_orthonormal_vector();
    let w = axis.cross(u);
    let on_ring = |a: f32| start.translation + (u * a.cos() + w * a.sin()) * radius;
    let from = v.screen_position(on_ring(0.0)).unwrap();
    let to = v.screen_position(on_ring(0.5)).unwrap();
    let mut t = 0.1;
    run(&ctx, &mut v, t, vec![egui::Event::PointerMoved(from), button(from, true)]);
    for k in 1..=6 {
        t += 0.05;
        let target = v.screen_position(on_ring(0.5 * k as f32 / 6.0)).unwrap();
        run(&ctx, &mut v, t, vec![egui::Event::PointerMoved(target)]);
    }
    run(&ctx, &mut v, t + 0.05, vec![button(to, false)]);
    run(&ctx, &mut v, t + 0.1, vec![]);
    let now = v.state().stage.actors[0].extra.pose[elbow];
    assert!(now.translation.distance(start.translation) < 1e-4, "the joint turns in place");
    let turn = now.rotation * start.rotation.inverse();
    let (turn_axis, angle) = turn.to_axis_angle();
    assert!(
        (angle - 0.5).abs() < 0.03 && turn_axis.dot(axis) > 0.99,
        "a half-radian turn about the ring's axis: {angle} about {turn_axis}"
    );
    assert!(v.state().has_corrections());
}

#[test]
fn the_creator_drags_a_new_bone_out_of_the_selected_joint() {
    let ctx = egui::Context::default();
    let mut v = Viewer::default();
    v.apply(Command::NewCharacter).unwrap();
    run(&ctx, &mut v, 0.0, vec![]);
    run(&ctx, &mut v, 0.05, vec![]);
    assert!(v.try_apply(Command::GrowBone("Arm".into())).is_ok() && v.growing());
    let hips = v.state().stage.actors[0].extra.pose[0].translation;
    let from = v.screen_position(hips).unwrap();
    let to = from + egui::vec2(80.0, -40.0);
    let mut t = 0.1;
    run(&ctx, &mut v, t, vec![egui::Event::PointerMoved(from), button(from, true)]);
    for k in 1..=5 {
        t += 0.05;
        run(&ctx, &mut v, t, vec![egui::Event::PointerMoved(from + (to - from) * (k as f32 / 5.0))]);
    }
    run(&ctx, &mut v, t + 0.05, vec![button(to, false)]);
    run(&ctx, &mut v, t + 0.1, vec![]);
    assert!(!v.growing());
    let arm = v.state().stage.actors[0].clip().unwrap().skeleton().find("Arm").expect("the new joint");
    assert_eq!(v.state().selected_name(), Some("Arm"), "the new joint is selected");
    let end = v.state().stage.actors[0].extra.pose[arm].translation;
    let on_screen = v.screen_position(end).unwrap();
    assert!(on_screen.distance(to) < 2.0, "the bone ends where the pointer let go: {on_screen:?} vs {to:?}");
    assert_eq!(v.snapshot().undo.as_deref(), Some("Add Arm"));
}
