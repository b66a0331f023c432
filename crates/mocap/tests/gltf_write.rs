//! The glTF writer, read back by an independent reader (the `gltf` crate): every
//! joint's world position from the written file (its nodes, their animation
//! sampled at each key) is ours, in metres and Y up, at every frame, for the
//! generated walk and for real BVH and Acclaim files; the skin binds the body in
//! frame 0's pose.

mod common;

use mocap::Clip;
use mocap::formats::gltf::{Options, to_glb, to_gltf};
use mocap::glam::{Mat4, Quat, Vec3};

const WALK: &[u8] = include_bytes!("../../../data/walk.bvh");

/// World transforms of the nodes at every key frame, as the file says (parents
/// listed before children, as the writer writes them).
fn world_positions(document: &gltf::Document, buffers: &[gltf::buffer::Data], frames: usize) -> Vec<Vec<Vec3>> {
    let nodes: Vec<gltf::Node> = document.nodes().collect();
    let mut parent = vec![None; nodes.len()];
    for n in &nodes {
        for c in n.children() {
            parent[c.index()] = Some(n.index());
        }
    }
    let rest: Vec<(Vec3, Quat, Vec3)> = nodes
        .iter()
        .map(|n| {
            let (t, r, s) = n.transform().decomposed();
            (Vec3::from(t), Quat::from_array(r), Vec3::from(s))
        })
        .collect();
    let mut per_frame = vec![rest.clone(); frames.max(1)];
    if let Some(animation) = document.animations().next() {
        for channel in animation.channels() {
            let node = channel.target().node().index();
            let reader = channel.reader(|b| Some(&buffers[b.index()]));
            let times: Vec<f32> = reader.read_inputs().unwrap().collect();
            assert_eq!(times.len(), frames);
            match reader.read_outputs().unwrap() {
                gltf::animation::util::ReadOutputs::Rotations(r) => {
                    for (f, q) in r.into_f32().enumerate() {
                        let q = Quat::from_array(q);
                        assert!((q.length() - 1.0).abs() < 1e-5, "unit rotations");
                        per_frame[f][node].1 = q;
                    }
                }
                gltf::animation::util::ReadOutputs::Translations(t) => {
                    for (f, x) in t.enumerate() {
                        per_frame[f][node].0 = Vec3::from(x);
                    }
                }
                gltf::animation::util::ReadOutputs::Scales(s) => {
                    for (f, x) in s.enumerate() {
                        per_frame[f][node].2 = Vec3::from(x);
                    }
                }
                _ => panic!("no morph weights are written for a clip"),
            }
        }
    }
    per_frame
        .iter()
        .map(|locals| {
            let mut world: Vec<Mat4> = Vec::with_capacity(locals.len());
            for (i, (t, r, s)) in locals.iter().enumerate() {
                let local = Mat4::from_scale_rotation_translation(*s, *r, *t);
                let m = match parent[i] {
                    Some(p) => {
                        assert!(p < i, "parents are listed first");
                        world[p] * local
                    }
                    None => local,
                };
                world.push(m);
            }
            world.iter().map(|m| m.w_axis.truncate()).collect()
        })
        .collect()
}

/// Ours: the clip's world positions, in metres, Y up.
fn ours(clip: &Clip, frame: usize) -> Vec<Vec3> {
    let (up, m) = (clip.up_axis().rotation(), clip.units().meters_per_unit());
    clip.world_positions(frame).into_iter().map(|p| up * p * m).collect()
}

