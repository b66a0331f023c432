//! Profiling aid: FK over every frame of a file, repeated.
fn main() {
    let path = std::env::args().nth(1).expect("file");
    let clip = mocap::bvh::parse(&std::fs::read(path).expect("read")).expect("parse");
    if std::env::args().nth(2).is_some() {
        #[allow(deprecated)]
        unsafe { std::arch::x86_64::_mm_setcsr(std::arch::x86_64::_mm_getcsr() | 0x8040) };
    }
    let mut world = Vec::new();
    let t = std::time::Instant::now();
    for _ in 0..20 {
        for f in 0..clip.frame_count() {
            clip.world_transforms_into(f, &mut world);
        }
    }
    let n = 20 * clip.frame_count() * clip.skeleton.len();
    println!("{:.1} M/s", n as f64 / t.elapsed().as_secs_f64() / 1e6);
}
