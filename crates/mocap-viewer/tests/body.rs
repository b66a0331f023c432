//! Body mode in the viewer (no GPU): the generated body replaces the capsules, its
//! matrices follow the pose, the weights view and the mode live in the fragment,
//! `m` cycles the three modes, and a skeleton too big for a body keeps capsules.

use mocap_render::DrawMode;
use mocap_viewer::Command;
use mocap_viewer::Viewer;

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");

#[test]
fn body_mode_draws_a_skinned_body_instead_of_capsules() {
    let mut v = Viewer::default();
    v.load("walk.bvh", WALK).unwrap();
    v.apply(Command::SetPlaying(false)).unwrap();
    v.apply_fragment("mode=body&draw=joints,weights");
    assert_eq!(v.state().settings.mode, DrawMode::Body);
    assert!(v.state().settings.show_weights);
    v.pose();
    let scene = v.scene();
    assert_eq!(scene.skinned.len(), 1);
    assert!(scene.capsules.is_empty(), "no capsules in body mode");
    let body = &scene.skinned[0];
    let joints = v.state().stage.actors[0].clip().unwrap().skeleton().len();
    assert_eq!(body.matrices.len(), joints);
    assert_eq!(body.mesh.joint_count() as usize, joints);
    assert!(body.weights_view);
    // The matrices follow the pose: at the bind frame (0) each matrix maps a joint's
    // bind position to where it is drawn.
    let pose = &v.state().stage.actors[0].extra.pose;
    let bind = v.state().stage.actors[0].clip().unwrap().bind_pose();
    for (j, m) in body.matrices.iter().enumerate() {
        let at = m.transform_point3(bind[j].translation);
        assert!(at.distance(pose[j].translation) < 1e-3, "joint {j}: {at} vs {}", pose[j].translation);
    }
    let fragment = v.state().view_fragment();
    assert!(fragment.contains("mode=body") && fragment.contains("weights"), "{fragment}");
    // Another frame moves the matrices.
    let at_zero = body.matrices.clone();
    v.apply(Command::Seek(20)).unwrap();
    v.pose();
    assert_ne!(v.scene().skinned[0].matrices, at_zero);
}

#[test]
fn m_cycles_capsules_sticks_body() {
    let mut v = Viewer::default();
    v.load("walk.bvh", WALK).unwrap();
    let mut seen = Vec::new();
    for _ in 0..3 {
        v.apply(Command::ToggleDrawMode).unwrap();
        seen.push(v.state().settings.mode);
    }
    assert_eq!(seen, [DrawMode::Sticks, DrawMode::Body, DrawMode::Capsules]);
}

#[test]
fn a_skeleton_too_big_for_a_body_keeps_its_capsules() {
    let depth = mocap::build::body::MAX_BODY_BONES + 10;
    let mut text = String::from("HIERARCHY\nROOT j0\n{\nOFFSET 0 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n");
    for i in 1..depth {
        text.push_str(&format!("JOINT j{i}\n{{\nOFFSET 0 0.01 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n"));
    }
    text.push_str("End Site\n{\nOFFSET 0 0.01 0\n}\n");
    text.push_str(&"}\n".repeat(depth));
    text.push_str("MOTION\nFrames: 1\nFrame Time: 0.1\n");
    text.push_str(&"0 0 0 ".repeat(depth));
    text.push('\n');
    let mut v = Viewer::default();
    v.load("deep.bvh", text.as_bytes()).unwrap();
    let mut edited = v.state().settings.clone();
    edited.mode = DrawMode::Body;
    v.apply(Command::SetSettings(edited)).unwrap();
    v.pose();
    assert!(v.scene().skinned.is_empty());
    assert!(v.scene().capsules.len() > 100, "drawn as capsules instead");
    v.pose();
    assert!(v.scene().skinned.is_empty(), "the build is not retried every frame");
}

#[test]
fn the_bodys_bounds_hold_the_posed_body_where_it_is_drawn() {
    // The shadow map is fitted to these bounds: a box elsewhere left body mode
    // without its shadow.
    let mut v = Viewer::default();
    v.load("walk.bvh", WALK).unwrap();
    v.apply(Command::SetPlaying(false)).unwrap();
    v.apply_fragment("mode=body");
    let c = &v.state().stage.actors[0];
    let skin = mocap_scene::body_skin(c.clip().unwrap(), c.extent).expect("a body");
    for frame in [0, 20, 40, 60] {
        v.apply(Command::Seek(frame)).unwrap();
        v.pose();
        let draw = &v.scene().skinned[0];
        let (lo, hi) = draw.world_bounds().expect("bounds");
        let (mut positions, mut normals) = (Vec::new(), Vec::new());
        mocap::runtime::skin::skin_vertices(&skin, &draw.matrices, &mut positions, &mut normals);
        let (mut vlo, mut vhi) = (mocap::glam::Vec3::INFINITY, mocap::glam::Vec3::NEG_INFINITY);
        for p in &positions {
            assert!(
                p.cmpge(lo - 1e-4).all() && p.cmple(hi + 1e-4).all(),
                "frame {frame}: vertex {p} outside {lo}..{hi}"
            );
            (vlo, vhi) = (vlo.min(*p), vhi.max(*p));
        }
        for t in v.state().stage.actors[0].extra.pose.iter() {
            assert!(
                t.translation.cmpge(lo).all() && t.translation.cmple(hi).all(),
                "frame {frame}: joint {} outside",
                t.translation
            );
        }
        // And no looser than a fifth of the body's height on any side (each
        // joint's box is turned with it, and the box around that is larger).
        let slack = (vhi.y - vlo.y) * 0.2;
        assert!(
            (vlo - lo).max_element() < slack && (hi - vhi).max_element() < slack,
            "frame {frame}: {lo}..{hi} around {vlo}..{vhi}"
        );
    }
}
