//! Capturing skeletal motion from vertex animation.
//!
//! Ground truth by construction: the generated body skinned to the walk, baked
//! into an MD2 (8-bit vertices), captured with the walk's skeleton as the rig, and
//! compared with the walk (joint positions as shares of the figure's height, bone
//! directions in degrees): every joint within 0.5 % and every long bone within 1°
//! on every frame; the same without the 8-bit step is exact. On the corpus's MD2 characters: the
//! automatic fit and bind, every tracked joint converging on every frame, and the
//! captured joints inside the model's bounds.

mod common;

use mocap::Clip;
use mocap::capture::{self, Options, Rig};
use mocap::glam::Vec3;
use mocap::runtime::skin;

fn walk() -> Clip {
    mocap::formats::bvh::parse(include_bytes!("../../../data/walk.bvh")).unwrap()
}

/// The walk's body, skinned on every frame, baked into MD2 bytes.
fn baked_walk(clip: &Clip) -> Vec<u8> {
    let bind = clip.bind_pose();
    let extent = clip.pose_extent();
    let body =
        mocap::build::body::build(clip.skeleton(), &bind, |_, l| (l * 0.2).clamp(extent * 0.008, extent * 0.04) * 1.8)
            .unwrap();
    let triangles: Vec<[u32; 3]> = body.indices().chunks_exact(3).map(|t| [t[0], t[1], t[2]]).collect();
    let (mut model, mut m, mut p, mut n) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let frames: Vec<(String, Vec<Vec3>)> = (0..clip.frame_count())
        .map(|f| {
            clip.world_transforms_into(f, &mut model);
            skin::skinning_matrices(&model, body.inverse_bind(), &mut m);
            skin::skin_vertices(&body, &m, &mut p, &mut n);
            (format!("walk{}", f + 1), p.clone())
        })
        .collect();
    mocap::formats::md2::write(&mocap::formats::md2::build(&frames, &triangles).unwrap())
}

/// Joint position errors (share of the height) over every joint and frame, and
/// bone direction errors (degrees) of the bones longer than a tenth of the height.
fn errors(clip: &Clip, cap: &capture::Capture) -> (Vec<f32>, Vec<f32>) {
    let height = clip.pose_extent();
    let (mut positions, mut directions) = (Vec::new(), Vec::new());
    for f in 0..clip.frame_count() {
        let truth = clip.world_positions(f);
        // The clip is in metres; the model's units (here the walk's centimetres) are read as inches.
        let got: Vec<Vec3> = cap.clip.world_positions(f).iter().map(|p| *p / cap.meters_per_unit).collect();
        assert_eq!(truth.len(), got.len());
        for (j, joint) in clip.skeleton().joints().iter().enumerate() {
            positions.push(truth[j].distance(got[j]) / height);
            if let Some(p) = joint.parent.filter(|_| joint.offset.length() > 0.1 * height) {
                let (a, b) = ((truth[j] - truth[p]).normalize_or_zero(), (got[j] - got[p]).normalize_or_zero());
                directions.push(a.dot(b).clamp(-1.0, 1.0).acos().to_degrees());
            }
        }
    }
    (positions, directions)
}

/// Sorted copy's value at share `q` (0–1).
fn percentile(values: &[f32], q: f64) -> f32 {
    let mut v = values.to_vec();
    v.sort_by(f32::total_cmp);
    v.get(((v.len() as f64 - 1.0) * q).round() as usize).copied().unwrap_or(0.0)
}

