//! Fuzzes the glTF reader: no input may panic, hang or allocate without bound;
//! what reads must survive FK, bounds, every take, and a write → read round trip.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    // The second half of the input is offered as the external file `a.bin`.
    let (file, companion) = data.split_at(data.len() / 2);
    let resources = |name: &str| (name == "a.bin").then(|| companion.to_vec());
    if let Ok(mut clip) = mocap::formats::gltf::parse(file, &resources, None) {
        let _ = clip.bounds();
        let mut out = Vec::new();
        clip.sample_world_positions_into(clip.duration() * 0.37, mocap::Interpolation::Linear, &mut out);
        let names: Vec<String> = clip.takes().iter().map(|t| t.name.clone()).collect();
        for name in names {
            assert!(clip.set_take(&name));
        }
        if let Ok(glb) = mocap::formats::gltf::to_glb(&clip, &Default::default()) {
            let none = |_: &str| None;
            let again = mocap::formats::gltf::parse(&glb, &none, None).expect("our own GLB reads");
            assert_eq!(again.skeleton().len(), clip.skeleton().len());
        }
    }
});
