//! A Z-up clip (no GPU): the viewer guesses its up axis and stands it up, the user
//! can set it (Clip panel, fragment, API), and dragging a joint by IK and reading
//! a root's rotation work in its turned axes.

mod support;

use mocap::glam::{Quat, Vec3};
use mocap_viewer::Command;
use mocap_viewer::Viewer;

/// A 2 m figure standing along +Z (legs down to z = 0, arms along X), walking
/// along +Y over 10 frames.
fn z_up_bvh() -> String {
    let mut s = String::from(
        "HIERARCHY\nROOT Hips\n{\nOFFSET 0 0 1\nCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n",
    );
    s.push_str("JOINT Chest\n{\nOFFSET 0 0 0.5\nCHANNELS 3 Zrotation Xrotation Yrotation\n");
    s.push_str(
        "JOINT Head\n{\nOFFSET 0 0 0.3\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{\nOFFSET 0 0 0.2\n}\n}\n",
    );
    for (name, x) in [("LeftArm", 0.2), ("RightArm", -0.2)] {
        s.push_str(&format!("JOINT {name}\n{{\nOFFSET {x} 0 0.3\nCHANNELS 3 Zrotation Xrotation Yrotation\nJOINT {name}Fore\n{{\nOFFSET {} 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{{\nOFFSET {} 0 0\n}}\n}}\n}}\n", x * 1.5, x * 1.5));
    }
    s.push_str("}\n");
    for (name, x) in [("LeftLeg", 0.1), ("RightLeg", -0.1)] {
        s.push_str(&format!("JOINT {name}\n{{\nOFFSET {x} 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nJOINT {name}Knee\n{{\nOFFSET 0 0 -0.5\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{{\nOFFSET 0 0 -0.5\n}}\n}}\n}}\n"));
    }
    s.push_str("}\nMOTION\nFrames: 10\nFrame Time: 0.1\n");
    for f in 0..10 {
        s.push_str(&format!("0 {} 1{}\n", f as f32 * 0.05, " 0".repeat(3 + 3 * 10)));
    }
    s
}

fn height(v: &Viewer) -> f32 {
    v.state().stage.actors[0].world_bounds().size().y
}

#[test]
fn a_z_up_clip_stands_up_and_the_axis_can_be_set() {
    let mut v = Viewer::default();
    v.load("zup.bvh", z_up_bvh().as_bytes()).unwrap();
    v.apply(Command::SetPlaying(false)).unwrap();
    v.pose();
    let s = v.snapshot();
    assert_eq!(s.clips[0].up, "z", "guessed from the motion");
    assert!((height(&v) - 2.0).abs() < 0.05, "it stands 2 m tall: {}", height(&v));
    assert!((v.state().stage.actors[0].world_ground() - v.state().stage.floor_height()).abs() < 1e-4, "on the floor");
    assert!(v.state().view_fragment().contains("up=z"), "{}", v.state().view_fragment());
    // Read as Y-up it lies on its back.
    assert!(v.try_apply(Command::SetUpAxis(0, mocap::UpAxis::Y)).is_ok());
    assert_eq!(v.snapshot().clips[0].up, "y");
    assert!(height(&v) < 0.5, "lying: {} m high", height(&v));
    // The fragment sets it back.
    v.apply_fragment("up=z");
    assert_eq!(v.snapshot().clips[0].up, "z");
    assert!((height(&v) - 2.0).abs() < 0.05);
    v.apply_fragment("up=q");
    assert_eq!(v.snapshot().clips[0].up, "z", "an unknown axis changes nothing");
}

#[test]
fn joints_are_dragged_and_read_in_the_turned_axes() {
    let mut v = Viewer::default();
    v.load("zup.bvh", z_up_bvh().as_bytes()).unwrap();
    v.apply(Command::SetPlaying(false)).unwrap();
    v.apply(Command::Seek(0)).unwrap();
    v.pose();
    let c = &v.state().stage.actors[0];
    // The root's local rotation (none in the file) reads as none, not as the turn.
    let root = mocap_viewer::character::drawn_local_rotation(c, 0).unwrap();
    assert!(root.angle_between(Quat::IDENTITY) < 1e-4, "{root:?}");
    // A hand dragged in the world reaches the target.
    let hand = c.clip().unwrap().skeleton().find("LeftArmFore").unwrap();
    let before = c.extra.pose[hand].translation;
    let target = before + Vec3::new(-0.1, 0.15, 0.1);
    let solve = v.drag_joint(0, hand, target).unwrap();
    assert!(solve.reached, "{solve:?}");
    assert!(
        v.state().stage.actors[0].extra.pose[hand].translation.distance(target) < 1e-3,
        "{} vs {target}",
        v.state().stage.actors[0].extra.pose[hand].translation
    );
}

#[test]
fn edits_keep_an_axis_set_by_hand_and_standing_the_file_up_guesses_again() {
    let mut v = Viewer::default();
    v.load("zup.bvh", z_up_bvh().as_bytes()).unwrap();
    v.apply(Command::SetPlaying(false)).unwrap();
    // The Edit menu's "Stand up a Z-up file" rewrites the data Y-up: still standing.
    v.try_apply(Command::Edit {
        character: 0,
        edit: mocap::ops::edit::Edit::UpAxis { from: 2, negative: false },
        label: "Stand up".into(),
    })
    .unwrap();
    v.pose();
    assert_eq!(v.snapshot().clips[0].up, "y", "the rewritten file is guessed Y-up");
    assert!((height(&v) - 2.0).abs() < 0.05, "{}", height(&v));
    support::undo(&mut v);
    assert_eq!(v.snapshot().clips[0].up, "z");
    // An axis set by hand survives an edit.
    assert!(v.try_apply(Command::SetUpAxis(0, mocap::UpAxis::Y)).is_ok());
    v.try_apply(Command::Edit { character: 0, edit: mocap::ops::edit::Edit::Reverse, label: "Reverse".into() })
        .unwrap();
    assert_eq!(v.snapshot().clips[0].up, "y");
}
