//! Frames on the software Vulkan driver (lavapipe) do not fault their memory in
//! again every frame: `render::Gpu` keeps what the driver frees for reuse
//! (glibc's trim threshold). A test binary of its own, so that no other test's
//! allocations are counted. Needs a Vulkan driver (`cargo xtask test` installs
//! lavapipe); `MOCAP_SKIP_GPU_TESTS=1` skips it elsewhere.

#[cfg(all(target_os = "linux", target_env = "gnu"))]
#[test]
fn frames_on_lavapipe_do_not_fault_their_memory_in_again() {
    use mocap_cli::render::{Gpu, Offscreen, Orbit, StageView};
    let gpu = match Gpu::new() {
        Ok(gpu) => gpu,
        Err(e) if std::env::var("MOCAP_SKIP_GPU_TESTS").is_ok_and(|v| v == "1") => {
            eprintln!("skipped (MOCAP_SKIP_GPU_TESTS=1): {e}");
            return;
        }
        Err(e) => panic!("{e} (or opt out with MOCAP_SKIP_GPU_TESTS=1)"),
    };
    if !gpu.adapter_name().contains("llvmpipe") {
        eprintln!("not lavapipe ({}): nothing to check", gpu.adapter_name());
        return;
    }
    let walk = include_bytes!("../../../data/walk.bvh");
    let clip = mocap::Asset::Clip(mocap::formats::bvh::parse(walk).expect("walk.bvh"));
    let stage = StageView::new(vec![("walk.bvh".to_owned(), clip.clone()); 64]);
    let mut offscreen = Offscreen::with_samples(&gpu, [1280, 720], 1);
    let camera = stage.camera(Orbit::default(), offscreen.size());
    let mut scene = mocap_render::Scene::default();
    let frame = |f: usize, scene: &mut mocap_render::Scene, offscreen: &mut Offscreen| {
        stage.scene_at(clip.timeline().time_of(f % clip.frame_count()), scene);
        offscreen.render(&gpu, scene, &camera).expect("render");
    };
    for f in 0..5 {
        frame(f, &mut scene, &mut offscreen);
    }
    let faults = || {
        // SAFETY: getrusage fills the struct it is given.
        let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
        unsafe { libc::getrusage(libc::RUSAGE_SELF, &mut usage) };
        usage.ru_minflt
    };
    let (before, frames) = (faults(), 20);
    for f in 5..5 + frames {
        frame(f, &mut scene, &mut offscreen);
    }
    let per_frame = (faults() - before) / frames as i64;
    eprintln!("{per_frame} page faults a frame ({} capsules)", scene.capsules.len());
    assert!(
        per_frame < 300,
        "{per_frame} page faults a frame: the driver's per-frame memory is handed back and faulted in again"
    );
}
