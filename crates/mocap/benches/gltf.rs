//! `cargo bench -p mocap --bench gltf`: glTF export and import, and retargeting,
//! on the 27 MB take (the rows of `../shared/corpus/bvh/assimp_cmu/01_01.bvh`
//! repeated to 36,000 frames), side by side with the `gltf` crate's own importer
//! reading the same GLB. Aims (issue 34): GLB export under 1 s; retargeting the
//! take onto a ~65-joint skeleton (Axis Neuron's `test.bvh`) under 1 s.
//! Figures are the best of three runs.

use std::hint::black_box;
use std::path::Path;
use std::time::{Duration, Instant};

const FRAMES: usize = 36_000;

fn corpus() -> std::path::PathBuf {
    let dir = std::env::var_os("MOCAP_CORPUS")
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|| Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus"));
    assert!(dir.join("MANIFEST.tsv").is_file(), "{}: corpus not found (set MOCAP_CORPUS)", dir.display());
    dir
}

#[path = "common/take.rs"]
mod take;

/// Header of 01_01.bvh with its rows repeated to `FRAMES` rows.
fn long_take(src: &[u8]) -> Vec<u8> {
    take::long_take(src, FRAMES)
}

/// The best of three runs of `f`.
fn best<T>(mut f: impl FnMut() -> T) -> (Duration, T) {
    let mut out = None;
    let mut best = Duration::MAX;
    for _ in 0..3 {
        let t = Instant::now();
        let r = f();
        best = best.min(t.elapsed());
        out = Some(r);
    }
    (best, out.expect("ran"))
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1e3
}

fn main() {
    let dir = corpus();
    let bytes = long_take(&std::fs::read(dir.join("bvh/assimp_cmu/01_01.bvh")).expect("01_01.bvh"));
    let clip = mocap::formats::bvh::parse(&bytes).expect("the take parses");
    println!(
        "take: {} bytes of BVH, {} frames × {} channels",
        bytes.len(),
        clip.frame_count(),
        clip.skeleton().channel_count()
    );

    let options = mocap::formats::gltf::Options { name: "take".into(), body: true };
    let (export, glb) = best(|| mocap::formats::gltf::to_glb(black_box(&clip), &options).expect("writes"));
    println!("GLB export (ours):              {:8.1} ms  ({} bytes; aim < 1000 ms)", ms(export), glb.len());

    let none = |_: &str| None;
    let (ours, back) = best(|| mocap::formats::gltf::parse(black_box(&glb), &none, None).expect("reads"));
    let (theirs, _) = best(|| gltf::import_slice(black_box(&glb)).expect("gltf crate reads"));
    println!(
        "GLB import to a clip (ours):    {:8.1} ms  ({} frames; document, buffers, skeleton, every frame sampled, skinned look)",
        ms(ours),
        back.frame_count()
    );
    println!(
        "GLB import, gltf::import_slice: {:8.1} ms  (the peer: document and buffers only, no accessor read)",
        ms(theirs)
    );

    let target = mocap::formats::bvh::parse(&std::fs::read(dir.join("bvh/axis_neuron/test.bvh")).expect("test.bvh"))
        .expect("target parses");
    let (retarget, (out, pairs)) =
        best(|| mocap::ops::retarget::retarget(black_box(&clip), &target, &Default::default()).expect("retargets"));
    println!(
        "retarget onto {} joints:        {:8.1} ms  ({} frames, {} joints mapped; aim < 1000 ms)",
        target.skeleton().len(),
        ms(retarget),
        out.frame_count(),
        pairs.len()
    );
}
