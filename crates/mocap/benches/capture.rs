//! `cargo bench -p mocap --bench capture`: capturing the largest corpus MD2
//! (`md2/irrlicht_faerie/faerie.md2`: 366 vertices, 198 frames) with the
//! automatic fit, every frame and every joint: the fit, the choice of tracked
//! vertices, and the frames solved, in milliseconds (best of five), plus the
//! frames solved per second. Reads `../shared/corpus` (or `$MOCAP_CORPUS`).

use mocap::capture::{self, Capturer, Options, Rig};
use std::path::PathBuf;
use std::time::Instant;

fn main() {
    let dir = std::env::var_os("MOCAP_CORPUS")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus"));
    let path = dir.join("md2/irrlicht_faerie/faerie.md2");
    let Ok(bytes) = std::fs::read(&path) else {
        eprintln!("{}: not found (the corpus is needed for this benchmark)", path.display());
        std::process::exit(1);
    };
    let md2 = mocap::formats::md2::parse(&bytes).expect("faerie parses");
    let options = Options::default();
    let (mut fit, mut choose, mut solve) = (f64::MAX, f64::MAX, f64::MAX);
    let mut joints = 0;
    for _ in 0..5 {
        let t0 = Instant::now();
        let frames = capture::model_frames(&md2);
        let rig = Rig::fit(&frames[0], 0, None);
        let t1 = Instant::now();
        let mut capturer = Capturer::new(&md2, &rig, &options).expect("capturer");
        joints = rig.joints.len();
        for _ in 0..joints {
            capturer.step();
        }
        let t2 = Instant::now();
        let done = capturer.finish().expect("capture");
        let t3 = Instant::now();
        assert_eq!(done.positions.len(), md2.frames.len());
        fit = fit.min((t1 - t0).as_secs_f64());
        choose = choose.min((t2 - t1).as_secs_f64());
        solve = solve.min((t3 - t2).as_secs_f64());
    }
    let frames = md2.frames.len();
    println!("capture of faerie.md2 ({} vertices, {frames} frames, {joints} joints), best of 5:", md2.vertex_count);
    println!("  fit and bind        {:8.2} ms", fit * 1e3);
    println!("  choose vertices     {:8.2} ms", choose * 1e3);
    println!(
        "  solve every frame   {:8.2} ms  ({:.0} frames/s, {:.0} joint solves/s)",
        solve * 1e3,
        frames as f64 / solve,
        (frames * joints) as f64 / solve
    );
    println!("  total               {:8.2} ms", (fit + choose + solve) * 1e3);
}
