//! Several characters at once: the shared timeline, different frame rates,
//! units, visibility, removal, layout, the fragment and failed loads.

use mocap_viewer::Command;
use mocap_viewer::{Layout, Selection, Viewer};

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");

/// A small figure in metres at `fps`, `frames` long, whose root moves 1 cm along X
/// per frame (so its x tells the frame shown); the head joint is called `head`.
fn metres_clip(fps: u32, frames: usize, head: &str) -> Vec<u8> {
    let mut s = format!(
        "HIERARCHY\nROOT Hips\n{{\n OFFSET 0 0 0\n CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation\n \
         JOINT Spine\n {{\n  OFFSET 0 0.5 0\n  CHANNELS 3 Zrotation Xrotation Yrotation\n  \
         JOINT {head}\n  {{\n   OFFSET 0 0.5 0\n   CHANNELS 3 Zrotation Xrotation Yrotation\n   \
         End Site\n   {{\n    OFFSET 0 0.25 0\n   }}\n  }}\n }}\n \
         JOINT Leg\n {{\n  OFFSET 0.1 0 0\n  CHANNELS 3 Zrotation Xrotation Yrotation\n  \
         End Site\n  {{\n   OFFSET 0 -0.9 0\n  }}\n }}\n}}\nMOTION\nFrames: {frames}\nFrame Time: {}\n",
        1.0 / f64::from(fps)
    );
    for f in 0..frames {
        s.push_str(&format!("{} 0.9 0 0 0 0 0 0 0 0 0 0 0 0 0\n", f as f64 * 0.01));
    }
    s.into_bytes()
}

/// walk.bvh (cm, 30 fps, 67 frames = 2.2 s) and a 120 fps clip in metres of 600 frames (4.99 s).
fn two() -> Viewer {
    let mut v = Viewer::default();
    v.load("walk.bvh", WALK).expect("walk.bvh");
    v.add("fast.bvh", &metres_clip(120, 600, "Head")).expect("fast.bvh");
    v.apply(Command::SetPlaying(false)).unwrap();
    v
}

#[test]
fn timeline_spans_the_longest_clip_in_the_first_clips_frames() {
    let mut v = two();
    let s = v.snapshot();
    assert_eq!(s.clips.len(), 2);
    assert_eq!((s.clips[0].frames, s.clips[1].frames), (67, 600));
    let t = v.state().timing().unwrap();
    assert_eq!(t.frame_time(), s.clips[0].frame_time);
    assert_eq!(t.frames(), 151, "4.99 s at 30 fps, rounded up to a whole frame");
    v.apply(Command::Seek(10_000)).unwrap();
    assert_eq!(v.state().frame(), 150);
    // Selecting a joint of the 120 fps clip counts the timeline in its frames.
    v.apply(Command::Select { character: 1, joint: Some(0) }).unwrap();
    assert_eq!(v.state().timing().unwrap().frames(), 600);
}

#[test]
fn clips_of_different_frame_rates_are_sampled_at_the_same_time() {
    let mut v = two();
    v.apply(Command::Seek(30)).unwrap(); // 1.0 s
    v.pose();
    let (walk, fast) = (&v.state().stage.actors[0], &v.state().stage.actors[1]);
    assert_eq!(walk.frame_at(v.state().playback.time), 30);
    assert_eq!(fast.frame_at(v.state().playback.time), 120);
    let x = fast.extra.pose[0].translation.x - fast.placement().x;
    assert!((x - 1.2).abs() < 1e-4, "root at 1.2 m after 1 s: {x}");
    // After its end the shorter clip holds its last pose.
    v.apply(Command::Seek(150)).unwrap();
    v.pose();
    assert_eq!(v.state().stage.actors[0].frame_at(v.state().playback.time), 66);
    assert_eq!(v.state().stage.actors[1].frame_at(v.state().playback.time), 599);
    // Playing (interpolated) samples both at the playhead time.
    v.apply(Command::SetPlaying(true)).unwrap();
    v.apply(Command::SetTime(0.5)).unwrap();
    v.pose();
    let fast = &v.state().stage.actors[1];
    let x = fast.extra.pose[0].translation.x - fast.placement().x;
    assert!((x - 0.6).abs() < 1e-4, "root at 0.6 m after 0.5 s: {x}");
}

