//! Acclaim ASF/AMC in the animation model: hand-computed FK for `axis` handling,
//! the CMU take against its BVH conversion on every frame, ASF/AMC → BVH keeping
//! every position, and every corpus file through the loader.

mod common;

use mocap::glam::{Quat, Vec3};
use mocap::{Input, LoadError, Loader, load};

fn loaded(files: &[(&str, &[u8])]) -> Vec<Result<mocap::Loaded, LoadError>> {
    let inputs: Vec<Input> = files.iter().map(|(name, bytes)| Input { name, bytes }).collect();
    load(&inputs)
}

/// A root and one bone `b` along +X (length 2) whose axis is `axis` (degrees, XYZ),
/// with rx ry rz dofs, then a child bone `c` along +Y (length 1).
fn two_bones(axis: [f32; 3]) -> String {
    format!(
        ":version 1.10\n:name T\n:units\n  mass 1.0\n  length 1.0\n  angle deg\n:root\n  order TX TY TZ RX RY RZ\n  axis XYZ\n  position 0 0 0\n  orientation 0 0 0\n:bonedata\n  begin\n    id 1\n    name b\n    direction 1 0 0\n    length 2\n    axis {} {} {} XYZ\n    dof rx ry rz\n    limits (-180 180)\n           (-90 90)\n           (-inf inf)\n  end\n  begin\n    id 2\n    name c\n    direction 0 1 0\n    length 1\n    axis 0 0 0 XYZ\n  end\n:hierarchy\n  begin\n    root b\n    b c\n  end\n",
        axis[0], axis[1], axis[2]
    )
}

fn pose(asf: &str, amc: &str) -> Vec<Vec3> {
    let results = loaded(&[("t.asf", asf.as_bytes()), ("t.amc", amc.as_bytes())]);
    let clip = results.into_iter().next().unwrap().unwrap().into_clip().unwrap();
    clip.world_positions(0)
}

fn close(a: Vec3, b: Vec3) -> bool {
    (a - b).length() < 1e-5
}

#[test]
fn a_bone_rotates_about_its_axis_frame() {
    // Joints: root, b (at the origin), c (at b's end), c_End (at c's end).
    // Axis identity: rz 90 turns b's +X direction to +Y; c (+Y) ends at (0,2,0)+R·(0,1,0) = (-1,2,0).
    let p = pose(&two_bones([0.0, 0.0, 0.0]), "1\nroot 0 0 0 0 0 0\nb 0 0 90\n");
    assert!(close(p[2], Vec3::new(0.0, 2.0, 0.0)), "{:?}", p);
    assert!(close(p[3], Vec3::new(-1.0, 2.0, 0.0)), "{:?}", p);
    // Axis z = 90: the bone's local X is world Y, so its rx (90) turns about world Y:
    // C·Rx(90)·C⁻¹ = Ry(90), taking +X to -Z and leaving +Y alone.
    let p = pose(&two_bones([0.0, 0.0, 90.0]), "1\nroot 0 0 0 0 0 0\nb 90 0 0\n");
    assert!(close(p[2], Vec3::new(0.0, 0.0, -2.0)), "{:?}", p);
    assert!(close(p[3], Vec3::new(0.0, 1.0, -2.0)), "{:?}", p);
    // Same axis, ry (90): about the bone's local Y = world -X; +X stays, +Y → (0,0,-1)... C·Ry(90)·C⁻¹ = Rx(-90)?
    // Rz(90)·Ry(90)·Rz(-90) is a rotation of 90° about Rz(90)·Y = -X: +Y goes to -Z... about -X by 90°: Y → -Z.
    let p = pose(&two_bones([0.0, 0.0, 90.0]), "1\nroot 0 0 0 0 0 0\nb 0 90 0\n");
    assert!(close(p[2], Vec3::new(2.0, 0.0, 0.0)), "{:?}", p);
    assert!(close(p[3], Vec3::new(2.0, 0.0, -1.0)), "{:?}", p);
    // rz about local Z = world Z: +X → +Y as with the identity axis.
    let p = pose(&two_bones([0.0, 0.0, 90.0]), "1\nroot 0 0 0 0 0 0\nb 0 0 90\n");
    assert!(close(p[2], Vec3::new(0.0, 2.0, 0.0)), "{:?}", p);
    assert!(close(p[3], Vec3::new(-1.0, 2.0, 0.0)), "{:?}", p);
    // Dofs compose extrinsically in dof order: rx 90 then rz 90 = Rz·Rx.
    let p = pose(&two_bones([0.0, 0.0, 0.0]), "1\nroot 0 0 0 0 0 0\nb 90 0 90\n");
    let m = Quat::from_rotation_z(90f32.to_radians()) * Quat::from_rotation_x(90f32.to_radians());
    assert!(close(p[3], m * Vec3::new(2.0, 0.0, 0.0) + m * Vec3::Y), "{:?}", p);
    // Root translation and rotation.
    let p = pose(&two_bones([0.0, 0.0, 0.0]), "1\nroot 1 2 3 0 90 0\nb 0 0 0\n");
    assert!(close(p[0], Vec3::new(1.0, 2.0, 3.0)));
    assert!(close(p[2], Vec3::new(1.0, 2.0, 1.0)), "{:?}", p);
}

