//! `mocap render` and the page build their scenes with one scene builder and
//! frame them with one rule: the same clip at the same view size gets the same
//! camera and the same primitives.

use mocap_cli::render::{Orbit, StageView};
use mocap_render::Scene;
use mocap_viewer::Command;

fn walk() -> Vec<u8> {
    std::fs::read(concat!(env!("CARGO_MANIFEST_DIR"), "/../../data/walk.bvh")).expect("data/walk.bvh")
}

#[test]
fn mocap_render_and_the_page_frame_a_clip_alike_wide_and_tall() {
    let bytes = walk();
    for size in [[640u32, 360u32], [360, 640], [320, 320]] {
        let clip = mocap::formats::bvh::parse(&bytes).unwrap();
        let stage = StageView::new(vec![("walk.bvh".to_owned(), clip.into())]);
        let cli = stage.orbit_camera(Orbit::default(), size);
        let mut page = mocap_viewer::Viewer::default();
        let camera =
            mocap_viewer::OrbitCamera { aspect: size[0] as f32 / size[1] as f32, ..page.state().camera.clone() };
        page.apply(Command::SetCamera(camera)).unwrap();
        page.load("walk.bvh", &bytes).unwrap();
        let page = &page.state().camera;
        assert!((cli.target - page.target).length() < 1e-5, "{size:?}: {} vs {}", cli.target, page.target);
        assert!((cli.distance - page.distance).abs() < 1e-4 * page.distance, "{size:?}: distance");
        assert!((cli.yaw - page.yaw).abs() < 1e-6 && (cli.pitch - page.pitch).abs() < 1e-6, "{size:?}: angles");
        let aspect = size[0] as f32 / size[1] as f32;
        let (a, b) = (cli.to_camera(aspect), page.to_camera(aspect));
        assert!(a.view.abs_diff_eq(b.view, 1e-4) && a.projection.abs_diff_eq(b.projection, 1e-4), "{size:?}: matrices");
    }
}

#[test]
fn mocap_render_and_the_page_draw_the_same_primitives() {
    let bytes = walk();
    let clip = mocap::formats::bvh::parse(&bytes).unwrap();
    let stage = StageView::new(vec![("walk.bvh".to_owned(), clip.into())]);
    let mut cli = Scene::default();
    stage.scene_at(0.0, &mut cli);
    let mut page = mocap_viewer::Viewer::default();
    page.load("walk.bvh", &bytes).unwrap();
    page.apply(Command::SetPlaying(false)).unwrap();
    page.apply(Command::Seek(0)).unwrap();
    page.pose();
    let page = page.scene();
    assert!(!cli.capsules.is_empty());
    assert_eq!(cli.capsules.len(), page.capsules.len());
    for (a, b) in cli.capsules.iter().zip(&page.capsules) {
        assert!((a.a - b.a).length() < 1e-5 && (a.b - b.b).length() < 1e-5, "{a:?} vs {b:?}");
        assert_eq!((a.radius, a.color), (b.radius, b.color));
    }
    assert_eq!(cli.grid.map(|g| format!("{g:?}")), page.grid.map(|g| format!("{g:?}")), "the same floor");
}