#[test]
fn centimetres_and_metres_stand_at_the_same_size_side_by_side() {
    let mut v = two();
    v.pose();
    let (walk, fast) = (&v.state().stage.actors[0], &v.state().stage.actors[1]);
    assert_eq!(walk.scale(), 0.01);
    assert_eq!(fast.scale(), 1.0);
    let (hw, hf) = (walk.world_bounds().size().y, fast.world_bounds().size().y);
    assert!((1.0..2.5).contains(&hw) && (1.0..2.5).contains(&hf), "heights {hw} {hf} m");
    assert!(walk.world_bounds().max.x < fast.world_bounds().min.x, "spread: lanes do not overlap");
    let centre = v.state().stage.bounds().center().x;
    assert!(centre.abs() < 1e-3, "the row is centred on x = 0: {centre}");
    assert!((v.scene().grid.unwrap().cell - 0.5).abs() < 1e-6);
    // The camera frames both.
    let target = v.state().camera.target;
    assert!(v.state().stage.bounds().min.x < target.x && target.x < v.state().stage.bounds().max.x);

    v.apply(Command::SetLayout(Layout::Overlay)).unwrap();
    assert!(v.state().stage.actors.iter().all(|c| c.layout_offset == mocap::glam::Vec3::ZERO));
    v.apply(Command::SetOffset(1, mocap::glam::Vec3::new(2.0, 0.0, 0.0))).unwrap();
    assert_eq!(v.snapshot().clips[1].offset, [2.0, 0.0, 0.0]);
}

#[test]
fn hidden_characters_are_not_drawn_and_removal_shifts_the_selection() {
    let mut v = two();
    v.pose();
    let all = v.scene().capsules.len();
    let colors = (v.state().stage.actors[0].extra.color, v.state().stage.actors[1].extra.color);
    assert_ne!(colors.0, colors.1, "each character has its own colour");
    assert!(v.scene().capsules.iter().any(|l| l.color == colors.1));
    assert!(v.try_apply(Command::SetVisible(1, false)).is_ok());
    assert!(!v.try_apply(Command::SetVisible(5, false)).is_ok());
    v.pose();
    assert!(v.scene().capsules.len() < all);
    assert!(!v.scene().capsules.iter().any(|l| l.color == colors.1), "hidden character drawn");
    assert!(!v.snapshot().clips[1].visible);

    v.try_apply(Command::SetVisible(1, true)).unwrap();
    v.apply(Command::Select { character: 1, joint: Some(2) }).unwrap();
    assert_eq!(v.snapshot().selected_character, Some(1));
    assert_eq!(v.snapshot().selected_joint.as_deref(), Some("Head"));
    assert!(v.try_apply(Command::CloseNow(0)).is_ok());
    assert!(!v.try_apply(Command::CloseNow(3)).is_ok());
    assert_eq!(v.state().selected, Some(Selection { character: 0, joint: 2 }));
    assert_eq!(v.snapshot().clips.len(), 1);
    assert_eq!(v.state().timing().unwrap().frames(), 600);
    assert!(v.try_apply(Command::CloseNow(0)).is_ok());
    assert_eq!(v.state().selected, None);
    v.pose();
    assert!(v.scene().capsules.is_empty() && v.scene().grid.is_none());
}

#[test]
fn a_failed_add_keeps_the_others_and_load_replaces_all() {
    let mut v = two();
    v.apply(Command::Seek(20)).unwrap();
    let err = v.add("bad.bvh", b"HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0\n").unwrap_err();
    assert!(err.starts_with("bad.bvh:"), "{err}");
    let s = v.snapshot();
    assert_eq!(s.clips.len(), 2);
    assert_eq!(s.error.as_deref(), Some(err.as_str()));
    assert_eq!(v.state().frame(), 20);
    // Adding keeps the playhead; loading replaces everything and starts at 0.
    v.add("third.bvh", &metres_clip(60, 10, "Head")).unwrap();
    assert_eq!((v.snapshot().clips.len(), v.state().frame(), v.snapshot().error), (3, 20, None));
    v.load("walk.bvh", WALK).unwrap();
    assert_eq!((v.snapshot().clips.len(), v.state().frame()), (1, 0));
    assert_eq!(v.state().stage.actors[0].extra.color, mocap_viewer::character::PALETTE[0]);
}

