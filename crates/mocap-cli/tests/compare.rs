//! `mocap compare` end to end: zero against itself, the turned arm's error in
//! JSON, the table, and clear refusals.

use std::path::Path;
use std::process::Command;

fn walk() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/walk.bvh")
}

fn run(args: &[&std::ffi::OsStr]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_mocap")).arg("compare").args(args).output().unwrap()
}

#[test]
fn a_take_against_itself_and_against_a_turned_copy() {
    let w = walk();
    let out = run(&[w.as_os_str(), w.as_os_str(), "--json".as_ref()]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["mpjpe"], 0.0);
    assert_eq!(v["worst_frame"], 0);
    assert_eq!(v["frames"].as_array().unwrap().len(), 67);
    // The copy: LeftArm's first rotation channel plus 20 degrees on every frame.
    let clip = mocap::formats::bvh::parse(&std::fs::read(&w).unwrap()).unwrap();
    let s = clip.skeleton();
    let arm = s.find("LeftArm").unwrap();
    let col = s.joints()[arm].columns().start + s.joints()[arm].channels.iter().position(|c| c.to_string() == "Zrotation").unwrap();
    let c = s.channel_count();
    let mut data = clip.motion().data().to_vec();
    data.chunks_mut(c).for_each(|r| r[col] += 20.0);
    let turned = mocap::Clip::new(s.clone(), mocap::Motion::new(clip.frame_time(), c, clip.frame_count(), data).unwrap()).unwrap();
    let dir = tempfile::tempdir().unwrap();
    let b = dir.path().join("turned.bvh");
    std::fs::write(&b, mocap::formats::bvh::write(&turned)).unwrap();
    let out = run(&[w.as_os_str(), b.as_os_str(), "--json".as_ref()]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let joint = |name: &str| v["joints"].as_array().unwrap().iter().find(|j| j["name"] == name).unwrap().clone();
    assert!(joint("LeftHand")["mean"].as_f64().unwrap() > 5.0, "{}", joint("LeftHand"));
    assert_eq!(joint("RightHand")["max"], 0.0);
    assert!((joint("LeftArm")["angle"].as_f64().unwrap() - 20.0).abs() < 0.1);
    assert!(v["mpjpe_m"].as_f64().unwrap() > 0.0);
    let table = run(&[w.as_os_str(), b.as_os_str(), "--align".as_ref(), "procrustes".as_ref()]);
    let text = String::from_utf8_lossy(&table.stdout);
    assert!(text.starts_with("MPJPE ") && text.contains("LeftHand"), "{text}");
}

#[test]
fn bad_requests_are_refused_clearly() {
    let w = walk();
    let out = run(&[w.as_os_str(), w.as_os_str(), "--align".as_ref(), "sideways".as_ref()]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("expected none, root, procrustes, root-once or procrustes-once"));
    let out = run(&[w.as_os_str(), "missing.bvh".as_ref()]);
    assert!(String::from_utf8_lossy(&out.stderr).contains("missing.bvh"));
}
