//! The bendy-tentacle demo (no GPU): the tip follows the target with each solver,
//! sliders bend it by forward kinematics when it does not follow, the skin is soft
//! or rigid, and dragging the red sphere in the view moves the target.

use mocap::glam::Vec3;
use mocap_viewer::Command;
use mocap_viewer::Viewer;
use mocap_viewer::tentacle::Solver;

fn demo(bones: usize) -> Viewer {
    let mut v = Viewer::default();
    v.apply(Command::OpenTentacle(bones)).unwrap();
    v.pose();
    v
}

fn tip(v: &Viewer) -> Vec3 {
    v.state().stage.actors[0].extra.pose.last().unwrap().translation
}

#[test]
fn the_tip_follows_the_target_with_every_solver() {
    for bones in [2, 5] {
        let mut v = demo(bones);
        assert_eq!(v.state().stage.actors[0].name, "tentacle");
        assert_eq!(v.scene().skinned.len(), 1, "drawn with its skin");
        let base = v.state().stage.actors[0].extra.pose[0].translation;
        for solver in Solver::ALL {
            let mut t = v.state().tentacle.clone().unwrap();
            t.solver = solver;
            t.target = base + Vec3::new(0.4, 0.5, 0.2) * (bones as f32 * 0.5) * 0.9 / Vec3::new(0.4, 0.5, 0.2).length();
            let target = t.target;
            v.apply(Command::SetTentacle(t)).unwrap();
            v.pose();
            assert!(tip(&v).distance(target) < 1e-3, "{bones} bones, {solver:?}: tip {} target {target}", tip(&v));
            assert_eq!(v.snapshot().demo.unwrap().tip, tip(&v).to_array());
        }
        // Out of reach: straight toward it.
        let mut edited = v.state().tentacle.clone().unwrap();
        edited.target = base + Vec3::new(10.0, 0.0, 0.0);
        v.apply(Command::SetTentacle(edited)).unwrap();
        v.pose();
        let reach = tip(&v) - base;
        assert!((reach.normalize() - Vec3::X).length() < 1e-3 && (reach.length() - bones as f32 * 0.5).abs() < 1e-3);
        assert!(
            v.scene().spheres.iter().any(|s| s.center == base + Vec3::new(10.0, 0.0, 0.0)),
            "the target sphere is drawn"
        );
    }
}

#[test]
fn sliders_bend_it_by_forward_kinematics() {
    let mut v = demo(2);
    let mut t = v.state().tentacle.clone().unwrap();
    t.follow = false;
    t.angles = vec![[90.0, 0.0], [0.0, 0.0]];
    v.apply(Command::SetTentacle(t)).unwrap();
    v.pose();
    let base = v.state().stage.actors[0].extra.pose[0].translation;
    // Bent 90° about Z at the base: the straight chain points along -X.
    assert!((tip(&v) - base - Vec3::new(-1.0, 0.0, 0.0)).length() < 1e-4, "{}", tip(&v) - base);
    let mut edited = v.state().tentacle.clone().unwrap();
    edited.angles = vec![[0.0, 0.0], [0.0, 90.0]];
    v.apply(Command::SetTentacle(edited)).unwrap();
    v.pose();
    assert!((tip(&v) - base - Vec3::new(0.0, 0.5, 0.5)).length() < 1e-4, "{}", tip(&v) - base);
}

#[test]
fn soft_and_rigid_skins_differ_only_in_weights() {
    let mut v = demo(3);
    v.pose();
    let soft = v.scene().skinned[0].mesh.clone();
    let mut edited = v.state().tentacle.clone().unwrap();
    edited.soft = false;
    v.apply(Command::SetTentacle(edited)).unwrap();
    v.apply(Command::RefreshTentacleSkin).unwrap();
    v.pose();
    let rigid = v.scene().skinned[0].mesh.clone();
    assert_ne!(soft, rigid);
    assert_eq!(soft.vertex_count(), rigid.vertex_count());
    // Opening files ends the demo.
    v.load("walk.bvh", include_bytes!("../../../data/walk.bvh")).unwrap();
    assert!(v.state().tentacle.is_none() && v.snapshot().demo.is_none());
}

#[test]
fn dragging_the_red_sphere_moves_the_target_and_the_tip_follows() {
    let ctx = egui::Context::default();
    let mut v = demo(2);
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
    run(&mut v, 0.0, vec![]);
    run(&mut v, 0.05, vec![]);
    let target = v.state().tentacle.as_ref().unwrap().target;
    let start = v.screen_position(target).expect("the target is on screen");
    let end = start + egui::vec2(-60.0, 20.0);
    let press = |pos, pressed| egui::Event::PointerButton {
        pos,
        button: egui::PointerButton::Primary,
        pressed,
        modifiers: egui::Modifiers::NONE,
    };
    run(&mut v, 0.1, vec![egui::Event::PointerMoved(start), press(start, true)]);
    for k in 1..=5 {
        run(&mut v, 0.1 + 0.05 * k as f64, vec![egui::Event::PointerMoved(start + (end - start) * (k as f32 / 5.0))]);
    }
    run(&mut v, 0.5, vec![press(end, false)]);
    run(&mut v, 0.55, vec![]);
    let moved = v.state().tentacle.as_ref().unwrap().target;
    let now = v.screen_position(moved).unwrap();
    assert!(now.distance(end) < 2.0, "the sphere is under the pointer: {now:?} vs {end:?}");
    assert!(tip(&v).distance(moved) < 1e-3, "the tip follows");
}
