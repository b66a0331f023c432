//! Fuzzes the BVH reader: no input may panic, hang or allocate without bound; what
//! parses must also survive FK, bounds and a write → parse round trip.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(clip) = mocap::bvh::parse(data) {
        let _ = clip.bounds();
        let _ = clip.units();
        let mut out = Vec::new();
        clip.sample_world_positions_into(clip.duration() * 0.37, mocap::Interpolation::Linear, &mut out);
        let text = mocap::bvh::write(&clip);
        let again = mocap::bvh::parse(text.as_bytes()).expect("rewritten clip parses");
        assert_eq!(again.frame_count(), clip.frame_count());
        assert_eq!(again.skeleton().len(), clip.skeleton().len());
    }
});