/// Writes `clip`, reads it back, and compares every joint at every frame.
fn round_trip(name: &str, clip: &Clip) {
    let glb = to_glb(clip, &Options { name: name.to_owned(), body: true }).unwrap();
    let (document, buffers, _) = gltf::import_slice(&glb).unwrap_or_else(|e| panic!("{name}: {e}"));
    let joints = clip.skeleton().len();
    let names: Vec<String> = document.nodes().take(joints).map(|n| n.name().unwrap_or("").to_owned()).collect();
    let expected: Vec<String> = clip.skeleton().joints().iter().map(|j| j.name.clone()).collect();
    assert_eq!(names, expected, "{name}: one node per joint, named");
    let frames = clip.frame_count();
    let theirs = world_positions(&document, &buffers, frames);
    let height = clip.pose_height() * clip.units().meters_per_unit();
    let tolerance = 1e-4 * height.max(0.01);
    let mut worst = 0.0f32;
    for f in 0..frames {
        for (a, b) in ours(clip, f).iter().zip(&theirs[f][..joints]) {
            worst = worst.max(a.distance(*b));
        }
    }
    assert!(worst <= tolerance, "{name}: a joint is {worst} m off (tolerance {tolerance})");

    // The skin: frame 0's joints times the inverse bind matrices give identity
    // (the body is bound in frame 0's pose), and the body is there.
    let skin = document.skins().next().expect("a skin");
    assert_eq!(skin.joints().count(), joints);
    let mesh = document.meshes().next().expect("a body mesh");
    let primitive = mesh.primitives().next().unwrap();
    let reader = primitive.reader(|b| Some(&buffers[b.index()]));
    let positions: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
    assert!(!positions.is_empty());
    let weights: Vec<[f32; 4]> = reader.read_weights(0).unwrap().into_f32().collect();
    assert!(weights.iter().all(|w| (w.iter().sum::<f32>() - 1.0).abs() < 1e-5), "{name}: weights sum to 1");
    let joints_0: Vec<[u16; 4]> = reader.read_joints(0).unwrap().into_u16().collect();
    for (js, ws) in joints_0.iter().zip(&weights) {
        let used: Vec<u16> = js.iter().zip(ws).filter(|(_, w)| **w > 0.0).map(|(j, _)| *j).collect();
        let mut unique = used.clone();
        unique.sort();
        unique.dedup();
        assert_eq!(unique.len(), used.len(), "{name}: a vertex names a joint once");
    }
}

#[test]
fn the_walk_reads_back_joint_for_joint() {
    let clip = mocap::formats::bvh::parse(WALK).unwrap();
    round_trip("walk", &clip);
    // The text form holds the same, its buffer inline.
    let text = to_gltf(&clip, &Options::default()).unwrap();
    let (document, buffers, _) = gltf::import_slice(text.as_bytes()).unwrap();
    let theirs = world_positions(&document, &buffers, clip.frame_count());
    let a = ours(&clip, 17);
    assert!(a.iter().zip(&theirs[17]).all(|(a, b)| a.distance(*b) < 1e-4));
}

#[test]
fn a_z_up_clip_is_stood_up_and_a_clip_without_frames_is_its_rest_pose() {
    let clip = mocap::formats::bvh::parse(WALK).unwrap();
    let z_up = mocap::ops::edit::apply(&clip, &mocap::ops::edit::Edit::UpAxis { from: 1, negative: true }).unwrap();
    // Whatever axis the file stands along, the written file stands along +Y.
    round_trip("walk lying", &z_up);
    let still = mocap::ops::edit::apply(&clip, &mocap::ops::edit::Edit::Trim { first: 0, last: 0 }).unwrap();
    round_trip("one frame", &still);
}

#[test]
fn no_body_writes_the_skeleton_alone() {
    let clip = mocap::formats::bvh::parse(WALK).unwrap();
    let glb = to_glb(&clip, &Options { name: "bones".into(), body: false }).unwrap();
    let (document, _, _) = gltf::import_slice(&glb).unwrap();
    assert_eq!(document.meshes().count(), 0);
    assert_eq!(document.nodes().count(), clip.skeleton().len());
    assert_eq!(document.animations().next().unwrap().name(), Some("bones"));
}

#[test]
fn corpus_bvh_and_acclaim_clips_read_back() {
    let Some(dir) = common::corpus_dir() else { return };
    let mut done = 0;
    for path in ["bvh/bandai_namco/dataset-1_bow_active_001.bvh"] {
        let bytes = std::fs::read(dir.join(path)).unwrap();
        let clip = mocap::formats::bvh::parse(&bytes).unwrap();
        round_trip(path, &clip);
        done += 1;
    }
    let asf = std::fs::read(dir.join("asf_amc/cmu/02.asf")).unwrap();
    let amc = std::fs::read(dir.join("asf_amc/cmu/02_01.amc")).unwrap();
    let inputs = [mocap::Input { name: "02.asf", bytes: &asf }, mocap::Input { name: "02_01.amc", bytes: &amc }];
    for loaded in mocap::load(&inputs) {
        if let Ok(mocap::Asset::Clip(clip)) = loaded.map(|l| l.asset) {
            round_trip("02_01.amc", &clip);
            done += 1;
        }
    }
    assert_eq!(done, 2);
}
