//! Quake 2 MD2 models in the viewer (no GPU): opening with a skin, animations on
//! the timeline and in the fragment, the mesh primitive the renderer gets, and the
//! whole UI drawing a model. Reads the corpus (`../shared/corpus`; a failure when
//! missing unless `MOCAP_SKIP_CORPUS=1`).

use mocap_viewer::Command;
use mocap_viewer::{OpenMode, Viewer};
use std::path::{Path, PathBuf};

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");

fn corpus_dir() -> Option<PathBuf> {
    let dir = std::env::var_os("MOCAP_CORPUS")
        .map(PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus"));
    if dir.join("MANIFEST.tsv").is_file() {
        return Some(dir);
    }
    if std::env::var("MOCAP_SKIP_CORPUS").is_ok_and(|v| v == "1") {
        return None;
    }
    panic!(
        "{}: corpus not found (put ../shared beside the repository, or opt out with MOCAP_SKIP_CORPUS=1)",
        dir.display()
    );
}

/// A viewer with the faerie and its BMP skin open (dropped together), paused at 0.
fn faerie() -> Option<Viewer> {
    let dir = corpus_dir()?.join("md2/irrlicht_faerie");
    let model = std::fs::read(dir.join("faerie.md2")).unwrap();
    let skin = std::fs::read(dir.join("faerie2.bmp")).unwrap();
    let mut v = Viewer::default();
    let errors = v.open_files(&[("faerie.md2", &model), ("faerie2.bmp", &skin)], OpenMode::Replace);
    assert!(errors.is_empty(), "{errors:?}");
    v.apply(Command::SetPlaying(false)).unwrap();
    Some(v)
}

#[test]
fn a_model_opens_with_its_skin_and_animations() {
    let Some(v) = faerie() else { return };
    let s = v.snapshot();
    assert_eq!(s.clips.len(), 1, "the image is the skin, not a character");
    let c = &s.clips[0];
    assert_eq!((c.name.as_str(), c.frames, c.joints, c.skin.as_deref()), ("faerie.md2", 198, 0, Some("faerie2.bmp")));
    assert_eq!(c.animation.as_deref(), Some("all"));
    assert_eq!(c.animations.len(), 20);
    assert!((c.frame_time - 0.1).abs() < 1e-12, "Quake 2 plays models at 10 fps");
}

#[test]
fn choosing_an_animation_sets_the_timeline_and_the_fragment() {
    let Some(mut v) = faerie() else { return };
    assert!(v.try_apply(Command::SetAnimation(0, "run".into())).is_ok());
    assert!(
        !v.try_apply(Command::SetAnimation(0, "fly".into())).is_ok()
            && !v.try_apply(Command::SetAnimation(3, "run".into())).is_ok()
    );
    let s = v.snapshot();
    assert_eq!((s.clips[0].frames, s.clips[0].animation.as_deref()), (6, Some("run")));
    v.apply(Command::Seek(2)).unwrap();
    v.pose();
    assert_eq!(v.snapshot().clips[0].model_frame, Some((42, "run3".to_owned())));
    let fragment = v.state().view_fragment();
    assert!(fragment.contains("anim=1:run"), "{fragment}");
    let Some(mut again) = faerie() else { return };
    again.apply_fragment(&fragment);
    again.pose();
    let s = again.snapshot();
    assert_eq!((s.clips[0].animation.as_deref(), s.frame), (Some("run"), 2));
    assert_eq!(s.clips[0].model_frame, Some((42, "run3".to_owned())));
    again.apply_fragment("anim=none");
    assert_eq!(again.snapshot().clips[0].animation.as_deref(), Some("all"));
}

#[test]
fn the_renderer_gets_two_frames_and_a_blend_or_the_nearest_frame() {
    let Some(mut v) = faerie() else { return };
    v.try_apply(Command::SetAnimation(0, "run".into())).unwrap();
    v.apply(Command::SetTime(0.15)).unwrap();
    v.apply(Command::SetPlaying(true)).unwrap();
    let mut edited = v.state().settings.clone();
    edited.between = mocap::Interpolation::Linear;
    v.apply(Command::SetSettings(edited)).unwrap();
    v.pose();
    let mesh = &v.scene().meshes;
    assert_eq!(mesh.len(), 1);
    assert_eq!((mesh[0].frames, mesh[0].blend), ([41, 42], 0.5));
    assert_eq!(mesh[0].tint, [255; 4], "textured: the skin's own colours");
    assert!(v.scene().capsules.is_empty() && v.scene().grid.is_some());
    // Interpolation off: switch at the halfway point (frame 1.5 of run shows 42).
    let mut edited = v.state().settings.clone();
    edited.between = mocap::Interpolation::Nearest;
    v.apply(Command::SetSettings(edited)).unwrap();
    v.pose();
    assert_eq!((v.scene().meshes[0].frames, v.scene().meshes[0].blend), ([42, 42], 0.0));
    v.try_apply(Command::SetVisible(0, false)).unwrap();
    v.pose();
    assert!(v.scene().meshes.is_empty());
}

#[test]
fn a_model_and_a_bvh_stand_side_by_side_at_one_scale() {
    let Some(mut v) = faerie() else { return };
    v.add("walk.bvh", WALK).unwrap();
    v.pose();
    let stage = &v.state().stage;
    let model = stage.actors[0].world_bounds();
    let walk = stage.actors[1].world_bounds();
    assert!(model.max.x < walk.min.x, "separate lanes");
    let (h_model, h_walk) = (model.size().y, walk.size().y);
    assert!((0.5..2.5).contains(&h_model) && (1.2..2.2).contains(&h_walk), "{h_model} m and {h_walk} m");
    let mesh = &v.scene().meshes[0];
    let (lo, _) = mesh.world_bounds().unwrap();
    assert!((lo.y - model.min.y).abs() < 1e-3, "the mesh is drawn where the stage placed it");
    // Both stand on the floor: the model on its standing frame's feet (its death
    // frames reach lower), the clip on its lowest point.
    let floor = v.scene().grid.as_ref().expect("a floor").center.y;
    assert!((floor - stage.floor_height()).abs() < 1e-5);
    for a in &stage.actors {
        assert!(
            (a.world_ground() - floor).abs() < 1e-3,
            "{} stands at {} over a floor at {floor}",
            a.name,
            a.world_ground()
        );
    }
    assert!(model.min.y < floor - 0.05, "the faerie's death frames sink below the floor ({} vs {floor})", model.min.y);
}

#[test]
fn the_ui_draws_a_model_with_its_panels() {
    let Some(mut v) = faerie() else { return };
    let ctx = egui::Context::default();
    for (i, t) in [0.0, 0.1, 0.2].into_iter().enumerate() {
        let input = egui::RawInput {
            time: Some(t),
            screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, egui::vec2(1280.0, 800.0))),
            ..Default::default()
        };
        let mut output = ctx.run_ui(input, |ui| {
            v.ui(ui, None);
        });
        output.textures_delta.clear();
        if i == 0 {
            v.apply(Command::SetPlaying(true)).unwrap();
        }
    }
    let s = v.snapshot();
    assert!(s.error.is_none() && s.time > 0.0);
    assert!(s.tree_labels.is_empty(), "a model has no joints to list");
}