#[test]
fn limits_units_and_documentation_reach_the_model() {
    let results = loaded(&[("t.asf", two_bones([0.0; 3]).as_bytes())]);
    let clip = results.into_iter().next().unwrap().unwrap().into_clip().unwrap();
    assert_eq!(clip.frame_count(), 0, "an ASF alone is its rest pose");
    let b = &clip.skeleton().joints()[1];
    assert_eq!(b.limits.len(), 3);
    assert_eq!((b.limits[1].min, b.limits[1].max), (-90.0, 90.0));
    assert_eq!(b.limits[2].max, f32::INFINITY);
    assert!(clip.metadata.iter().any(|(k, v)| k == "units length" && v == "1"));
    assert!(clip.metadata.iter().any(|(k, v)| k == "name" && v == "T"));
}

#[test]
fn a_motion_needs_its_skeleton_and_a_loader_remembers_the_last_one() {
    let amc = b"1\nroot 0 0 0 0 0 0\nb 0 0 0\n";
    let err = loaded(&[("t.amc", amc)]).pop().unwrap().unwrap_err();
    assert!(matches!(err, LoadError::MissingSkeleton { .. }));
    assert!(err.to_string().contains("t.amc") && err.to_string().contains(".asf"), "{err}");
    let named =
        loaded(&[("x.amc", b"#!OML:ASF H:\\Terrain\\JustinFriday.ASF\n:FULLY-SPECIFIED\n1\nroot 0 0 0 0 0 0\n")])
            .pop()
            .unwrap()
            .unwrap_err();
    assert!(named.to_string().ends_with("(the motion names JustinFriday.ASF)"), "{named}");
    let mut loader = Loader::default();
    let asf = two_bones([0.0; 3]);
    assert!(loader.load(&[Input { name: "t.asf", bytes: asf.as_bytes() }])[0].is_ok());
    let again = loader.load(&[Input { name: "later.amc", bytes: amc }]);
    assert_eq!(again.len(), 1);
    assert_eq!(again[0].as_ref().unwrap().clip().unwrap().frame_count(), 1);
    assert_eq!(loader.skeleton_name(), Some("t.asf"));
}

#[test]
fn amc_errors_name_the_file_line_and_column() {
    let asf = two_bones([0.0; 3]);
    let err =
        loaded(&[("t.asf", asf.as_bytes()), ("t.amc", b"1\nroot 0 0 0 0 0 0\nzz 1 2 3\n")]).pop().unwrap().unwrap_err();
    assert!(err.to_string().starts_with("t.amc:3:1:"), "{err}");
    let err =
        loaded(&[("t.asf", asf.as_bytes()), ("t.amc", b"1\nroot 0 0 0 0 0 0\nb 1 2\n")]).pop().unwrap().unwrap_err();
    assert!(err.to_string().starts_with("t.amc:3:"), "{err}");
}

