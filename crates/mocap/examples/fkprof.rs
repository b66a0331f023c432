//! Profiling aid: FK over every frame of a file, per frame (`frame`) or batched (`batch`).
/// Passes over the clip per frame (enough samples for a profiler).
const REPEAT: usize = 30;

fn main() {
    let path = std::env::args().nth(1).expect("file");
    let batched = std::env::args().nth(2).as_deref() == Some("batch");
    let clip = mocap::formats::bvh::parse(&std::fs::read(path).expect("read")).expect("parse");
    let mut world = Vec::new();
    let mut sum = 0.0f32;
    let t = std::time::Instant::now();
    if batched {
        clip.for_each_frame_positions(|_, p| sum += p[0].x);
    } else {
        for _ in 0..REPEAT {
            for f in 0..clip.frame_count() {
                clip.world_transforms_into(f, &mut world);
                sum += world[0].translation.x;
            }
        }
    }
    let n = clip.frame_count() * clip.skeleton().len() * if batched { 1 } else { REPEAT };
    println!("{n} joint transforms, {:.1} M/s ({sum})", n as f64 / t.elapsed().as_secs_f64() / 1e6);
}
