//! Runs the whole egui UI headlessly (no GPU) for a few frames: panels, tree,
//! inspector plot, error banner and keyboard shortcuts must not panic.

use mocap_viewer::Command;
use mocap_viewer::Viewer;

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");

fn frame(ctx: &egui::Context, viewer: &mut Viewer, time: f64, events: Vec<egui::Event>) {
    let input = egui::RawInput {
        time: Some(time),
        screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(1280.0, 800.0))),
        events,
        ..Default::default()
    };
    let mut output = ctx.run_ui(input, |ui| {
        viewer.ui(ui, None);
    });
    output.textures_delta.clear();
}

fn key(key: egui::Key) -> egui::Event {
    egui::Event::Key { key, physical_key: None, pressed: true, repeat: false, modifiers: egui::Modifiers::NONE }
}

#[test]
fn ui_runs_plays_and_reacts_to_keys() {
    let ctx = egui::Context::default();
    let mut v = Viewer::default();
    frame(&ctx, &mut v, 0.0, vec![]);
    v.load("walk.bvh", WALK).unwrap();
    v.apply(Command::Select { character: v.state().current(), joint: Some(7) }).unwrap();
    frame(&ctx, &mut v, 0.0, vec![]);
    frame(&ctx, &mut v, 0.2, vec![]);
    assert_eq!(v.state().frame(), 6, "0.2 s at 30 fps");
    frame(&ctx, &mut v, 0.3, vec![key(egui::Key::Space)]);
    assert!(!v.state().playback.playing);
    let f = v.state().frame();
    frame(&ctx, &mut v, 0.4, vec![key(egui::Key::ArrowRight)]);
    assert_eq!(v.state().frame(), f + 1);
    frame(&ctx, &mut v, 0.5, vec![key(egui::Key::End)]);
    assert_eq!(v.state().frame(), 66);
    frame(&ctx, &mut v, 0.6, vec![key(egui::Key::Home), key(egui::Key::A), key(egui::Key::F), key(egui::Key::Num3)]);
    assert_eq!(v.state().frame(), 0);
    assert!(v.state().settings.show_axes && v.state().settings.follow_root);
    let _ = v.load("bad.bvh", b"HIERARCHY\nJOINT");
    frame(&ctx, &mut v, 0.7, vec![]);
    let s = v.snapshot();
    assert!(s.error.is_some());
    assert!(s.tree_labels.iter().any(|l| l == "LeftForeArm"), "tree drawn: {:?}", s.tree_labels);
}

#[test]
fn ui_draws_several_characters() {
    let ctx = egui::Context::default();
    let mut v = Viewer::default();
    v.load("walk.bvh", WALK).unwrap();
    v.add("again.bvh", WALK).unwrap();
    v.try_apply(Command::SetVisible(0, false)).unwrap();
    v.apply(Command::Select { character: 1, joint: Some(4) }).unwrap();
    frame(&ctx, &mut v, 0.0, vec![]);
    frame(&ctx, &mut v, 0.1, vec![key(egui::Key::Space), key(egui::Key::ArrowRight)]);
    let s = v.snapshot();
    assert_eq!(s.clips.len(), 2);
    let hips = s.tree_labels.iter().filter(|l| *l == "Hips").count();
    assert_eq!(hips, 2, "one joint tree per character: {:?}", s.tree_labels);
    assert_eq!((s.selected_character, s.selected_joint.as_deref()), (Some(1), Some("Head")));
    v.try_apply(Command::CloseNow(0)).unwrap();
    frame(&ctx, &mut v, 0.2, vec![]);
    assert_eq!(v.snapshot().tree_labels.iter().filter(|l| *l == "Hips").count(), 1);
}

/// A valid BVH whose joints nest `depth` levels deep (a chain), one frame.
fn deep_bvh(depth: usize) -> Vec<u8> {
    let mut s = String::from("HIERARCHY\nROOT j0\n{\nOFFSET 0 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n");
    for i in 1..depth {
        s.push_str(&format!("JOINT j{i}\n{{\nOFFSET 0 0.01 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n"));
    }
    s.push_str("End Site\n{\nOFFSET 0 0.01 0\n}\n");
    s.push_str(&"}\n".repeat(depth));
    s.push_str("MOTION\nFrames: 1\nFrame Time: 0.033333\n");
    s.push_str(&"1 2 3 ".repeat(depth));
    s.push('\n');
    s.into_bytes()
}

#[test]
fn a_200000_level_deep_skeleton_opens_draws_and_a_good_file_follows() {
    // Run on a thread with a small stack (as a wasm page has): nothing may recurse on depth.
    let worker = std::thread::Builder::new().stack_size(1 << 20).spawn(|| {
        let ctx = egui::Context::default();
        let mut v = Viewer::default();
        v.load("deep.bvh", &deep_bvh(200_000)).expect("a deep file is valid");
        v.try_apply(Command::SelectNamed { character: 0, name: "j199999".into() }).unwrap();
        frame(&ctx, &mut v, 0.0, vec![]);
        frame(&ctx, &mut v, 0.1, vec![key(egui::Key::ArrowRight)]);
        let s = v.snapshot();
        assert_eq!(s.clips[0].joints, 200_000);
        assert_eq!(s.selected_joint.as_deref(), Some("j199999"));
        assert!(s.tree_labels.len() >= 1000, "the tree lists the chain: {}", s.tree_labels.len());
        v.load("walk.bvh", WALK).expect("a good file after the deep one");
        frame(&ctx, &mut v, 0.2, vec![]);
        assert!(v.snapshot().tree_labels.iter().any(|l| l == "LeftForeArm"));
    });
    worker.unwrap().join().expect("no stack overflow");
}

#[test]
fn a_held_view_keeps_its_playhead_and_asks_for_no_frames() {
    let ctx = egui::Context::default();
    let mut v = Viewer::default();
    v.load("walk.bvh", WALK).unwrap();
    let asks_for_frames = |ctx: &egui::Context, v: &mut Viewer, time: f64| {
        let input = egui::RawInput { time: Some(time), ..Default::default() };
        let mut output = ctx.run_ui(input, |ui| {
            v.ui(ui, None);
        });
        output.textures_delta.clear();
        output.viewport_output.values().any(|o| o.repaint_delay.is_zero())
    };
    assert!(asks_for_frames(&ctx, &mut v, 0.0), "playing asks for the next frame");
    assert!(asks_for_frames(&ctx, &mut v, 0.1));
    let f = v.state().frame();
    assert_eq!(f, 3, "0.1 s at 30 fps");
    v.hold(true);
    assert!(v.is_held());
    // egui itself paints once more after a frame that asked for one.
    asks_for_frames(&ctx, &mut v, 0.2);
    assert!(!asks_for_frames(&ctx, &mut v, 0.3), "held: no frame asked for");
    assert!(!asks_for_frames(&ctx, &mut v, 0.4));
    assert_eq!(v.state().frame(), f, "held: the playhead stays");
    v.hold(false);
    assert!(asks_for_frames(&ctx, &mut v, 0.5), "let go: frames again");
    assert_eq!(v.state().frame(), f, "no jump over the hold");
    asks_for_frames(&ctx, &mut v, 0.6);
    assert_eq!(v.state().frame(), f + 3, "then real time again");
}