#[test]
fn fragment_round_trips_layout_hidden_and_selection_with_a_character() {
    let make = || {
        let mut v = two();
        v.add("colon.bvh", &metres_clip(60, 30, "mix:Head")).unwrap();
        v
    };
    let mut v = make();
    v.apply(Command::SetLayout(Layout::Overlay)).unwrap();
    v.try_apply(Command::SetVisible(1, false)).unwrap();
    v.try_apply(Command::SelectNamed { character: 2, name: "mix:Head".into() }).unwrap();
    v.apply(Command::Seek(7)).unwrap();
    v.apply(Command::SetOffset(2, mocap::glam::Vec3::new(0.25, 0.0, -1.1))).unwrap();
    let fragment = v.state().view_fragment();
    assert!(fragment.contains("layout=overlay"), "{fragment}");
    assert!(fragment.contains("hide=2&") || fragment.ends_with("hide=2"), "{fragment}");
    assert!(fragment.contains("sel=3:mix%3AHead"), "{fragment}");
    assert!(fragment.contains("offset=3:0.25,0,-1.1"), "{fragment}");

    let mut w = make();
    w.apply_fragment(&fragment);
    assert_eq!(w.state().view_fragment(), fragment);
    assert_eq!(w.state().selected, v.state().selected);
    assert_eq!(w.state().stage.layout, Layout::Overlay);
    assert!(!w.state().stage.actors[1].visible && w.state().stage.actors[0].visible);
    assert_eq!(w.state().frame(), 7);
    assert_eq!(w.state().camera, v.state().camera);
    assert_eq!(w.snapshot().clips, v.snapshot().clips, "visibility, colours, offsets");

    // `sel=Name` is the first character; `hide=none` shows all again.
    w.apply_fragment("sel=Hips&hide=none&layout=spread");
    assert_eq!(w.state().selected, Some(Selection { character: 0, joint: 0 }));
    assert!(w.state().stage.actors.iter().all(|c| c.visible));
    assert_eq!(w.state().stage.layout, Layout::Spread);
    w.apply_fragment("sel=2:Head");
    assert_eq!(w.state().selected, Some(Selection { character: 1, joint: 2 }));
    w.apply_fragment("sel=Hips");
    w.apply_fragment("sel=3%3Amix%253AHead"); // as URLSearchParams writes 3:mix%3AHead
    assert_eq!(w.state().selected, Some(Selection { character: 2, joint: 2 }));
    w.apply_fragment("offset=none");
    assert!(w.state().stage.actors.iter().all(|c| c.offset == mocap::glam::Vec3::ZERO));
    w.apply_fragment("offset=1:1,2,nan;2:1,1,1");
    assert!(
        w.state().stage.actors.iter().all(|c| c.offset == mocap::glam::Vec3::ZERO),
        "unreadable offsets are ignored"
    );
    w.apply_fragment("sel=9:Head&hide=x&layout=bogus");
    assert_eq!(w.state().selected, None);
    assert_eq!(w.state().stage.layout, Layout::Spread);
}

#[test]
fn more_than_eight_characters_wrap_into_rows_and_colours_cycle() {
    let mut v = Viewer::default();
    let clip = metres_clip(30, 5, "Head");
    for i in 0..9 {
        v.add(&format!("c{i}.bvh"), &clip).unwrap();
    }
    let zs: std::collections::BTreeSet<i64> =
        v.state().stage.actors.iter().map(|c| (c.placement().z * 1000.0).round() as i64).collect();
    assert_eq!(zs.len(), 3, "three rows of three: {zs:?}");
    let xs: std::collections::BTreeSet<i64> =
        v.state().stage.actors.iter().map(|c| (c.placement().x * 1000.0).round() as i64).collect();
    assert_eq!(xs.len(), 3, "three lanes per row: {xs:?}");
    let palette = mocap_viewer::character::PALETTE;
    assert_eq!(v.state().stage.actors[6].extra.color, palette[0], "colours cycle after {}", palette.len());
    // Removing one frees its colour for the next character.
    v.try_apply(Command::CloseNow(2)).unwrap();
    v.add("c9.bvh", &clip).unwrap();
    assert_eq!(v.state().stage.actors.last().map(|c| c.extra.color), Some(palette[2]));
}
