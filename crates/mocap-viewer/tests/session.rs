//! Autosave's session (no GPU, no browser): the work stored by one viewer opens in
//! another as it was (characters with their edits and how they are shown, the
//! history with undo and redo, what is saved, the view), each asset stored once;
//! a damaged session is refused whole and what is open stays.

use mocap_viewer::session::{self, Stored};
use mocap_viewer::{Command, OpenMode, Viewer};
use std::collections::HashMap;

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");
const BVA: &[u8] = include_bytes!("../../../data/walk.bva");

fn assets(stored: &Stored) -> HashMap<String, Vec<u8>> {
    stored.assets.iter().cloned().collect()
}

/// Applies an edit in the CLI's spec grammar to character 1.
fn edit(v: &mut Viewer, spec: &str) {
    let clip = v.state().stage.actors[0].clip().unwrap().clone();
    let edit = spec.parse::<mocap::ops::edit::EditSpec>().unwrap().resolve(&clip);
    v.apply(Command::Edit { character: 0, edit, label: spec.into() }).unwrap();
}

/// Two characters: the walk trimmed then reversed (one edit undone, so there is a
/// redo), hidden BVA beside it moved by hand, a camera and a frame.
fn worked() -> Viewer {
    let mut v = Viewer::default();
    assert!(v.open_files(&[("walk.bvh", WALK), ("walk.bva", BVA)], OpenMode::Replace).is_empty());
    for spec in ["trim:0:40", "reverse", "fps:60"] {
        edit(&mut v, spec);
    }
    v.apply(Command::Undo).unwrap();
    v.apply(Command::SetVisible(1, false)).unwrap();
    v.apply(Command::ApplyFragment("t=0.5&cam=1.2,0.5,4,0,0.9,0&layout=overlay".into())).unwrap();
    v
}

#[test]
fn a_stored_session_opens_as_it_was() {
    let v = worked();
    let stored = v.store_session();
    assert!(stored.unsaved);
    let pool = assets(&stored);
    let restored = session::parse(&stored.manifest, &|k| pool.get(k).cloned()).expect("reads back");
    let mut w = Viewer::default();
    w.load("other.bvh", WALK).unwrap();
    w.apply(Command::Restore(Box::new(restored))).unwrap();
    let (a, b) = (v.snapshot(), w.snapshot());
    assert_eq!(b.clips.len(), 2);
    for (x, y) in a.clips.iter().zip(&b.clips) {
        assert_eq!(
            (&x.name, x.frames, x.frame_time, x.visible, x.edited, x.unsaved),
            (&y.name, y.frames, y.frame_time, y.visible, y.edited, y.unsaved)
        );
    }
    assert_eq!(a.view, b.view, "the view");
    assert_eq!(v.state().stage.actors[0].asset, w.state().stage.actors[0].asset, "the edited clip, bit for bit");
    // Undo and redo go on where they were.
    w.apply(Command::Redo).unwrap();
    assert_eq!(w.snapshot().clips[0].frame_time, 1.0 / 60.0);
    w.apply(Command::Undo).unwrap();
    w.apply(Command::Undo).unwrap();
    w.apply(Command::Undo).unwrap();
    assert_eq!(w.snapshot().clips[0].frames, 67, "back to the file as opened");
    assert!(!w.snapshot().clips[0].unsaved);
}

#[test]
fn each_asset_is_stored_once_and_saving_is_remembered() {
    let mut v = worked();
    let stored = v.store_session();
    // The walk as opened, after the trim, after the reverse, after the resample; the BVA.
    assert_eq!(stored.assets.len(), 5, "{:?}", stored.assets.iter().map(|(k, _)| k).collect::<Vec<_>>());
    // Saving marks the character saved; the stored session says so.
    v.apply(Command::SaveBvh).unwrap();
    let _ = v.take_requests();
    assert!(!v.snapshot().clips[0].unsaved && v.snapshot().clips[0].edited);
    let again = v.store_session();
    assert!(!again.unsaved);
    assert_eq!(assets(&again).keys().collect::<std::collections::BTreeSet<_>>(), assets(&stored).keys().collect());
    let pool = assets(&again);
    let mut w = Viewer::default();
    w.apply(Command::Restore(Box::new(session::parse(&again.manifest, &|k| pool.get(k).cloned()).unwrap()))).unwrap();
    assert!(!w.snapshot().clips[0].unsaved);
    // An edit after the restore is unsaved again.
    edit(&mut w, "reverse");
    assert!(w.snapshot().clips[0].unsaved);
    // The stamp follows what is stored, not the view.
    let stamp = w.session_stamp();
    w.apply(Command::Seek(10)).unwrap();
    assert_eq!(w.session_stamp(), stamp);
    w.apply(Command::Undo).unwrap();
    assert_ne!(w.session_stamp(), stamp);
}

#[test]
fn a_damaged_session_is_refused_and_changes_nothing() {
    let stored = worked().store_session();
    let pool = assets(&stored);
    let first_key = stored.assets[0].0.clone();
    let cases: Vec<(String, Box<dyn Fn(&str) -> Option<Vec<u8>>>, &str)> = vec![
        ("{".into(), Box::new(|_| None), "damaged"),
        (stored.manifest.replace("\"version\":1", "\"version\":9"), Box::new(|_| None), "version 9"),
        (stored.manifest.clone(), Box::new(|_| None), "lacks its file"),
        (
            stored.manifest.clone(),
            {
                let pool = pool.clone();
                let key = first_key.clone();
                Box::new(move |k| pool.get(k).map(|b| if k == key { b[..b.len() / 2].to_vec() } else { b.clone() }))
            },
            "is damaged",
        ),
        (
            stored.manifest.replace("\"character\":0", "\"character\":7"),
            Box::new(move |k| pool.get(k).cloned()),
            "character 8",
        ),
    ];
    for (manifest, asset, needle) in cases {
        let error = session::parse(&manifest, &*asset).expect_err(needle);
        assert!(error.contains(needle), "{needle}: {error}");
    }
}