#[test]
fn a_baked_walk_is_captured_back_close_to_the_truth() {
    let clip = walk();
    let md2 = mocap::formats::md2::parse(&baked_walk(&clip)).unwrap();
    assert_eq!(md2.frames.len(), clip.frame_count());
    let mut model = Vec::new();
    clip.world_transforms_into(0, &mut model);
    let mut rig = Rig::from_skeleton(clip.skeleton(), &model, 0);
    let setup = &capture::model_frames(&md2)[0];
    rig.bind(setup);
    let cap = capture::capture(&md2, &rig, &Options::default()).unwrap();
    println!("{}", cap.report.text());
    assert!(
        cap.report.joints.iter().all(|j| j.tracked.is_ok() && j.failures.is_empty()),
        "every joint tracked and converging"
    );
    let (positions, directions) = errors(&clip, &cap);
    let (p50, p95, max) = (percentile(&positions, 0.5), percentile(&positions, 0.95), percentile(&positions, 1.0));
    let (d50, d95, dmax) = (percentile(&directions, 0.5), percentile(&directions, 0.95), percentile(&directions, 1.0));
    println!(
        "joint error, share of the height: median {:.3} %, 95th percentile {:.3} %, worst {:.3} %",
        p50 * 100.0,
        p95 * 100.0,
        max * 100.0
    );
    println!("long-bone direction error: median {d50:.2}°, 95th percentile {d95:.2}°, worst {dmax:.2}°");
    // One 8-bit step of this figure is 0.4 % of its height. The figures:
    // every joint on every frame within 0.5 % of the height, every long bone
    // within 1°.
    assert!(max < 0.005, "joint errors: median {p50}, 95th percentile {p95}, worst {max}");
    assert!(dmax < 1.0, "bone directions: median {d50}°, 95th percentile {d95}°, worst {dmax}°");
    // The source's method alone (each vertex's stored 8-bit place) is noisier:
    // averaging the rigid parts' shapes is what reaches those figures.
    let raw = capture::capture(&md2, &rig, &Options { average_shapes: false, ..Options::default() }).unwrap();
    let (raw_positions, _) = errors(&clip, &raw);
    let raw_max = percentile(&raw_positions, 1.0);
    println!("stored vertex places: worst joint error {:.3} %", raw_max * 100.0);
    assert!(raw_max > max && raw_max < 0.01, "stored places {raw_max}, averaged {max}");
    // The captured clip is a normal clip: it saves as BVH and reads back.
    let again = mocap::formats::bvh::parse(mocap::formats::bvh::write(&cap.clip).as_bytes()).unwrap();
    assert_eq!(again.frame_count(), clip.frame_count());
    assert_eq!(cap.animations.len(), 1);
    assert_eq!(cap.animations[0].name, "walk");
    // And in the source's per-frame layout.
    let frames = cap.frames();
    let bytes = capture::frames::write(&frames);
    let back = capture::frames::parse(&bytes).unwrap();
    assert_eq!(back.bones.len(), clip.skeleton().len());
    assert_eq!(back.frames[5].name, "walk6");
    let (p, _) = back.frames[5].to_y_up(0).unwrap();
    assert!(p.distance(cap.positions[5][0]) < 1e-4);
}

#[test]
fn without_quantisation_the_capture_is_exact() {
    // The same walk as float frames (no 8-bit MD2 in between): the method itself
    // puts every joint where it was and every long bone within a tenth of a degree.
    let clip = walk();
    let md2 = mocap::formats::md2::parse(&baked_walk(&clip)).unwrap();
    let frames = float_frames(&clip);
    let mut model = Vec::new();
    clip.world_transforms_into(0, &mut model);
    let mut rig = Rig::from_skeleton(clip.skeleton(), &model, 0);
    rig.bind(&frames[0]);
    let tris: Vec<[usize; 3]> = md2.triangles.iter().map(|t| t.vertices.map(usize::from)).collect();
    let options = Options { rigid_tolerance: 1e-5, ..Options::default() };
    let cap = capture::Capturer::from_frames(
        frames,
        md2.frames.iter().map(|f| f.name.clone()).collect(),
        md2.animations.clone(),
        &tris,
        &rig,
        &options,
    )
    .unwrap()
    .finish()
    .unwrap();
    let height = clip.pose_extent();
    let tracked: Vec<usize> = (0..clip.skeleton().len()).filter(|&j| cap.report.joints[j].tracked.is_ok()).collect();
    assert!(
        tracked.len() + 4 >= clip.skeleton().len(),
        "{} of {} joints tracked",
        tracked.len(),
        clip.skeleton().len()
    );
    for f in 0..clip.frame_count() {
        let truth = clip.world_positions(f);
        for &j in &tracked {
            let e = truth[j].distance(cap.positions[f][j]) / height;
            assert!(e < 1e-4, "frame {f}: {} solved {:.5} % away", clip.skeleton().joints()[j].name, e * 100.0);
        }
    }
}

