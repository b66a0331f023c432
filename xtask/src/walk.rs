//! Generates the default clip, `data/walk.bvh`: a procedural walk cycle written by
//! this project (centimetres, Y up, walking along +Z, 30 fps), and `data/walk.bva`,
//! the same walk converted by the core (`mocap`): BVH text → clip → BVA segments.

use std::f64::consts::TAU;
use std::fmt::Write;

/// One joint of the generated skeleton: name, parent index, offset (cm).
struct Bone {
    name: &'static str,
    parent: Option<usize>,
    offset: [f64; 3],
}

const BONES: &[Bone] = &[
    Bone { name: "Hips", parent: None, offset: [0.0, 0.0, 0.0] },
    Bone { name: "Spine", parent: Some(0), offset: [0.0, 10.0, 0.0] },
    Bone { name: "Chest", parent: Some(1), offset: [0.0, 15.0, 0.0] },
    Bone { name: "Neck", parent: Some(2), offset: [0.0, 22.0, 0.0] },
    Bone { name: "Head", parent: Some(3), offset: [0.0, 9.0, 1.0] },
    Bone { name: "LeftShoulder", parent: Some(2), offset: [4.0, 18.0, 0.0] },
    Bone { name: "LeftArm", parent: Some(5), offset: [14.0, 0.0, 0.0] },
    Bone { name: "LeftForeArm", parent: Some(6), offset: [0.0, -28.0, 0.0] },
    Bone { name: "LeftHand", parent: Some(7), offset: [0.0, -25.0, 0.0] },
    Bone { name: "RightShoulder", parent: Some(2), offset: [-4.0, 18.0, 0.0] },
    Bone { name: "RightArm", parent: Some(9), offset: [-14.0, 0.0, 0.0] },
    Bone { name: "RightForeArm", parent: Some(10), offset: [0.0, -28.0, 0.0] },
    Bone { name: "RightHand", parent: Some(11), offset: [0.0, -25.0, 0.0] },
    Bone { name: "LeftUpLeg", parent: Some(0), offset: [9.0, -4.0, 0.0] },
    Bone { name: "LeftLeg", parent: Some(13), offset: [0.0, -42.0, 0.0] },
    Bone { name: "LeftFoot", parent: Some(14), offset: [0.0, -41.0, 0.0] },
    Bone { name: "LeftToe", parent: Some(15), offset: [0.0, -5.0, 12.0] },
    Bone { name: "RightUpLeg", parent: Some(0), offset: [-9.0, -4.0, 0.0] },
    Bone { name: "RightLeg", parent: Some(17), offset: [0.0, -42.0, 0.0] },
    Bone { name: "RightFoot", parent: Some(18), offset: [0.0, -41.0, 0.0] },
    Bone { name: "RightToe", parent: Some(19), offset: [0.0, -5.0, 12.0] },
];

/// End Site offsets for the leaves (cm).
fn end_site(name: &str) -> [f64; 3] {
    match name {
        "Head" => [0.0, 18.0, 0.0],
        "LeftHand" | "RightHand" => [0.0, -16.0, 0.0],
        _ => [0.0, 0.0, 6.0],
    }
}

const FPS: f64 = 30.0;
const CYCLE_S: f64 = 1.1;
const CYCLES: usize = 2;
const SPEED_CM_S: f64 = 125.0;
const HIP_HEIGHT: f64 = 91.0;

/// Rotation (Z, X, Y degrees) of a joint at walk phase `p` (radians).
fn rotation(name: &str, p: f64) -> [f64; 3] {
    let (s, c) = p.sin_cos();
    let swing = |phase: f64| 8.0 + 55.0 * phase.cos().max(0.0).powi(2);
    match name {
        "Hips" => [3.0 * s, 2.0, 6.0 * s],
        "Spine" => [-1.5 * s, 2.0, -4.0 * s],
        "Chest" => [-1.5 * s, 1.0, -5.0 * s],
        "Neck" => [0.0, -3.0, 2.0 * s],
        "Head" => [0.0, 2.0, 2.0 * s],
        "LeftShoulder" => [0.0, 0.0, 0.0],
        "RightShoulder" => [0.0, 0.0, 0.0],
        "LeftArm" => [6.0, 22.0 * s, 0.0],
        "RightArm" => [-6.0, -22.0 * s, 0.0],
        "LeftForeArm" => [0.0, -18.0 + 12.0 * s, 0.0],
        "RightForeArm" => [0.0, -18.0 - 12.0 * s, 0.0],
        "LeftUpLeg" => [0.0, -26.0 * s - 4.0, 0.0],
        "RightUpLeg" => [0.0, 26.0 * s - 4.0, 0.0],
        "LeftLeg" => [0.0, swing(p), 0.0],
        "RightLeg" => [0.0, swing(p + TAU / 2.0), 0.0],
        "LeftFoot" => [0.0, -12.0 * c.max(0.0) + 8.0 * s, 0.0],
        "RightFoot" => [0.0, 12.0 * c.min(0.0) - 8.0 * s, 0.0],
        _ => [0.0, 0.0, 0.0],
    }
}

