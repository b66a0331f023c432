//! `cargo bench -p mocap-cli`: native frame time of the renderer at 1280×720 for 1,
//! 16 and 64 characters of a 60-joint skeleton, in capsule and stick modes, on
//! whatever Vulkan adapter is present (lavapipe on a machine without a GPU).
//! The skeleton is `../shared/corpus/bvh/animated_drawings/jesse_dance.bvh`.
//!
//! Then the same for capsules without shadows, to show where the time goes on a
//! software rasteriser, and in the fast look (what a window draws while playing
//! once frames are slow; never a final image).
//!
//! Then body mode (generated bodies skinned on the GPU) for 1, 16 and 64 of the
//! same characters, and the time to build the body of the corpus skeleton with the
//! most joints.
//!
//! Then 1, 16 and 64 textured MD2 characters (`md2/waste/tris.md2` with its PCX
//! skin, running; frames blended on the GPU), and the time to load the largest
//! corpus model (`md2/irrlicht_faerie/faerie.md2` with its BMP skin: parse, build
//! the drawing mesh, decode the skin).
//!
//! "frame" is a whole frame as a window would show it: pose every character,
//! build the primitives, draw (shadow map + scene; 4× MSAA where the scene needs
//! it, one sample with blended outlines for capsules, lines and spheres, as
//! `SceneRenderer::samples_for` says) and wait for the GPU; the median of five
//! runs of 20 frames, and the best run.
//! "+ readback" adds copying the pixels back to memory, as `mocap render` does.

use mocap_cli::render::{Gpu, Offscreen, Orbit, StageView};
use mocap_render::DrawMode;
use std::path::Path;
use std::time::Instant;

const FRAMES: usize = 20;
/// Runs of [`FRAMES`] frames timed for each line: "frame" is their median
/// (this machine's speed wanders from minute to minute), with the best.
const RUNS: usize = 5;

fn main() {
    let corpus = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus");
    let path = corpus.join("bvh/animated_drawings/jesse_dance.bvh");
    let Ok(bytes) = std::fs::read(&path) else {
        println!("skipping: {} not found", path.display());
        return;
    };
    let clip = mocap::Asset::Clip(mocap::formats::bvh::parse(&bytes).expect("parse"));
    let gpu = match Gpu::new() {
        Ok(gpu) => gpu,
        Err(e) => {
            println!("skipping: {e}");
            return;
        }
    };
    let joints = clip.clip().map_or(0, |c| c.skeleton().joint_count());
    println!(
        "adapter: {}   skeleton: {joints} joints (+ End Sites), 1280x720, shadows on, samples as the renderer chooses",
        gpu.adapter_name()
    );
    let mut offscreen = Offscreen::new(&gpu, [1280, 720]);
    for mode in [DrawMode::Capsules, DrawMode::Sticks] {
        for count in [1usize, 16, 64] {
            measure(&gpu, &mut offscreen, &clip, mode, count, true);
        }
    }
    println!("capsules, no shadows:");
    for count in [1usize, 16, 64] {
        measure(&gpu, &mut offscreen, &clip, DrawMode::Capsules, count, false);
    }
    // What a window draws while playing once frames are slow (the viewer's
    // automatic rule, crates/mocap-viewer/src/quality.rs); never a final image.
    println!(
        "capsules, the fast look (a playing window's frames once they are slow: no MSAA, shadow-map texels twice as large, one lookup, capsules under 2 pixels left out):"
    );
    let mut fast = Offscreen::with_samples(&gpu, [1280, 720], 1);
    fast.set_fast_look(true);
    for count in [1usize, 16, 64] {
        measure(&gpu, &mut fast, &clip, DrawMode::Capsules, count, true);
    }
    println!("body mode (generated skinned bodies, GPU skinning), shadows on:");
    for count in [1usize, 16, 64] {
        measure(&gpu, &mut offscreen, &clip, DrawMode::Body, count, true);
    }
    body_build_time(&corpus);
    let read = |p: &str| std::fs::read(corpus.join(p)).expect("corpus MD2 file");
    let (model, skin) = (read("md2/waste/tris.md2"), read("md2/waste/waste.pcx"));
    let files = [mocap::Input { name: "tris.md2", bytes: &model }, mocap::Input { name: "waste.pcx", bytes: &skin }];
    let Some(Ok(loaded)) = mocap::load(&files).pop() else { panic!("tris.md2 loads") };
    let mut waste = loaded.asset;
    if let Some(m) = waste.model_mut() {
        m.set_animation_by_name("run");
    }
    println!("MD2 tris.md2 + waste.pcx (running, textured, blended on the GPU), shadows on:");
    for count in [1usize, 16, 64] {
        measure(&gpu, &mut offscreen, &waste, DrawMode::Capsules, count, true);
    }
    let (model, skin) = (read("md2/irrlicht_faerie/faerie.md2"), read("md2/irrlicht_faerie/faerie2.bmp"));
    let files =
        [mocap::Input { name: "faerie.md2", bytes: &model }, mocap::Input { name: "faerie2.bmp", bytes: &skin }];
    let runs = 50;
    let start = Instant::now();
    for _ in 0..runs {
        std::hint::black_box(mocap::load(std::hint::black_box(&files)));
    }
    let load_ms = start.elapsed().as_secs_f64() * 1e3 / runs as f64;
    println!(
        "load faerie.md2 ({} KB) + faerie2.bmp: {load_ms:.2} ms (parse, drawing mesh, skin decode)",
        model.len() / 1024
    );
}

