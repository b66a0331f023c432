//! `cargo bench -p mocap --bench compare`: two 36,000-frame takes compared
//! (`../shared/corpus/bvh/assimp_cmu/01_01.bvh`'s rows repeated; the second a
//! copy with one arm turned), with each alignment; aim under 0.2 s. Best of five.

use mocap::ops::compare::{Align, compare};
use mocap::{Clip, Motion};
use std::time::Instant;

fn main() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus/bvh/assimp_cmu/01_01.bvh");
    let Ok(bytes) = std::fs::read(&path) else {
        println!("skipping: {} not found", path.display());
        return;
    };
    let clip = mocap::formats::bvh::parse(&bytes).expect("parse");
    let c = clip.skeleton().channel_count();
    let rows = clip.motion().data();
    let frames = 36_000;
    let data: Vec<f32> = (0..frames).flat_map(|k| rows[(k % clip.frame_count()) * c..][..c].to_vec()).collect();
    let a = Clip::new(clip.skeleton().clone(), Motion::new(clip.frame_time(), c, frames, data.clone()).unwrap()).unwrap();
    let arm = a.skeleton().find("LeftArm").map_or(3, |j| a.skeleton().joints()[j].columns().start);
    let turned: Vec<f32> = data.chunks(c).flat_map(|r| {
        let mut r = r.to_vec();
        if let Some(v) = r.get_mut(arm) {
            *v += 15.0;
        }
        r
    }).collect();
    let b = Clip::new(clip.skeleton().clone(), Motion::new(clip.frame_time(), c, frames, turned).unwrap()).unwrap();
    println!("compare two {frames}-frame takes, {} joints (aim < 0.2 s):", a.skeleton().joint_count());
    for (name, align) in [("none", Align::None), ("root", Align::Root), ("procrustes", Align::Procrustes)] {
        let mut best = f64::MAX;
        let mut mpjpe = 0.0;
        for _ in 0..5 {
            let t0 = Instant::now();
            let r = compare(&a, &b, align, &[]).expect("compare");
            best = best.min(t0.elapsed().as_secs_f64());
            mpjpe = r.mpjpe;
        }
        println!("  --align {name:<10} {:7.1} ms   (MPJPE {mpjpe:.3} file units)", best * 1000.0);
    }
}
