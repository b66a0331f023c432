//! Onion skin and trails (no GPU): the scene gains the poses either side of the
//! frame and the paths; they follow the frame; the fragment keeps them.

use mocap_viewer::{Command, Viewer};

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");

fn viewer(onion: bool, trails: bool, frame: usize) -> Viewer {
    let mut v = Viewer::default();
    v.load("walk.bvh", WALK).unwrap();
    v.apply(Command::SetPlaying(false)).unwrap();
    let mut s = v.state().settings.clone();
    (s.onion, s.trails, s.onion_count, s.onion_step) = (onion, trails, 3, 0.2);
    v.apply(Command::SetSettings(s)).unwrap();
    v.apply(Command::Seek(frame)).unwrap();
    v.pose();
    v
}

#[test]
fn onion_skin_adds_fading_poses_either_side() {
    let plain = viewer(false, false, 30);
    let onion = viewer(true, false, 30);
    let bones = plain.state().stage.actors[0].extra.drawable.figure.iter().filter(|j| j.parent.is_some()).count();
    let added = onion.scene().lines.len() - plain.scene().lines.len();
    assert_eq!(added, 6 * bones, "three poses each side, one line per bone");
    let alphas: Vec<u8> = onion.scene().lines.iter().map(|l| l.color[3]).collect();
    assert!(alphas.iter().max() > alphas.iter().min(), "they fade with distance");
    // Near the start only the poses after the frame exist.
    let early = viewer(true, false, 0);
    assert_eq!(early.scene().lines.len() - plain.scene().lines.len(), 3 * bones);
    assert!(onion.state().view_fragment().contains("onion"));
}

#[test]
fn trails_draw_the_root_path_on_the_floor_and_follow_the_frame() {
    let a = viewer(false, true, 10);
    let b = viewer(false, true, 50);
    let plain = viewer(false, false, 10);
    assert!(a.scene().overlay_lines.len() > plain.scene().overlay_lines.len() + 20, "a path with ticks");
    assert_eq!(a.scene().spheres.len(), plain.scene().spheres.len() + 1, "the current point");
    let floor = a.state().stage.floor_height();
    let path: Vec<_> = a.scene().overlay_lines.iter().skip(plain.scene().overlay_lines.len()).collect();
    assert!(path.iter().all(|l| (l.a.y - floor).abs() < 0.01), "on the floor");
    let point = |v: &Viewer| v.scene().spheres.last().unwrap().center;
    assert!(point(&a).distance(point(&b)) > 0.2, "the current point walks with the frame");
    assert!(a.state().view_fragment().contains("trails"));
}

#[test]
fn a_link_keeps_the_onion_skins_count_and_spacing() {
    let mut v = viewer(true, false, 30);
    let mut s = v.state().settings.clone();
    (s.onion_count, s.onion_step) = (5, 0.1);
    v.apply(Command::SetSettings(s)).unwrap();
    let fragment = v.state().view_fragment();
    assert!(fragment.contains("onion=5,0.1"), "{fragment}");
    let mut opened = viewer(false, false, 30);
    opened.apply_fragment(&fragment);
    let s = &opened.state().settings;
    assert_eq!((s.onion, s.onion_count, s.onion_step), (true, 5, 0.1));
    opened.pose();
    let bones = opened.state().stage.actors[0].extra.drawable.figure.iter().filter(|j| j.parent.is_some()).count();
    assert_eq!(opened.scene().lines.len(), 10 * bones, "five poses each side (0.5 s either way of 1 s)");
    // Out of the View menu's range, or unreadable: left as it is.
    for bad in ["onion=9,0.2", "onion=3,5", "onion=3", "onion=x,0.2"] {
        opened.apply_fragment(bad);
        assert_eq!((opened.state().settings.onion_count, opened.state().settings.onion_step), (5, 0.1), "{bad}");
    }
}
