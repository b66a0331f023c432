//! glTF characters in the viewer (no GPU): a GLB with two animations opens as
//! one character whose own look is drawn untinted in the default look, its
//! animations are chosen like a model's (menu, command, fragment), and sticks
//! mode shows its skeleton.

use mocap::formats::gltf::{Options, to_glb};
use mocap_render::DrawMode;
use mocap_viewer::{Command, OpenMode, Viewer};

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");

/// The walk as GLB with a second animation: the first one, turned 90° about Y
/// at the hips (so the two differ).
fn two_takes() -> Vec<u8> {
    let clip = mocap::formats::bvh::parse(WALK).unwrap();
    let glb = to_glb(&clip, &Options { name: "walk".into(), body: true }).unwrap();
    let json_len = u32::from_le_bytes(glb[12..16].try_into().unwrap()) as usize;
    let mut json: serde_json::Value = serde_json::from_slice(&glb[20..20 + json_len]).unwrap();
    let mut second = json["animations"][0].clone();
    second["name"] = "turned".into();
    // Keep only the channels of nodes other than the hips' rotation: the hips hold their rest rotation.
    let channels: Vec<serde_json::Value> = second["channels"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|c| !(c["target"]["node"] == 0 && c["target"]["path"] == "rotation"))
        .cloned()
        .collect();
    second["channels"] = channels.into();
    json["animations"].as_array_mut().unwrap().push(second);
    let mut text = serde_json::to_vec(&json).unwrap();
    while text.len() % 4 != 0 {
        text.push(b' ');
    }
    let bin = &glb[20 + json_len..];
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend(((20 + text.len() + bin.len()) as u32).to_le_bytes());
    out.extend((text.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(&text);
    out.extend(bin);
    out
}

#[test]
fn a_glb_character_opens_with_its_look_and_its_animations() {
    let glb = two_takes();
    let mut v = Viewer::default();
    let errors = v.open_files(&[("walk.glb", &glb)], OpenMode::Replace);
    assert!(errors.is_empty(), "{errors:?}");
    v.apply(Command::SetPlaying(false)).unwrap();
    let s = v.snapshot();
    assert_eq!(s.clips.len(), 1);
    assert_eq!(s.clips[0].animations, ["walk", "turned"]);
    assert_eq!(s.clips[0].animation.as_deref(), Some("walk"));
    assert_eq!(s.clips[0].frames, 67);

    // The default look draws the character's own mesh, untinted, and no capsules.
    assert_eq!(v.state().settings.mode, DrawMode::default());
    v.pose();
    let scene = v.scene();
    assert_eq!(scene.skinned.len(), 1, "its own look");
    assert_eq!(scene.skinned[0].tint, [255; 4], "drawn in its own colours");
    assert!(scene.capsules.is_empty(), "the look stands for the bones");
    let vertices = scene.skinned[0].mesh.vertex_count();
    assert!(vertices > 1000, "{vertices} vertices");
    let at_walk = scene.skinned[0].matrices.clone();

    // Another animation by command; the fragment carries it to a fresh page.
    assert!(v.try_apply(Command::SetAnimation(0, "turned".into())).is_ok());
    assert!(v.try_apply(Command::SetAnimation(0, "fly".into())).is_err());
    v.apply(Command::Seek(10)).unwrap();
    v.pose();
    assert_ne!(v.scene().skinned[0].matrices, at_walk);
    let fragment = v.state().view_fragment();
    assert!(fragment.contains("anim=1:turned"), "{fragment}");
    let mut again = Viewer::default();
    again.open_files(&[("walk.glb", &glb)], OpenMode::Replace);
    again.apply_fragment(&fragment);
    assert_eq!(again.snapshot().clips[0].animation.as_deref(), Some("turned"));

    // Sticks show the skeleton instead.
    v.apply_fragment("mode=sticks");
    v.pose();
    assert!(v.scene().skinned.is_empty());
}

#[test]
fn retarget_onto_a_glb_character_adds_it_wearing_the_look() {
    let glb = two_takes();
    let bow = std::fs::read(std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/walk.bvh")).unwrap();
    let mut v = Viewer::default();
    assert!(v.open_files(&[("walk.glb", &glb)], OpenMode::Replace).is_empty());
    assert!(v.open_files(&[("moves.bvh", &bow)], OpenMode::Add).is_empty());
    v.apply(Command::SetPlaying(false)).unwrap();
    // The Edit menu's entry opens the window on the current character (the BVH).
    assert!(v.try_apply(Command::OpenRetargetDialog(1)).is_ok());
    let dialog = v.state().retarget_dialog.clone().expect("the window is open");
    assert_eq!(dialog.source, 1);
    // A map naming no joint is refused and nothing opens.
    let bad = mocap::ops::retarget::Options { map: vec![("Wing".into(), "Hips".into())], ..Default::default() };
    assert!(v.try_apply(Command::Retarget { source: 1, target: 0, options: bad }).is_err());
    assert_eq!(v.snapshot().clips.len(), 2);
    v.try_apply(Command::Retarget { source: 1, target: 0, options: dialog.options() }).unwrap();
    let s = v.snapshot();
    assert_eq!(s.clips.len(), 3);
    assert_eq!(s.clips[2].name, "moves.bvh on walk.glb");
    assert_eq!(s.clips[2].joints, s.clips[0].joints, "exactly the target's skeleton");
    assert_eq!(s.clips[2].frames, s.clips[1].frames, "the source's frames");
    assert!(v.state().retarget_dialog.is_none(), "the window closes");
    v.pose();
    let looks = v.scene().skinned.iter().filter(|d| d.tint == [255; 4]).count();
    assert_eq!(looks, 2, "the target and the result wear the glTF look");
}

#[test]
fn a_damaged_glb_is_named_in_the_banner_and_what_was_open_stays() {
    let glb = two_takes();
    let mut v = Viewer::default();
    assert!(v.open_files(&[("walk.glb", &glb)], OpenMode::Replace).is_empty());
    for (name, bytes) in [
        ("cut.glb", &glb[..glb.len() / 2]),
        ("draco.gltf", &br#"{"asset":{"version":"2.0"},"extensionsRequired":["KHR_draco_mesh_compression"]}"#[..]),
    ] {
        let errors = v.open_files(&[(name, bytes)], OpenMode::Replace);
        assert_eq!(errors.len(), 1, "{errors:?}");
        assert!(errors[0].starts_with(name), "{}", errors[0]);
        let s = v.snapshot();
        assert_eq!(s.clips.len(), 1, "the character stays open");
        assert_eq!(s.clips[0].name, "walk.glb");
    }
    let errors = v.open_files(
        &[("draco.gltf", br#"{"asset":{"version":"2.0"},"extensionsRequired":["KHR_draco_mesh_compression"]}"#)],
        OpenMode::Add,
    );
    assert!(errors[0].contains("KHR_draco_mesh_compression"), "{}", errors[0]);
}

/// The walk as a glTF character with one blend shape lifting its top tenth,
/// weighted from 0 at the first frame to 1 at the last.
fn breathing() -> Vec<u8> {
    let clip = mocap::formats::bvh::parse(WALK).unwrap();
    let glb = to_glb(&clip, &Options { name: "walk".into(), body: true }).unwrap();
    let none = |_: &str| None;
    let read = mocap::formats::gltf::parse(&glb, &none, None).unwrap();
    let mut c = (**read.character.as_ref().unwrap()).clone();
    let look = c.look.as_mut().unwrap();
    let top = look.skin.positions().iter().map(|p| p.y).fold(f32::NEG_INFINITY, f32::max);
    let moved = (look.skin.positions().iter().enumerate())
        .filter(|(_, p)| p.y > top - 0.1)
        .map(|(v, _)| (v as u32, [0.0, 0.2, 0.0]))
        .collect();
    look.morph = Some(mocap::model::character::Morph { targets: vec![moved], rest: vec![0.0] });
    let frames = c.takes[0].motion.frame_count();
    c.takes[0].weights = (0..frames).map(|f| f as f32 / (frames - 1) as f32).collect();
    let clip = read.clone().with_character(std::sync::Arc::new(c));
    to_glb(&clip, &Options { name: "walk".into(), body: true }).unwrap()
}

#[test]
fn blend_shapes_play_with_the_take() {
    let mut v = Viewer::default();
    v.load("breathing.glb", &breathing()).unwrap();
    v.apply(Command::SetPlaying(false)).unwrap();
    let shape_at = |v: &mut Viewer, frame: usize| {
        v.apply(Command::Seek(frame)).unwrap();
        v.pose();
        let body = v.scene().skinned.first().expect("the look is drawn");
        body.shape.clone()
    };
    assert!(shape_at(&mut v, 0).is_none(), "weight 0 at the first frame: the mesh as it is");
    let last = v.state().stage.actors[0].clip().unwrap().frame_count() - 1;
    let end = shape_at(&mut v, last).expect("weight 1 at the last frame");
    let middle = shape_at(&mut v, last / 2).expect("a weight halfway");
    let look = v.state().stage.actors[0].clip().unwrap().character.as_deref().unwrap().look.clone().unwrap();
    let base = look.skin.positions();
    let lifted = |shape: &[mocap::glam::Vec3]| shape.iter().zip(base).map(|(s, b)| s.y - b.y).fold(0.0, f32::max);
    assert!((lifted(&end) - 0.2).abs() < 1e-4, "the top lifted 0.2 m at the end: {}", lifted(&end));
    let half = 0.2 * (last / 2) as f32 / last as f32;
    assert!((lifted(&middle) - half).abs() < 1e-4, "{} at the middle frame, {half} expected", lifted(&middle));
    // Paused on one frame, the same shape is handed on (not made again).
    let again = shape_at(&mut v, last / 2).unwrap();
    assert!(std::sync::Arc::ptr_eq(&middle, &again));
}

#[test]
fn warming_up_the_gltf_code_writes_and_reads_a_glb_and_changes_nothing() {
    let mut v = Viewer::default();
    assert!(!v.warm_up_gltf(), "nothing open: nothing to write");
    let errors = v.open_files(&[("walk.bvh", WALK)], OpenMode::Replace);
    assert!(errors.is_empty(), "{errors:?}");
    v.apply(Command::Seek(12)).unwrap();
    let before = v.snapshot();
    assert!(before.clips[0].frames > mocap_viewer::WARM_UP_FRAMES, "the walk is cut to the warm-up's frames");
    assert!(v.warm_up_gltf());
    assert_eq!(v.snapshot(), before, "nothing the user sees changed");
    assert_eq!(v.state().stage.actors.len(), 1, "nothing was opened");
}

#[test]
fn a_skeleton_too_large_to_warm_up_with_is_left_alone() {
    // A chain of joints one over the warm-up's limit, two frames.
    let joints = mocap_viewer::WARM_UP_MAX_JOINTS + 1;
    let mut text = String::from(
        "HIERARCHY\nROOT j0\n{\nOFFSET 0 0 0\nCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n",
    );
    for j in 1..joints {
        text += &format!("JOINT j{j}\n{{\nOFFSET 0 1 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n");
    }
    text += "End Site\n{\nOFFSET 0 1 0\n}\n";
    text += &"}\n".repeat(joints);
    let channels = 6 + 3 * (joints - 1);
    text += &format!(
        "MOTION\nFrames: 2\nFrame Time: 0.033333\n{}\n{}\n",
        vec!["0"; channels].join(" "),
        vec!["1"; channels].join(" ")
    );
    let mut v = Viewer::default();
    let errors = v.open_files(&[("chain.bvh", text.as_bytes())], OpenMode::Replace);
    assert!(errors.is_empty(), "{errors:?}");
    assert!(!v.warm_up_gltf());
}
