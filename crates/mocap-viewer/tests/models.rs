//! Quake 2 MD2 models in the viewer (no GPU): opening with a skin, animations on
//! the timeline and in the fragment, the mesh primitive the renderer gets, and the
//! whole UI drawing a model. Reads the corpus (`../shared/corpus`; a failure when
//! missing unless `MOCAP_SKIP_CORPUS=1`).

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
    panic!("{}: corpus not found (put ../shared beside the repository, or opt out with MOCAP_SKIP_CORPUS=1)", dir.display());
}

/// A viewer with the faerie and its BMP skin open (dropped together), paused at 0.
fn faerie() -> Option<Viewer> {
    let dir = corpus_dir()?.join("md2/irrlicht_faerie");
    let model = std::fs::read(dir.join("faerie.md2")).unwrap();
    let skin = std::fs::read(dir.join("faerie2.bmp")).unwrap();
    let mut v = Viewer::default();
    let errors = v.open_files(&[("faerie.md2", &model), ("faerie2.bmp", &skin)], OpenMode::Replace);
    assert!(errors.is_empty(), "{errors:?}");
    v.set_playing(false);
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
    assert!(v.set_animation(0, "run"));
    assert!(!v.set_animation(0, "fly") && !v.set_animation(3, "run"));
    let s = v.snapshot();
    assert_eq!((s.clips[0].frames, s.clips[0].animation.as_deref()), (6, Some("run")));
    v.seek(2);
    v.pose();
    assert_eq!(v.snapshot().clips[0].model_frame, Some((42, "run3".to_owned())));
    let fragment = v.view_fragment();
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
    v.set_animation(0, "run");
    v.playback.time = 0.15;
    v.playback.playing = true;
    v.settings.interpolate = true;
    v.pose();
    let mesh = &v.scene().meshes;
    assert_eq!(mesh.len(), 1);
    assert_eq!((mesh[0].frames, mesh[0].blend), ([41, 42], 0.5));
    assert_eq!(mesh[0].tint, [255; 4], "textured: the skin's own colours");
    assert!(v.scene().capsules.is_empty() && v.scene().grid.is_some());
    // Interpolation off: switch at the halfway point (frame 1.5 of run shows 42).
    v.settings.interpolate = false;
    v.pose();
    assert_eq!((v.scene().meshes[0].frames, v.scene().meshes[0].blend), ([42, 42], 0.0));
    v.set_visible(0, false);
    v.pose();
    assert!(v.scene().meshes.is_empty());
}

#[test]
fn a_model_and_a_bvh_stand_side_by_side_at_one_scale() {
    let Some(mut v) = faerie() else { return };
    v.add("walk.bvh", WALK).unwrap();
    v.pose();
    let stage = &v.stage;
    let model = stage.actors[0].world_bounds();
    let walk = stage.actors[1].world_bounds();
    assert!(model.max.x < walk.min.x, "separate lanes");
    let (h_model, h_walk) = (model.size().y, walk.size().y);
    assert!((0.5..2.5).contains(&h_model) && (1.2..2.2).contains(&h_walk), "{h_model} m and {h_walk} m");
    let mesh = &v.scene().meshes[0];
    let (lo, _) = mesh.world_bounds().unwrap();
    assert!((lo.y - model.min.y).abs() < 1e-3, "the mesh is drawn where the stage placed it");
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
        let mut output = ctx.run_ui(input, |ui| v.ui(ui, None));
        output.textures_delta.clear();
        if i == 0 {
            v.set_playing(true);
        }
    }
    let s = v.snapshot();
    assert!(s.error.is_none() && s.time > 0.0);
    assert!(s.tree_labels.is_empty(), "a model has no joints to list");
}
