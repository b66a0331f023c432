//! Commands change the viewer; requests to the page come back from the frame
//! (no flags); a refused command says why in the banner and changes nothing.

use mocap_viewer::{Command, HostRequest, OpenMode, Viewer};

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");

/// One frame of the whole UI (no GPU), returning what it asks of the page.
fn frame(ctx: &egui::Context, v: &mut Viewer, time: f64) -> Vec<HostRequest> {
    let input = egui::RawInput {
        time: Some(time),
        screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(1280.0, 800.0))),
        ..Default::default()
    };
    let mut requests = Vec::new();
    let mut out = ctx.run_ui(input, |ui| requests = v.ui(ui, None));
    out.textures_delta.clear();
    requests
}

#[test]
fn requests_to_the_page_are_returned_by_the_frame_once() {
    let ctx = egui::Context::default();
    let mut v = Viewer::default();
    v.load("walk.bvh", WALK).unwrap();
    frame(&ctx, &mut v, 0.0);
    v.apply(Command::Open(OpenMode::Add)).unwrap();
    v.apply(Command::Share).unwrap();
    v.apply(Command::SaveBvh).unwrap();
    let requests = frame(&ctx, &mut v, 0.1);
    assert_eq!(requests.len(), 3, "{requests:?}");
    assert_eq!(requests[0], HostRequest::PickFiles(OpenMode::Add));
    assert_eq!(requests[1], HostRequest::Share);
    match &requests[2] {
        HostRequest::Save { name, bytes } => {
            assert_eq!(name, "walk.bvh");
            assert_eq!(bytes, mocap::formats::bvh::write(v.state().stage.actors[0].clip().unwrap()).as_bytes());
        }
        other => panic!("expected a save, got {other:?}"),
    }
    assert!(frame(&ctx, &mut v, 0.2).is_empty(), "each request is handed over once");
}

#[test]
fn a_refused_command_says_why_and_changes_nothing() {
    let mut v = Viewer::default();
    v.load("walk.bvh", WALK).unwrap();
    let before = v.snapshot();
    v.apply(Command::SetAnimation(0, "run".to_owned())).unwrap_err();
    let notice = v.state().notice.clone().expect("a notice");
    assert!(notice.headline().contains("no animation `run`"), "{}", notice.headline());
    v.apply(Command::GrowBone("Tail".to_owned())).unwrap_err();
    assert!(v.state().notice.as_ref().unwrap().headline().contains("select a joint"), "{:?}", v.state().notice);
    v.apply(Command::Edit {
        character: 0,
        edit: mocap::ops::edit::Edit::Trim { first: 50, last: 10 },
        label: "Trim".into(),
    })
    .unwrap_err();
    assert!(v.state().notice.as_ref().unwrap().headline().starts_with("Could not do that: "), "{:?}", v.state().notice);
    let after = v.snapshot();
    assert_eq!(after.clips, before.clips, "nothing changed");
    assert!(v.take_requests().is_empty());
    v.apply(Command::DismissNotice).unwrap();
    assert!(v.state().notice.is_none());
}

#[test]
fn the_keys_help_lists_every_binding_from_the_one_table() {
    let help = mocap_viewer::keys::help();
    for b in &mocap_viewer::keys::BINDINGS {
        assert!(help.contains(b.written), "{} missing from the help: {help}", b.written);
        assert!(b.command.tooltip().contains(b.written), "{:?}: {}", b.command, b.command.tooltip());
    }
    assert!(help.contains("k in Edit mode"));
}

#[test]
fn save_as_gltf_asks_the_page_to_save_the_edited_clip_as_glb() {
    let ctx = egui::Context::default();
    let mut v = Viewer::default();
    v.load("walk.bvh", WALK).unwrap();
    v.try_apply(Command::Edit { character: 0, edit: mocap::ops::edit::Edit::Reverse, label: "Reverse".into() })
        .unwrap();
    frame(&ctx, &mut v, 0.0);
    v.apply(Command::SaveGltf).unwrap();
    let requests = frame(&ctx, &mut v, 0.1);
    let [HostRequest::Save { name, bytes }] = requests.as_slice() else { panic!("one save: {requests:?}") };
    assert_eq!(name, "walk-edited.glb");
    let clip = v.state().stage.actors[0].clip().unwrap();
    let options = mocap::formats::gltf::Options { name: "walk-edited".into(), body: true };
    assert_eq!(bytes, &mocap::formats::gltf::to_glb(clip, &options).unwrap(), "the edited clip, as the core writes it");
    assert_eq!(&bytes[..4], b"glTF");
}