#[test]
fn capture_skeleton_adds_a_clip_inside_the_model_and_its_rig_can_be_saved_and_dropped_back() {
    let Some(mut v) = faerie() else { return };
    assert!(v.try_apply(Command::StartCapture(0)).is_ok());
    let (done, total) = v.state().capture_progress().unwrap();
    assert!(done == 0 && total > 198, "joints then frames: {total} steps");
    // A few budgets of work: progress moves, nothing is added yet.
    v.step_capture();
    let (later, _) = v.state().capture_progress().unwrap_or((total, total));
    assert!(later > 0);
    v.apply(Command::FinishCapture).unwrap();
    assert!(v.state().capture_progress().is_none());
    let s = v.snapshot();
    assert_eq!(s.clips.len(), 2);
    assert_eq!(s.clips[1].name, "faerie-capture.bvh");
    assert_eq!(s.clips[1].frames, 198);
    assert_eq!(s.layout, "overlay", "the skeleton shows inside the mesh");
    assert_eq!(s.clips[0].animation.as_deref(), Some("all"), "the model plays every frame, in step with the clip");
    // Where they are drawn, the skeleton's joints are inside the model's mesh.
    v.pose();
    let (lo, hi) = v.scene().meshes[0].world_bounds().expect("the model is drawn");
    let grow = (hi - lo) * 0.05;
    for t in v.state().stage.actors[1].extra.pose.iter() {
        let p = t.translation;
        assert!(p.cmpge(lo - grow).all() && p.cmple(hi + grow).all(), "joint at {p} outside the model's {lo}..{hi}");
    }
    let result = v.state().capture_result.clone().unwrap();
    assert!(result.report.joints.iter().filter(|j| j.tracked.is_ok()).count() > 15);
    assert!(result.animations.iter().any(|(n, a, b)| n == "run" && b - a == 5));
    // Save rig downloads JSON; dropped back, the next capture uses it.
    let (name, json) = v.rig_download().unwrap();
    assert_eq!(name, "faerie-rig.json");
    assert!(v.open_files(&[("faerie-rig.json", json.as_bytes())], OpenMode::Add).is_empty());
    assert!(v.state().capture_rig.is_some() && v.snapshot().clips.len() == 2, "a rig is kept, not opened");
    v.try_apply(Command::StartCapture(0)).unwrap();
    v.apply(Command::FinishCapture).unwrap();
    assert_eq!(v.snapshot().clips.len(), 3);
    assert_eq!(v.state().capture_result.as_ref().unwrap().rig, result.rig, "the dropped rig was used");
    // A bad rig, a rig for another model, a clip: clear errors, nothing lost.
    let errors = v.open_files(&[("bad.json", b"{\"format\": 1}")], OpenMode::Add);
    assert!(errors[0].starts_with("bad.json: rig:"), "{errors:?}");
    let mut other = result.rig.clone();
    other.binding.truncate(10);
    assert!(v.open_files(&[("other-rig.json", other.to_json().as_bytes())], OpenMode::Add).is_empty());
    assert!(v.try_apply(Command::StartCapture(0)).unwrap_err().contains("binds 10 vertices"));
    assert!(v.try_apply(Command::StartCapture(1)).unwrap_err().contains("only a model"));
    assert_eq!(v.snapshot().clips.len(), 3);
}