#[test]
fn a_windows_media_file_named_asf_is_refused_clearly() {
    let mut bytes =
        vec![0x30, 0x26, 0xB2, 0x75, 0x8E, 0x66, 0xCF, 0x11, 0xA6, 0xD9, 0x00, 0xAA, 0x00, 0x62, 0xCE, 0x6C];
    bytes.extend((0..500u32).map(|i| (i * 37 % 251) as u8));
    let err = loaded(&[("movie.asf", &bytes)]).pop().unwrap().unwrap_err();
    let text = err.to_string();
    assert!(
        text.starts_with("movie.asf:1:1:")
            && text.contains("not an Acclaim skeleton")
            && text.contains("Windows Media"),
        "{text}"
    );
}

/// CMU bone names and their joints in the cgspeed BVH conversion.
const CMU_BVH: [(&str, &str); 30] = [
    ("lhipjoint", "LHipJoint"),
    ("lfemur", "LeftUpLeg"),
    ("ltibia", "LeftLeg"),
    ("lfoot", "LeftFoot"),
    ("ltoes", "LeftToeBase"),
    ("rhipjoint", "RHipJoint"),
    ("rfemur", "RightUpLeg"),
    ("rtibia", "RightLeg"),
    ("rfoot", "RightFoot"),
    ("rtoes", "RightToeBase"),
    ("lowerback", "LowerBack"),
    ("upperback", "Spine"),
    ("thorax", "Spine1"),
    ("lowerneck", "Neck"),
    ("upperneck", "Neck1"),
    ("head", "Head"),
    ("lclavicle", "LeftShoulder"),
    ("lhumerus", "LeftArm"),
    ("lradius", "LeftForeArm"),
    ("lwrist", "LeftHand"),
    ("lhand", "LeftFingerBase"),
    ("lfingers", "LFingers"),
    ("lthumb", "LThumb"),
    ("rclavicle", "RightShoulder"),
    ("rhumerus", "RightArm"),
    ("rradius", "RightForeArm"),
    ("rwrist", "RightHand"),
    ("rhand", "RightFingerBase"),
    ("rfingers", "RFingers"),
    ("rthumb", "RThumb"),
];

/// The direction of the bone that starts at joint `j` (towards its first child).
fn bone_direction(skeleton: &mocap::Skeleton, positions: &[Vec3], j: usize) -> Vec3 {
    let child = skeleton.joints().iter().position(|c| c.parent == Some(j)).expect("a bone has an end");
    (positions[child] - positions[j]).normalize()
}

#[test]
fn cmu_01_01_amc_agrees_with_its_bvh_conversion_on_every_frame() {
    let Some(dir) = common::corpus_dir() else { return };
    let asf = std::fs::read(dir.join("asf_amc/cmu/01.asf")).unwrap();
    let amc = std::fs::read(dir.join("asf_amc/cmu/01_01.amc")).unwrap();
    let bvh = std::fs::read(dir.join("bvh/assimp_cmu/01_01.bvh")).unwrap();
    let acclaim = loaded(&[("01.asf", &asf), ("01_01.amc", &amc)]).pop().unwrap().unwrap().into_clip().unwrap();
    let converted = mocap::formats::bvh::parse(&bvh).unwrap();
    assert_eq!(acclaim.frame_count() + 1, converted.frame_count(), "the BVH has a T-pose first");
    let pairs: Vec<(usize, usize)> = CMU_BVH
        .iter()
        .map(|(a, b)| (acclaim.skeleton().find(a).unwrap(), converted.skeleton().find(b).unwrap()))
        .collect();
    let (mut pa, mut pb) = (Vec::new(), Vec::new());
    let mut worst = 0.0f32;
    let mut worst_at = (0, "");
    for frame in 0..acclaim.frame_count() {
        acclaim.world_positions_into(frame, &mut pa);
        converted.world_positions_into(frame + 1, &mut pb);
        for (n, &(a, b)) in pairs.iter().enumerate() {
            let da = bone_direction(acclaim.skeleton(), &pa, a);
            let db = bone_direction(converted.skeleton(), &pb, b);
            // atan2 of |cross| and dot: acos near 1 loses the small angles in f32.
            let angle = da.cross(db).length().atan2(da.dot(db)).to_degrees();
            if angle > worst {
                worst = angle;
                worst_at = (frame, CMU_BVH[n].0);
            }
        }
    }
    eprintln!("largest limb direction difference: {worst}° (frame {}, {})", worst_at.0, worst_at.1);
    assert!(worst < 0.01, "largest limb direction difference {worst}° (frame {}, {})", worst_at.0, worst_at.1);
}

