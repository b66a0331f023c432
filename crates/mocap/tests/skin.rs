//! Skinning on the CPU (the reference the GPU is checked against) and the body
//! built for any skeleton: bind pose gives the bind mesh, one influence is a rigid
//! transform, 50/50 is the midpoint, bad skins are refused, and every corpus
//! skeleton's body is closed with weights summing to 1.

mod common;

use mocap::Transform;
use mocap::glam::{Quat, Vec3};
use mocap::runtime::skin::{self, Skin, SkinError};
use std::collections::HashMap;

fn t(translation: Vec3, rotation: Quat) -> Transform {
    Transform { rotation, translation, scale: Vec3::ONE }
}

/// Two joints (at the origin and at y = 1) and three vertices: rigid to joint 0,
/// rigid to joint 1, and half and half.
fn two_joint_skin() -> (Skin, Vec<Transform>) {
    let bind = vec![t(Vec3::ZERO, Quat::IDENTITY), t(Vec3::Y, Quat::IDENTITY)];
    let positions = vec![Vec3::new(0.5, 0.5, 0.0), Vec3::new(0.5, 1.5, 0.0), Vec3::new(0.5, 1.0, 0.0)];
    let normals = vec![Vec3::X; 3];
    let joints = vec![[0, 0, 0, 0], [1, 0, 0, 0], [0, 1, 0, 0]];
    let weights = vec![[2.0, 0.0, 0.0, 0.0], [1.0, 0.0, 0.0, 0.0], [0.5, 0.5, 0.0, 0.0]];
    (Skin::new(positions, normals, vec![0, 1, 2], joints, weights, &bind).unwrap(), bind)
}

#[test]
fn bind_pose_rigid_and_half_and_half() {
    let (skin, bind) = two_joint_skin();
    assert_eq!(skin.weights()[0], [1.0, 0.0, 0.0, 0.0], "weights are normalised");
    let (mut p, mut n, mut m) = (Vec::new(), Vec::new(), Vec::new());
    skin::skinning_matrices(&bind, skin.inverse_bind(), &mut m);
    skin::skin_vertices(&skin, &m, &mut p, &mut n);
    for (a, b) in p.iter().zip(skin.positions()) {
        assert!(a.distance(*b) < 1e-6, "the bind pose gives the bind mesh");
    }
    // Joint 1 turns 90° about Z and moves up by 1.
    let posed = vec![bind[0], t(Vec3::new(0.0, 2.0, 0.0), Quat::from_rotation_z(std::f32::consts::FRAC_PI_2))];
    skin::skinning_matrices(&posed, skin.inverse_bind(), &mut m);
    skin::skin_vertices(&skin, &m, &mut p, &mut n);
    let rigid = posed[1].translation + posed[1].rotation * (skin.positions()[1] - Vec3::Y);
    assert!(p[1].distance(rigid) < 1e-5, "one influence is that joint's rigid motion: {} vs {rigid}", p[1]);
    assert!(p[0].distance(skin.positions()[0]) < 1e-6);
    let a = skin.positions()[2];
    let by1 = posed[1].translation + posed[1].rotation * (a - Vec3::Y);
    assert!(p[2].distance((a + by1) * 0.5) < 1e-5, "50/50 is the midpoint of the two rigid motions");
    assert!((n[1] - Vec3::Y).length() < 1e-5, "normals turn with their joint");
}

#[test]
fn invalid_skins_are_refused_with_a_reason() {
    let bind = vec![Transform::IDENTITY];
    let one = |joints: [u32; 4], weights: [f32; 4], indices: Vec<u32>| {
        Skin::new(vec![Vec3::ZERO], vec![Vec3::Y], indices, vec![joints], vec![weights], &bind)
    };
    assert!(matches!(one([3, 0, 0, 0], [1.0, 0.0, 0.0, 0.0], vec![]), Err(SkinError::Joint { joint: 3, .. })));
    assert!(matches!(one([0, 0, 0, 0], [0.0; 4], vec![]), Err(SkinError::Weights { .. })));
    assert!(matches!(one([0, 0, 0, 0], [f32::NAN, 1.0, 0.0, 0.0], vec![]), Err(SkinError::Weights { .. })));
    assert!(matches!(one([0, 0, 0, 0], [-1.0, 2.0, 0.0, 0.0], vec![]), Err(SkinError::Weights { .. })));
    assert!(matches!(one([0, 0, 0, 0], [1.0, 0.0, 0.0, 0.0], vec![0, 0, 1]), Err(SkinError::Index { vertex: 1, .. })));
    assert!(matches!(one([0, 0, 0, 0], [1.0, 0.0, 0.0, 0.0], vec![0, 0]), Err(SkinError::Triangles(2))));
    let flat = [Transform { scale: Vec3::ZERO, ..Transform::IDENTITY }];
    assert!(matches!(
        Skin::new(vec![Vec3::ZERO], vec![Vec3::Y], vec![], vec![[0; 4]], vec![[1.0, 0.0, 0.0, 0.0]], &flat),
        Err(SkinError::Bind(0))
    ));
    let e = one([3, 0, 0, 0], [1.0, 0.0, 0.0, 0.0], vec![]).unwrap_err().to_string();
    assert!(e.contains("vertex 0") && e.contains("joint 3"), "{e}");
}