#[test]
fn a_rig_is_set_up_by_hand_and_used_by_the_capture() {
    use mocap::glam::Vec3;
    use mocap_viewer::rig_edit::{RIG_JOINT, RIG_SPIN};
    let Some(mut v) = faerie() else { return };
    v.try_apply(Command::FitRig { model: 0, template: None }).unwrap();
    let handles = v.rig_handles();
    let joints = v.state().rig_edit.as_ref().unwrap().rig.joints.len();
    assert_eq!(handles.iter().filter(|h| h.character == RIG_JOINT).count(), joints);
    assert!(handles.iter().any(|h| h.character == RIG_SPIN));
    assert_eq!(v.handles().len(), handles.len(), "while a rig is set up, its handles are the ones grabbed");
    // Drag the left hand 5 cm up: the rig joint follows (file units).
    let hand = v.state().rig_edit.as_ref().unwrap().rig.joints.iter().position(|j| j.name == "LeftHand").unwrap();
    let h = *handles.iter().find(|h| h.character == RIG_JOINT && h.joint == hand).unwrap();
    let before = Vec3::from_array(v.state().rig_edit.as_ref().unwrap().rig.joints[hand].position);
    v.drag_rig(h, h.world + Vec3::new(0.0, 0.05, 0.0), egui::Pos2::ZERO);
    let after = Vec3::from_array(v.state().rig_edit.as_ref().unwrap().rig.joints[hand].position);
    assert!((after - before - Vec3::new(0.0, 0.05 / 0.0254, 0.0)).length() < 1e-3, "{before} → {after}");
    assert_eq!(v.state().rig_edit.as_ref().unwrap().selected, Some(hand));
    // A spin handle turns the bone's spin, kept across it.
    let s = *handles.iter().find(|h| h.character == RIG_SPIN).unwrap();
    v.drag_rig(s, s.world + Vec3::new(0.0, 0.0, 0.1), egui::Pos2::ZERO);
    let rig = v.state().rig_edit.as_ref().unwrap().rig.clone();
    let j = &rig.joints[s.joint];
    let child = rig.children()[s.joint][0];
    let axis = (Vec3::from_array(rig.joints[child].position) - Vec3::from_array(j.position)).normalize();
    assert!(Vec3::from_array(j.spin.unwrap()).dot(axis).abs() < 1e-4);
    v.apply(Command::BindRig).unwrap();
    v.apply(Command::FinishRigEdit).unwrap();
    assert!(v.state().rig_edit.is_none());
    v.try_apply(Command::StartCapture(0)).unwrap();
    v.apply(Command::FinishCapture).unwrap();
    assert_eq!(
        v.state().capture_result.as_ref().unwrap().rig.joints[hand].position,
        after.to_array(),
        "the capture used the rig set up"
    );
    assert!(v.try_apply(Command::FitRig { model: 1, template: None }).unwrap_err().contains("on a model"));
}