#[test]
fn asf_amc_to_bvh_keeps_every_position() {
    let Some(dir) = common::corpus_dir() else { return };
    let asf = std::fs::read(dir.join("asf_amc/cmu/02.asf")).unwrap();
    let amc = std::fs::read(dir.join("asf_amc/cmu/02_01.amc")).unwrap();
    let clip = loaded(&[("02.asf", &asf), ("02_01.amc", &amc)]).pop().unwrap().unwrap().into_clip().unwrap();
    let back = mocap::formats::bvh::parse(mocap::formats::bvh::write(&clip).as_bytes()).unwrap();
    assert_eq!(back.frame_count(), clip.frame_count());
    let height = clip.pose_height();
    let (mut pa, mut pb) = (Vec::new(), Vec::new());
    for frame in 0..clip.frame_count() {
        clip.world_positions_into(frame, &mut pa);
        back.world_positions_into(frame, &mut pb);
        for (j, (a, b)) in pa.iter().zip(&pb).enumerate() {
            let name = &clip.skeleton().joints()[j].name;
            let k = back.skeleton().find(name).unwrap();
            assert!((*a - pb[k]).length() <= 1e-4 * height, "frame {frame} {name}: {a} vs {b}");
        }
    }
}

#[test]
fn every_corpus_acclaim_file_loads() {
    let Some(dir) = common::corpus_dir() else { return };
    let cmu = dir.join("asf_amc/cmu");
    for (asf, amcs, frames) in
        [("01.asf", vec!["01_01.amc", "01_06.amc"], vec![2751, 5133]), ("02.asf", vec!["02_01.amc"], vec![343])]
    {
        let skeleton = std::fs::read(cmu.join(asf)).unwrap();
        let motions: Vec<Vec<u8>> = amcs.iter().map(|m| std::fs::read(cmu.join(m)).unwrap()).collect();
        let mut files = vec![(asf, skeleton.as_slice())];
        files.extend(amcs.iter().zip(&motions).map(|(n, b)| (*n, b.as_slice())));
        let results = loaded(&files);
        assert_eq!(results.len(), amcs.len(), "one clip per motion, none for the used skeleton");
        for ((result, name), n) in results.into_iter().zip(&amcs).zip(frames) {
            let l = result.unwrap();
            assert_eq!(&l.name, name);
            assert_eq!(l.clip().unwrap().frame_count(), n);
            assert_eq!(l.clip().unwrap().skeleton().joint_count(), 31);
            assert_eq!(
                l.clip().unwrap().units(),
                mocap::Units::CmuInches,
                "{name}: {}",
                l.clip().unwrap().pose_height()
            );
            let b = l.clip().unwrap().bounds();
            assert!(b.min.is_finite() && b.max.is_finite());
        }
    }
    let simple = std::fs::read(dir.join("asf_amc/handmade/simple_test.asf")).unwrap();
    let clip = loaded(&[("simple_test.asf", &simple)]).pop().unwrap().unwrap().into_clip().unwrap();
    assert_eq!(clip.skeleton().joint_count(), 2);
    let p = clip.world_positions(0);
    assert!(close(p[2], Vec3::new(0.0, 0.0, 2.0)), "the leaf bone ends 2 along +Z: {p:?}");
}
