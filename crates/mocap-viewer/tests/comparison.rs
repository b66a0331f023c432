//! Compare ▸ with (no GPU): the ghost in the reference's place coloured by
//! error, the report kept current with edits, ended when a take is closed.

use mocap_viewer::{Command, OpenMode, Viewer};

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");

fn two_walks() -> Viewer {
    let mut v = Viewer::default();
    v.load("walk.bvh", WALK).unwrap();
    v.open_files(&[("walk-2.bvh", WALK)], OpenMode::Add);
    v.apply(Command::SetPlaying(false)).unwrap();
    v
}

#[test]
fn a_comparison_draws_the_ghost_and_follows_edits() {
    let mut v = two_walks();
    assert_eq!(v.state().stage.actors.len(), 2);
    v.pose();
    let before = v.scene().overlay_lines.len();
    v.apply(Command::Compare(Some((0, 1)))).unwrap();
    v.pose();
    let c = v.state().comparison.clone().unwrap();
    assert_eq!(c.report.mpjpe, 0.0, "the same take");
    let ghost = v.scene().overlay_lines.len() - before;
    assert!(ghost >= 20, "one line per bone: {ghost}");
    // The same take: the ghost lies on the reference's own bones, in its place.
    let a_pose: Vec<_> = v.state().stage.actors[0].extra.pose.iter().map(|t| t.translation).collect();
    for l in &v.scene().overlay_lines[before..] {
        assert!(a_pose.iter().any(|p| p.distance(l.b) < 1e-4), "{:?} is on the reference", l.b);
    }
    // Edit the second take: the report is made again.
    v.apply(Command::Edit { character: 1, edit: mocap::ops::edit::Edit::Reverse, label: "Reverse".into() }).unwrap();
    v.pose();
    let after = v.state().comparison.clone().unwrap();
    assert!(after.report.mpjpe > 1.0, "{}", after.report.mpjpe);
    assert_eq!(after.report.frames.len(), 67);
    let lines = &v.scene().overlay_lines[v.scene().overlay_lines.len() - ghost..];
    let colours: std::collections::HashSet<[u8; 4]> = lines.iter().map(|l| l.color).collect();
    assert!(colours.len() > 3, "bones coloured by their errors");
    // Closing a take ends the comparison.
    v.apply(Command::CloseNow(1)).unwrap();
    v.pose();
    assert!(v.state().comparison.is_none());
}

#[test]
fn a_comparison_with_itself_is_refused() {
    let mut v = two_walks();
    assert!(v.apply(Command::Compare(Some((0, 0)))).is_err());
    assert!(v.apply(Command::Compare(Some((0, 7)))).is_err());
    assert!(v.state().comparison.is_none());
}
