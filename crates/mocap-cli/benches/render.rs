//! `cargo bench -p mocap-cli`: native frame time of the renderer at 1280×720 for 1,
//! 16 and 64 characters of a 60-joint skeleton (sticks: instanced bones and joints),
//! on whatever Vulkan adapter is present (lavapipe on a machine without a GPU).
//! The skeleton is `../shared/corpus/bvh/animated_drawings/jesse_dance.bvh`.

use mocap_cli::render::{Gpu, Offscreen, Orbit, Stage};
use std::path::Path;
use std::time::Instant;

fn main() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus/bvh/animated_drawings/jesse_dance.bvh");
    let Ok(bytes) = std::fs::read(&path) else {
        println!("skipping: {} not found", path.display());
        return;
    };
    let clip = mocap::bvh::parse(&bytes).expect("parse");
    let gpu = match Gpu::new() {
        Ok(gpu) => gpu,
        Err(e) => {
            println!("skipping: {e}");
            return;
        }
    };
    let joints = clip.skeleton.joints.iter().filter(|j| !j.end_site).count();
    println!("adapter: {}   skeleton: {joints} joints (+ End Sites), 1280x720, 4x MSAA", gpu.adapter_name());
    let mut offscreen = Offscreen::new(&gpu, [1280, 720]);
    for count in [1usize, 16, 64] {
        let stage = Stage::new(vec![&clip; count]);
        let camera = stage.camera(Orbit::default(), offscreen.size());
        let mut scene = mocap_render::Scene::default();
        // Warm up (pipelines, buffer growth), then time whole frames: pose every
        // character, build the primitives, draw, and wait for the pixels.
        stage.scene_at(0.0, &mut scene);
        offscreen.draw(&gpu, &scene, &camera).expect("draw");
        let frames = 20;
        let start = Instant::now();
        for f in 0..frames {
            stage.scene_at(f as f64 * clip.frame_time(), &mut scene);
            offscreen.draw(&gpu, &scene, &camera).expect("draw");
        }
        let ms = start.elapsed().as_secs_f64() * 1e3 / frames as f64;
        println!(
            "{count:>3} characters: {ms:>7.2} ms/frame  ({} bone segments, {} joint spheres, {} grid lines; draw calls per frame: 2 instanced)",
            scene.lines.len(),
            scene.spheres.len(),
            scene.grid.map_or(0, |g| 2 * (2 * g.half_cells + 1))
        );
    }
}