/// Times building the body of the corpus BVH skeleton with the most joints.
fn body_build_time(corpus: &Path) {
    let manifest = std::fs::read_to_string(corpus.join("MANIFEST.tsv")).unwrap_or_default();
    let largest = manifest
        .lines()
        .filter_map(|l| l.split('\t').next())
        .filter(|p| p.ends_with(".bvh"))
        .filter_map(|p| {
            Some((p.to_owned(), mocap::load_one(p, &std::fs::read(corpus.join(p)).ok()?).ok()?.clip()?.clone()))
        })
        .max_by_key(|(_, c)| c.skeleton().len());
    let Some((path, clip)) = largest else { return };
    let extent = clip.pose_extent();
    let runs = 20;
    let start = Instant::now();
    let mut vertices = 0;
    for _ in 0..runs {
        // The body the viewer and `mocap render` build (mocap_scene::body_skin).
        let body = mocap_scene::body_skin(&clip, extent).expect("a body");
        vertices = body.positions().len();
    }
    let ms = start.elapsed().as_secs_f64() * 1e3 / runs as f64;
    println!("body for {path} ({} joints, {vertices} vertices): built in {ms:.2} ms", clip.skeleton().len());
}

/// Times whole frames of `count` characters and prints one line.
fn measure(gpu: &Gpu, offscreen: &mut Offscreen, clip: &mocap::Asset, mode: DrawMode, count: usize, shadows: bool) {
    let stage = StageView::new(vec![("clip".to_owned(), clip.clone()); count]).with_mode(mode);
    let camera = stage.camera(Orbit::default(), offscreen.size());
    let mut scene = mocap_render::Scene::default();
    let pose = |f: usize, scene: &mut mocap_render::Scene| {
        stage.scene_at(clip.timeline().time_of(f % clip.frame_count().max(1)), scene);
        scene.shadows = shadows;
    };
    // Warm up (pipelines, buffer growth), then time whole frames.
    pose(0, &mut scene);
    offscreen.draw(gpu, &scene, &camera).expect("draw");
    let mut runs: Vec<f64> = (0..RUNS)
        .map(|_| {
            let start = Instant::now();
            for f in 0..FRAMES {
                pose(f, &mut scene);
                offscreen.render(gpu, &scene, &camera).expect("render");
            }
            start.elapsed().as_secs_f64() * 1e3 / FRAMES as f64
        })
        .collect();
    runs.sort_by(f64::total_cmp);
    let (frame_ms, best_ms) = (runs[RUNS / 2], runs[0]);
    let start = Instant::now();
    for f in 0..FRAMES {
        pose(f, &mut scene);
        offscreen.draw(gpu, &scene, &camera).expect("draw");
    }
    let readback_ms = start.elapsed().as_secs_f64() * 1e3 / FRAMES as f64;
    println!(
        "{:<8} {count:>3} characters: frame {frame_ms:>7.2} ms (best {best_ms:>6.2}), + readback {readback_ms:>7.2} ms  ({} sample(s); {} capsules, {} lines, {} spheres, {} meshes, {} bodies; draw calls per frame: {})",
        if clip.model().is_some() { "md2" } else { mode.name() },
        offscreen.samples(),
        scene.capsules.len(),
        scene.lines.len(),
        scene.spheres.len(),
        scene.meshes.len(),
        scene.skinned.len(),
        offscreen.draw_calls(),
    );
}