#[test]
fn closing_characters_keeps_the_rig_and_the_capture_on_their_model() {
    let Some(mut v) = faerie() else { return };
    v.add("walk.bvh", WALK).unwrap();
    // Model second: close the walk before it, the rig follows the model.
    let dir = corpus_dir().unwrap().join("md2/irrlicht_faerie");
    v.add("faerie.md2", &std::fs::read(dir.join("faerie.md2")).unwrap()).unwrap();
    v.try_apply(Command::FitRig { model: 2, template: None }).unwrap();
    v.try_apply(Command::StartCapture(0)).unwrap();
    assert!(v.try_apply(Command::CloseNow(1)).is_ok());
    assert_eq!(v.state().rig_edit.as_ref().map(|e| e.model), Some(1));
    assert!(v.try_apply(Command::CloseNow(0)).is_ok(), "closing the model being captured ends the capture");
    assert!(v.state().capture_job.is_none() && v.state().rig_edit.as_ref().map(|e| e.model) == Some(0));
    v.load("walk.bvh", WALK).unwrap();
    assert!(v.state().rig_edit.is_none(), "opening files in place of everything ends the set-up");
}

#[test]
fn a_model_saves_as_gltf_and_opens_again_as_the_same_model() {
    let Some(mut v) = faerie() else { return };
    let (name, bytes) = v.save_gltf(0).expect("a model saves as glTF");
    assert_eq!(name, "faerie.glb");
    let errors = v.open_files(&[("faerie.glb", &bytes)], OpenMode::Add);
    assert!(errors.is_empty(), "{errors:?}");
    let s = v.snapshot();
    let (a, b) = (&s.clips[0], &s.clips[1]);
    assert_eq!((b.frames, b.animations.len()), (a.frames, a.animations.len()), "every frame and animation");
    assert!(b.skin.is_some(), "its skin came along");
    // The same shape at the same frame.
    let (m, n) = (v.state().stage.actors[0].model().unwrap(), v.state().stage.actors[1].model().unwrap());
    for (p, q) in m.mesh.frame_positions(42).iter().zip(n.mesh.frame_positions(42)) {
        assert!((0..3).all(|k| (p[k] - q[k]).abs() < 1e-3), "{p:?} vs {q:?}");
    }
}