fn closed(indices: &[u32]) -> bool {
    let mut edges: HashMap<(u32, u32), usize> = HashMap::new();
    for t in indices.chunks(3) {
        for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
            *edges.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    edges.values().all(|&n| n == 2)
}

/// The capsule mode's radius rule (mocap-render's `bone_radius`), here so the core
/// tests need no renderer.
fn radius(size: f32) -> impl Fn(usize, f32) -> f32 {
    move |_, length: f32| {
        if length > size * 0.75 { size * 0.004 } else { (length * 0.2).clamp(size * 0.008, size * 0.04) }
    }
}

#[test]
fn every_corpus_skeleton_gets_a_closed_body_with_whole_weights() {
    let Some(dir) = common::corpus_dir() else { return };
    let manifest = std::fs::read_to_string(dir.join("MANIFEST.tsv")).unwrap();
    let mut checked = 0;
    for line in manifest.lines().skip(1) {
        let path = line.split('\t').next().unwrap_or("");
        if !(path.ends_with(".bvh") || path.ends_with(".asf") || path.ends_with(".bva")) || line.contains("MALFORMED") {
            continue;
        }
        let Ok(asset) = mocap::load_one(path, &std::fs::read(dir.join(path)).unwrap()) else { continue };
        let Some(clip) = asset.clip() else { continue };
        let mut bind = Vec::new();
        if clip.frame_count() > 0 {
            clip.world_transforms_into(0, &mut bind);
        } else {
            mocap::local_to_model(clip.skeleton(), &mocap::LocalPose::rest(clip.skeleton()), &mut bind);
        }
        let body = mocap::build::body::build(clip.skeleton(), &bind, radius(clip.pose_extent()))
            .unwrap_or_else(|e| panic!("{path}: {e}"));
        assert!(!body.indices().is_empty(), "{path}");
        assert!(closed(body.indices()), "{path}: every edge is shared by two triangles");
        for (v, w) in body.weights().iter().enumerate() {
            let sum: f32 = w.iter().sum();
            assert!(
                (sum - 1.0).abs() < 1e-5 && w.iter().all(|x| (0.0..=1.0).contains(x)),
                "{path}: vertex {v} weights {w:?}"
            );
        }
        assert!(
            body.positions().iter().all(|p| p.is_finite())
                && body.normals().iter().all(|n| (n.length() - 1.0).abs() < 1e-3),
            "{path}"
        );
        // Skinned by its own bind pose it stays where it was built.
        let (mut m, mut p, mut n) = (Vec::new(), Vec::new(), Vec::new());
        skin::skinning_matrices(&bind, body.inverse_bind(), &mut m);
        skin::skin_vertices(&body, &m, &mut p, &mut n);
        let extent = clip.pose_extent().max(1e-3);
        assert!(p.iter().zip(body.positions()).all(|(a, b)| a.distance(*b) <= 1e-3 * extent), "{path}");
        checked += 1;
    }
    assert!(checked >= 20, "{checked} skeletons");
}

#[test]
fn a_bent_elbow_leaves_no_gap() {
    // Shoulder → elbow → wrist along +X; bend the elbow 90°: the surface stays one
    // piece where the two tubes meet (every point of the elbow's ring of vertices
    // on one tube has a close point on the other).
    let text = "HIERARCHY\nROOT s\n{\nOFFSET 0 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nJOINT e\n{\nOFFSET 1 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nJOINT w\n{\nOFFSET 1 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{\nOFFSET 0.2 0 0\n}\n}\n}\n}\nMOTION\nFrames: 2\nFrame Time: 0.1\n0 0 0 0 0 0 0 0 0\n0 0 0 90 0 0 0 0 0\n";
    let clip = mocap::formats::bvh::parse(text.as_bytes()).unwrap();
    let mut bind = Vec::new();
    clip.world_transforms_into(0, &mut bind);
    let body = mocap::build::body::build(clip.skeleton(), &bind, |_, _| 0.1).unwrap();
    let mut posed = Vec::new();
    clip.world_transforms_into(1, &mut posed);
    let (mut m, mut p, mut n) = (Vec::new(), Vec::new(), Vec::new());
    skin::skinning_matrices(&posed, body.inverse_bind(), &mut m);
    skin::skin_vertices(&body, &m, &mut p, &mut n);
    let elbow = posed[1].translation;
    // Tubes: s→e (vertices 0..V), e→w (V..2V). Near the elbow, the first tube's
    // far cap and the second tube's near cap: the same sphere blend, so they match.
    let v = mocap::build::body::TUBE_VERTICES as usize;
    let near_elbow = |range: std::ops::Range<usize>| {
        p[range].iter().filter(|q| q.distance(elbow) < 0.101).copied().collect::<Vec<_>>()
    };
    let (upper, lower) = (near_elbow(0..v), near_elbow(v..2 * v));
    assert!(upper.len() >= 12 && lower.len() >= 12);
    // Linear blending loses some volume at a 90° bend (cos 45° at the 50/50 ring),
    // but nothing pinches to the axis and nothing bulges.
    for q in upper.iter().chain(&lower) {
        let d = q.distance(elbow);
        assert!((0.06..=0.1001).contains(&d), "the elbow stays round: {q} at {d}");
    }
    // The outside corner of the bend is covered: the upper arm came in along +X and
    // the forearm leaves along +Y, so the corner faces (1, -1, 0); a gap between the
    // tubes would leave no surface there.
    let outer = Vec3::new(1.0, -1.0, 0.0).normalize();
    let corner = upper.iter().chain(&lower).map(|q| (*q - elbow).normalize().dot(outer)).fold(f32::MIN, f32::max);
    assert!(corner > 0.95, "the outer corner is covered ({corner})");
}