#[test]
fn a_bad_rig_is_refused_with_a_reason() {
    let clip = walk();
    let md2 = mocap::formats::md2::parse(&baked_walk(&clip)).unwrap();
    let mut model = Vec::new();
    clip.world_transforms_into(0, &mut model);
    let rig = Rig::from_skeleton(clip.skeleton(), &model, 0);
    let e = capture::capture(&md2, &rig, &Options::default()).unwrap_err();
    assert!(e.0.contains("vertices are bound"), "{e}");
    let mut far = rig.clone();
    far.setup_frame = 9999;
    far.bind(&capture::model_frames(&md2)[0]);
    assert!(capture::capture(&md2, &far, &Options::default()).unwrap_err().0.contains("set-up frame"));
}

#[test]
fn corpus_characters_are_captured_by_the_automatic_fit() {
    let Some(dir) = common::corpus_dir() else { return };
    for path in ["md2/waste/tris.md2", "md2/irrlicht_faerie/faerie.md2"] {
        let md2 = mocap::formats::md2::parse(&std::fs::read(dir.join(path)).unwrap()).unwrap();
        let frames = capture::model_frames(&md2);
        let rig = Rig::fit(&frames[0], 0, None);
        let cap = capture::capture(&md2, &rig, &Options::default()).unwrap();
        println!("{path}\n{}", cap.report.text());
        let tracked = cap.report.joints.iter().filter(|j| j.tracked.is_ok()).count();
        assert!(tracked * 2 >= cap.report.joints.len(), "{path}: only {tracked} joints tracked");
        for j in cap.report.joints.iter().filter(|j| j.tracked.is_ok()) {
            assert!(j.failures.is_empty(), "{path}: {} did not converge on frames {:?}", j.name, j.failures);
        }
        // The captured joints stay inside the model's bounds (a little margin).
        let mut inside = 0usize;
        let mut all = 0usize;
        for (f, joints) in cap.positions.iter().enumerate() {
            let (lo, hi) =
                frames[f].iter().fold((Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)), |(lo, hi), p| {
                    (lo.min(*p), hi.max(*p))
                });
            let margin = (hi - lo) * 0.02;
            for (j, p) in joints.iter().enumerate() {
                all += 1;
                let ok = p.cmpge(lo - margin).all() && p.cmple(hi + margin).all();
                inside += usize::from(ok);
                if !ok && f % 20 == 0 {
                    println!("{path}: frame {f}: {} outside the bounds at {p}", cap.report.joints[j].name);
                }
            }
        }
        let share = inside as f64 / all as f64;
        println!("{path}: {:.1} % of captured joint positions inside the model's bounds", share * 100.0);
        assert!(share > 0.97, "{path}: {:.1} % inside", share * 100.0);
        let again = mocap::formats::bvh::parse(mocap::formats::bvh::write(&cap.clip).as_bytes()).unwrap();
        assert_eq!(again.frame_count(), md2.frames.len());
        assert!(
            cap.animation_clip("run").is_some_and(|c| c.frame_count() == 6),
            "{path}: the run animation has its 6 frames"
        );
        // The viewer captures from the drawing mesh (vertices split per texture
        // coordinate, welded back): the same motion, in metres.
        let mesh = mocap::MorphMesh::from_md2(&md2);
        let from_mesh = capture::Capturer::from_mesh(&mesh, &rig, &Options::default()).unwrap().finish().unwrap();
        assert_eq!(from_mesh.positions, cap.positions, "{path}");
        assert_eq!(from_mesh.meters_per_unit, 0.0254);
    }
}

/// The walk's body skinned on every frame, as float vertex frames (no MD2).
fn float_frames(clip: &Clip) -> Vec<Vec<Vec3>> {
    let bind = clip.bind_pose();
    let extent = clip.pose_extent();
    let body =
        mocap::build::body::build(clip.skeleton(), &bind, |_, l| (l * 0.2).clamp(extent * 0.008, extent * 0.04) * 1.8)
            .unwrap();
    let (mut model, mut m, mut p, mut n) = (Vec::new(), Vec::new(), Vec::new(), Vec::new());
    (0..clip.frame_count())
        .map(|f| {
            clip.world_transforms_into(f, &mut model);
            skin::skinning_matrices(&model, body.inverse_bind(), &mut m);
            skin::skin_vertices(&body, &m, &mut p, &mut n);
            p.clone()
        })
        .collect()
}