fn write_joint(out: &mut String, index: usize, depth: usize) {
    let pad = "\t".repeat(depth);
    let bone = &BONES[index];
    let kind = if bone.parent.is_none() { "ROOT" } else { "JOINT" };
    let [x, y, z] = bone.offset;
    let _ = writeln!(out, "{pad}{kind} {}\n{pad}{{\n{pad}\tOFFSET {x:.2} {y:.2} {z:.2}", bone.name);
    if bone.parent.is_none() {
        let _ = writeln!(out, "{pad}\tCHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation");
    } else {
        let _ = writeln!(out, "{pad}\tCHANNELS 3 Zrotation Xrotation Yrotation");
    }
    let children: Vec<usize> = (0..BONES.len()).filter(|&j| BONES[j].parent == Some(index)).collect();
    if children.is_empty() {
        let [x, y, z] = end_site(bone.name);
        let _ = writeln!(out, "{pad}\tEnd Site\n{pad}\t{{\n{pad}\t\tOFFSET {x:.2} {y:.2} {z:.2}\n{pad}\t}}");
    }
    for child in children {
        write_joint(out, child, depth + 1);
    }
    let _ = writeln!(out, "{pad}}}");
}

/// Joints in the order their channels appear (depth-first, file order).
fn channel_order(index: usize, out: &mut Vec<usize>) {
    out.push(index);
    for j in (0..BONES.len()).filter(|&j| BONES[j].parent == Some(index)) {
        channel_order(j, out);
    }
}

/// The whole BVH file text.
pub fn walk_bvh() -> String {
    let mut out = String::from("HIERARCHY\n");
    write_joint(&mut out, 0, 0);
    let frames = (CYCLE_S * FPS).round() as usize * CYCLES + 1;
    let _ = writeln!(out, "MOTION\nFrames: {frames}\nFrame Time: {:.6}", 1.0 / FPS);
    let mut order = Vec::new();
    channel_order(0, &mut order);
    for f in 0..frames {
        let t = f as f64 / FPS;
        let p = TAU * t / CYCLE_S;
        let mut row: Vec<String> = Vec::new();
        for &j in &order {
            let name = BONES[j].name;
            if BONES[j].parent.is_none() {
                let bob = HIP_HEIGHT + 1.8 * (2.0 * p).cos();
                let sway = 2.0 * p.sin();
                row.extend([sway, bob, SPEED_CM_S * t - 137.0].iter().map(|v| format!("{v:.3}")));
            }
            row.extend(rotation(name, p).iter().map(|v| format!("{v:.3}")));
        }
        out.push_str(&row.join(" "));
        out.push('\n');
    }
    out
}

/// The walk as BVA text, made by the shipped code: [`walk_bvh`] parsed with
/// `mocap::formats::bvh::parse`, converted with `mocap::formats::bva::from_clip`, written with
/// `mocap::formats::bva::write`.
pub fn walk_bva() -> Result<String, String> {
    let clip =
        mocap::formats::bvh::parse(walk_bvh().as_bytes()).map_err(|e| format!("walk.bvh does not parse: {e}"))?;
    let (bva, _warnings) = mocap::formats::bva::from_clip(&clip);
    Ok(mocap::formats::bva::write(&bva))
}

#[cfg(test)]
mod tests {
    const STALE: &str = "run `cargo xtask gen-walk`";

    #[test]
    fn committed_default_clip_matches_the_generator() {
        let committed = std::fs::read_to_string(crate::util::root().join("data/walk.bvh")).unwrap_or_default();
        assert!(committed == super::walk_bvh(), "data/walk.bvh is stale: {STALE}");
        let committed = std::fs::read(crate::util::root().join("data/walk.bva")).unwrap_or_default();
        let expected = super::walk_bva().expect("walk.bva");
        assert!(committed == expected.as_bytes(), "data/walk.bva is missing or stale: {STALE}");
    }

    #[test]
    fn walk_bva_segments_stand_where_the_bvh_joints_are() {
        let bvh = mocap::formats::bvh::parse(super::walk_bvh().as_bytes()).expect("walk.bvh parses");
        let bytes = std::fs::read(crate::util::root().join("data/walk.bva"))
            .unwrap_or_else(|e| panic!("data/walk.bva: {e}: {STALE}"));
        let bva = mocap::load_one("walk.bva", &bytes).expect("walk.bva loads").clip().cloned().expect("a clip");
        let joints: Vec<usize> =
            (0..bvh.skeleton().len()).filter(|&j| !bvh.skeleton().joints()[j].is_end_site()).collect();
        let height = bvh.pose_height();
        assert!(height > 100.0, "figure height {height} cm");
        assert_eq!(bva.frame_count(), bvh.frame_count());
        assert_eq!(bva.frame_time(), bvh.frame_time());
        // Each segment is a root joint followed by its End Site in the loaded clip.
        assert_eq!(bva.skeleton().len(), 2 * joints.len());
        for frame in 0..bvh.frame_count() {
            let want = bvh.world_positions(frame);
            let got = bva.world_positions(frame);
            for (k, &j) in joints.iter().enumerate() {
                let name = &bvh.skeleton().joints()[j].name;
                assert_eq!(&bva.skeleton().joints()[2 * k].name, name);
                let error = (got[2 * k] - want[j]).length();
                assert!(
                    error <= 1e-3 * height,
                    "frame {frame}, {name}: segment at {} but joint at {} ({error} cm)",
                    got[2 * k],
                    want[j]
                );
            }
        }
    }
}
